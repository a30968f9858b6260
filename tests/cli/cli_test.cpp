// The decode command as users meet it: the contract's options, output formats, and one
// clear line with exit status 2 for every kind of bad input.
#include <gtest/gtest.h>

#include <QJsonArray>
#include <QJsonDocument>
#include <QJsonObject>
#include <sstream>

#include "support/paths.h"
#include "vcd_text.h"

using namespace busdecode::test;

namespace {

int countLines(const std::string& s) {
    return int(splitLines(s).size());
}

// One SPI word (mode 3) and, on separate lines, two UART bytes at 115200 baud.
std::string mixedCapture() {
    VcdText v({"cs", "sclk", "mosi", "miso", "tx"}, {1, 1, 1, 1, 1});
    v.spiWord(0, 1, 2, 3, 1000, 100, 0x80000000u, 0x10001B2Eu, 32);
    std::int64_t t = v.uartByte(4, 2000, 115200, 'O');
    v.uartByte(4, t + 5000, 115200, 'K');
    return v.str(200000);
}

std::string writeTemp(const std::string& name, const std::string& text) {
    const std::string path = tempDir() + "/" + name;
    writeFile(path, text);
    return path;
}

}  // namespace

TEST(Cli, ListShowsEveryBuiltInDecoderWithRolesAndOptions) {
    auto r = runDecode({"--list"});
    ASSERT_EQ(r.status, 0) << r.err;
    for (const char* id : {"bissc", "spi", "ssi", "tmc8100", "tmcl", "uart"})
        EXPECT_NE(("\n" + r.out).find(std::string("\n") + id + "  "), std::string::npos)
            << id << "\n"
            << r.out;
    EXPECT_NE(r.out.find("glitch_ns"), std::string::npos);
    EXPECT_NE(r.out.find("cpol"), std::string::npos);
}

// docs/decoders.txt is what `decode --list` prints, field kinds and all.
TEST(Cli, DocsDecodersTxtIsTheList) {
    auto r = runDecode({"--list"});
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(readFile(sourceDir() + "/docs/decoders.txt"), r.out)
        << "docs/decoders.txt: remake it with `build/bin/decode --list > docs/decoders.txt`";
}

// The built-in plugins Qt loaded in a run (QT_DEBUG_PLUGINS=1 makes it say so on stderr:
// `qt.core.library: ".../busdecode_spi.so" loaded library`).
std::vector<std::string> pluginsLoaded(const std::vector<std::string>& args, int status = 0) {
    std::string cmd = "QT_DEBUG_PLUGINS=1 " + shellQuote(binDir() + "/decode");
    for (const auto& a : args)
        cmd += " " + shellQuote(a);
    const RunResult r = runCommand(cmd);
    EXPECT_EQ(r.status, status) << r.err;
    std::vector<std::string> ids;
    for (const auto& l : splitLines(r.err)) {
        const auto so = l.find(".so\" loaded library");
        const auto name = l.rfind("busdecode_", so);
        if (so != std::string::npos && name != std::string::npos)
            ids.push_back(l.substr(name + 10, so - name - 10));
    }
    return ids;
}

TEST(Cli, LoadsOnlyThePluginsOfTheDecodersAskedFor) {
    const auto path = writeTemp("plugins.vcd", mixedCapture());
    using Ids = std::vector<std::string>;
    EXPECT_EQ(pluginsLoaded({path, "--proto", "spi"}), Ids{"spi"});
    EXPECT_EQ(pluginsLoaded({path, "--proto", "uart", "--proto", "spi", "--map", "uart.rx=top.tx"}),
              (Ids{"spi", "uart"}));
    // A decoder stacked on another brings that one's code along (StackedFactory): TMCL
    // on UART runs without the uart plugin.
    EXPECT_EQ(
        pluginsLoaded({path, "--proto", "tmcl", "--map", "host=top.tx", "--opt", "baud=115200"}),
        Ids{"tmcl"});
    // Listing, and an unknown decoder's error naming all there are: every plugin.
    const Ids all{"bissc", "spi", "ssi", "tmc8100", "tmcl", "uart"};
    EXPECT_EQ(pluginsLoaded({"--list"}), all);
    EXPECT_EQ(pluginsLoaded({path, "--proto", "nosuch"}, 2), all);
}

TEST(Cli, AnUnknownDecoderIsNamedWithEveryDecoderThereIs) {
    const auto path = writeTemp("unknown.vcd", mixedCapture());
    auto r = runDecode({path, "--proto", "nosuch"});
    EXPECT_EQ(r.status, 2);
    EXPECT_NE(r.err.find("unknown decoder 'nosuch' (available: bissc, spi, ssi, tmc8100, tmcl, "
                         "uart"),
              std::string::npos)
        << r.err;
}

TEST(Cli, JsonlHasTheContractKeysInTimeOrderAcrossTwoBuses) {
    const auto path = writeTemp("mixed.vcd", mixedCapture());
    auto r = runDecode({path, "--proto", "spi", "--proto", "uart", "--opt", "uart.baud=115200",
                        "--format", "jsonl"});
    ASSERT_EQ(r.status, 0) << r.err;
    double last = -1;
    int spi = 0, uart = 0;
    for (const auto& l : splitLines(r.out)) {
        QJsonParseError err;
        auto doc = QJsonDocument::fromJson(QByteArray::fromStdString(l), &err);
        ASSERT_EQ(err.error, QJsonParseError::NoError) << l;
        auto o = doc.object();
        for (const char* k : {"proto", "type", "start_ns", "end_ns", "errors"})
            EXPECT_TRUE(o.contains(k)) << l;
        EXPECT_GE(o["start_ns"].toDouble(), last);
        last = o["start_ns"].toDouble();
        if (o["proto"] == "spi") {
            ++spi;
            EXPECT_EQ(o["mosi"].toInteger(), 0x80000000LL);
            EXPECT_EQ(o["miso"].toInteger(), 0x10001B2ELL);
            EXPECT_EQ(o["bits"].toInt(), 32);
        }
        if (o["proto"] == "uart" && o["type"] == "byte") {
            EXPECT_EQ(o["value"].toInt(), uart == 0 ? 'O' : 'K');
            EXPECT_EQ(o["line"].toString(), "tx");
            ++uart;
        }
    }
    EXPECT_EQ(spi, 1);
    EXPECT_EQ(uart, 2);
}

TEST(Cli, TextOutputHasOneLinePerEventAndASummary) {
    const auto path = writeTemp("mixed_text.vcd", mixedCapture());
    auto r = runDecode({path, "--proto", "uart", "--opt", "baud=115200"});
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_NE(r.out.find("# summary:"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("uart"), std::string::npos);
}

TEST(Cli, TextHeaderGivesTheTickAsARateWithAnSIPrefix) {
    // A VCD in ns ticks at 1 GS/s; a Saleae export with 12 decimals at 1 TS/s.
    auto r = runDecode(
        {writeTemp("header.vcd", mixedCapture()), "--proto", "uart", "--opt", "baud=115200"});
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(r.out.substr(0, r.out.find('\n')),
              "# " + tempDir() + "/header.vcd (vcd, 1 GS/s timebase) uart.tx=top.tx")
        << r.out;
    const auto csv =
        writeTemp("header.csv", "Time[s], MA, SLO\n0.000000000000, 1, 1\n0.000001000000, 0, 1\n");
    r = runDecode({csv, "--proto", "bissc"});
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_NE(r.out.find("(saleae-csv, 1 TS/s timebase)"), std::string::npos) << r.out;
}

TEST(Cli, AHintEndsTheTextWhenNoFrameIsCleanAndGoesToStderrWithJsonl) {
    // 32-bit frames decoded with the default width, 26: every frame fails.
    const std::string csv = sourceDir() + "/captures/bissc_10mhz_long_cable.csv";
    const std::string hint =
        "bissc: none of the 6 answered frames came out clean (CRC right, stop bit low) with "
        "bits=26: check the data width (--opt bits=auto finds it from the traffic)";
    auto r = runDecode({csv, "--proto", "bissc"});
    ASSERT_EQ(r.status, 0) << r.err;
    const auto text = splitLines(r.out);
    ASSERT_FALSE(text.empty());
    EXPECT_EQ(text.back().rfind("# hint: " + hint, 0), 0u) << r.out;
    EXPECT_EQ(r.err, "");

    r = runDecode({csv, "--proto", "bissc", "--format", "jsonl"});
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(r.out.find("hint"), std::string::npos);
    EXPECT_EQ(r.err.rfind("decode: " + csv + ": hint: " + hint, 0), 0u) << r.err;
    EXPECT_EQ(countLines(r.err), 1);

    // The right width: no hint.
    r = runDecode({csv, "--proto", "bissc", "--opt", "bits=auto"});
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(r.out.find("# hint"), std::string::npos) << r.out;
}

TEST(Cli, StandardInputIsACapture) {
    const auto path = writeTemp("stdin.vcd", mixedCapture());
    auto r = runCommand(shellQuote(binDir() + "/decode") +
                        " - --proto uart --opt baud=115200 --format jsonl < " + shellQuote(path));
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(countLines(r.out), 2) << r.out;
}

// The scope options do nothing to logic lines: said, not ignored in silence.
TEST(Cli, ThresholdOnALogicCaptureIsAHint) {
    const std::string hint =
        "# hint: --threshold and --hysteresis do nothing: the capture's lines are logic levels, "
        "not voltages";
    const std::string vcd = sourceDir() + "/captures/bissc_1mhz_26bit.vcd";
    for (const char* option : {"--threshold", "--hysteresis"}) {
        const auto r = runDecode({vcd, "--proto", "bissc", option, "0.2"});
        ASSERT_EQ(r.status, 0) << r.err;
        EXPECT_NE(r.out.find(hint), std::string::npos) << r.out;
    }
    auto r = runDecode({vcd, "--proto", "bissc"});
    EXPECT_EQ(r.out.find("# hint"), std::string::npos) << r.out;
    const std::string scope = sourceDir() + "/tests/data/real/formats/rigol/DS1054Z-A.csv";
    r = runDecode({scope, "--proto", "uart", "--map", "rx=CH1", "--threshold", "2.5"});
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_NE(r.out.find("# hint: CH1: threshold 2.5 V"), std::string::npos) << r.out;
    EXPECT_EQ(r.out.find("do nothing"), std::string::npos) << r.out;
}

// A vector mapped whole is refused (which bit?); a one-bit signal declared with its index
// ("tx [0]") answers to its base name, unless another bit shares it.
TEST(Cli, VectorsAreMappedByTheirBits) {
    auto vcd = [](const std::string& vars) {
        return "$timescale 1 us $end\n" + vars +
               "$enddefinitions $end\n#0 1! b1111 \"\n#100 0! b1110 \"\n#110 1! b1111 \"\n"
               "#200 1!\n";
    };
    const auto bus = writeTemp("vector.vcd", vcd("$var wire 1 ! tx [0] $end\n"
                                                 "$var wire 4 \" bus [3:0] $end\n"));
    auto r = runDecode({bus, "--proto", "uart", "--map", "rx=bus", "--opt", "baud=100000"});
    EXPECT_EQ(r.status, 2);
    EXPECT_EQ(r.err, "decode: " + bus +
                         ": decoder uart: --map rx=bus: bus[3:0] is a vector of 4 bits: map "
                         "one of them (--map rx=bus[BIT])\n");
    r = runDecode({bus, "--proto", "uart", "--map", "rx=bus[0]", "--opt", "baud=100000"});
    EXPECT_EQ(r.status, 0) << r.err;
    r = runDecode({bus, "--proto", "uart", "--opt", "baud=100000"});
    EXPECT_EQ(r.status, 0) << r.err;
    EXPECT_NE(r.out.find("uart.tx=tx[0]"), std::string::npos) << r.out;
    const auto two = writeTemp("two_bits.vcd", vcd("$var wire 1 ! d [0] $end\n"
                                                   "$var wire 1 \" d [1] $end\n"));
    r = runDecode({two, "--proto", "uart", "--map", "rx=d", "--opt", "baud=100000"});
    EXPECT_EQ(r.status, 2);
    EXPECT_NE(r.err.find("--map rx=d: no such signal"), std::string::npos) << r.err;
}

struct BadInput {
    std::vector<std::string> args;
    std::string expect;  // a piece of the one-line message
};

// Readable test names in ctest output instead of the raw bytes of the parameter.
void PrintTo(const BadInput& b, std::ostream* os) {
    *os << '"' << b.expect << '"';
}

class CliErrors : public ::testing::TestWithParam<BadInput> {};

TEST_P(CliErrors, OneLineOnStderrAndExitStatus2) {
    const auto path = writeTemp("ok.vcd", mixedCapture());
    std::vector<std::string> args;
    for (auto a : GetParam().args)
        args.push_back(a == "@" ? path : a);
    auto r = runDecode(args);
    EXPECT_EQ(r.status, 2) << r.out << r.err;
    EXPECT_EQ(countLines(r.err), 1) << r.err;
    EXPECT_NE(r.err.find(GetParam().expect), std::string::npos) << r.err;
}

INSTANTIATE_TEST_SUITE_P(
    Cases, CliErrors,
    ::testing::Values(
        BadInput{{"/nonexistent/cap.vcd", "--proto", "spi"}, "/nonexistent/cap.vcd"},
        BadInput{{"@", "--proto", "nosuch"}, "unknown decoder 'nosuch' (available: "},
        BadInput{{"@", "--proto", "ssi"}, "role 'data' is not bound"},
        BadInput{{"@", "--proto", "ssi"}, "signals: top.cs, top.sclk, top.mosi, top.miso, top.tx"},
        BadInput{{"@", "--proto", "spi", "--opt", "cpol=2"},
                 "option cpol=2: expected an integer from 0 to 1"},
        BadInput{{"@", "--proto", "spi", "--opt", "speed=3"}, "unknown option 'speed'"},
        BadInput{{"@", "--proto", "uart", "--opt", "parity=maybe"}, "one of"},
        BadInput{{"@", "--proto", "spi", "--map", "sclk=nosuch"},
                 "--map sclk=nosuch: no such signal"},
        BadInput{{"@", "--proto", "spi", "--map", "sclk=top.sclk,cs=top.cs"},
                 "one --map per role: --map ROLE=SIGNAL --map ROLE=SIGNAL"},
        BadInput{{"@", "--proto", "spi", "--format", "xml"}, "--format xml"},
        BadInput{{"@", "--proto", "spi", "--threads", "3"},
                 "--threads 3: expected 1 (read and decode on one thread) or 2"},
        BadInput{{"@"}, "no decoder chosen"}, BadInput{{"--proto", "spi"}, "no capture given"},
        BadInput{{"@", "--proto", "spi", "--bogus"},
                 "decode: unknown option '--bogus' (see decode --help)"},
        BadInput{{"@", "--proto", "spi", "--bogus=1"}, "unknown option '--bogus'"},
        BadInput{{"monitor", "--bogus"}, "decode monitor: unknown argument '--bogus'"},
        BadInput{{"@", "--proto", "spi", "--opt", "bits=8", "--opt", "spi.bits=16"},
                 "--opt spi.bits=16: bits is set already for spi (--opt bits=8): it takes one "
                 "value"},
        BadInput{{"@", "--proto", "spi", "--map", "cs=top.cs", "--map", "cs=top.tx"},
                 "--map cs=top.tx: cs is set already for spi (--map cs=top.cs)"},
        BadInput{{"@", "--proto", "spi", "--report", "-"},
                 "--report -: standard output carries the events; name a file"},
        BadInput{{"verify", "@", "--rules", "r.toml", "--junit", "-"},
                 "--junit -: standard output carries the verdicts; name a file"},
        BadInput{{"@", "--proto", "spi", "--report", "a.txt", "--report", "b.txt"},
                 "--report is given 2 times: it takes one value"},
        BadInput{{"@", "--proto", "spi", "--report", ""}, "--report: the file name is empty"},
        BadInput{{"", "--proto", "spi"}, "a capture's name is empty"},
        BadInput{{"@", "--proto", "bissc", "--map", "ma=sclk", "--map", "sl=miso", "--opt",
                  "mt_bits=30"},
                 "decode: decoder bissc: mt_bits (30) exceeds bits (26)"},
        BadInput{{"-", "-", "--proto", "spi"},
                 "standard input (-) is given as a capture twice: it can be read once"},
        BadInput{{"verify", "@", "--report", "r.txt"},
                 "decode: --report belongs to plain 'decode', not to 'decode verify'"},
        BadInput{{"verify", "@", "--format", "jsonl"},
                 "decode: --format belongs to plain 'decode', not to 'decode verify'"},
        // A bit shorter than two ticks of the capture (1 ns): no sample point per bit.
        BadInput{{"@", "--proto", "uart", "--opt", "baud=600000000"},
                 "decoder uart: option baud=6e+08: a bit lasts 1.66667e-09 s, less than two "
                 "ticks of the capture's time base (1e-09 s a tick)"},
        BadInput{{"@", "--proto", "spi", "--lcm", "nosuch://x"},
                 "--lcm: cannot open LCM URL 'nosuch://x': LCM provider \"nosuch\" not found"},
        BadInput{{"@", "--proto", "spi", "--lcm", "udpm://239.255.76.67:99999"},
                 "LCM URL 'udpm://239.255.76.67:99999': Bad multicast port"}));

TEST(Cli, JsonlIsUtf8WhateverTheCaptureHolds) {
    // A $date in Latin-1 and a signal name with a byte that is never UTF-8.
    const auto path = writeTemp("latin1.vcd",
                                "$date 29 d\xE9"
                                "cembre $end\n$timescale 1 ns $end\n"
                                "$var wire 1 ! tx\xFF $end\n$enddefinitions $end\n#0 1!\n#10 0!\n");
    auto r = runDecode({path, "--proto", "uart", "--map", "tx=0", "--format", "jsonl"});
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(r.out.find('\xE9'), std::string::npos);
    EXPECT_EQ(r.out.find('\xFF'), std::string::npos);
    EXPECT_NE(r.out.find("d\xEF\xBF\xBD"
                         "cembre"),
              std::string::npos)
        << r.out;
    for (const auto& line : splitLines(r.out)) {
        QJsonParseError error;
        QJsonDocument::fromJson(QByteArray::fromStdString(line), &error);
        EXPECT_EQ(error.error, QJsonParseError::NoError) << line;
    }
}

TEST(Cli, TimesPastWhatNanosecondsHoldAreAnError) {
    // At 1 s a tick, 10^10 ticks are 317 years: start_ns would not fit 64 bits.
    const auto path = writeTemp("centuries.vcd",
                                "$timescale 1 s $end\n$var wire 1 ! tx $end\n$enddefinitions $end\n"
                                "#0 1!\n#5 0!\n#10000000000 1!\n");
    // SPI: its bits are clocked, so a tick of 1 s does not stop it decoding.
    auto r = runDecode(
        {path, "--proto", "spi", "--map", "sclk=tx", "--map", "mosi=tx", "--format", "jsonl"});
    EXPECT_EQ(r.status, 2);
    EXPECT_EQ(countLines(r.err), 1) << r.err;
    EXPECT_NE(r.err.find(path + ":6: time beyond 4611686018 ticks"), std::string::npos) << r.err;
}

TEST(Cli, MalformedVcdNamesFileAndLine) {
    const auto path = writeTemp(
        "bad.vcd",
        "$timescale 1 ns $end\n$var wire 1 ! a $end\n$enddefinitions $end\n#0 1!\n#10 1?\n");
    auto r = runDecode({path, "--proto", "uart", "--map", "tx=a"});
    EXPECT_EQ(r.status, 2);
    EXPECT_NE(r.err.find(path + ":5:"), std::string::npos) << r.err;
}
