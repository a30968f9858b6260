// The command line's numbers and options: arguments (NUL- or newline-separated, as argv)
// for --rate, --proto, --map, --opt and --glitch, each parsed as decode parses it and the
// requests run through a real Session over a small capture of the usual line names.
// Anything may be refused, but only as an InputError; an accepted rate is a timebase
// with positive terms that maps ticks to times in order.
#include <memory>
#include <string>
#include <vector>

#include "capture/capture_reader.h"
#include "core/options.h"
#include "core/registry.h"
#include "core/sample_rate.h"
#include "core/session.h"
#include "core/waveform.h"
#include "fuzz_harness.h"
#include "reader_targets.h"

namespace busdecode::fuzz {

namespace {

std::vector<std::string> splitArgs(const std::uint8_t* data, std::size_t size) {
    std::vector<std::string> args(1);
    for (std::size_t i = 0; i < size && args.size() < 64; ++i) {
        const char c = char(data[i]);
        if (c == '\0' || c == '\n')
            args.emplace_back();
        else
            args.back() += c;
    }
    return args;
}

void checkRate(const std::string& text) {
    double hz = 0;
    try {
        hz = rateArgument("--rate", text);
    } catch (const InputError&) {
        return;
    }
    const SampleRate r = sampleRateOf(hz);
    if (!r.timebase) throw HarnessFailure("--rate " + text + " accepted, but has no timebase");
    const Timebase tb = *r.timebase;
    if (tb.num <= 0 || tb.den <= 0) throw HarnessFailure("--rate " + text + ": a timebase <= 0");
    if (tb.toNs(1'000'000) < tb.toNs(1000) || tb.toNs(kMaxEdgeTick) < 0)
        throw HarnessFailure("--rate " + text + ": times out of order");
    const SampleRate with_unit = parseSampleRate(text + " kHz", true);
    if (with_unit.timebase && (with_unit.timebase->num <= 0 || with_unit.timebase->den <= 0))
        throw HarnessFailure(text + " kHz: a timebase <= 0");
}

Waveform smallCapture() {
    WaveBuilder b(Timebase{1, 1'000'000'000},
                  {"cs", "sclk", "mosi", "miso", "clk", "data", "rx", "tx", "ma", "slo"},
                  {1, 1, 0, 0, 1, 1, 1, 1, 1, 1});
    for (std::uint32_t k = 0; k < 40; ++k)
        for (std::uint32_t line = 0; line < 10; ++line)
            b.set(line, Tick(100 + 37 * k + 3 * line), ((k + line) & 1) != 0);
    return b.build(5000);
}

// --proto/--map/--opt as buildRequests() reads them: `proto.key` scopes to one decoder.
void addTo(std::vector<DecoderRequest>& reqs, const std::string& text, bool is_map) {
    const auto eq = text.find('=');
    if (eq == std::string::npos || eq == 0 || reqs.empty()) return;
    std::string key = text.substr(0, eq);
    const std::string value = text.substr(eq + 1);
    std::string scope;
    if (const auto dot = key.find('.'); dot != std::string::npos) {
        scope = key.substr(0, dot);
        key = key.substr(dot + 1);
    }
    for (auto& r : reqs)
        if (scope.empty() || r.proto == scope) (is_map ? r.map : r.options)[key] = value;
}

}  // namespace

void runCliArgsTarget(const std::uint8_t* data, std::size_t size) {
    registerDecoders();
    const std::vector<std::string> args = splitArgs(data, size);
    std::vector<DecoderRequest> reqs;
    for (std::size_t i = 0; i + 1 < args.size(); ++i) {
        const std::string& flag = args[i];
        const std::string& value = args[i + 1];
        if (flag == "--rate") {
            checkRate(value);
        } else if (flag == "--proto") {
            if (Registry::instance().find(value) && reqs.size() < 4)
                reqs.push_back({value, {}, {}});
        } else if (flag == "--map" || flag == "--opt") {
            addTo(reqs, value, flag == "--map");
        } else {
            continue;
        }
        ++i;
    }
    if (reqs.empty()) return;
    const Waveform w = smallCapture();
    auto reader = memoryReader(w);
    try {
        Session s(reqs, *reader, "args");
        s.run();
    } catch (const InputError& e) {
        if (std::string(e.what()).empty()) throw HarnessFailure("an empty error message");
        if (oneLine(e.what()).find('\n') != std::string::npos)
            throw HarnessFailure("an error that oneLine() leaves on two lines");
    } catch (const std::exception& e) {
        throw HarnessFailure(std::string("the options threw something else: ") + e.what());
    }
}

}  // namespace busdecode::fuzz
