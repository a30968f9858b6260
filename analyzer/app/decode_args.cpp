#include "decode_args.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <map>

#include "core/registry.h"
#include "plugin_loader.h"

namespace busdecode {

namespace {

std::pair<std::string, std::string> splitAssignment(const std::string& what, const std::string& s) {
    auto eq = s.find('=');
    if (eq == std::string::npos || eq == 0)
        throw InputError(fmt::format("{} '{}': expected KEY=VALUE", what, s));
    return {s.substr(0, eq), s.substr(eq + 1)};
}

bool declaresOption(const DecoderInfo& info, const std::string& key) {
    if (key == "glitch_ns") return true;
    for (const auto& o : info.options)
        if (o.key == key) return true;
    return false;
}

bool declaresRole(const DecoderInfo& info, const std::string& role) {
    for (const auto& r : info.roles)
        if (r.name == role) return true;
    return false;
}

}  // namespace

std::vector<DecoderRequest> buildRequests(const std::vector<std::string>& protos,
                                          const std::vector<std::string>& maps,
                                          const std::vector<std::string>& opts) {
    std::vector<DecoderRequest> reqs;
    std::vector<const DecoderInfo*> infos;
    for (const auto& p : protos) {
        const DecoderFactory* f = Registry::instance().find(p);
        if (!f) {
            loadPlugins();  // every plugin: one may provide it without saying so
            f = Registry::instance().find(p);
        }
        if (!f)
            Registry::instance().create(p, {});  // throws "unknown decoder ... (available: ...)"
        reqs.push_back({p, {}, {}});
        infos.push_back(&f->info());
    }
    // A `proto.` prefix scopes a key to one decoder id; otherwise it goes to every
    // requested decoder that declares it.
    std::map<std::pair<std::size_t, std::string>, std::string> given;  // what set each key
    auto apply = [&](const std::string& what, const std::string& text, bool is_map) {
        auto [key, value] = splitAssignment(what, text);
        std::string scope;
        if (auto dot = key.find('.'); dot != std::string::npos) {
            std::string prefix = key.substr(0, dot);
            for (const auto& p : protos)
                if (p == prefix) scope = prefix;
            if (!scope.empty()) key = key.substr(dot + 1);
        }
        bool used = false;
        for (std::size_t i = 0; i < reqs.size(); ++i) {
            if (!scope.empty() && reqs[i].proto != scope) continue;
            const bool known =
                is_map ? declaresRole(*infos[i], key) : declaresOption(*infos[i], key);
            if (!known && (scope.empty() && reqs.size() > 1)) continue;
            if (!known) {
                // Let the decoder's own validation produce the error listing valid keys.
                if (is_map) {
                    std::vector<std::string> roles;
                    for (const auto& r : infos[i]->roles)
                        roles.push_back(r.name);
                    throw InputError(
                        fmt::format("decoder {}: unknown role '{}' in --map (roles: {})",
                                    reqs[i].proto, key, fmt::join(roles, ", ")));
                }
                Options::resolve(*infos[i], {{key, value}});
            }
            auto& slot = (is_map ? reqs[i].map : reqs[i].options)[key];
            auto& first = given[{i, (is_map ? "map " : "opt ") + key}];
            if (!first.empty())
                throw InputError(
                    fmt::format("{} {}: {} is set already for {} ({} {}): it takes "
                                "one value",
                                what, text, key, reqs[i].proto, what, first));
            first = text;
            slot = value;
            used = true;
        }
        if (!used) {
            std::vector<std::string> keys;
            for (const auto* info : infos) {
                if (is_map)
                    for (const auto& r : info->roles)
                        keys.push_back(info->id + "." + r.name);
                else
                    for (const auto& o : info->options)
                        keys.push_back(info->id + "." + o.key);
            }
            throw InputError(fmt::format("{} {}: no chosen decoder has '{}' (valid: {})", what,
                                         text, key, fmt::join(keys, ", ")));
        }
    };
    for (const auto& m : maps)
        apply("--map", m, true);
    for (const auto& o : opts)
        apply("--opt", o, false);
    // Option values too, once here rather than when each capture is open: a wrong call.
    for (std::size_t i = 0; i < reqs.size(); ++i) {
        auto options = reqs[i].options;
        options.erase("glitch_ns");  // the session's own option, checked there
        Options::resolve(*infos[i], options);
    }
    return reqs;
}

std::string hintLine(const std::string& capture, const std::string& hint) {
    return fmt::format("decode: {}: hint: {}\n", oneLine(capture), oneLine(hint));
}

}  // namespace busdecode
