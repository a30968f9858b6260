#include "lcm_channels.h"

#include <cctype>

namespace busdecode {

namespace {

void appendChannelPart(std::string& out, std::string_view part) {
    for (char c : part) {
        unsigned char u = static_cast<unsigned char>(c);
        out += std::isalnum(u) ? static_cast<char>(std::toupper(u)) : '_';
    }
}

}  // namespace

std::string lcmChannelFor(std::string_view proto, std::string_view type) {
    std::string out = "DECODE_";
    appendChannelPart(out, proto);
    out += '_';
    appendChannelPart(out, type);
    return out;
}

}  // namespace busdecode
