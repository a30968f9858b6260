#include "declared_fields.h"

#include <fmt/format.h>

#include "core/registry.h"

namespace busdecode::fuzz {

namespace {

bool fitsKind(const Value& v, FieldSpec::Kind kind) {
    using K = FieldSpec::Kind;
    switch (kind) {
        case K::Int:
            return std::holds_alternative<std::int64_t>(v) ||
                   std::holds_alternative<std::uint64_t>(v);
        case K::Number:
            return std::holds_alternative<double>(v);
        case K::Bool:
            return std::holds_alternative<bool>(v);
        case K::Text:
            return std::holds_alternative<std::string>(v);
        case K::IntList:
            return std::holds_alternative<std::vector<std::int64_t>>(v);
        case K::Any:
            break;
    }
    return true;
}

// The field names an option's value gives ("a,b@3": a and b), for a "<option>" spec.
bool namedByOption(const std::string& key, const std::string& spec,
                   const std::vector<DecoderRequest>& requests, const std::string& proto) {
    const std::string option = spec.substr(1, spec.size() - 2);
    for (const auto& r : requests) {
        if (r.proto != proto) continue;
        const auto it = r.options.find(option);
        if (it == r.options.end()) continue;
        std::size_t from = 0;
        while (from <= it->second.size()) {
            const std::size_t comma = std::min(it->second.find(',', from), it->second.size());
            const std::string item = it->second.substr(from, comma - from);
            if (item.substr(0, item.find('@')) == key) return true;
            from = comma + 1;
        }
    }
    return false;
}

const FieldSpec* declarationOf(const std::string& key, const EventTypeSpec& type,
                               const std::vector<DecoderRequest>& requests,
                               const std::string& proto) {
    for (const auto& f : type.fields)
        if (f.name == key) return &f;
    for (const auto& f : type.fields)
        if (f.name.starts_with('<') && namedByOption(key, f.name, requests, proto)) return &f;
    return nullptr;
}

}  // namespace

std::string undeclaredField(const Event& e, const std::vector<DecoderRequest>& requests) {
    const DecoderFactory* factory = Registry::instance().find(e.proto);
    if (!factory) return fmt::format("{} {}: no decoder '{}'", e.proto, e.type, e.proto);
    const EventTypeSpec* type = findEventType(factory->info(), e.type);
    if (!type) return fmt::format("{} {}: the type is not declared", e.proto, e.type);
    for (const Field& f : e.fields) {
        const FieldSpec* spec = declarationOf(f.key, *type, requests, e.proto);
        if (!spec) return fmt::format("{} {}: field '{}' is not declared", e.proto, e.type, f.key);
        if (!isNull(f.value) && !fitsKind(f.value, spec->kind))
            return fmt::format("{} {}: field '{}' is not of its declared kind {}", e.proto, e.type,
                               f.key, fieldKindName(spec->kind));
    }
    return "";
}

}  // namespace busdecode::fuzz
