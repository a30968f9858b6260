// Differential test: the same real traffic (sigrok-dumps uart/rxtx_overlapped.sr) read
// from the sigrok session, from sigrok-cli 0.7.2's VCD export and from its CSV export
// (captures/uart_rxtx_overlapped_sigrok-cli.{vcd,csv}, made with
// `sigrok-cli -i rxtx_overlapped.sr -O vcd|csv`) decodes to the same characters at the
// same times.
#include <gtest/gtest.h>

#include <fmt/format.h>

#include "capture/capture_reader.h"
#include "core/registry.h"
#include "core/session.h"
#include "support/decode_events.h"
#include "support/paths.h"
#include "uart_decoder.h"

namespace busdecode {
namespace {

std::vector<std::string> decodeFile(const std::string& path) {
    Registry::instance().add(makeUartFactory());
    CaptureFacts facts;
    const auto events = test::decodeEvents(
        path, {{"uart", {{"rx", "RX"}, {"tx", "TX"}}, {{"baud", "115200"}}}}, {}, &facts);
    std::vector<std::string> lines;
    for (const Event& e : events)
        lines.push_back(fmt::format("{} {} {} {}", facts.timebase.toNs(e.start),
                                    std::get<std::string>(*e.get("line")), asInt(*e.get("value")),
                                    e.errors.size()));
    return lines;
}

TEST(UartDifferential, SessionVcdAndCsvOfOneCaptureDecodeAlike) {
    const auto sr =
        decodeFile(test::realCaptures() + "/sigrok-dumps/uart/rxtx_overlapped/rxtx_overlapped.sr");
    ASSERT_EQ(sr.size(), 17u);  // 10 on rx, 7 on tx (sigrok-test's expected outputs)
    EXPECT_EQ(decodeFile(test::sourceDir() + "/captures/uart_rxtx_overlapped_sigrok-cli.vcd"), sr);
    EXPECT_EQ(decodeFile(test::sourceDir() + "/captures/uart_rxtx_overlapped_sigrok-cli.csv"), sr);
}

}  // namespace
}  // namespace busdecode
