#include "tmc8100_datagram.h"

#include <fmt/format.h>

namespace busdecode::tmc8100 {

namespace {
std::uint8_t byteOf(std::uint32_t w, int i) {
    return std::uint8_t(w >> (8 * i));
}  // i=3: first sent
bool printable(std::uint8_t c) {
    return c >= 0x20 && c <= 0x7E;
}
bool allPrintable(std::uint32_t w) {
    for (int i = 0; i < 4; ++i)
        if (!printable(byteOf(w, i))) return false;
    return true;
}
}  // namespace

std::string asciiOf(std::uint32_t w) {
    std::string s;
    for (int i = 3; i >= 0; --i)
        s += printable(byteOf(w, i)) ? char(byteOf(w, i)) : '.';
    return s;
}

Command appCommand(std::uint32_t word, EncoderProtocol protocol) {
    Command c;
    c.code = byteOf(word, 3);
    switch (c.code) {
        case 0x80:
            c.name = "read_encoder";
            c.replies = {ReplyKind::RawPosition, ReplyKind::BinaryPosition, ReplyKind::Flags};
            if (protocol == EncoderProtocol::Biss) c.replies.push_back(ReplyKind::ClockEdges);
            break;
        case 0xFF:
            c.name = "get_version";
            c.replies = {ReplyKind::Version};
            break;
        case 0xFE:
            c.name = "get_protocol";
            c.replies = {ReplyKind::Protocol};
            break;
        case 0x00:
            c.name = word == 0 ? "dummy" : "unknown";
            break;
        default:
            c.name = "unknown";
            break;
    }
    return c;
}

bool isBootloaderQuery(std::uint8_t code) {
    return code == 0xB0 || code == 0xB8;
}
bool isProgramWrite(std::uint8_t code) {
    return (code & 0xF8) == 0x08;
}
int programAddress(std::uint32_t word) {
    return int((word >> 16) & 0x7FF);
}

Command bootloaderCommand(std::uint32_t word) {
    Command c;
    c.code = byteOf(word, 3);
    if (word == 0) {
        c.name = "bootloader_version";
        c.replies = {ReplyKind::BootloaderVersion};
    } else if (c.code == 0xB0) {
        c.name = "chip_id";
        c.replies = {ReplyKind::ChipId};
    } else if (c.code == 0xB8) {
        c.name = "chip_revision";
        c.replies = {ReplyKind::ChipRevision};
    } else if (isProgramWrite(c.code)) {
        // [0x08 | addr[10:8], addr[7:0], data_hi, data_lo]: one 16-bit instruction.
        c.name = "program_write";
        c.address = programAddress(word);
        c.data = int(word & 0xFFFF);
    } else if ((c.code & 0xF8) == 0x88) {
        c.name = "program_verify";
        c.address = programAddress(word);
        c.replies = {ReplyKind::ProgramWord};
    } else if (word == 0x10000000) {
        c.name = "start_program";
        c.switches_to_app = true;
    } else {
        c.name = "unknown";
    }
    return c;
}

ReplyKind kindFromTag(std::uint32_t word) {
    switch (byteOf(word, 3)) {
        case 0x10:
            return ReplyKind::RawPosition;
        case 0x20:
            return ReplyKind::BinaryPosition;
        case 0x70:
            return ReplyKind::Flags;
        case 0x71:
            return ReplyKind::ClockEdges;
        case 0xFF:
            return ReplyKind::Version;
        default:
            return allPrintable(word) ? ReplyKind::Protocol : ReplyKind::Unknown;
    }
}

bool matches(ReplyKind kind, std::uint32_t word) {
    switch (kind) {
        case ReplyKind::RawPosition:
        case ReplyKind::BinaryPosition:
        case ReplyKind::Flags:
        case ReplyKind::ClockEdges:
        case ReplyKind::Version:
            return kindFromTag(word) == kind;
        case ReplyKind::Protocol:
        case ReplyKind::ChipId:
            return allPrintable(word);
        default:
            return true;  // bootloader replies have no tag to check
    }
}

std::string meaningName(ReplyKind kind, EncoderProtocol protocol) {
    switch (kind) {
        case ReplyKind::RawPosition:
            return "raw_position";
        case ReplyKind::BinaryPosition:
            return "binary_position";
        case ReplyKind::Flags:
            return protocol == EncoderProtocol::Biss ? "status_crc" : "flags";
        case ReplyKind::ClockEdges:
            return "clock_edges";
        case ReplyKind::Version:
            return "version";
        case ReplyKind::Protocol:
            return "protocol";
        case ReplyKind::BootloaderVersion:
            return "bootloader_version";
        case ReplyKind::ChipId:
            return "chip_id";
        case ReplyKind::ChipRevision:
            return "chip_revision";
        case ReplyKind::ProgramWord:
            return "program_word";
        case ReplyKind::Unknown:
            return "unknown";
    }
    return "unknown";
}

std::string describeReply(ReplyKind kind, std::uint32_t word, EncoderProtocol protocol, Event& e) {
    e.set("meaning", meaningName(kind, protocol));
    const auto b2 = byteOf(word, 2), b1 = byteOf(word, 1), b0 = byteOf(word, 0);
    const std::int64_t st = word & 0xFFFF;
    switch (kind) {
        case ReplyKind::RawPosition:
            e.set("position", st);
            return fmt::format("raw position (as received, Gray) 0x{:04X}", st);
        case ReplyKind::BinaryPosition:
            e.set("position", st);
            return fmt::format("binary position 0x{:04X} ({})", st, st);
        case ReplyKind::Flags:
            if (protocol == EncoderProtocol::Biss) {
                // BiSS demo: [0x70, nE:nW, CRC received, CRC calculated ^ 0x3F]; both CRCs
                // are then in the inverted form sent on the wire and compare directly.
                e.set("nE", std::int64_t((b2 >> 1) & 1));
                e.set("nW", std::int64_t(b2 & 1));
                e.set("crc_rx", std::int64_t(b1));
                e.set("crc_calc", std::int64_t(b0));
                e.set("crc_ok", b1 == b0);
                return fmt::format("nE={} nW={} CRC received 0x{:02X} calculated 0x{:02X}",
                                   (b2 >> 1) & 1, b2 & 1, b1, b0);
            }
            e.set("flags", std::int64_t(b2));
            return fmt::format("encoder flags 0x{:02X}", b2);
        case ReplyKind::ClockEdges:
            e.set("clock_edges", std::int64_t(b0));
            return fmt::format("{} clock edges", b0);
        case ReplyKind::Version:
            e.set("major", std::int64_t(b1));
            e.set("minor", std::int64_t(b0));
            return fmt::format("firmware version {}.{}", b1, b0);
        case ReplyKind::Protocol:
            e.set("text", asciiOf(word));
            return fmt::format("encoder protocol \"{}\"", asciiOf(word));
        case ReplyKind::BootloaderVersion:
            e.set("version", std::int64_t(byteOf(word, 3)));
            return fmt::format("bootloader version 0x{:02X}", byteOf(word, 3));
        case ReplyKind::ChipId:
            e.set("text", asciiOf(word));
            return fmt::format("chip id \"{}\"", asciiOf(word));
        case ReplyKind::ChipRevision:
            e.set("revision", std::int64_t(byteOf(word, 3)));
            return fmt::format("chip revision 0x{:02X}", byteOf(word, 3));
        case ReplyKind::ProgramWord:
            e.set("data", st);
            return fmt::format("program word 0x{:04X}", st);
        case ReplyKind::Unknown:
            break;
    }
    return fmt::format("word 0x{:08X}", word);
}

}  // namespace busdecode::tmc8100
