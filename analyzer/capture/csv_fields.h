#pragma once
// The small text steps every CSV-like header parser takes: blanks (and a line's CR)
// trimmed, one pair of double quotes taken off a field, names compared in lower case.
#include <cctype>
#include <string>
#include <string_view>

namespace busdecode {

inline std::string_view trimBlanks(std::string_view s) {
    while (!s.empty() && (s.front() == ' ' || s.front() == '\t'))
        s.remove_prefix(1);
    while (!s.empty() && (s.back() == ' ' || s.back() == '\t' || s.back() == '\r'))
        s.remove_suffix(1);
    return s;
}

// A field's text: blanks trimmed, then one pair of surrounding quotes removed.
inline std::string_view trimField(std::string_view s) {
    s = trimBlanks(s);
    if (s.size() >= 2 && s.front() == '"' && s.back() == '"') s = s.substr(1, s.size() - 2);
    return s;
}

inline std::string asciiLower(std::string_view s) {
    std::string out(s);
    for (auto& c : out)
        c = char(std::tolower(static_cast<unsigned char>(c)));
    return out;
}

}  // namespace busdecode
