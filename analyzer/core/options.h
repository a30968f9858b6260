#pragma once
// Validated decoder options. Parsing and checking happen once in the core against the
// decoder's OptionSpecs; decoders read typed values and never see bad input.
#include <cstdint>
#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>

#include "decoder_info.h"

namespace busdecode {

// A user error (bad option, unbound role, unreadable file...). The CLI prints what()
// as one line and exits 2.
class InputError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

class Options {
public:
    Options() = default;
    // Applies defaults, then `given` (key -> text). Throws InputError naming the decoder,
    // the option and the valid choices or range.
    static Options resolve(const DecoderInfo& info,
                           const std::map<std::string, std::string>& given);

    bool has(const std::string& key) const { return values_.count(key) != 0; }
    const std::string& text(const std::string& key) const;
    std::int64_t integer(const std::string& key) const;
    double number(const std::string& key) const;
    bool flag(const std::string& key) const;
    bool isAuto(const std::string& key) const { return has(key) && text(key) == "auto"; }
    const std::map<std::string, std::string>& all() const { return values_; }
    void setRaw(const std::string& key, const std::string& v) { values_[key] = v; }

private:
    std::map<std::string, std::string> values_;
};

// `text` with its control characters (newline, tab, ESC...) shown as \xNN: an error or
// hint line stays one line whatever file name, option or header it quotes.
std::string oneLine(std::string_view text);

// Parses a number the way users write it: 9600, 1e6, 0x43, 2.5, -3.
std::optional<double> parseNumber(const std::string& s);
std::optional<std::int64_t> parseInteger(const std::string& s);

}  // namespace busdecode
