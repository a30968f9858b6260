// RS-422 from a scope: a UART line written as a differential pair (TX+, TX-) whose
// negative wire goes open halfway decodes every character from the pair, and the pair
// fault is reported from the moment the open wire stops following.
#include <gtest/gtest.h>

#include <algorithm>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "capture/capture_reader.h"
#include "capture/scope_csv_writer.h"
#include "core/registry.h"
#include "core/session.h"
#include "support/decode_events.h"
#include "support/paths.h"
#include "uart_decoder.h"
#include "uart_generator.h"

namespace busdecode {
namespace {

TEST(UartRs422Scope, AnOpenWireDecodesEveryCharacterAndIsReported) {
    Registry::instance().add(makeUartFactory());
    WaveBuilder wb(Timebase{1, 1'000'000'000}, {"TX"}, {1});
    UartFormat f;
    f.baud = 115200;
    UartGenerator gen(wb, 0, f);
    const std::string text = "RS-422 with one wire open";
    double t = 20'000;
    for (char c : text)
        t = gen.sendChar(t, std::uint8_t(c)) + 3'000;
    const Waveform w = wb.build(wb.ticksFromNs(t + 50'000));
    // Open between the characters: from the 12th on the negative wire floats.
    const double open_ns = 20'000 + 11 * (10 * gen.bitNs() + 3'000) - 1'500;
    AnalogStyle s;
    s.sample_ns = 200;
    s.low_v = 0;
    s.high_v = 3.3;
    s.rise_ns = 0.2 * gen.bitNs();
    s.snr_db = 23;
    s.ringing = 0.1;
    s.ring_ns = 400;
    s.differential = true;
    s.open_line = 0;
    s.open_after_ns = open_ns;
    const std::string p = test::tempDir() + "/rs422.csv";
    writeScopeCsv(w, p, ScopeDialect::Rigol, s);
    OpenOptions o;
    o.pairs = {"TX+,TX-"};
    auto reader = openCapture(p, o);
    const auto bytes = test::eventsOfType(
        test::decodeEvents(*reader, {{"uart", {{"rx", "TX+,TX-"}}, {{"baud", "115200"}}}}), "byte");
    ASSERT_EQ(bytes.size(), text.size());
    // Every character decodes; those after the wire opened carry the pair fault.
    for (std::size_t i = 0; i < text.size(); ++i) {
        EXPECT_EQ(asInt(*bytes[i].get("value")), std::uint8_t(text[i])) << i;
        const bool after = double(bytes[i].end) > open_ns;
        EXPECT_EQ(bytes[i].errors,
                  after ? std::vector<std::string>{"pair_fault"} : std::vector<std::string>{})
            << i;
    }
    const auto notes = reader->notes();
    const auto fault = std::find_if(notes.begin(), notes.end(), [](const std::string& n) {
        return n.find("pair_fault") != std::string::npos;
    });
    ASSERT_NE(fault, notes.end()) << fmt::format("{}", fmt::join(notes, "\n"));
    EXPECT_NE(fault->find("TX- does not follow TX+"), std::string::npos) << *fault;
    double from = 0;
    ASSERT_EQ(std::sscanf(fault->c_str() + fault->find("from ") + 5, "%lf", &from), 1);
    // The open wire shows at once, or at the next start bit at the latest.
    EXPECT_GE(from * 1e9, open_ns - 2 * s.sample_ns);
    EXPECT_LE(from * 1e9, open_ns + 1'500 + s.sample_ns * 2);
}

}  // namespace
}  // namespace busdecode
