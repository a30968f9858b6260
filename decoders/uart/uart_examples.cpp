#include "uart_examples.h"

#include "uart_generator.h"

namespace busdecode {

namespace {

std::vector<std::uint32_t> chars(const std::string& s) {
    return {s.begin(), s.end()};
}

UartExample rxtx() {
    // A modem-style dialogue on two lines; the answer starts before the command ends.
    UartFormat f;
    f.baud = 9600;
    WaveBuilder wb(Timebase{1, 10'000'000}, {"rx", "tx"}, {1, 1});  // 100 ns ticks
    UartGenerator rx(wb, 0, f), tx(wb, 1, f);
    const double t = tx.sendChars(200'000, chars("AT+VERSION?\r\n"), 50'000);
    const double end = rx.sendChars(t - 3 * 10 * tx.bitNs(), chars("+VERSION:1.0\r\nOK\r\n"));
    return {{"uart_rxtx_9600_8n1.vcd",
             ExampleFormat::Vcd,
             "Two lines at 9600 8N1: a command on tx, its answer on rx overlapping it",
             {{"uart", {}, {}}},
             wb.build(wb.ticksFromNs(end + 1e6))}};
}

UartExample faults() {
    // 7E1 at 19200 sampled at 250 kHz (sigrok dense CSV): clean text, a parity error, a
    // framing error, a break, and clean text again.
    UartFormat f;
    f.baud = 19200;
    f.bits = 7;
    f.parity = Parity::Even;
    WaveBuilder wb(Timebase::fromSampleRate(250'000), {"tx"}, {1});
    UartGenerator tx(wb, 0, f);
    double t = tx.sendChars(100'000, chars("Hi!"), 20'000);
    t = tx.sendChar(t + 100'000, 'P', {.bad_parity = true});
    t = tx.sendChar(t + 100'000, 'F', {.bad_stop = true});
    t = tx.sendBreak(t + 100'000, 2e6);
    t = tx.sendChars(t + 200'000, chars("ok"));
    return {{"uart_7e1_faults.csv",
             ExampleFormat::SigrokCsv,
             "One line at 19200 7E1 (sigrok CSV): parity error, framing error, a 2 ms break",
             {{"uart", {}, {{"baud", "19200"}, {"bits", "7"}, {"parity", "even"}}}},
             wb.build(wb.ticksFromNs(t + 500'000))}};
}

}  // namespace

std::vector<UartExample> uartExamples() {
    return {rxtx(), faults()};
}

// make_examples finds them here (this library is linked whole: CMake OBJECT library).
[[maybe_unused]] const bool kListed = listExamples("uart", uartExamples);

}  // namespace busdecode
