#pragma once
// Hand-made events shaped like the decoders' (docs/contract.md fields), 1 ns ticks.
#include <string>
#include <vector>

#include "core/event.h"
#include "core/session.h"

namespace busdecode::test {

inline Event bisscFrame(Tick start, std::int64_t position, bool crc_ok = true, int ne = 1,
                        int nw = 1, double clock_hz = 1e6, std::int64_t line_delay_ns = 100,
                        std::int64_t proc_cycles = 0, std::int64_t timeout_ns = 20000) {
    Event e;
    e.proto = "bissc";
    e.instance = "bissc";
    e.type = "frame";
    e.start = start;
    e.end = start + 60000;
    e.set("position", position).set("st", position).set("mt", std::int64_t(0));
    e.set("nE", std::int64_t(ne)).set("nW", std::int64_t(nw));
    e.set("crc_rx", std::int64_t(0x15)).set("crc_ok", crc_ok);
    e.set("cds", std::int64_t(0)).set("cdm", std::int64_t(0));
    e.set("line_delay_ns", line_delay_ns).set("proc_cycles", proc_cycles);
    e.set("clock_hz", clock_hz).set("timeout_ns", timeout_ns);
    e.set("extra_clocks", std::int64_t(0)).set("clocks", std::int64_t(26 + 13 + proc_cycles));
    if (!crc_ok) e.error("crc");
    return e;
}

inline Event ssiFrame(Tick start, std::int64_t raw, bool repeat_match = true, double tm_ns = 20000,
                      double clock_hz = 500e3) {
    Event e;
    e.proto = "ssi";
    e.instance = "ssi";
    e.type = "frame";
    e.start = start;
    e.end = start + 52000;
    e.set("raw", raw).set("bits", std::int64_t(25)).set("position", raw & 0xFFFF);
    e.set("repeats", std::int64_t(2)).set("repeat_match", repeat_match);
    e.set("clock_hz", clock_hz).set("tm_ns", tm_ns);
    if (!repeat_match) e.error("repeat_mismatch");
    return e;
}

inline Event bisscRegister(Tick start, std::int64_t address, std::int64_t data,
                           bool crc_ok = true) {
    Event e;
    e.proto = "bissc";
    e.instance = "bissc";
    e.type = "register";
    e.start = start;
    e.end = start + 2'000'000;
    e.set("op", std::string("read")).set("id", std::int64_t(0)).set("address", address);
    e.set("data", data).set("crc_ok", crc_ok);
    if (!crc_ok) e.error("crc");
    return e;
}

inline CaptureFacts facts(Tick end, std::string file = "test.vcd") {
    CaptureFacts f;
    f.file = std::move(file);
    f.format = "vcd";
    f.timebase = Timebase{1, 1'000'000'000};
    f.start = 0;
    f.end = end;
    f.protos = {"bissc"};
    f.bindings = {{"bissc", "bissc", "ma", "MA"}, {"bissc", "bissc", "sl", "SLO"}};
    f.edges = 12345;
    f.bytes = 67890;
    return f;
}

}  // namespace busdecode::test
