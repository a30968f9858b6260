// Error messages that say what is wrong, on one line: a VCD without its header, an .sr
// entry in a compression this build cannot read, a role left unbound in the second
// capture, control characters in names, the --map error on a VCD of 10^5 signals, a
// rules path that is a directory, a rules table that checks nothing.
#include <gtest/gtest.h>

#include "robustness_cli.h"
#include "zip_builder.h"

using namespace busdecode::test;

namespace {

const char* kSpiVcd =
    "$timescale 1 ns $end\n$var wire 1 ! cs $end\n$var wire 1 \" sclk $end\n"
    "$var wire 1 # mosi $end\n$enddefinitions $end\n#0 1! 1\" 0#\n#10 0!\n#20 1!\n";

TEST(Messages, VcdWithoutHeaderIsNotCalledAnEmptyCsv) {
    const auto p = caseFile("bare.vcd", "#0\n#10\n#20\n");
    EXPECT_EQ(oneLineFailure({p, "--proto", "spi"}),
              "decode: " + p +
                  ": VCD value changes without a VCD header: a VCD starts with $timescale, $var "
                  "... and $enddefinitions");
    const auto q = caseFile("bare2.vcd", "#0\n1!\n#10\n0!\n");
    EXPECT_EQ(oneLineFailure({q, "--proto", "spi"}),
              "decode: " + q +
                  ":2: VCD value changes without a VCD header: a VCD starts with $timescale, "
                  "$var ... and $enddefinitions");
}

// buildStoredZip's entries with `name` marked as compressed by ZIP method `method`, in
// the local and the central header (its bytes are never decompressed).
std::string zipWithMethod(std::string zip, const std::string& name, std::uint16_t method) {
    auto mark = [&](const std::string& sig, std::size_t method_at, std::size_t name_at) {
        for (std::size_t at = zip.find(sig); at != std::string::npos; at = zip.find(sig, at + 4))
            if (zip.compare(at + name_at, name.size(), name) == 0) {
                zip[at + method_at] = char(method & 0xff);
                zip[at + method_at + 1] = char(method >> 8);
            }
    };
    mark(std::string("PK\x03\x04", 4), 8, 30);
    mark(std::string("PK\x01\x02", 4), 10, 46);
    return zip;
}

TEST(Messages, SrEntryInAnUnsupportedCompressionSaysSo) {
    const std::string meta =
        "[device 1]\ncapturefile=logic-1\ntotal probes=1\nsamplerate=1 MHz\nunitsize=1\n"
        "probe1=a\n";
    const std::string zip = busdecode::fuzz::buildStoredZip(
        {{"version", "2"}, {"metadata", meta}, {"logic-1-1", std::string(16, '\1')}});
    const auto p = caseFile("lzma.sr", zipWithMethod(zip, "metadata", 14));
    EXPECT_EQ(oneLineFailure({p, "--proto", "uart", "--map", "rx=a"}),
              "decode: " + p +
                  ": entry metadata is compressed with a method this build cannot read (ZIP "
                  "method 14, LZMA); re-save the session with sigrok (Deflate)");
    const auto q = caseFile("zstd_chunk.sr", zipWithMethod(zip, "logic-1-1", 93));
    EXPECT_NE(oneLineFailure({q, "--proto", "uart", "--map", "rx=a"})
                  .find("entry logic-1-1 is compressed with a method this build cannot read"),
              std::string::npos);
}

TEST(Messages, UnboundRoleNamesTheCaptureItIsIn) {
    const auto first = caseFile("first.vcd", kSpiVcd);
    std::string other = kSpiVcd;
    other.replace(other.find("sclk"), 4, "clock");
    const auto second = caseFile("second.vcd", other);
    const std::string err = oneLineFailure({first, second, "--proto", "spi"});
    EXPECT_EQ(err.rfind("decode: " + second + ": decoder spi: role 'sclk' is not bound", 0), 0u)
        << err;
}

TEST(Messages, ControlCharactersInNamesAndOptionsStayOnOneLine) {
    const std::string dir = tempDir() + "/new\nline";
    const std::string err = oneLineFailure({dir + "/x.vcd", "--proto", "spi"});
    EXPECT_NE(err.find("new\\x0aline"), std::string::npos) << err;
    const auto p = caseFile("opt.vcd", kSpiVcd);
    EXPECT_NE(oneLineFailure({p, "--proto", "spi", "--opt", "bits\n=8"}).find("bits\\x0a"),
              std::string::npos);
    // A header's name with an escape sequence in it is not echoed raw either.
    std::string esc = kSpiVcd;
    esc.replace(esc.find("mosi"), 4, "mo\x1b[2Jsi");
    const auto e = caseFile("esc.vcd", esc);
    const std::string err2 = oneLineFailure({e, "--proto", "spi", "--map", "mosi=nothing"});
    EXPECT_EQ(err2.find('\x1b'), std::string::npos) << err2;
    EXPECT_NE(err2.find("mo\\x1b[2Jsi"), std::string::npos) << err2;
}

// A VCD declaring `n` one-bit signals top.sig_0, top.sig_1... and no value change.
std::string wideVcd(int n) {
    std::string v = "$timescale 1 ns $end\n$scope module top $end\n";
    for (int i = 0; i < n; ++i)
        v += "$var wire 1 s" + std::to_string(i) + " sig_" + std::to_string(i) + " $end\n";
    return v + "$upscope $end\n$enddefinitions $end\n#0\n";
}

TEST(Messages, MapErrorOnAHugeVcdListsTheClosestFewAndTheCount) {
    const auto p = caseFile("wide.vcd", wideVcd(100'000));
    const std::string err = oneLineFailure({p, "--proto", "spi", "--map", "sclk=sig_4242x"});
    EXPECT_LT(err.size(), 600u) << err.substr(0, 600);
    EXPECT_NE(err.find("100000 in all; the closest: top.sig_4242"), std::string::npos) << err;
}

TEST(Messages, MapErrorPastTheSignalsKeptSaysHowManyWereDeclared) {
    // Past 2^17 declarations only the signals --map or a role names are kept: none here.
    const auto p = caseFile("wider.vcd", wideVcd(131'073));
    const std::string err = oneLineFailure({p, "--proto", "spi", "--map", "sclk=sig_4242x"});
    EXPECT_NE(err.find("(signals: none kept: 131073 signals declared: only the 0 that --map or "
                       "a role names were kept)"),
              std::string::npos)
        << err;
}

TEST(Messages, AHeaderDeclaringARoleMillionsOfTimesIsRefused) {
    // A decompression bomb's header: one name a role binds, declared without end. Memory
    // stops at 2^20 declarations kept instead of growing with the file.
    std::string v = "$timescale 1 ns $end\n";
    for (int i = 0; i < (1 << 20) + 8; ++i)
        v += "$var wire 1 ! ma $end\n";
    v += "$enddefinitions $end\n#0\n";
    const auto p = caseFile("bomb.vcd", v);
    const std::string err = oneLineFailure({p, "--proto", "bissc"});
    EXPECT_NE(err.find(p + ":1048578: more than 1048576 declarations of the signals --map and "
                           "the roles name (of 1048577 in all)"),
              std::string::npos)
        << err;
}

TEST(Messages, RulesThatAreADirectory) {
    const auto p = caseFile("cap.vcd", kSpiVcd);
    const RunResult r = runDecode({"verify", p, "--rules", tempDir()});
    EXPECT_EQ(r.status, 2);
    EXPECT_EQ(r.err, "decode verify: " + tempDir() + ": is a directory, not a rules file\n");
}

TEST(Messages, AnEmptyRulesTableIsAnError) {
    const auto p = caseFile("cap2.vcd", kSpiVcd);
    const auto rules = caseFile("empty_table.toml", "[decode]\nproto = \"spi\"\n\n[spi]\n");
    const RunResult r = runDecode({"verify", p, "--rules", rules});
    EXPECT_EQ(r.status, 2) << r.out;
    EXPECT_EQ(r.err.rfind("decode verify: " + rules +
                              ":4: [spi]: no rules in this table (it would "
                              "check nothing; valid keys: max_crc_errors",
                          0),
              0u)
        << r.err;
}

}  // namespace
