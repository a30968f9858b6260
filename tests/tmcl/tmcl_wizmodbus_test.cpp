// A real RS-485 capture that is not TMCL (Modbus RTU, sigrok-dumps wizmodbus.sr): the
// TMCL layer must say so (checksums fail, datagrams cut short) without crashing.
#include <gtest/gtest.h>

#include "capture/capture_reader.h"
#include "core/registry.h"
#include "core/session.h"
#include "support/decode_events.h"
#include "support/paths.h"
#include "tmcl_decoder.h"
#include "uart_decoder.h"

namespace busdecode {
namespace {

std::vector<Event> decodeWiz(std::map<std::string, std::string> map) {
    Registry::instance().add(makeUartFactory());
    Registry::instance().add(makeTmclFactory());
    const std::string path =
        test::realCaptures() + "/sigrok-dumps/uart/modbus_rtu/wizmodbus/wizmodbus.sr";
    return test::decodeEvents(path, {{"tmcl", std::move(map), {{"baud", "9600"}}}});
}

void expectNotTmcl(const std::vector<Event>& events, const std::string& what) {
    // 44 requests (8 bytes) and 44 replies (9 or 8 bytes) of Modbus RTU.
    ASSERT_GE(events.size(), 80u) << what;
    std::size_t faulty = 0, clean = 0;
    for (const auto& e : events) {
        EXPECT_EQ(e.proto, "tmcl");
        if (e.hasError("checksum") || e.hasError("short_frame"))
            ++faulty;
        else
            ++clean;
    }
    EXPECT_GT(faulty, 20 * clean) << what;  // a 9-byte group passes the 8-bit sum by chance only
}

TEST(TmclOnModbus, HalfDuplexBusLine) {
    expectNotTmcl(decodeWiz({{"bus", "2"}}), "bus");
}

TEST(TmclOnModbus, SeparateLines) {
    expectNotTmcl(decodeWiz({{"host", "0"}, {"module", "3"}}), "lines");
}

}  // namespace
}  // namespace busdecode
