#pragma once
// The INI text of sigrok and DSView sessions (.sr `metadata`, .dsl `header`): `[section]`
// lines, then `key = value` lines; `;` and `#` start comments. One reading for the three
// readers of it (sr_reader.cpp, sr_analog_samples.cpp, dsl_reader.cpp).
#include <cstddef>
#include <functional>
#include <map>
#include <string>
#include <string_view>

namespace busdecode {

struct IniLine {
    std::string_view section;  // the last `[...]` line, brackets kept ("" before any)
    std::string_view key;      // trimmed; the whole line where there is no '='
    std::string_view value;    // trimmed
    bool has_value = false;    // the line has an '='
    bool indented = false;     // starts with a blank (DSView: a probe's own settings)
    std::size_t number = 0;    // 1-based
};

// Calls `on` for every line that is not blank, a comment or a section.
void forEachIniLine(std::string_view text, const std::function<void(const IniLine&)>& on);

// A sigrok session's `metadata`: the keys of its `[device N]` section, which give the
// sample rate, the logic word's size and the names of the probes and analog channels.
class SrMetadata {
public:
    explicit SrMetadata(std::string_view text);
    const std::string* find(const std::string& key) const;
    int number(const std::string& key) const;  // 0 where absent or not a number
    // Probe `bit`'s name (0-based): its `probe<bit+1>` key, else D<bit> (a disabled probe).
    std::string probeName(int bit) const;
    int highestProbe() const;  // the highest N of the `probe<N>` keys, 0 if none
    const std::map<std::string, std::string>& keys() const { return keys_; }

private:
    std::map<std::string, std::string> keys_;
};

}  // namespace busdecode
