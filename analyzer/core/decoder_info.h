#pragma once
// A decoder declares itself as data (the libsigrokdecode idea): roles, options with
// defaults and allowed values, event types. `decode --list`, option validation and
// automatic role binding all work from this declaration.
#include <string>
#include <utility>
#include <vector>

namespace busdecode {

struct RoleSpec {
    std::string name;                  // "clk", "data", ...
    bool required = true;              // optional roles may stay unbound
    std::vector<std::string> aliases;  // signal names bound automatically (case-insensitive)
    std::string help;
};

struct OptionSpec {
    enum class Kind { Int, Float, Bool, Choice, String };
    std::string key;
    Kind kind = Kind::Int;
    std::string default_value;         // as text, parsed like a user value
    std::vector<std::string> choices;  // Choice: the allowed values
    double min = -1e300, max = 1e300;  // Int/Float: inclusive range
    std::string help;
    bool allow_auto = false;  // Int/Float: also accepts the word "auto"
};

// Builders, so declarations read as one line per option.
OptionSpec intOption(std::string key, std::string def, double min, double max, std::string help,
                     bool allow_auto = false);
OptionSpec numberOption(std::string key, std::string def, double min, double max, std::string help,
                        bool allow_auto = false);
OptionSpec boolOption(std::string key, std::string def, std::string help);
// The default is the first choice unless `def` names another.
OptionSpec choiceOption(std::string key, std::vector<std::string> choices, std::string help,
                        std::string def = "");
OptionSpec textOption(std::string key, std::string def, std::string help);

// A field of an event type and the kind of its values (null aside): `decode --list` shows
// it, and read() types a DataFrame column by it when no event of the capture had a value,
// so that a table's columns do not depend on which fields a capture's events filled. A
// name in angle brackets, "<status_bits>", stands for the fields that option's value names.
struct FieldSpec {
    enum class Kind { Any, Int, Number, Bool, Text, IntList };
    FieldSpec(const char* n, Kind k = Kind::Any) : name(n), kind(k) {}
    FieldSpec(std::string n, Kind k = Kind::Any) : name(std::move(n)), kind(k) {}
    std::string name;
    Kind kind = Kind::Any;
};

const char* fieldKindName(FieldSpec::Kind kind);  // "int", "number", "bool", "text", "list"

struct EventTypeSpec {
    std::string type;
    std::string help;
    std::vector<FieldSpec> fields;  // besides the common ones, in the order events list them
};

struct DecoderInfo {
    std::string id;  // "ssi"
    std::string name;
    std::string description;
    std::vector<RoleSpec> roles;
    std::vector<OptionSpec> options;
    std::vector<EventTypeSpec> events;
    // At least one of these optional roles must be bound (e.g. uart: rx or tx).
    std::vector<std::string> need_one_of;
};

// The declaration of `type` among `d`'s events, or null.
const EventTypeSpec* findEventType(const DecoderInfo& d, const std::string& type);

}  // namespace busdecode
