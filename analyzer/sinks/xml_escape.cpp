#include "xml_escape.h"

#include "core/utf8.h"

namespace busdecode {

std::string xmlEscape(const std::string& s) {
    std::string out;
    out.reserve(s.size());
    for (std::size_t i = 0; i < s.size(); ++i) {
        const auto c = static_cast<unsigned char>(s[i]);
        switch (c) {
            case '&':
                out += "&amp;";
                break;
            case '<':
                out += "&lt;";
                break;
            case '>':
                out += "&gt;";
                break;
            case '"':
                out += "&quot;";
                break;
            case '\'':
                out += "&apos;";
                break;
            case '\n':
                out += "&#10;";
                break;
            case '\t':
                out += "&#9;";
                break;
            default:
                if (c < 0x20) continue;  // not allowed in XML 1.0
                if (c < 0x80)
                    out += char(c);
                else
                    i += appendUtf8OrReplacement(out, s, i) - 1;
        }
    }
    return out;
}

}  // namespace busdecode
