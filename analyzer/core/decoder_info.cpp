#include "decoder_info.h"

namespace busdecode {

namespace {

OptionSpec make(std::string key, OptionSpec::Kind kind, std::string def, std::string help) {
    OptionSpec o;
    o.key = std::move(key);
    o.kind = kind;
    o.default_value = std::move(def);
    o.help = std::move(help);
    return o;
}

// Integer and real options differ only in their kind.
OptionSpec ranged(OptionSpec::Kind kind, std::string key, std::string def, double min, double max,
                  std::string help, bool allow_auto) {
    OptionSpec o = make(std::move(key), kind, std::move(def), std::move(help));
    o.min = min;
    o.max = max;
    o.allow_auto = allow_auto;
    return o;
}

}  // namespace

OptionSpec intOption(std::string key, std::string def, double min, double max, std::string help,
                     bool allow_auto) {
    return ranged(OptionSpec::Kind::Int, std::move(key), std::move(def), min, max, std::move(help),
                  allow_auto);
}

OptionSpec numberOption(std::string key, std::string def, double min, double max, std::string help,
                        bool allow_auto) {
    return ranged(OptionSpec::Kind::Float, std::move(key), std::move(def), min, max,
                  std::move(help), allow_auto);
}

OptionSpec boolOption(std::string key, std::string def, std::string help) {
    return make(std::move(key), OptionSpec::Kind::Bool, std::move(def), std::move(help));
}

OptionSpec choiceOption(std::string key, std::vector<std::string> choices, std::string help,
                        std::string def) {
    if (def.empty() && !choices.empty()) def = choices.front();
    OptionSpec o = make(std::move(key), OptionSpec::Kind::Choice, std::move(def), std::move(help));
    o.choices = std::move(choices);
    return o;
}

OptionSpec textOption(std::string key, std::string def, std::string help) {
    return make(std::move(key), OptionSpec::Kind::String, std::move(def), std::move(help));
}

const char* fieldKindName(FieldSpec::Kind kind) {
    switch (kind) {
        case FieldSpec::Kind::Int:
            return "int";
        case FieldSpec::Kind::Number:
            return "number";
        case FieldSpec::Kind::Bool:
            return "bool";
        case FieldSpec::Kind::Text:
            return "text";
        case FieldSpec::Kind::IntList:
            return "list";
        case FieldSpec::Kind::Any:
            break;
    }
    return "any";
}

const EventTypeSpec* findEventType(const DecoderInfo& d, const std::string& type) {
    for (const auto& e : d.events)
        if (e.type == type) return &e;
    return nullptr;
}

}  // namespace busdecode
