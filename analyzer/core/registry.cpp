#include "registry.h"

#include <algorithm>

#include <fmt/format.h>
#include <fmt/ranges.h>

namespace busdecode {

Registry& Registry::instance() {
    static Registry r;
    return r;
}

void Registry::add(std::shared_ptr<const DecoderFactory> f) {
    if (!f || find(f->info().id)) return;
    factories_.push_back(std::move(f));
}

const DecoderFactory* Registry::find(const std::string& id) const {
    for (const auto& f : factories_)
        if (f->info().id == id) return f.get();
    return nullptr;
}

std::vector<const DecoderFactory*> Registry::all() const {
    std::vector<const DecoderFactory*> out;
    for (const auto& f : factories_)
        out.push_back(f.get());
    std::sort(out.begin(), out.end(), [](auto* a, auto* b) { return a->info().id < b->info().id; });
    return out;
}

std::unique_ptr<Decoder> Registry::create(const std::string& id,
                                          const std::map<std::string, std::string>& options) const {
    const DecoderFactory* f = find(id);
    if (!f) {
        std::vector<std::string> ids;
        for (auto* x : all())
            ids.push_back(x->info().id);
        throw InputError(
            fmt::format("unknown decoder '{}' (available: {})", id, fmt::join(ids, ", ")));
    }
    return f->create(Options::resolve(f->info(), options));
}

}  // namespace busdecode
