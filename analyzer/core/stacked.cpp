#include "stacked.h"

#include "registry.h"

namespace busdecode {

LowerStack::LowerStack(const std::string& lower_id, const Options& upper_options,
                       std::vector<int> role_map, Handler on_lower_event)
    : role_map_(std::move(role_map)), handler_(std::move(on_lower_event)) {
    const DecoderFactory* f = Registry::instance().find(lower_id);
    if (!f) throw InputError("stacked decoder needs '" + lower_id + "', which is not loaded");
    std::map<std::string, std::string> passed;
    for (const auto& spec : f->info().options)
        if (upper_options.has(spec.key)) passed[spec.key] = upper_options.text(spec.key);
    lower_ = f->create(Options::resolve(f->info(), passed));
    lower_roles_ = int(f->info().roles.size());
    lower_->setSink(this);
}

LowerStack::~LowerStack() = default;

void LowerStack::start(const DecoderContext& upper_ctx) {
    DecoderContext c = upper_ctx;
    c.sink = this;
    c.initial_levels.assign(lower_roles_, -1);
    for (std::size_t u = 0; u < role_map_.size() && u < upper_ctx.initial_levels.size(); ++u)
        if (role_map_[u] >= 0) c.initial_levels[role_map_[u]] = upper_ctx.initial_levels[u];
    lower_->start(c);
}

void LowerStack::edge(Tick t, int upper_role, bool level) {
    if (upper_role >= 0 && upper_role < int(role_map_.size()) && role_map_[upper_role] >= 0)
        lower_->edge(t, role_map_[upper_role], level);
}

void LowerStack::advance(Tick now) {
    lower_->advance(now);
}
void LowerStack::finish(Tick end) {
    lower_->finish(end);
}

void LowerStack::glitch(Tick t, int upper_role) {
    if (upper_role >= 0 && upper_role < int(role_map_.size()) && role_map_[upper_role] >= 0)
        lower_->glitch(t, role_map_[upper_role]);
}

Tick LowerStack::watermark(Tick now) const {
    return lower_->watermark(now);
}

}  // namespace busdecode
