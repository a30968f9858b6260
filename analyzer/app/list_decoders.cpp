#include "list_decoders.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "core/registry.h"

namespace busdecode {

const char* optionKindName(OptionSpec::Kind k) {
    switch (k) {
        case OptionSpec::Kind::Int:
            return "int";
        case OptionSpec::Kind::Float:
            return "number";
        case OptionSpec::Kind::Bool:
            return "0/1";
        case OptionSpec::Kind::Choice:
            return "choice";
        case OptionSpec::Kind::String:
            return "text";
    }
    return "";
}

namespace {

// "position:int, crc_ok:bool, ...": each field with the kind of its values.
std::string fieldList(const std::vector<FieldSpec>& fields) {
    std::vector<std::string> shown;
    for (const auto& f : fields)
        shown.push_back(f.kind == FieldSpec::Kind::Any
                            ? f.name
                            : fmt::format("{}:{}", f.name, fieldKindName(f.kind)));
    return fmt::format("{}", fmt::join(shown, ", "));
}

}  // namespace

void printDecoderList(std::FILE* out) {
    const auto all = Registry::instance().all();
    if (all.empty()) fmt::print(out, "no decoders found (plugins directory missing?)\n");
    for (const auto* f : all) {
        const DecoderInfo& d = f->info();
        fmt::print(out, "{}  {}\n", d.id, d.name);
        if (!d.description.empty()) fmt::print(out, "    {}\n", d.description);
        fmt::print(out, "  roles:\n");
        for (const auto& r : d.roles)
            fmt::print(out, "    {:<10} {:<9} auto: {}{}\n", r.name,
                       r.required ? "required" : "optional", fmt::join(r.aliases, " "),
                       r.help.empty() ? "" : "  -- " + r.help);
        if (!d.need_one_of.empty())
            fmt::print(out, "    (bind at least one of: {})\n", fmt::join(d.need_one_of, ", "));
        fmt::print(out, "  options:\n");
        for (const auto& o : d.options) {
            std::string allowed;
            if (o.kind == OptionSpec::Kind::Choice)
                allowed = fmt::format(" [{}]", fmt::join(o.choices, "|"));
            else if (o.kind == OptionSpec::Kind::Int || o.kind == OptionSpec::Kind::Float) {
                if (o.min > -1e299 || o.max < 1e299)
                    allowed =
                        fmt::format(" [{}..{}]", o.min > -1e299 ? fmt::format("{}", o.min) : "",
                                    o.max < 1e299 ? fmt::format("{}", o.max) : "");
                if (o.allow_auto) allowed += " or auto";
            }
            fmt::print(out, "    {:<14} {:<7} default {:<8}{}  {}\n", o.key, optionKindName(o.kind),
                       o.default_value.empty() ? "-" : o.default_value, allowed, o.help);
        }
        fmt::print(out, "    {:<14} {:<7} default {:<8}  {}\n", "glitch_ns", "number", "0",
                   "ignore pulses shorter than this on every mapped line (ns)");
        fmt::print(out, "  events:\n");
        for (const auto& e : d.events)
            fmt::print(out, "    {:<14} {}{}\n", e.type, e.help,
                       e.fields.empty() ? "" : fmt::format(" ({})", fieldList(e.fields)));
        fmt::print(out, "\n");
    }
}

}  // namespace busdecode
