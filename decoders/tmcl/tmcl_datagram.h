#pragma once
// TMCL datagrams over RS-232/RS-485/USB (TMCM-1690 TMCL manual 3.1, 3.2): 9 bytes,
// command = address, command, type, motor/bank, value (4 bytes, MSB first), checksum;
// reply = reply address, module address, status, command, value, checksum. The checksum
// is the 8-bit sum of bytes 0..7. GetVersion (136) type 0 is answered with the host
// address and 8 ASCII characters, without checksum.
#include <array>
#include <cstdint>
#include <string>

namespace busdecode::tmcl {

using Datagram = std::array<std::uint8_t, 9>;

inline constexpr int kGetVersion = 136;

std::uint8_t checksumOf(const Datagram& d);
inline bool checksumOk(const Datagram& d) {
    return checksumOf(d) == d[8];
}
std::int32_t valueOf(const Datagram& d);  // bytes 4..7, MSB first, signed

struct Command {
    int address = 0, command = 0, type = 0, motor = 0;
    std::int32_t value = 0;
    bool checksum_ok = false;
};
struct Reply {
    int reply_address = 0, module_address = 0, status = 0, command = 0;
    std::int32_t value = 0;
    bool checksum_ok = false;
};

Command parseCommand(const Datagram& d);
Reply parseReply(const Datagram& d);

// The command as the TMCL-IDE writes it: "SAP 4, 0, 51200", "MVP ABS, 0, 90000".
std::string mnemonicText(const Command& c);
// Name of the axis or global parameter the command addresses, or "".
std::string parameterName(const Command& c);
// The IDE line with the parameter name as comment: "SAP 4, 0, 51200  // Max velocity".
std::string ideLine(const Command& c);
std::string mnemonicOf(int command);  // "SAP", "GetVersion", or "unknown"
std::string statusText(int status);   // "" when the code is unknown

// A reply rather than a command: the status byte is a known status code and the command
// byte a known command (a command's motor/bank byte is rarely a command number).
bool looksLikeReply(const Datagram& d);
// Bytes 1..8 are printable ASCII: the GetVersion string reply.
bool isVersionString(const Datagram& d);

Datagram makeCommand(int address, int command, int type, int motor, std::int32_t value);
Datagram makeReply(int reply_address, int module_address, int status, int command,
                   std::int32_t value);
Datagram makeVersionReply(int reply_address, const std::string& version);  // 8 characters

}  // namespace busdecode::tmcl
