#include "session_ini.h"

#include <algorithm>
#include <cstdlib>

#include <fmt/format.h>

#include "csv_fields.h"

namespace busdecode {

void forEachIniLine(std::string_view text, const std::function<void(const IniLine&)>& on) {
    IniLine l;
    for (std::size_t at = 0; at < text.size();) {
        std::size_t nl = text.find('\n', at);
        if (nl == std::string_view::npos) nl = text.size();
        const std::string_view raw = text.substr(at, nl - at);
        at = nl + 1;
        ++l.number;
        const std::string_view line = trimBlanks(raw);
        if (line.empty() || line.front() == ';' || line.front() == '#') continue;
        if (line.front() == '[') {
            l.section = line;
            continue;
        }
        const auto eq = line.find('=');
        l.has_value = eq != std::string_view::npos;
        l.key = l.has_value ? trimBlanks(line.substr(0, eq)) : line;
        l.value = l.has_value ? trimBlanks(line.substr(eq + 1)) : std::string_view();
        l.indented = raw.front() == ' ' || raw.front() == '\t';
        on(l);
    }
}

SrMetadata::SrMetadata(std::string_view text) {
    forEachIniLine(text, [this](const IniLine& l) {
        if (l.has_value && l.section.rfind("[device", 0) == 0)
            keys_[std::string(l.key)] = std::string(l.value);
    });
}

const std::string* SrMetadata::find(const std::string& key) const {
    const auto it = keys_.find(key);
    return it == keys_.end() ? nullptr : &it->second;
}

int SrMetadata::number(const std::string& key) const {
    const std::string* v = find(key);
    return v ? std::atoi(v->c_str()) : 0;
}

std::string SrMetadata::probeName(int bit) const {
    const std::string* name = find(fmt::format("probe{}", bit + 1));
    return name ? *name : fmt::format("D{}", bit);
}

int SrMetadata::highestProbe() const {
    int highest = 0;
    for (auto it = keys_.lower_bound("probe");
         it != keys_.end() && it->first.rfind("probe", 0) == 0; ++it)
        highest = std::max(highest, std::atoi(it->first.c_str() + 5));
    return highest;
}

}  // namespace busdecode
