// TMCL decoder on generated UART traffic: every command of the table with positive and
// negative values, a bad checksum answered with status 1, GetVersion, on two lines and
// on one half-duplex line, at 9600 and 115200 baud; resynchronisation and cut datagrams.
#include <gtest/gtest.h>

#include <optional>

#include <fmt/format.h>

#include "core/registry.h"
#include "core/session.h"
#include "tmcl_decoder.h"
#include "tmcl_generator.h"
#include "tmcl_tables.h"
#include "uart_decoder.h"

namespace busdecode {
namespace {

using namespace tmcl;

class TmclTraffic : public ::testing::Test {
protected:
    static void SetUpTestSuite() {
        Registry::instance().add(makeUartFactory());
        Registry::instance().add(makeTmclFactory());
    }
};

struct Exchange {
    Datagram command;
    std::optional<Datagram> reply;
    bool version_reply = false;
    double cmd_start = 0, cmd_end = 0, reply_start = 0, reply_end = 0;  // ns, filled by send
};

std::vector<Exchange> allCommandsTraffic() {
    std::vector<Exchange> out;
    for (const auto& info : commandTable()) {
        for (int sign : {1, -1}) {
            const std::int32_t value = sign * (100000 + info.number * 1237);
            const int type =
                info.number == kGetVersion ? (sign > 0 ? 0 : 1) : (info.number * 7) % 256;
            const int motor = info.number % 3;
            Exchange ex;
            ex.command = makeCommand(1, info.number, type, motor, value);
            if (info.number == kGetVersion && type == 0) {
                ex.reply = makeVersionReply(2, "1690V103");
                ex.version_reply = true;
            } else if (info.number != 137 && info.number != 255) {  // these two send no reply
                ex.reply = makeReply(2, 1, 100, info.number, value);
            }
            out.push_back(ex);
        }
    }
    // A command with a bad checksum, answered with status 1.
    Exchange bad;
    bad.command = makeCommand(1, 5, 4, 0, 51200);
    bad.command[8] ^= 0x5A;
    bad.reply = makeReply(2, 1, 1, 5, 51200);
    out.push_back(bad);
    return out;
}

Waveform sendTraffic(std::vector<Exchange>& traffic, double baud, bool half_duplex) {
    WaveBuilder wb(Timebase{1, 1'000'000'000},
                   half_duplex ? std::vector<std::string>{"rs485"}
                               : std::vector<std::string>{"host", "module"},
                   half_duplex ? std::vector<std::uint8_t>{1} : std::vector<std::uint8_t>{1, 1});
    TmclTrafficGenerator gen(wb, 0, half_duplex ? 0 : 1, baud);
    double t = 10 * gen.charNs();
    for (auto& ex : traffic) {
        ex.cmd_start = t;
        ex.cmd_end = t = gen.sendFromHost(t, ex.command);
        if (ex.reply) {
            ex.reply_start = t + 1.5 * gen.charNs();
            ex.reply_end = t = gen.sendFromModule(ex.reply_start, *ex.reply);
        }
        t += 6 * gen.charNs();
    }
    return wb.build(wb.ticksFromNs(t + 20 * gen.charNs()));
}

std::int64_t intField(const Event& e, const char* key) {
    const Value* v = e.get(key);
    EXPECT_TRUE(v && !isNull(*v)) << key << " in " << e.summary;
    return v ? asInt(*v) : -1;
}

void expectExact(const std::vector<Exchange>& traffic, const std::vector<Event>& events) {
    std::size_t i = 0;
    for (const auto& ex : traffic) {
        ASSERT_LT(i, events.size());
        const Event& c = events[i++];
        const Command want = parseCommand(ex.command);
        ASSERT_EQ(c.type, "command") << c.summary;
        EXPECT_EQ(intField(c, "address"), want.address);
        EXPECT_EQ(intField(c, "command"), want.command);
        EXPECT_EQ(std::get<std::string>(*c.get("mnemonic")), mnemonicOf(want.command));
        EXPECT_EQ(intField(c, "type_no"), want.type);
        EXPECT_EQ(intField(c, "motor"), want.motor);
        EXPECT_EQ(intField(c, "value"), want.value);
        EXPECT_EQ(std::get<bool>(*c.get("checksum_ok")), want.checksum_ok);
        EXPECT_EQ(c.hasError("checksum"), !want.checksum_ok);
        EXPECT_EQ(c.summary.rfind(mnemonicText(want), 0), 0u) << c.summary;
        EXPECT_NEAR(double(c.start), ex.cmd_start, 2);
        if (!ex.reply) continue;
        ASSERT_LT(i, events.size());
        const Event& r = events[i++];
        ASSERT_EQ(r.type, "reply") << r.summary;
        EXPECT_TRUE(r.errors.empty()) << r.summary;
        if (ex.version_reply) {
            EXPECT_EQ(std::get<std::string>(*r.get("version")), "1690V103");
            EXPECT_EQ(intField(r, "command"), kGetVersion);
        } else {
            const Reply want_r = parseReply(*ex.reply);
            EXPECT_EQ(intField(r, "reply_address"), want_r.reply_address);
            EXPECT_EQ(intField(r, "module_address"), want_r.module_address);
            EXPECT_EQ(intField(r, "status"), want_r.status);
            EXPECT_EQ(std::get<std::string>(*r.get("status_text")), statusText(want_r.status));
            EXPECT_EQ(intField(r, "command"), want_r.command);
            EXPECT_EQ(intField(r, "value"), want_r.value);
            EXPECT_EQ(std::get<bool>(*r.get("checksum_ok")), true);
        }
        // Paired with its command: round trip from command start to reply end.
        EXPECT_NEAR(double(intField(r, "rtt_ns")), ex.reply_end - ex.cmd_start, 4);
        EXPECT_NEAR(double(intField(r, "latency_ns")), ex.reply_start - ex.cmd_end, 4);
    }
    EXPECT_EQ(i, events.size());
}

std::vector<Event> tmclEvents(const Waveform& w, std::map<std::string, std::string> opts) {
    std::vector<Event> out;
    for (auto& e : decodeWaveform(w, {{"tmcl", {}, std::move(opts)}}))
        if (e.proto == "tmcl") out.push_back(std::move(e));
    return out;
}

TEST_F(TmclTraffic, AllCommandsOnTwoLines) {
    for (double baud : {9600.0, 115200.0}) {
        auto traffic = allCommandsTraffic();
        const auto w = sendTraffic(traffic, baud, false);
        expectExact(traffic, tmclEvents(w, {{"baud", fmt::format("{:g}", baud)}}));
    }
}

TEST_F(TmclTraffic, AllCommandsOnOneHalfDuplexLine) {
    for (double baud : {9600.0, 115200.0}) {
        auto traffic = allCommandsTraffic();
        const auto w = sendTraffic(traffic, baud, true);
        expectExact(traffic, tmclEvents(w, {{"baud", fmt::format("{:g}", baud)}}));
    }
}

TEST_F(TmclTraffic, AutoBaud) {
    auto traffic = allCommandsTraffic();
    const auto w = sendTraffic(traffic, 115200, true);
    expectExact(traffic, tmclEvents(w, {{"baud", "auto"}}));
}

TEST_F(TmclTraffic, BadChecksumAnsweredWithStatus1) {
    std::vector<Exchange> traffic(1);
    traffic[0].command = makeCommand(1, 6, 71, 0, 0);
    traffic[0].command[8] = std::uint8_t(traffic[0].command[8] + 1);
    traffic[0].reply = makeReply(2, 1, 1, 6, 0);
    const auto w = sendTraffic(traffic, 9600, true);
    const auto events = tmclEvents(w, {});
    ASSERT_EQ(events.size(), 2u);
    EXPECT_EQ(events[0].errors, std::vector<std::string>{"checksum"});
    EXPECT_EQ(std::get<bool>(*events[0].get("checksum_ok")), false);
    EXPECT_EQ(asInt(*events[1].get("status")), 1);
    EXPECT_EQ(std::get<std::string>(*events[1].get("status_text")), "Wrong checksum");
    EXPECT_EQ(std::get<std::string>(*events[1].get("request")),
              "GAP 71, 0  // Absolute encoder position");
}

TEST_F(TmclTraffic, GetVersionStringReplyOnBothLineKinds) {
    for (bool half : {false, true}) {
        std::vector<Exchange> traffic(1);
        traffic[0].command = makeCommand(1, kGetVersion, 0, 0, 0);
        traffic[0].reply = makeVersionReply(2, "1690V103");
        traffic[0].version_reply = true;
        const auto w = sendTraffic(traffic, 115200, half);
        expectExact(traffic, tmclEvents(w, {{"baud", "115200"}}));
    }
}

TEST_F(TmclTraffic, PauseInsideADatagramResynchronises) {
    WaveBuilder wb(Timebase{1, 1'000'000'000}, {"host"}, {1});
    TmclTrafficGenerator gen(wb, 0, 0, 9600);
    const Datagram sap = makeCommand(1, 5, 4, 0, 51200);
    double t = gen.charNs();
    for (int i = 0; i < 5; ++i)
        t = UartGenerator(wb, 0, UartFormat{}).sendChar(t, sap[i]);
    t = gen.sendFromHost(t + 10 * gen.charNs(), sap);
    t = gen.sendFromHost(t + 10 * gen.charNs(), makeCommand(1, 1, 0, 0, 3));
    // The capture ends in the middle of a third datagram.
    UartGenerator(wb, 0, UartFormat{}).sendChars(t + 10 * gen.charNs(), {1, 2, 3});
    const auto events = tmclEvents(wb.build(wb.lastTick() + wb.ticksFromNs(2 * gen.charNs())), {});
    ASSERT_EQ(events.size(), 4u);
    EXPECT_EQ(events[0].errors, std::vector<std::string>{"short_frame"});
    EXPECT_EQ(asInt(*events[0].get("length")), 5);
    EXPECT_EQ(events[1].summary, "SAP 4, 0, 51200  // Motor nominal current");
    EXPECT_TRUE(events[1].errors.empty());
    EXPECT_EQ(events[2].summary, "ROR 0, 3");
    EXPECT_EQ(events[3].errors, std::vector<std::string>{"short_frame"});
    EXPECT_EQ(asInt(*events[3].get("length")), 3);
}

TEST_F(TmclTraffic, RepliesWithoutCommandsOnTheModuleLine) {
    WaveBuilder wb(Timebase{1, 1'000'000'000}, {"module"}, {1});
    TmclTrafficGenerator gen(wb, 0, 0, 9600);
    double t = gen.sendFromModule(gen.charNs(), makeReply(2, 1, 100, 6, -42));
    gen.sendFromModule(t + 3 * gen.charNs(), makeReply(2, 1, 4, 5, 7));
    const auto events = tmclEvents(wb.build(wb.lastTick() + 1000000), {});
    ASSERT_EQ(events.size(), 2u);
    EXPECT_EQ(events[0].type, "reply");
    EXPECT_EQ(asInt(*events[0].get("value")), -42);
    EXPECT_FALSE(events[0].has("rtt_ns"));
    EXPECT_EQ(std::get<std::string>(*events[1].get("status_text")), "Invalid value");
}

TEST_F(TmclTraffic, AddressesSettleAmbiguousDatagramsOnABus) {
    // "SAP 100, 1, 7" has a reply's shape (100 = OK, 1 = ROR). At the start of a capture
    // nothing tells it apart; with the addresses given it is a command.
    WaveBuilder wb(Timebase{1, 1'000'000'000}, {"rs485"}, {1});
    TmclTrafficGenerator gen(wb, 0, 0, 115200);
    gen.exchange(gen.charNs(), makeCommand(1, 5, 100, 1, 7), makeReply(2, 1, 100, 5, 7),
                 gen.charNs());
    const auto w = wb.build(wb.lastTick() + 100000);
    const auto guessed = tmclEvents(w, {{"baud", "115200"}});
    ASSERT_EQ(guessed.size(), 2u);
    EXPECT_EQ(guessed[0].type, "reply");  // the documented limit of guessing
    const auto told =
        tmclEvents(w, {{"baud", "115200"}, {"host_address", "2"}, {"module_address", "1"}});
    ASSERT_EQ(told.size(), 2u);
    EXPECT_EQ(told[0].type, "command");
    EXPECT_EQ(told[0].summary, "SAP 100, 1, 7  // Velocity I");
    EXPECT_EQ(told[1].type, "reply");
    EXPECT_TRUE(told[1].has("rtt_ns"));
}

TEST_F(TmclTraffic, InvertedLines) {
    WaveBuilder wb(Timebase{1, 1'000'000'000}, {"host", "module"}, {0, 0});
    UartFormat f;
    f.baud = 9600;
    f.invert = true;
    UartGenerator host(wb, 0, f), module(wb, 1, f);
    const Datagram cmd = makeCommand(1, 1, 0, 0, 500), reply = makeReply(2, 1, 100, 1, 500);
    double t = host.sendChars(1e5, {cmd.begin(), cmd.end()});
    module.sendChars(t + 1e6, {reply.begin(), reply.end()});
    const auto events = tmclEvents(wb.build(wb.lastTick() + 1000000), {{"invert", "1"}});
    ASSERT_EQ(events.size(), 2u);
    EXPECT_EQ(events[0].summary, "ROR 0, 500");
    EXPECT_EQ(asInt(*events[1].get("status")), 100);
}

}  // namespace
}  // namespace busdecode
