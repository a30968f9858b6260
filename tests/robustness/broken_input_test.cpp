// Broken input files through the real CLI: each must fail with exit status 2 and one
// exact line on stderr naming the file (and, for text, the line). The files are made
// here, in the test's temporary directory (the 10 MB line is never committed).
#include <gtest/gtest.h>

#include <random>

#include "support/paths.h"
#include "zip_builder.h"

using namespace busdecode::test;

namespace {

// A small valid VCD header with the four SPI lines.
const char* kVcdHeader =
    "$timescale 1 ns $end\n"
    "$scope module top $end\n"
    "$var wire 1 ! cs $end\n"
    "$var wire 1 \" sclk $end\n"
    "$var wire 1 # mosi $end\n"
    "$var wire 1 $ miso $end\n"
    "$var wire 8 % bus $end\n"
    "$upscope $end\n"
    "$enddefinitions $end\n";

std::string writeCase(const std::string& name, const std::string& bytes) {
    const std::string path = tempDir() + "/" + name;
    writeFile(path, bytes);
    return path;
}

std::string srMetadata(const std::string& unitsize) {
    return "[global]\nsigrok version=0.5.2\n\n[device 1]\ncapturefile=logic-1\n"
           "total probes=4\nsamplerate=1 MHz\ntotal analog=0\nprobe1=cs\nprobe2=sclk\n"
           "probe3=mosi\nprobe4=miso\nunitsize=" +
           unitsize + "\n";
}

// Decodes `path` with SPI and returns the one line on stderr; expects exit status 2.
std::string failureOf(const std::string& path, std::vector<std::string> extra = {}) {
    std::vector<std::string> args = {path, "--proto", "spi"};
    args.insert(args.end(), extra.begin(), extra.end());
    const RunResult r = runDecode(args);
    EXPECT_EQ(r.status, 2) << path << "\nstdout: " << r.out.substr(0, 500) << "\nstderr: " << r.err;
    std::string err = r.err;
    EXPECT_FALSE(err.empty()) << path;
    if (!err.empty() && err.back() == '\n') err.pop_back();
    EXPECT_EQ(err.find('\n'), std::string::npos) << "more than one line: " << err;
    return err;
}

TEST(BrokenInput, EmptyFile) {
    const auto p = writeCase("empty.vcd", "");
    EXPECT_EQ(failureOf(p), "decode: " + p + ": empty file");
}

TEST(BrokenInput, BinaryGarbage) {
    std::mt19937 rng(7);
    std::string bytes;
    for (int i = 0; i < 4096; ++i)
        bytes += char(rng() & 0xff);
    const auto p = writeCase("garbage.bin", bytes);
    EXPECT_EQ(
        failureOf(p),
        "decode: " + p +
            ": unknown format: binary data that is neither VCD, CSV nor a sigrok .sr session");
}

TEST(BrokenInput, VcdWithoutEnddefinitions) {
    std::string text = kVcdHeader;
    text.erase(text.find("$enddefinitions"));
    const auto p = writeCase("no_enddefinitions.vcd", text + "#0 1! 1\"\n#10 0!\n");
    EXPECT_EQ(failureOf(p),
              "decode: " + p + ":9: expected a $keyword in the VCD header, found '#0'");
}

TEST(BrokenInput, VcdUnknownIdentifierCode) {
    const auto p =
        writeCase("unknown_id.vcd", std::string(kVcdHeader) + "#0 1! 1\"\n#10 0!\n#20 1&\n");
    EXPECT_EQ(failureOf(p), "decode: " + p + ":12: value change for undeclared identifier '&'");
}

TEST(BrokenInput, VcdTimeGoingBackwards) {
    const auto p =
        writeCase("backwards.vcd", std::string(kVcdHeader) + "#0 1! 1\"\n#20 0!\n#10 1!\n");
    EXPECT_EQ(failureOf(p), "decode: " + p + ":12: time going backwards (#10 after #20)");
}

TEST(BrokenInput, VcdCutInsideItsLastTimeSaysSo) {
    const auto p = writeCase("cut.vcd", std::string(kVcdHeader) + "#0 1! 1\"\n#200 0!\n#21");
    EXPECT_EQ(failureOf(p), "decode: " + p +
                                ":12: time going backwards (#21 after #200); the capture ends "
                                "inside this line (cut short while written?)");
}

TEST(BrokenInput, VcdVectorChangeForUndeclaredSignal) {
    const auto p =
        writeCase("undeclared.vcd", std::string(kVcdHeader) + "#0 1! 1\"\n#10 b1010 (\n");
    EXPECT_EQ(failureOf(p), "decode: " + p + ":11: value change for undeclared identifier '('");
}

TEST(BrokenInput, VcdTenMegabyteLine) {
    std::string text = kVcdHeader;
    text += "#0 1! 1\"\n#10 ";
    text += std::string(10 << 20, '0') + "\n#20 0!\n";
    const auto p = writeCase("long_line.vcd", text);
    EXPECT_EQ(failureOf(p), "decode: " + p + ":11: line longer than 1 MiB (not a text capture?)");
}

TEST(BrokenInput, CsvRaggedRow) {
    const auto p = writeCase("ragged.csv",
                             "; Channels (4/4): cs, sclk, mosi, miso\n; Samplerate: 1 MHz\n"
                             "logic,logic,logic,logic\n1,1,0,0\n1,0,0\n1,1,0,0\n");
    EXPECT_EQ(failureOf(p),
              "decode: " + p + ":5: expected 4 fields like the header (line 3), found 3");
}

TEST(BrokenInput, CsvNonNumericTime) {
    const auto p = writeCase("bad_time.csv",
                             "Time [s],cs,sclk,mosi,miso\n0.000000,1,1,0,0\n0.000001,0,1,0,0\n"
                             "abc,0,0,0,0\n");
    EXPECT_EQ(failureOf(p), "decode: " + p + ":4: expected a time in seconds, found 'abc'");
}

TEST(BrokenInput, CsvDuplicatedColumnName) {
    const auto p = writeCase("duplicate.csv",
                             "Time [s],cs,sclk,mosi,mosi\n0.000000,1,1,0,0\n0.000001,0,1,0,0\n");
    EXPECT_EQ(failureOf(p), "decode: " + p + ":1: duplicate column name 'mosi'");
}

TEST(BrokenInput, SrMissingChunk) {
    const std::string samples(64, '\x01');
    const auto p = writeCase("missing_chunk.sr",
                             busdecode::fuzz::buildStoredZip({{"version", "2"},
                                                              {"metadata", srMetadata("1")},
                                                              {"logic-1-1", samples},
                                                              {"logic-1-3", samples}}));
    EXPECT_EQ(failureOf(p), "decode: " + p + ": missing chunk logic-1-2");
}

TEST(BrokenInput, SrWrongUnitsize) {
    const auto p =
        writeCase("wrong_unitsize.sr",
                  busdecode::fuzz::buildStoredZip({{"version", "2"},
                                                   {"metadata", srMetadata("0")},
                                                   {"logic-1-1", std::string(64, '\x01')}}));
    EXPECT_EQ(failureOf(p),
              "decode: " + p + ": unitsize=0 not supported (1 to 8 bytes per sample)");
}

TEST(BrokenInput, SrUnitsizeTooSmallForItsProbes) {
    std::string meta = srMetadata("1");
    meta.replace(meta.find("total probes=4"), 14, "total probes=12");
    const auto p = writeCase(
        "narrow_unitsize.sr",
        busdecode::fuzz::buildStoredZip(
            {{"version", "2"}, {"metadata", meta}, {"logic-1-1", std::string(64, '\x01')}}));
    EXPECT_EQ(failureOf(p), "decode: " + p + ": 12 probes do not fit in unitsize=1");
}

TEST(BrokenInput, SrChunkNotAWholeNumberOfSamples) {
    const auto p = writeCase(
        "odd_chunk.sr", busdecode::fuzz::buildStoredZip({{"version", "2"},
                                                         {"metadata", srMetadata("2")},
                                                         {"logic-1-1", std::string(63, '\x01')}}));
    EXPECT_EQ(
        failureOf(p),
        "decode: " + p + ": logic data of 63 bytes is not a whole number of samples of unitsize=2");
}

}  // namespace
