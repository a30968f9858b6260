// The sample points of UART characters and TMCL datagrams in the report's waveforms: mid-bit
// after each start edge, the level read there, and the character's fields above them.
#include <gtest/gtest.h>

#include <filesystem>
#include <regex>

#include "report/sample_plan.h"
#include "report/waveform_svg.h"
#include "support/paths.h"

namespace busdecode {
namespace {

// 'A' (0x41) on tx at 1 Mbaud 8N1 (1 ns ticks), idle high, start edge at 10 us.
FrameWave uartA(const std::string& parity = "none") {
    FrameWave w;
    w.event.proto = w.event.instance = "uart";
    w.event.type = "byte";
    w.event.start = 10'000;
    const int bits = parity == "none" ? 10 : 11;
    w.event.end = 10'000 + 1000 * bits;
    w.event.set("value", std::int64_t(0x41)).set("line", std::string("tx"));
    w.from = 9'000;
    w.to = w.event.end + 1000;
    LineWave l;
    l.role = l.signal = "tx";
    l.level_before = 1;
    // start 0, data LSB first 1 0 0 0 0 0 1 0, [parity 0 for even], stop bit 1
    std::vector<int> wire = {0, 1, 0, 0, 0, 0, 0, 1, 0};
    if (parity != "none") wire.push_back(0);
    wire.push_back(1);
    int level = 1;
    for (std::size_t k = 0; k < wire.size(); ++k)
        if (wire[k] != level) {
            level = wire[k];
            l.edges.emplace_back(Tick(10'000 + 1000 * k), std::uint8_t(level));
        }
    w.lines.push_back(l);
    return w;
}

const Timebase kNs{1, 1'000'000'000};

TEST(SamplePoints, UartCharacterSampledMidBit) {
    const FrameWave w = uartA();
    const SamplePlan p = planFor(w, kNs, {{"bits", "8"}, {"parity", "none"}, {"stop", "1"}});
    EXPECT_EQ(p.data_role, "tx");
    ASSERT_EQ(p.t_ns.size(), 10u);
    for (std::size_t k = 0; k < 10; ++k)
        EXPECT_DOUBLE_EQ(p.t_ns[k], 10'500.0 + 1000.0 * double(k)) << k;
    ASSERT_EQ(p.segments.size(), 3u);
    EXPECT_EQ(p.segments[0].label, "start");
    EXPECT_EQ(p.segments[1].label, "0x41");
    EXPECT_EQ(p.segments[1].count, 8u);
    EXPECT_EQ(p.segments[2].label, "stop");

    const std::string svg = waveformSvg(w, kNs, {});
    std::string bits;
    static const std::regex bit(R"re(<text class="bit"[^>]*>([01])<)re");
    for (auto it = std::sregex_iterator(svg.begin(), svg.end(), bit); it != std::sregex_iterator();
         ++it)
        bits += (*it)[1].str();
    EXPECT_EQ(bits, "0100000101");  // start, 0x41 LSB first, stop
}

TEST(SamplePoints, UartParityFaultMarked) {
    FrameWave w = uartA("even");
    w.event.error("parity");
    const SamplePlan p = planFor(w, kNs, {{"bits", "8"}, {"parity", "even"}, {"stop", "1"}});
    ASSERT_EQ(p.t_ns.size(), 11u);
    ASSERT_EQ(p.segments.size(), 4u);
    EXPECT_EQ(p.segments[2].label, "parity");
    EXPECT_TRUE(p.segments[2].fault);
    EXPECT_FALSE(p.segments[3].fault);
}

TEST(SamplePoints, TwoStopBitsSampledTwice) {
    FrameWave w = uartA();
    w.event.end = 10'000 + 11'000;  // 1 + 8 + 2 bits
    const SamplePlan p = planFor(w, kNs, {{"bits", "8"}, {"parity", "none"}, {"stop", "2"}});
    ASSERT_EQ(p.t_ns.size(), 11u);
    EXPECT_DOUBLE_EQ(p.t_ns.back(), 20'500.0);
    EXPECT_EQ(p.segments.back().count, 2u);
}

// An SSI burst at 1 MHz (1 ns ticks): the clock idles high, falls at 10 us + k us and
// rises 0.5 us later, 14 times; the decoder measured the data 700 ns late.
FrameWave ssiBurst() {
    FrameWave w;
    w.event.proto = w.event.instance = "ssi";
    w.event.type = "frame";
    w.event.start = 10'000;
    w.event.end = 24'000;
    w.event.set("delay_ns", std::int64_t(700)).set("clock_hz", 1e6);
    w.from = 9'000;
    w.to = 25'000;
    LineWave clk;
    clk.role = clk.signal = "clk";
    clk.level_before = 1;
    for (int k = 0; k < 14; ++k) {
        clk.edges.emplace_back(Tick(10'000 + 1000 * k), std::uint8_t(0));
        clk.edges.emplace_back(Tick(10'500 + 1000 * k), std::uint8_t(1));
    }
    w.lines.push_back(clk);
    return w;
}

TEST(SamplePoints, SsiSampledWhereTheDecoderReads) {
    // The points follow the delay_ns option (auto: mid-window from the measured delay), not
    // the measured delay the event reports, which the decoder applies only when told.
    struct Case {
        std::string edge, delay;
        double offset_ns;
    };
    for (const auto& c :
         {Case{"falling", "0", 0}, Case{"falling", "300", 300}, Case{"falling", "auto", 700},
          Case{"rising", "0", 0}, Case{"rising", "auto", 200}}) {
        SCOPED_TRACE(c.edge + " delay_ns=" + c.delay);
        const SamplePlan p = planFor(
            ssiBurst(), kNs, {{"bits", "13"}, {"sample_edge", c.edge}, {"delay_ns", c.delay}});
        ASSERT_EQ(p.t_ns.size(), 13u);  // the first sampling edge latches: no bit
        const double first_edge = c.edge == "rising" ? 11'500 : 11'000;
        for (std::size_t i = 0; i < p.t_ns.size(); ++i)
            EXPECT_NEAR(p.t_ns[i], first_edge + 1000.0 * double(i) + c.offset_ns, 1e-6) << i;
        ASSERT_TRUE(p.delay_ns);
        EXPECT_EQ(*p.delay_ns, 700);  // the marker still shows the measured delay
    }
}

// The report of a real example capture: the sample points in each waveform whose title
// holds `kind` ("uart byte at").
std::vector<int> samplePointsPerWaveform(const std::vector<std::string>& args,
                                         const std::string& name, const std::string& kind) {
    const std::string dir = test::tempDir() + "/samples";
    std::filesystem::create_directories(dir);
    const std::string html = dir + "/" + name + ".html";
    std::vector<std::string> all = args;
    all.insert(all.end(), {"--report", html});
    const auto r = test::runDecode(all);
    EXPECT_EQ(r.status, 0) << r.err;
    const std::string page = test::readFile(html);
    std::vector<int> out;
    for (auto at = page.find("<svg class=\"waveform"); at != std::string::npos;) {
        const auto end = page.find("</svg>", at);
        const std::string svg = page.substr(at, end - at);
        at = page.find("<svg class=\"waveform", end);
        if (svg.find(kind) == std::string::npos) continue;
        int n = 0;
        for (auto p = svg.find("class=\"sample-point\""); p != std::string::npos;
             p = svg.find("class=\"sample-point\"", p + 1))
            ++n;
        out.push_back(n);
    }
    return out;
}

TEST(SamplePoints, UartExampleCaptureWithFaults) {
    // 7E1: start, 7 data, parity, stop: 10 sample points a character.
    const auto counts = samplePointsPerWaveform(
        {test::sourceDir() + "/captures/uart_7e1_faults.csv", "--proto", "uart", "--opt",
         "baud=19200", "--opt", "bits=7", "--opt", "parity=even"},
        "uart_7e1", "uart byte at");
    ASSERT_GE(counts.size(), 3u);  // the faulty characters and a clean one
    for (int n : counts)
        EXPECT_EQ(n, 10);
}

TEST(SamplePoints, TmclDatagramsOfNineCharacters) {
    for (const auto& [file, baud] :
         {std::pair<std::string, std::string>{"tmcl_rs485_9600.vcd", "9600"},
          {"tmcl_lines_115200.vcd", "115200"},
          {"tmcl_lines_115200.vcd", "auto"}}) {
        SCOPED_TRACE(file + " baud=" + baud);
        const auto counts = samplePointsPerWaveform(
            {test::sourceDir() + "/captures/" + file, "--proto", "tmcl", "--opt", "baud=" + baud},
            "tmcl_" + baud, "tmcl ");
        ASSERT_FALSE(counts.empty());
        int full = 0;
        for (int n : counts) {
            EXPECT_EQ(n % 10, 0) << n;  // whole 8N1 characters
            EXPECT_LE(n, 90);
            full += n == 90;
        }
        EXPECT_GT(full, 0);  // a whole datagram: nine characters
    }
}

}  // namespace
}  // namespace busdecode
