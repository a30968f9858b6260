// The text line's time column is formatted from integers; it must read exactly as
// "{:>14.9f}" of the time in seconds always did, and the reused-buffer forms must
// write what the string forms return.
#include <gtest/gtest.h>

#include <limits>
#include <random>

#include <fmt/format.h>

#include "core/number_text.h"
#include "sinks/event_format.h"

using namespace busdecode;

namespace {

Event eventAt(Tick start) {
    Event e;
    e.proto = "spi";
    e.type = "transfer";
    e.start = start;
    e.end = start + 10;
    e.add("mosi", std::uint64_t(0xA5)).add("bits", std::int64_t(8));
    return e;
}

std::string oldTimeColumn(std::int64_t ns) {
    return fmt::format("{:>14.9f}", double(ns) / 1e9);
}

}  // namespace

TEST(EventFormat, TimeColumnAsTheDoubleFormatHad) {
    const Timebase ns{1, 1'000'000'000};
    std::mt19937_64 rng(7);
    std::vector<std::int64_t> starts = {0,
                                        1,
                                        -1,
                                        999'999'999,
                                        1'000'000'000,
                                        -1'000'000'000,
                                        123'456'789'012,
                                        999'999'999'999'999,
                                        -999'999'999'999'999};
    for (int i = 0; i < 100000; ++i) {
        const int digits = int(rng() % 16);
        std::int64_t mod = 1;
        for (int k = 0; k < digits; ++k)
            mod *= 10;
        std::int64_t v = std::int64_t(rng() % std::uint64_t(mod));
        starts.push_back(rng() % 2 ? -v : v);
    }
    for (std::int64_t t : starts) {
        const std::string line = eventToText(eventAt(t), ns);
        ASSERT_EQ(line.substr(0, line.find(" s  ")), oldTimeColumn(t)) << t;
    }
}

TEST(EventFormat, AppendFormsMatchStringForms) {
    const Timebase tb{1, 100'000'000};
    Event e = eventAt(12345);
    e.error("short_frame");
    std::string text = "keep:", json = "keep:";
    appendEventText(text, e, tb);
    appendEventJson(json, e, tb);
    EXPECT_EQ(text, "keep:" + eventToText(e, tb));
    EXPECT_EQ(json, "keep:" + eventToJson(e, tb));
    EXPECT_EQ(eventToText(e, tb),
              "   0.000123450 s  spi      transfer     mosi=165 bits=8  !short_frame");
    EXPECT_EQ(eventToJson(e, tb),
              "{\"proto\":\"spi\",\"type\":\"transfer\",\"start_ns\":123450,\"end_ns\":123550,"
              "\"mosi\":165,\"bits\":8,\"errors\":[\"short_frame\"]}");
}

TEST(EventFormat, NameAndTypeColumnsAsFmtPadsThem) {
    // "{:<8} {:<12}": padded to the width, and names longer than it written whole.
    const Timebase tb{1, 1'000'000'000};
    for (const std::string name :
         {"", "s", "spi", "tmc8100", "spi_bus1", "tmc8100#2", "a_long_instance"})
        for (const std::string type :
             {"", "frame", "encoder_read", "register_read", "a_longer_event_type"})
            for (const bool instance : {false, true}) {
                Event e;
                (instance ? e.instance : e.proto) = name;
                if (instance) e.proto = "unused";
                e.type = type;
                e.start = 5;
                e.summary = "summary";
                e.error("crc");
                const std::string shown = instance && name.empty() ? e.proto : name;
                EXPECT_EQ(eventToText(e, tb),
                          fmt::format("{:>14.9f} s  {:<8} {:<12} summary  !crc", 5e-9, shown, type))
                    << name << " / " << type;
            }
}

TEST(EventFormat, AddAppendsSetReplaces) {
    Event e;
    e.add("a", std::int64_t(1)).add("b", std::int64_t(2));
    e.set("a", std::int64_t(3));
    ASSERT_EQ(e.fields.size(), 2u);
    EXPECT_EQ(std::get<std::int64_t>(*e.get("a")), 3);
    EXPECT_EQ(std::get<std::int64_t>(*e.get("b")), 2);
}

TEST(EventFormat, AddKeepsTheValueType) {
    Event e;
    const Value v = std::int64_t(-4);
    e.add("u", std::uint64_t(7)).add("b", true).add("d", 2.5).add("n", Null{}).add("v", v);
    e.add(std::string("s"), std::string("text"));
    EXPECT_EQ(std::get<std::uint64_t>(*e.get("u")), 7u);
    EXPECT_EQ(std::get<bool>(*e.get("b")), true);
    EXPECT_EQ(std::get<double>(*e.get("d")), 2.5);
    EXPECT_TRUE(isNull(*e.get("n")));
    EXPECT_EQ(std::get<std::int64_t>(*e.get("v")), -4);
    EXPECT_EQ(std::get<std::string>(*e.get("s")), "text");
    EXPECT_EQ(e.fields[5].key, "s");
}

TEST(NumberText, DecimalAsTheFormatStringHad) {
    std::mt19937_64 rng(5);
    for (int i = 0; i < 20000; ++i) {
        const std::uint64_t u = rng() >> (rng() % 64);
        const auto s = std::int64_t(rng()) >> (rng() % 64);
        std::string got = "x";
        appendDecimal(got, u);
        appendDecimal(got, s);
        appendDecimal(got, int(s));
        ASSERT_EQ(got, "x" + fmt::format("{}{}{}", u, s, int(s)));
    }
}

TEST(NumberText, ShortLineAsTheFormatStringHad) {
    std::mt19937_64 rng(7);
    for (int i = 0; i < 20000; ++i) {
        const std::uint64_t u = rng() >> (rng() % 64);
        const auto s = std::int64_t(rng()) >> (rng() % 64);
        const int width = int(rng() % 17);  // ShortLine::hex() pads to 16 digits at most
        ShortLine line;
        line.text("pos=").dec(u).text(" (0x").hex(u, width).text(") d=").dec(s).dec(int(s));
        ASSERT_EQ(line.view(), fmt::format("pos={} (0x{:0{}X}) d={}{}", u, u, width, s, int(s)));
    }
    // The ends of the ranges, and the numbers where a digit is added.
    for (const std::uint64_t u :
         {std::uint64_t(0), std::uint64_t(9), std::uint64_t(10), std::uint64_t(99),
          std::uint64_t(100), std::uint64_t(101), ~std::uint64_t(0)}) {
        ShortLine line;
        line.dec(u).text(" ").hex(u, 16).text(" ").dec(-std::int64_t(u % 1000));
        ASSERT_EQ(line.view(), fmt::format("{} {:016X} {}", u, u, -std::int64_t(u % 1000)));
    }
    ShortLine extremes;
    extremes.dec(std::numeric_limits<std::int64_t>::min()).text(" ").dec(std::int64_t(-1));
    EXPECT_EQ(extremes.view(), fmt::format("{} -1", std::numeric_limits<std::int64_t>::min()));
}

TEST(NumberText, ShortLineDropsWhatWouldOverflow) {
    ShortLine line;
    const std::string piece(100, 'a');
    line.text(piece).text(piece).text(piece).text("end");
    EXPECT_EQ(line.view(), piece + piece + "end");  // the third piece did not fit
    // Numbers up to the last byte: kept while their digits fit, whatever they copy.
    ShortLine full;
    const std::string pad(ShortLine::kCapacity - 7, 'p');
    full.text(pad).dec(std::uint64_t(123456)).hex(0xA, 1).dec(std::uint64_t(42)).dec(7);
    EXPECT_EQ(full.view(), pad + "123456A");
}

TEST(HexText, AsTheFormatStringHad) {
    std::mt19937_64 rng(3);
    for (int i = 0; i < 20000; ++i) {
        const std::uint64_t v = rng() >> (rng() % 64);
        const int width = int(rng() % 20);
        std::string got = "x";
        appendHex(got, v, width);
        ASSERT_EQ(got, "x" + fmt::format("{:0{}X}", v, width));
    }
}

TEST(NumberText, SiPrefixBringsTheMagnitudeBelowAThousand) {
    EXPECT_EQ(siPower(999), 0);
    EXPECT_EQ(siPower(1000), 1);
    EXPECT_EQ(siPower(24e6), 2);
    EXPECT_STREQ(siPrefix(siPower(24e6)), "M");
    EXPECT_DOUBLE_EQ(24e6 / siScale(2), 24.0);
    EXPECT_STREQ(siPrefix(siPower(1e12)), "T");
    EXPECT_EQ(siPower(1e30), 6);  // E at most
    EXPECT_STREQ(siPrefix(6), "E");
}
