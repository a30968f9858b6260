// The HTML report of a faulty capture opens in headless Chromium: the screenshot is a
// non-empty PNG with more than one colour, and the DOM holds the report's SVG pictures:
// the captured edges of faulty and clean frames with their sample points and fields, and
// plots with axis titles, units and round tick values.
#include <gtest/gtest.h>

#include <fmt/format.h>
#include <zlib.h>

#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <regex>
#include <set>

#include "bissc_generator.h"
#include "capture/capture_writer.h"
#include "capture/scope_csv_writer.h"
#include "fault_captures.h"
#include "support/paths.h"

namespace busdecode {
namespace {

std::string findChromium() {
    for (const char* p :
         {"/usr/bin/chromium", "/usr/bin/chromium-browser", "/usr/bin/google-chrome"})
        if (std::filesystem::exists(p)) return p;
    return "";
}

std::uint32_t be32(const std::string& s, std::size_t at) {
    return (std::uint32_t(std::uint8_t(s[at])) << 24) |
           (std::uint32_t(std::uint8_t(s[at + 1])) << 16) |
           (std::uint32_t(std::uint8_t(s[at + 2])) << 8) | std::uint32_t(std::uint8_t(s[at + 3]));
}

// Decodes an 8-bit RGB/RGBA PNG far enough to count its distinct pixel values.
// Returns -1 when the file is not such a PNG.
int distinctPixels(const std::string& png, int* width_out) {
    if (png.size() < 33 || png.compare(0, 8, "\x89PNG\r\n\x1a\n") != 0) return -1;
    std::uint32_t w = 0, h = 0;
    int channels = 0;
    std::string idat;
    for (std::size_t p = 8; p + 8 <= png.size();) {
        const std::uint32_t len = be32(png, p);
        const std::string type = png.substr(p + 4, 4);
        if (p + 12 + len > png.size()) return -1;
        if (type == "IHDR") {
            w = be32(png, p + 8);
            h = be32(png, p + 12);
            const int depth = std::uint8_t(png[p + 16]), color = std::uint8_t(png[p + 17]);
            if (depth != 8 || (color != 2 && color != 6)) return -1;
            channels = color == 2 ? 3 : 4;
        } else if (type == "IDAT") {
            idat += png.substr(p + 8, len);
        }
        p += 12 + len;
    }
    if (!w || !h || !channels) return -1;
    const std::size_t stride = std::size_t(w) * channels;
    std::string raw((stride + 1) * h, '\0');
    uLongf raw_len = raw.size();
    if (uncompress(reinterpret_cast<Bytef*>(raw.data()), &raw_len,
                   reinterpret_cast<const Bytef*>(idat.data()), idat.size()) != Z_OK ||
        raw_len != raw.size())
        return -1;
    std::vector<std::uint8_t> prev(stride, 0), cur(stride);
    std::set<std::uint32_t> colours;
    for (std::uint32_t y = 0; y < h; ++y) {
        const auto* row = reinterpret_cast<const std::uint8_t*>(raw.data()) + y * (stride + 1);
        const int filter = row[0];
        for (std::size_t i = 0; i < stride; ++i) {
            const int a = i >= std::size_t(channels) ? cur[i - channels] : 0;
            const int b = prev[i];
            const int c = i >= std::size_t(channels) ? prev[i - channels] : 0;
            int pred = 0;
            switch (filter) {
                case 1:
                    pred = a;
                    break;
                case 2:
                    pred = b;
                    break;
                case 3:
                    pred = (a + b) / 2;
                    break;
                case 4: {
                    const int pa = std::abs(b - c), pb = std::abs(a - c),
                              pc = std::abs(a + b - 2 * c);
                    pred = (pa <= pb && pa <= pc) ? a : (pb <= pc ? b : c);
                    break;
                }
                default:
                    break;
            }
            cur[i] = std::uint8_t(row[1 + i] + pred);
        }
        for (std::size_t x = 0; x < w && colours.size() < 1000; ++x) {
            const std::uint8_t* px = &cur[x * channels];
            colours.insert((std::uint32_t(px[0]) << 16) | (std::uint32_t(px[1]) << 8) | px[2]);
        }
        prev = cur;
    }
    if (width_out) *width_out = int(w);
    return int(colours.size());
}

struct Rendered {
    std::string page, dom, png;  // the report, its DOM as Chromium built it, the screenshot
    int width = 0, colours = 0;
};

// Decodes `capture` with --report into `name`.html and has headless Chromium screenshot
// it (kept as `name`.png in the test's temporary folder, to be looked at) and dump its DOM.
Rendered render(const std::string& chromium, const std::string& name,
                const std::vector<std::string>& decode_args) {
    const std::string dir = test::tempDir() + "/html";
    std::filesystem::create_directories(dir);
    const std::string html = dir + "/" + name + ".html";
    std::vector<std::string> args = decode_args;
    args.insert(args.end(), {"--report", html});
    const auto r = test::runDecode(args);
    EXPECT_EQ(r.status, 0) << r.err;
    Rendered out;
    out.page = test::readFile(html);
    const std::string flags =
        "--headless --no-sandbox --disable-gpu --disable-quic --no-first-run "
        "--disable-background-networking --disable-component-update --disable-sync "
        "--window-size=1200,3600 ";
    const std::string url = "file://" + html;
    out.png = dir + "/" + name + ".png";
    std::filesystem::remove(out.png);
    auto run = [&](const std::string& what, const std::string& profile) {
        std::filesystem::create_directories(profile);
        return test::runCommand(test::shellQuote(chromium) + " " + flags +
                                "--user-data-dir=" + test::shellQuote(profile) + " " + what + " " +
                                test::shellQuote(url) + " 2>/dev/null");
    };
    const auto shot = run("--screenshot=" + test::shellQuote(out.png), dir + "/profile-" + name);
    EXPECT_TRUE(std::filesystem::exists(out.png)) << "chromium made no screenshot: " << shot.err;
    const std::string image = test::readFile(out.png);
    out.colours = distinctPixels(image, &out.width);
    out.dom = run("--dump-dom", dir + "/profile-" + name + "-dom").out;
    return out;
}

bool has(const std::string& dom, const std::string& what) {
    return dom.find(what) != std::string::npos;
}

// Tick labels of the x axes that are round numbers ("0", "20", "2.5"): at least `n`.
int roundTicks(const std::string& dom) {
    static const std::regex tick(R"re(class="tick x"[^>]*>(-?[0-9]+(\.[0-9]+)?)<)re");
    int n = 0;
    for (auto it = std::sregex_iterator(dom.begin(), dom.end(), tick); it != std::sregex_iterator();
         ++it) {
        const double v = std::stod((*it)[1].str());
        const double mag = v == 0 ? 1 : std::pow(10.0, std::floor(std::log10(std::fabs(v))));
        const double m = std::fabs(v) / mag;
        n += std::fabs(m - std::round(m * 2) / 2) < 1e-6;  // 1, 1.5, 2, 2.5, 5 ... x 10^k
    }
    return n;
}

std::string findCapture(const std::string& rule) {
    for (const auto& c : test::faultCaptures(test::tempDir() + "/verify"))
        if (c.failing_rule == rule) return c.path;
    return "";
}

// A BiSS-C capture whose frame 12 has a wrong CRC and answers late (5 busy clocks).
std::string lateAckCrcCapture() {
    const std::string path = test::tempDir() + "/html/biss_late_ack_crc.vcd";
    std::filesystem::create_directories(test::tempDir() + "/html");
    BisscGenConfig cfg;
    cfg.line_delay_ns = 180;
    BisscGenerator gen(cfg);
    for (int i = 0; i < 40; ++i) {
        BisscFrameSpec f;
        f.data = (std::uint64_t(1) << 26) - 100 + 9 * std::uint64_t(i);  // crosses zero
        f.data &= (std::uint64_t(1) << 26) - 1;
        f.corrupt_crc = i == 12;
        f.proc_cycles = i == 12 ? 5 : 0;
        gen.addFrame(f);
    }
    writeVcd(gen.build(), path);
    return path;
}

TEST(HtmlReport, BisscCrcFaultAndLateAckAsCaptured) {
    const std::string chromium = findChromium();
    if (chromium.empty()) GTEST_SKIP() << "chromium is not installed (Debian package `chromium`)";
    const Rendered r = render(chromium, "bissc", {lateAckCrcCapture(), "--proto", "bissc"});
    EXPECT_EQ(r.width, 1200);
    EXPECT_GT(r.colours, 10) << "the screenshot is (nearly) uniform";
    const std::string& dom = r.dom;
    // The faulty frame and a clean one, each with MA and SL as captured.
    EXPECT_TRUE(has(dom, R"(<svg class="waveform faulty")")) << dom.substr(0, 400);
    EXPECT_TRUE(has(dom, R"(<svg class="waveform clean")"));
    EXPECT_TRUE(has(dom, R"(<path class="edges" data-role="ma")"));
    EXPECT_TRUE(has(dom, R"(<path class="edges" data-role="sl")"));
    EXPECT_TRUE(has(dom, R"(class="sample-point")"));
    EXPECT_TRUE(has(dom, "line delay 180 ns"));
    EXPECT_TRUE(has(dom, R"(class="field-name" )"));
    EXPECT_TRUE(has(dom, ">CRC</text>"));
    EXPECT_TRUE(has(dom, "errors crc"));
    // Axes with titles and units.
    EXPECT_TRUE(has(dom, "time from the event's start (us)"));
    EXPECT_TRUE(has(dom, "position (counts)"));
    EXPECT_TRUE(has(dom, "velocity (counts/s)"));
    EXPECT_TRUE(has(dom, "velocity (rev/min)"));
    EXPECT_TRUE(has(dom, "events with errors"));
    EXPECT_GE(roundTicks(dom), 20);
    // The position wraps at 2^26: drawn unwrapped, largest jump 9 counts.
    EXPECT_TRUE(has(dom, "unwrapped (the word wraps at 67108864)"));
    EXPECT_TRUE(has(dom, "largest jump 9 at"));
    // Constant values are said, not drawn.
    EXPECT_TRUE(has(dom, R"(<p class="constant">frame clock_hz: 1.000 MHz in all 40 events.</p>)"))
        << dom.substr(dom.find("constant"), 200);
}

TEST(HtmlReport, SsiRepeatMismatchAsCaptured) {
    const std::string chromium = findChromium();
    if (chromium.empty()) GTEST_SKIP() << "chromium is not installed (Debian package `chromium`)";
    const std::string capture = findCapture("ssi.max_repeat_mismatches");
    ASSERT_FALSE(capture.empty());
    const Rendered r = render(chromium, "ssi", {capture, "--proto", "ssi"});
    EXPECT_GT(r.colours, 10) << "the screenshot is (nearly) uniform";
    const std::string& dom = r.dom;
    EXPECT_TRUE(has(dom, R"(<svg class="waveform faulty")"));
    EXPECT_TRUE(has(dom, R"(<svg class="waveform clean")"));
    EXPECT_FALSE(has(dom, "ssi summary at"));  // an event of no length has no waveform
    EXPECT_TRUE(has(dom, R"(<path class="edges" data-role="clk")"));
    EXPECT_TRUE(has(dom, R"(<path class="edges" data-role="data")"));
    EXPECT_TRUE(has(dom, R"(class="sample-point")"));
    EXPECT_TRUE(has(dom, ">DATA</text>"));
    EXPECT_TRUE(has(dom, ">repeat 2</text>"));
    EXPECT_TRUE(has(dom, "errors repeat_mismatch"));
    EXPECT_TRUE(has(dom, "time from the event's start (us)"));
    EXPECT_TRUE(has(dom, "position (counts)"));
    EXPECT_TRUE(has(dom, "velocity (rev/min)"));
    EXPECT_GE(roundTicks(dom), 15);
}

// A BiSS-C capture as a scope records it (Rigol CSV: 0.7 V to 5.7 V, slow noisy edges
// with ringing) whose frame 3 has a wrong CRC.
std::string scopeBisscCapture(bool differential = false) {
    const std::string path =
        test::tempDir() + (differential ? "/html/biss_rs422_scope.csv" : "/html/biss_scope.csv");
    std::filesystem::create_directories(test::tempDir() + "/html");
    BisscGenConfig cfg;
    cfg.line_delay_ns = 600;
    cfg.idle_ns = 3000;
    BisscGenerator gen(cfg);
    for (int i = 0; i < 6; ++i) {
        BisscFrameSpec f;
        f.data = 1000 + std::uint64_t(i);
        f.corrupt_crc = i == 3;
        gen.addFrame(f);
    }
    const AnalogStyle style{.sample_ns = 10,
                            .low_v = 0,
                            .high_v = 5,
                            .offset_v = 0.7,
                            .rise_ns = 150,
                            .snr_db = 26,
                            .ringing = 0.1,
                            .differential = differential};
    writeScopeCsv(gen.build(), path, ScopeDialect::Rigol, style);
    return path;
}

// The numbers in the text of the first element of class `cls` ("threshold 3.2 V, ...").
std::vector<double> numbersIn(const std::string& dom, const std::string& cls) {
    std::vector<double> out;
    auto at = dom.find("class=\"" + cls + "\"");
    if (at == std::string::npos) return out;
    at = dom.find('>', at) + 1;
    static const std::regex number(R"(-?[0-9]+(\.[0-9]+)?)");
    const std::string text = dom.substr(at, dom.find('<', at) - at);
    for (auto it = std::sregex_iterator(text.begin(), text.end(), number);
         it != std::sregex_iterator(); ++it)
        out.push_back(std::stod(it->str()));
    return out;
}

TEST(HtmlReport, ScopeCaptureDrawsVoltageWithThreshold) {
    const std::string chromium = findChromium();
    if (chromium.empty()) GTEST_SKIP() << "chromium is not installed (Debian package `chromium`)";
    const Rendered r = render(chromium, "bissc_scope", {scopeBisscCapture(), "--proto", "bissc"});
    EXPECT_GT(r.colours, 10) << "the screenshot is (nearly) uniform";
    const std::string& dom = r.dom;
    EXPECT_TRUE(has(dom, R"(<svg class="waveform faulty")"));
    EXPECT_TRUE(has(dom, "errors crc"));
    for (const char* role : {"ma", "sl"}) {
        SCOPED_TRACE(role);
        EXPECT_TRUE(has(dom, fmt::format(R"(<path class="edges" data-role="{}")", role)));
        EXPECT_TRUE(has(dom, fmt::format(R"(<path class="volt-trace" data-role="{}")", role)));
        EXPECT_TRUE(has(dom, fmt::format(R"(<line class="threshold" data-role="{}")", role)));
        EXPECT_TRUE(has(dom, fmt::format(R"(<rect class="hysteresis" data-role="{}")", role)));
    }
    // The threshold found from the data: midway between 0.7 V and 5.7 V.
    const auto thr = numbersIn(dom, "threshold-label");
    ASSERT_EQ(thr.size(), 2u);
    EXPECT_NEAR(thr[0], 3.2, 0.2);
    EXPECT_GT(thr[1], 0.1);
    // The trace: many points, reaching both levels.
    // Found by hand: std::regex recurses per character of the path and overflows the stack.
    const std::string trace_start = R"(class="volt-trace" data-role="ma" d=")";
    const auto d = dom.find(trace_start);
    ASSERT_NE(d, std::string::npos);
    const auto d_begin = dom.begin() + std::ptrdiff_t(d + trace_start.size());
    const auto d_end = std::find(d_begin, dom.end(), '"');
    EXPECT_GT(std::count(d_begin, d_end, 'L'), 200);
    static const std::regex tick(R"re(class="volt-tick"[^>]*>(-?[0-9.]+) V<)re");
    std::vector<double> ticks;
    for (auto it = std::sregex_iterator(dom.begin(), dom.end(), tick); it != std::sregex_iterator();
         ++it)
        ticks.push_back(std::stod((*it)[1].str()));
    ASSERT_GE(ticks.size(), 2u);
    EXPECT_LT(ticks[0], 1.0);  // the low level, noise and ringing below it
    EXPECT_GT(ticks[1], 5.4);  // the high level
    EXPECT_TRUE(has(dom, R"(class="sample-point")"));
}

// RS-422 as a scope records it: each line the difference of its two wires, drawn so.
TEST(HtmlReport, DifferentialScopeCaptureDrawsThePairsVoltage) {
    const std::string html = test::tempDir() + "/html/biss_rs422.html";
    const auto r = test::runDecode({scopeBisscCapture(true), "--proto", "bissc", "--map",
                                    "ma=MA+,MA-", "--map", "sl=SLO+,SLO-", "--report", html});
    ASSERT_EQ(r.status, 0) << r.err;
    const std::string page = test::readFile(html);
    EXPECT_TRUE(has(page, "errors crc"));
    for (const char* role : {"ma", "sl"}) {
        SCOPED_TRACE(role);
        EXPECT_TRUE(has(page, fmt::format(R"(<path class="volt-trace" data-role="{}")", role)));
        EXPECT_TRUE(has(page, fmt::format(R"(<line class="threshold" data-role="{}")", role)));
    }
    // A difference swings both ways: the threshold at 0 V.
    const auto thr = numbersIn(page, "threshold-label");
    ASSERT_EQ(thr.size(), 2u);
    EXPECT_NEAR(thr[0], 0.0, 0.3);
}

TEST(HtmlReport, RendersInHeadlessChromium) {
    const std::string chromium = findChromium();
    if (chromium.empty()) GTEST_SKIP() << "chromium is not installed (Debian package `chromium`)";
    const std::string dir = test::tempDir() + "/html";
    const auto& caps = test::faultCaptures(test::tempDir() + "/verify");
    const test::FaultCapture* crc = nullptr;
    for (const auto& c : caps)
        if (c.failing_rule == "bissc.max_crc_errors") crc = &c;
    ASSERT_NE(crc, nullptr);
    std::filesystem::create_directories(dir);
    const std::string html = dir + "/report.html";
    const auto r = test::runDecode({crc->path, "--proto", "bissc", "--report", html});
    ASSERT_EQ(r.status, 0) << r.err;
    const std::string page = test::readFile(html);
    ASSERT_NE(page.find("<svg class=\"timing\""), std::string::npos);

    const std::string flags =
        "--headless --no-sandbox --disable-gpu --disable-quic --no-first-run "
        "--disable-background-networking --disable-component-update --disable-sync "
        "--window-size=1200,1600 ";
    const std::string url = "file://" + html;
    const std::string png = dir + "/shot.png";
    auto run = [&](const std::string& what, const std::string& profile) {
        std::filesystem::create_directories(profile);
        return test::runCommand(test::shellQuote(chromium) + " " + flags +
                                "--user-data-dir=" + test::shellQuote(profile) + " " + what + " " +
                                test::shellQuote(url) + " 2>/dev/null");
    };
    const auto shot = run("--screenshot=" + test::shellQuote(png), dir + "/profile1");
    ASSERT_TRUE(std::filesystem::exists(png)) << "chromium made no screenshot: " << shot.err;
    const std::string image = test::readFile(png);
    EXPECT_GT(image.size(), 1000u);
    int width = 0;
    const int colours = distinctPixels(image, &width);
    EXPECT_EQ(width, 1200);
    EXPECT_GT(colours, 10) << "the screenshot is (nearly) uniform";

    const auto dom = run("--dump-dom", dir + "/profile2");
    EXPECT_NE(dom.out.find("<svg class=\"position\""), std::string::npos) << dom.out.substr(0, 500);
    // Every timing value of this capture is constant: said in words, not drawn.
    EXPECT_NE(dom.out.find("<p class=\"constant\">frame line_delay_ns: 120 ns in all"),
              std::string::npos);
    EXPECT_NE(dom.out.find("<svg class=\"timing\""), std::string::npos);
    EXPECT_NE(dom.out.find("<path class=\"edges\""), std::string::npos);
}

}  // namespace
}  // namespace busdecode
