// The capture layer's events on LCM: `decode --lcm file://...` of a generated RS-422
// scope capture whose negative wire goes open publishes the pair fault and the line's
// signal quality as generic event_fields_t messages on their channels, fields as in jsonl.
#include <gtest/gtest.h>

#include <unistd.h>
#include <cstdio>
#include <lcm/lcm-cpp.hpp>
#include <map>

#include "busdecode_lcm/event_fields_t.hpp"
#include "capture/scope_csv_writer.h"
#include "core/waveform.h"
#include "support/paths.h"

namespace busdecode {
namespace {

// "U" and "S" at 115200 Bd on TX, the negative wire open from 60 us on.
std::string rs422Capture() {
    WaveBuilder b(Timebase{1, 1'000'000'000}, {"TX"}, {1});
    const double bit = 1e9 / 115200;
    double t = 20'000;
    for (const char c : std::string("US")) {
        b.setNs(0, t, false);
        for (int i = 0; i < 8; ++i)
            b.setNs(0, t + (1 + i) * bit, (std::uint8_t(c) >> i) & 1);
        b.setNs(0, t + 9 * bit, true);
        t += 10 * bit + 30'000;
    }
    AnalogStyle s;
    s.sample_ns = 200;
    s.rise_ns = 1'000;
    s.snr_db = 30;
    s.differential = true;
    s.open_line = 0;
    s.open_after_ns = 60'000;
    const std::string p = test::tempDir() + "/lcm_rs422.csv";
    writeScopeCsv(b.build(b.ticksFromNs(t + 20'000)), p, ScopeDialect::Rigol, s);
    return p;
}

std::map<std::string, busdecode_lcm::event_field_t> fieldsOf(
    const busdecode_lcm::event_fields_t& m) {
    std::map<std::string, busdecode_lcm::event_field_t> out;
    for (const auto& f : m.fields)
        out[f.key] = f;
    return out;
}

TEST(LcmScopeFindings, PairFaultAndSignalArePublishedOnTheirChannels) {
    const std::string log_path = test::tempDir() + "/findings.lcmlog";
    const auto r =
        test::runDecode({rs422Capture(), "--proto", "uart", "--map", "rx=TX+,TX-", "--opt",
                         "baud=115200", "--lcm", "file://" + log_path + "?mode=w"});
    ASSERT_EQ(r.status, 0) << r.err;
    lcm::LogFile log(log_path, "r");
    ASSERT_TRUE(log.good());
    std::vector<busdecode_lcm::event_fields_t> faults, signals;
    while (const lcm::LogEvent* ev = log.readNextEvent()) {
        busdecode_lcm::event_fields_t m;
        if (ev->channel != "DECODE_CAPTURE_PAIR_FAULT" && ev->channel != "DECODE_CAPTURE_SIGNAL")
            continue;
        ASSERT_GE(m.decode(ev->data, 0, ev->datalen), 0);
        (ev->channel == "DECODE_CAPTURE_SIGNAL" ? signals : faults).push_back(m);
    }
    ASSERT_EQ(faults.size(), 1u);
    EXPECT_EQ(faults[0].proto, "capture");
    EXPECT_EQ(faults[0].type, "pair_fault");
    EXPECT_EQ(faults[0].errors, std::vector<std::string>{"pair_fault"});
    EXPECT_NEAR(double(faults[0].start_ns), 60'000, 9'000);
    auto f = fieldsOf(faults[0]);
    EXPECT_EQ(f["pair"].text, "TX+,TX-");
    EXPECT_EQ(f["wire"].text, "TX-");
    EXPECT_EQ(f["working"].text, "TX+");
    EXPECT_EQ(f["kind"].text, "open");
    ASSERT_EQ(signals.size(), 1u);
    auto s = fieldsOf(signals[0]);
    EXPECT_EQ(s["line"].text, "TX+,TX-");
    // The difference of two wires swinging 0..3.3 V: -3.3 V to 3.3 V (half once open).
    EXPECT_GT(s["swing_v"].number, 3.0);
    EXPECT_NEAR(s["rise_median_ns"].number, 800, 200);
}

}  // namespace
}  // namespace busdecode
