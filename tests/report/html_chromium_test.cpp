// The HTML report of a faulty capture opens in headless Chromium: the screenshot is a
// non-empty PNG with more than one colour, and the DOM holds the report's SVG pictures.
#include <gtest/gtest.h>

#include <zlib.h>

#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <set>

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
    EXPECT_NE(dom.out.find("<svg class=\"histogram\""), std::string::npos);
    EXPECT_NE(dom.out.find("<svg class=\"timing\""), std::string::npos);
    EXPECT_NE(dom.out.find("<path class=\"wave\""), std::string::npos);
}

}  // namespace
}  // namespace busdecode
