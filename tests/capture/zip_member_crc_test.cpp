// A session member whose bytes do not match its CRC is an input error naming the file and
// the member, on every path that reads ZIP members: libzip checks a CRC only on a read at
// the member's end, which the .sr analog reader (its last channel) and the DSView readers
// (which read a block's exact size) never made.
#include <gtest/gtest.h>

#include <cstdint>
#include <string>

#include "capture_util.h"

namespace busdecode::test {
namespace {

std::uint32_t le32(const std::string& s, std::size_t at) {
    return std::uint32_t(std::uint8_t(s[at])) | std::uint32_t(std::uint8_t(s[at + 1])) << 8 |
           std::uint32_t(std::uint8_t(s[at + 2])) << 16 |
           std::uint32_t(std::uint8_t(s[at + 3])) << 24;
}

std::uint16_t le16(const std::string& s, std::size_t at) {
    return std::uint16_t(std::uint8_t(s[at]) | std::uint8_t(s[at + 1]) << 8);
}

// The archive with `member`'s CRC changed in its local and central headers (its data as
// it was): what a bit flipped in the data gives, without depending on how the
// decompressor takes the flip.
std::string withWrongCrc(std::string zip, const std::string& member) {
    int patched = 0;
    for (std::size_t at = 0; at + 46 <= zip.size(); ++at) {
        const std::uint32_t signature = le32(zip, at);
        const bool local = signature == 0x04034b50, central = signature == 0x02014b50;
        if (!local && !central) continue;
        const std::size_t name_at = at + (local ? 30 : 46);
        const std::uint16_t name_len = le16(zip, at + (local ? 26 : 28));
        if (zip.compare(name_at, name_len, member) != 0 || name_len != member.size()) continue;
        zip[at + (local ? 14 : 16)] ^= 0x5a;
        ++patched;
    }
    EXPECT_EQ(patched, 2) << member;
    return zip;
}

void expectCorrupt(const std::string& real, const std::string& member,
                   const std::vector<std::string>& args) {
    const std::string path = tempDir() + "/crc_" + member.substr(0, member.find('/')) + "_" +
                             real.substr(real.rfind('/') + 1);
    writeFile(path, withWrongCrc(readFile(realCaptures() + "/formats/" + real), member));
    std::vector<std::string> all{path};
    all.insert(all.end(), args.begin(), args.end());
    const RunResult r = runDecode(all);
    EXPECT_EQ(r.status, 2) << r.err;
    EXPECT_NE(r.err.find(member + " is corrupt: CRC error"), std::string::npos) << r.err;
}

TEST(ZipMemberCrc, SigrokAnalogSessionsLastChannel) {
    expectCorrupt("tek-mdo/RTC.sr", "analog-1-2-1", {"--proto", "uart", "--map", "rx=SCL"});
}

TEST(ZipMemberCrc, DsviewLogicBlock) {
    expectCorrupt("dsview/demo_spi.dsl", "L-0/2",
                  {"--proto", "spi", "--map", "sclk=clk", "--map", "mosi=mosi", "--map",
                   "miso=miso", "--map", "cs=cs"});
}

TEST(ZipMemberCrc, DsviewOscilloscopeChannel) {
    expectCorrupt("dsview/demo_square_dso.dsl", "O-1/0", {"--proto", "uart", "--map", "rx=1"});
}

}  // namespace
}  // namespace busdecode::test
