#include "fault_captures.h"

#include <filesystem>
#include <functional>

#include "bissc_generator.h"
#include "capture/capture_writer.h"
#include "ssi_generator.h"

namespace busdecode::test {

const char* const kBisscRules = R"(# rules for the generated BiSS-C captures
[bissc]
max_crc_errors = 0
max_errors = 0
max_warnings = 2
clock_hz = [0.5e6, 2e6]
max_line_delay_ns = 500
max_proc_cycles = 4
min_frames = 30
timeout_us = [12.5, 40]
max_position_jump = 1000
)";

const char* const kSsiRules = R"(# rules for the generated SSI captures
[ssi]
max_repeat_mismatches = 0
tm_us = [15, 25]
clock_hz = [100e3, 2e6]
min_frames = 30
)";

namespace {

constexpr int kFrames = 40;

// 40 BiSS-C frames at 1 MHz, 26-bit positions counting up by 7; `tweak` changes the
// configuration, `spec` one frame. Returns the start of frame `mark` (and `mark2`) in ns.
double writeBissc(const std::string& path, const std::function<void(BisscGenConfig&)>& tweak,
                  const std::function<void(int, BisscFrameSpec&)>& spec, int mark, int mark2 = -1,
                  double* second_ns = nullptr) {
    BisscGenConfig cfg;
    cfg.line_delay_ns = 120;
    tweak(cfg);
    BisscGenerator gen(cfg);
    for (int i = 0; i < kFrames; ++i) {
        BisscFrameSpec f;
        f.data = 100000 + 7 * std::uint64_t(i);
        spec(i, f);
        gen.addFrame(f);
    }
    writeVcd(gen.build(), path);
    if (second_ns && mark2 >= 0)
        *second_ns = cfg.timebase.toNsF(double(gen.frames()[std::size_t(mark2)].start));
    return mark >= 0 ? cfg.timebase.toNsF(double(gen.frames()[std::size_t(mark)].start)) : 0;
}

double writeSsi(const std::string& path, const std::function<void(SsiGenConfig&)>& tweak,
                const std::function<void(int, SsiGenFrame&)>& spec, int mark) {
    SsiGenConfig cfg;
    cfg.clock_hz = 500e3;
    tweak(cfg);
    std::vector<SsiGenFrame> frames;
    for (int i = 0; i < kFrames; ++i) {
        SsiGenFrame f;
        f.word = 0x10000 + 11 * std::uint64_t(i);
        f.repeats = 2;
        f.pause_ns = 60000;
        spec(i, f);
        frames.push_back(f);
    }
    const SsiGenerated g = generateSsi(cfg, frames);
    writeVcd(g.wave, path);
    return mark >= 0 ? g.wave.timebase.toNsF(double(g.frames[std::size_t(mark)].start)) : 0;
}

std::vector<FaultCapture> make(const std::string& dir) {
    std::filesystem::create_directories(dir);
    std::vector<FaultCapture> out;
    auto none = [](auto&) {};
    auto biss = [&](const std::string& name, const std::string& rule, auto tweak, auto spec,
                    int mark, int mark2 = -1) {
        FaultCapture c;
        c.path = dir + "/" + name + ".vcd";
        c.proto = "bissc";
        c.failing_rule = rule;
        c.first_ns = writeBissc(c.path, tweak, spec, mark, mark2, &c.second_ns);
        out.push_back(c);
    };
    auto ssi = [&](const std::string& name, const std::string& rule, auto tweak, auto spec,
                   int mark) {
        FaultCapture c;
        c.path = dir + "/" + name + ".vcd";
        c.proto = "ssi";
        c.failing_rule = rule;
        c.first_ns = writeSsi(c.path, tweak, spec, mark);
        out.push_back(c);
    };
    auto noFrame = [](int, auto&) {};

    biss("biss_clean", "", none, noFrame, -1);
    biss(
        "biss_crc", "bissc.max_crc_errors", none,
        [](int i, BisscFrameSpec& f) { f.corrupt_crc = i == 17 || i == 30; }, 17, 30);
    biss(
        "biss_error", "bissc.max_errors", none,
        [](int i, BisscFrameSpec& f) { f.ne = i == 21 ? 0 : 1; }, 21);
    // Three warnings with two allowed: the rule fails at the third.
    biss(
        "biss_warning", "bissc.max_warnings", none,
        [](int i, BisscFrameSpec& f) { f.nw = (i == 5 || i == 9 || i == 26) ? 0 : 1; }, 26);
    biss(
        "biss_slow_clock", "bissc.clock_hz", [](BisscGenConfig& c) { c.clock_hz = 250e3; }, noFrame,
        0);
    biss(
        "biss_line_delay", "bissc.max_line_delay_ns",
        [](BisscGenConfig& c) { c.line_delay_ns = 800; }, noFrame, 0);
    biss(
        "biss_proc", "bissc.max_proc_cycles", none,
        [](int i, BisscFrameSpec& f) { f.proc_cycles = i == 12 ? 6 : 1; }, 12);
    biss(
        "biss_timeout", "bissc.timeout_us", [](BisscGenConfig& c) { c.timeout_ns = 50000; },
        noFrame, 0);
    biss(
        "biss_jump", "bissc.max_position_jump", none,
        [](int i, BisscFrameSpec& f) {
            if (i >= 33) f.data += 50000;
        },
        33);
    ssi("ssi_clean", "", none, noFrame, -1);
    ssi(
        "ssi_mismatch", "ssi.max_repeat_mismatches", none,
        [](int i, SsiGenFrame& f) {
            if (i == 14) f.flips = {{1, 5}};
        },
        14);
    ssi(
        "ssi_tm", "ssi.tm_us", [](SsiGenConfig& c) { c.tm_ns = 40000; }, noFrame, 0);
    return out;
}

}  // namespace

const RegisterCapture& registerCapture(const std::string& dir) {
    static const RegisterCapture capture = [&] {
        std::filesystem::create_directories(dir);
        ControlItemSpec rd;
        rd.address = 0x7E;
        rd.data = {0x69, 0x43};
        const ControlSequence seq = buildControlSequence({rd});
        BisscGenConfig cfg;
        BisscGenerator gen(cfg);
        for (std::size_t i = 0; i < seq.cdm.size(); ++i) {
            BisscFrameSpec f;
            f.data = 5000 + i;
            f.cdm = seq.cdm[i];
            f.cds = seq.cds[i];
            gen.addFrame(f);
        }
        RegisterCapture c;
        c.path = dir + "/biss_registers.vcd";
        writeVcd(gen.build(), c.path);
        for (const auto& ev : seq.events)
            c.first_ns.push_back(
                cfg.timebase.toNsF(double(gen.frames()[std::size_t(ev.first_frame)].start)));
        return c;
    }();
    return capture;
}

const std::vector<FaultCapture>& faultCaptures(const std::string& dir) {
    static const std::vector<FaultCapture> captures = make(dir);
    return captures;
}

}  // namespace busdecode::test
