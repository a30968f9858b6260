#pragma once
// What the TMC8100's 32-bit SPI datagrams mean (docs/protocols.md §3.1, the SSI application
// note [D1] in its §0, and the TMC8100 example firmwares): command names by first byte,
// the replies each command queues, and what a reply word says. Pure functions, no state:
// the decoder pairs replies with commands, this file only knows the datagram formats.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "core/event.h"

namespace busdecode::tmc8100 {

// Which program runs on the chip: the application firmware's command loop or the ROM
// bootloader (used before "start program").
enum class Firmware { Unknown, App, Bootloader };

// The firmware's encoder protocol (from the 0xFE reply or the `encoder` option): the BiSS
// demo queues a fourth reply (0x71 clock edges) and a status+CRC word instead of flags.
enum class EncoderProtocol { Unknown, Ssi, Biss };

enum class ReplyKind {
    RawPosition,        // 0x10 00 ST_hi ST_lo: single-turn as received (Gray)
    BinaryPosition,     // 0x20 00 ST_hi ST_lo: converted by the firmware
    Flags,              // 0x70 flags 00 00 (SSI) / 0x70 nE:nW CRC_rx CRC_calc^0x3F (BiSS)
    ClockEdges,         // 0x71 00 00 edges (BiSS demo)
    Version,            // 0xFF 00 major minor
    Protocol,           // four ASCII characters ("SSI ", "BISS")
    BootloaderVersion,  // bootloader 0x00 query
    ChipId,             // bootloader 0xB0 query: four ASCII characters
    ChipRevision,       // bootloader 0xB8 query
    ProgramWord,        // bootloader verify read: .. .. data_hi data_lo
    Unknown,
};

struct Command {
    std::uint8_t code = 0;
    std::string
        name;  // read_encoder, get_version, get_protocol, dummy, unknown, or a bootloader name
    std::vector<ReplyKind> replies;  // what the firmware queues in answer, in FIFO order
    bool switches_to_app = false;    // bootloader "start program"
    std::optional<int> address;      // bootloader program write / verify
    std::optional<int> data;         // bootloader program write
};

// Application command loop: the firmware tests only the first byte. A word whose first
// byte is 0 but which carries other bytes is not the documented dummy (00 00 00 00):
// it is reported as unknown rather than given a meaning.
Command appCommand(std::uint32_t word, EncoderProtocol protocol);
// Bootloader datagrams (the demo scripts' download sequence).
Command bootloaderCommand(std::uint32_t word);
// First bytes that only the bootloader understands (auto detection).
bool isBootloaderQuery(std::uint8_t code);  // chip id, chip revision
bool isProgramWrite(std::uint8_t code);
int programAddress(std::uint32_t word);

// The reply kind a word's first byte announces, for replies that arrive unasked.
ReplyKind kindFromTag(std::uint32_t word);
// Whether `word` is a plausible reply of `kind` (tag byte, ASCII for texts).
bool matches(ReplyKind kind, std::uint32_t word);

// Adds the reply's `meaning` and its own fields (position, flags, major/minor, text...)
// to `e` and returns the summary text.
std::string describeReply(ReplyKind kind, std::uint32_t word, EncoderProtocol protocol, Event& e);

std::string meaningName(ReplyKind kind, EncoderProtocol protocol);
// Four bytes as text, non-printing bytes as '.'.
std::string asciiOf(std::uint32_t word);

}  // namespace busdecode::tmc8100
