#include "tmcl_examples.h"

#include "tmcl_generator.h"

namespace busdecode {

using namespace tmcl;

namespace {

constexpr int kHost = 2, kModule = 1, kOk = 100;

TmclExample rs485() {
    // A TMCM-1690 set-up session on one half-duplex RS-485 line at 9600 baud.
    WaveBuilder wb(Timebase{1, 10'000'000}, {"rs485"}, {1});  // 100 ns ticks
    TmclTrafficGenerator g(wb, 0, 0, 9600);
    const double turn = 2e6, pause = 5e6;  // module answers after 2 ms; host waits 5 ms
    double t = 1e6;
    auto ask = [&](const Datagram& cmd, const Datagram& reply) {
        t = g.exchange(t, cmd, reply, turn) + pause;
    };
    ask(makeCommand(kModule, kGetVersion, 0, 0, 0), makeVersionReply(kHost, "1690V103"));
    ask(makeCommand(kModule, 6, 71, 0, 0), makeReply(kHost, kModule, kOk, 6, 123456));   // GAP 71
    ask(makeCommand(kModule, 5, 13, 0, 5), makeReply(kHost, kModule, kOk, 5, 5));        // SAP 13
    ask(makeCommand(kModule, 5, 94, 0, 2000), makeReply(kHost, kModule, kOk, 5, 2000));  // SAP 94
    ask(makeCommand(kModule, 4, 0, 0, -90000),
        makeReply(kHost, kModule, kOk, 4, -90000));                                   // MVP ABS
    ask(makeCommand(kModule, 2, 0, 0, 500), makeReply(kHost, kModule, kOk, 2, 500));  // ROL
    Datagram bad = makeCommand(kModule, 5, 4, 0, 51200);  // a byte hit on the way
    bad[6] ^= 0x10;
    ask(bad, makeReply(kHost, kModule, 1, 5, 51200));
    ask(makeCommand(kModule, 10, 42, 2, 0), makeReply(kHost, kModule, kOk, 10, -7));  // GGP 42, 2
    ask(makeCommand(kModule, 3, 0, 0, 0), makeReply(kHost, kModule, kOk, 3, 0));      // MST
    return {{"tmcl_rs485_9600.vcd",
             ExampleFormat::Vcd,
             "TMCL on one half-duplex RS-485 line at 9600: GetVersion, GAP/SAP/MVP/ROL/GGP/MST, a "
             "command with a bad checksum answered with status 1",
             {{"tmcl", {}, {}}},
             wb.build(wb.ticksFromNs(t))}};
}

TmclExample lines() {
    // TMC8100-Eval traffic through the Landungsbruecke at 115200 on two lines: UF_CH2
    // SPI accesses (docs/protocols.md 4.6), a binary GetVersion, a command the module does not
    // answer (137) and a command cut short by a pause.
    WaveBuilder wb(Timebase{1, 100'000'000}, {"host", "module"}, {1, 1});  // 10 ns ticks
    TmclTrafficGenerator g(wb, 0, 1, 115200);
    const double turn = 300e3, pause = 1e6;
    double t = 200e3;
    auto ask = [&](const Datagram& cmd, const Datagram& reply) {
        t = g.exchange(t, cmd, reply, turn) + pause;
    };
    ask(makeCommand(kModule, 145, 0, 0, std::int32_t(0xFE000000u)),
        makeReply(kHost, kModule, kOk, 145, 0x53534920));
    ask(makeCommand(kModule, 145, 0, 0, std::int32_t(0x80000000u)),
        makeReply(kHost, kModule, kOk, 145, 0));
    ask(makeCommand(kModule, 145, 2, 0, 0), makeReply(kHost, kModule, kOk, 145, 1));
    ask(makeCommand(kModule, 145, 1, 0, 0), makeReply(kHost, kModule, kOk, 145, 0x10001234));
    ask(makeCommand(kModule, kGetVersion, 1, 0, 0),
        makeReply(kHost, kModule, kOk, kGetVersion, 0x06A00103));
    t = g.sendFromHost(t, makeCommand(kModule, 137, 0, 0, 1234)) + pause;  // no reply
    const Datagram cut = makeCommand(kModule, 6, 106, 0, 0);
    UartFormat f;
    f.baud = 115200;
    UartGenerator host(wb, 0, f);
    for (int i = 0; i < 4; ++i)
        t = host.sendChar(t, cut[i]);
    t += pause;
    ask(makeCommand(kModule, 6, 106, 0, 0), makeReply(kHost, kModule, kOk, 6, -1));
    return {{"tmcl_lines_115200.vcd",
             ExampleFormat::Vcd,
             "TMCL on host and module lines at 115200: TMC8100-Eval UF_CH2 accesses, binary "
             "GetVersion, an unanswered command, a datagram cut short",
             {{"tmcl", {}, {{"baud", "115200"}}}},
             wb.build(wb.ticksFromNs(t))}};
}

}  // namespace

std::vector<TmclExample> tmclExamples() {
    return {rs485(), lines()};
}

// make_examples finds them here (this library is linked whole: CMake OBJECT library).
[[maybe_unused]] const bool kListed = listExamples("tmcl", tmclExamples);

}  // namespace busdecode
