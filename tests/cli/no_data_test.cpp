// Stretches of a capture that hold no data, as decode reports them: Keysight's 9.9E+37
// samples (over range, or no data), the dead time between the segments of a LeCroy
// sequence capture, a scope file with no samples at all, a Saleae CSV's `X` cells, and
// what follows a Saleae CSV's last change. None makes an edge, a byte or an overshoot of
// its own, and what reaches into them is marked or named.
#include <gtest/gtest.h>

#include <QJsonArray>
#include <QJsonDocument>
#include <QJsonObject>
#include <QVariant>
#include <algorithm>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "support/paths.h"

using namespace busdecode::test;

namespace {

constexpr int kSamplesPerBit = 20;  // 1 Mbaud at 50 ns a sample

// Levels (0 or 1) of an idle-high UART line: `idle` bits, then each byte as 8N1.
std::vector<int> uartBits(int idle, const std::vector<int>& bytes) {
    std::vector<int> bits(std::size_t(idle), 1);
    for (const int b : bytes) {
        bits.push_back(0);
        for (int i = 0; i < 8; ++i)
            bits.push_back(b >> i & 1);
        bits.push_back(1);
    }
    return bits;
}

std::string volts(int level) {
    return level ? "5.00000E+00" : "2.00000E-02";
}

std::vector<QJsonObject> jsonl(const std::string& out) {
    std::vector<QJsonObject> events;
    for (const auto& line : splitLines(out))
        events.push_back(QJsonDocument::fromJson(QByteArray::fromStdString(line)).object());
    return events;
}

// A number field of an event.
double numberOf(const QJsonObject& e, const char* key) {
    return e[key].toVariant().toReal();
}

std::string errorsOf(const QJsonObject& e) {
    return QJsonDocument(e["errors"].toArray()).toJson(QJsonDocument::Compact).toStdString();
}

TEST(NoData, KeysightOverRangeSamplesMakeNoEdgeAndNoOvershoot) {
    // Every 97th sample, the first among them, is 9.9E+37, on both levels.
    const std::vector<int> bits = uartBits(3, {0x41, 0x5A, 0x00, 0xFF});
    int changes = 0;
    for (std::size_t i = 1; i < bits.size(); ++i)
        changes += bits[i] != bits[i - 1];
    std::string csv = "x-axis,1\nsecond,Volt\n";
    for (std::size_t k = 0; k < (bits.size() + 3) * kSamplesPerBit; ++k) {
        const int level = k / kSamplesPerBit < bits.size() ? bits[k / kSamplesPerBit] : 1;
        csv += fmt::format("{:.8E},{}\n", double(k) * 50e-9,
                           k % 97 == 0 ? "+9.900000E+37" : volts(level));
    }
    const std::string path = tempDir() + "/overrange.csv";
    writeFile(path, csv);
    const auto r = runDecode(
        {path, "--proto", "uart", "--map", "tx=1", "--opt", "baud=1000000", "--format", "jsonl"});
    ASSERT_EQ(r.status, 0) << r.err;
    std::vector<int> values;
    for (const auto& e : jsonl(r.out)) {
        if (e["type"] == "byte") {
            values.push_back(e["value"].toInt());
            EXPECT_EQ(errorsOf(e), "[]") << values.size();
        } else if (e["type"] == "signal") {
            EXPECT_LT(numberOf(e, "overshoot_pct"), 1.0);
            EXPECT_GT(numberOf(e, "overshoot_pct"), 0.0);  // read as a number
            EXPECT_EQ(e["rises"].toInt() + e["falls"].toInt(), changes);
        }
    }
    EXPECT_EQ(values, (std::vector<int>{0x41, 0x5A, 0x00, 0xFF}));
    const std::size_t samples = (bits.size() + 3) * kSamplesPerBit;
    EXPECT_NE(r.err.find(fmt::format("1: {} samples of 9.9e37 (over range, or no data) each "
                                     "taken as the sample before",
                                     (samples + 96) / 97)),
              std::string::npos)
        << r.err;
}

TEST(NoData, ALeCroySegmentGapIsAnEventAndMarksTheByteCutByIt) {
    // Segment 1: 'A' and idle. Segment 2, a second later, starts inside a byte's low
    // bits, then sends 'Z'. Each segment holds 500 samples.
    const std::vector<int> one = uartBits(2, {0x41});
    std::vector<int> two(4, 0);
    for (const int b : uartBits(10, {0x5A}))
        two.push_back(b);
    std::string csv =
        "LECROYWR204M,51184,Waveform\nSegments,2,SegmentSize,500\n"
        "Segment,TrigTime,TimeSinceSegment1\n#1,22-Jan-2015 11:35:11,0\n"
        "#2,22-Jan-2015 11:35:12,1.0\nTime,Ampl\n";
    for (const auto& bits : {one, two})
        for (std::size_t k = 0; k < 500; ++k) {
            const std::size_t bit = k / kSamplesPerBit;
            csv += fmt::format("{:e},{}\n", double(k) * 50e-9,
                               volts(bit < bits.size() ? bits[bit] : 1));
        }
    const std::string path = tempDir() + "/sequence.csv";
    writeFile(path, csv);
    const auto r = runDecode({path, "--proto", "uart", "--map", "tx=Ampl", "--opt", "baud=1000000",
                              "--format", "jsonl"});
    ASSERT_EQ(r.status, 0) << r.err;
    std::vector<std::string> seen;
    for (const auto& e : jsonl(r.out)) {
        const std::string type = e["type"].toString().toStdString();
        if (type == "signal") {
            // No fall measured across the gap (it would take the better part of a second).
            EXPECT_LT(numberOf(e, "fall_p99_ns"), 100.0);
            EXPECT_GT(numberOf(e, "fall_p99_ns"), 0.0);  // read as a number
            continue;
        }
        seen.push_back(fmt::format(
            "{} {} {} {}", type, e["start_ns"].toInteger(),
            type == "segment_gap" ? e["segment"].toInt() : e["value"].toInt(-1), errorsOf(e)));
    }
    // A falling edge is timed halfway between the samples around it: 25 ns before its bit.
    const std::vector<std::string> want = {
        "byte 1975 65 []",
        "segment_gap 24950 2 [\"segment_gap\"]",
        // The line was low when segment 2 began: what it carries was not all recorded.
        "byte 1000000000 248 [\"segment_gap\"]",
        fmt::format("byte {} 90 []", 1000000000 + (4 + 10) * 1000 - 25),
    };
    EXPECT_EQ(seen, want) << r.out;
}

TEST(NoData, AFileOfHeadersAloneSaysItHoldsNoSamples) {
    const std::string path = tempDir() + "/headers.csv";
    writeFile(path, "X,CH1,Start,Increment,\nSequence,Volt,0.000000e+00,2.000000e-08\n");
    const auto r = runDecode({path, "--proto", "uart", "--map", "tx=CH1"});
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_NE(r.out.find("# hint: CH1: the capture holds no samples"), std::string::npos) << r.out;
    EXPECT_EQ(r.out.find("threshold"), std::string::npos) << r.out;
}

TEST(NoData, ASaleaeXStretchIsAnEventAndMarksTheByteOnItsLineOnly) {
    // rx and tx each send 0x55 and 0x0F at 100 kbaud; tx has no data through the middle of
    // its first byte.
    std::string csv = "Time [s],rx,tx\n";
    std::vector<std::pair<double, std::string>> rows;  // (us, "rx,tx")
    const std::vector<int> bits = uartBits(1, {0x55, 0x0F});
    int rx = 1, tx = 1;
    for (std::size_t b = 0; b < bits.size(); ++b) {
        const double us = double(b) * 10;
        rx = tx = bits[b];
        const std::string txt = us >= 25 && us < 55 ? "X" : std::to_string(tx);
        csv += fmt::format("{:.9f},{},{}\n", us * 1e-6, rx, txt);
    }
    csv += fmt::format("{:.9f},1,1\n", double(bits.size()) * 10e-6);
    const std::string path = tempDir() + "/saleae_x.csv";
    writeFile(path, csv);
    const auto r =
        runDecode({path, "--proto", "uart", "--opt", "baud=100000", "--format", "jsonl"});
    ASSERT_EQ(r.status, 0) << r.err;
    std::vector<std::string> seen;
    for (const auto& e : jsonl(r.out))
        seen.push_back(fmt::format("{} {} {} {}", e["type"].toString().toStdString(),
                                   e["start_ns"].toInteger(), e["line"].toString().toStdString(),
                                   errorsOf(e)));
    std::vector<std::string> want = {
        "byte 10000 rx []",  "byte 10000 tx [\"no_data\"]", "no_data 30000 tx [\"no_data\"]",
        "byte 110000 rx []", "byte 110000 tx []",
    };
    std::sort(seen.begin(), seen.end());  // rx and tx bytes start together
    std::sort(want.begin(), want.end());
    EXPECT_EQ(seen, want) << r.out;
}

TEST(NoData, ASaleaeCsvEndingAtAStopBitsEdgeSaysTheFrameMayHaveGoneOn) {
    // 0x0D at 100 kbaud: its last data bit is 0, so the last change is the stop bit's rise.
    std::string csv = "Time [s],tx\n0.000000000,1\n";
    const std::vector<int> bits = uartBits(1, {0x0D});
    for (std::size_t b = 1; b + 1 < bits.size(); ++b)
        if (bits[b] != bits[b - 1]) csv += fmt::format("{:.9f},{}\n", double(b) * 10e-6, bits[b]);
    csv += fmt::format("{:.9f},1\n", double(bits.size() - 1) * 10e-6);
    const std::string path = tempDir() + "/saleae_end.csv";
    writeFile(path, csv);
    const std::string hint =
        "the last frame is cut by the capture's end (short_frame), but a saleae-csv records "
        "no end: it ends at its last change, and the traffic may have gone on past it";
    auto r = runDecode({path, "--proto", "uart", "--opt", "baud=100000"});
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_NE(r.out.find("!short_frame"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("# hint: " + hint), std::string::npos) << r.out;
    // The same rows and one more, the idle line's last: the frame is whole, no hint.
    writeFile(path, csv + fmt::format("{:.9f},1\n", double(bits.size() + 2) * 10e-6));
    r = runDecode({path, "--proto", "uart", "--opt", "baud=100000"});
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(r.out.find("short_frame"), std::string::npos) << r.out;
    EXPECT_EQ(r.out.find("records no end"), std::string::npos) << r.out;
}

}  // namespace
