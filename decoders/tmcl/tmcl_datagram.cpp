#include "tmcl_datagram.h"

#include <sstream>

#include <fmt/format.h>

#include "tmcl_tables.h"

namespace busdecode::tmcl {

std::uint8_t checksumOf(const Datagram& d) {
    std::uint8_t sum = 0;
    for (int i = 0; i < 8; ++i)
        sum = std::uint8_t(sum + d[i]);
    return sum;
}

std::int32_t valueOf(const Datagram& d) {
    const std::uint32_t v = (std::uint32_t(d[4]) << 24) | (std::uint32_t(d[5]) << 16) |
                            (std::uint32_t(d[6]) << 8) | std::uint32_t(d[7]);
    return std::int32_t(v);
}

Command parseCommand(const Datagram& d) {
    return Command{d[0], d[1], d[2], d[3], valueOf(d), checksumOk(d)};
}

Reply parseReply(const Datagram& d) {
    return Reply{d[0], d[1], d[2], d[3], valueOf(d), checksumOk(d)};
}

std::string mnemonicOf(int command) {
    const auto* info = findCommand(command);
    return info ? info->mnemonic : "unknown";
}

std::string statusText(int status) {
    const auto* s = findStatus(status);
    return s ? s->text : "";
}

std::string mnemonicText(const Command& c) {
    const auto* info = findCommand(c.command);
    if (!info) return fmt::format("Command {} {}, {}, {}", c.command, c.type, c.motor, c.value);
    std::string out = info->mnemonic;
    std::istringstream fields(info->layout);
    std::string field;
    bool first = true;
    while (std::getline(fields, field, ',')) {
        field.erase(0, field.find_first_not_of(' '));
        if (field.empty()) continue;
        std::string text;
        if (field == "M")
            text = std::to_string(c.motor);
        else if (field == "V")
            text = std::to_string(c.value);
        else if (field == "T")
            text = std::to_string(c.type);
        else if (field.rfind("T:", 0) == 0) {
            const char* sym = typeSymbol(field.substr(2), c.type);
            text = sym ? sym : std::to_string(c.type);
        }
        out += (first ? " " : ", ") + text;
        first = false;
    }
    return out;
}

std::string parameterName(const Command& c) {
    const auto* info = findCommand(c.command);
    if (!info) return "";
    const std::string_view kind = info->parameters;
    if (kind == "axis") {
        const auto* p = findAxisParameter(c.type);
        return p ? p->name : "";
    }
    if (kind == "global") return globalParameterName(c.motor, c.type);
    return "";
}

std::string ideLine(const Command& c) {
    std::string line = mnemonicText(c);
    const std::string name = parameterName(c);
    if (!name.empty()) line += "  // " + name;
    return line;
}

bool looksLikeReply(const Datagram& d) {
    return d[3] != 0 && findStatus(d[2]) && findCommand(d[3]);
}

bool isVersionString(const Datagram& d) {
    for (int i = 1; i < 9; ++i)
        if (d[i] < 0x20 || d[i] > 0x7E) return false;
    return true;
}

namespace {
Datagram withValue(Datagram d, std::int32_t value) {
    const auto v = std::uint32_t(value);
    d[4] = std::uint8_t(v >> 24);
    d[5] = std::uint8_t(v >> 16);
    d[6] = std::uint8_t(v >> 8);
    d[7] = std::uint8_t(v);
    d[8] = checksumOf(d);
    return d;
}
}  // namespace

Datagram makeCommand(int address, int command, int type, int motor, std::int32_t value) {
    return withValue(Datagram{std::uint8_t(address), std::uint8_t(command), std::uint8_t(type),
                              std::uint8_t(motor)},
                     value);
}

Datagram makeReply(int reply_address, int module_address, int status, int command,
                   std::int32_t value) {
    return withValue(Datagram{std::uint8_t(reply_address), std::uint8_t(module_address),
                              std::uint8_t(status), std::uint8_t(command)},
                     value);
}

Datagram makeVersionReply(int reply_address, const std::string& version) {
    Datagram d{std::uint8_t(reply_address)};
    for (int i = 0; i < 8; ++i)
        d[1 + i] = i < int(version.size()) ? std::uint8_t(version[i]) : ' ';
    return d;
}

}  // namespace busdecode::tmcl
