#include "stream_sinks.h"

#include <cerrno>
#include <cstring>
#include <map>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "core/number_text.h"
#include "core/options.h"
#include "event_format.h"

namespace busdecode {

namespace {

// Counts per decoder instance, printed after the events of a text run.
struct Tally {
    std::map<std::string, std::uint64_t> by_type;
    std::map<std::string, std::uint64_t> by_error;
    std::uint64_t faulty = 0;
};

// A full disk, a closed pipe (where the caller ignores SIGPIPE), a closed stdout: the run
// ends with an error rather than going on to lose every event and exit 0.
[[noreturn]] void cannotWrite(std::FILE* out) {
    throw InputError(fmt::format("{}: cannot write: {}",
                                 out == stdout ? "standard output" : "output",
                                 std::strerror(errno)));
}

void put(std::FILE* out, std::string_view s) {
    if (std::fwrite(s.data(), 1, s.size(), out) != s.size()) cannotWrite(out);
}

void flush(std::FILE* out) {
    if (std::fflush(out) != 0) cannotWrite(out);
}

// "100 MS/s", "1 GS/s" (a VCD in ns), "1 TS/s" (ps): the tick as a rate.
std::string rateText(double hz) {
    const int p = siPower(hz);
    return fmt::format("{:.6g} {}S/s", hz / siScale(p), siPrefix(p));
}

class TextSink : public OutputSink {
public:
    explicit TextSink(std::FILE* out) : out_(out) {}
    // appendEventText prints the summary, and fields only for events without one.
    bool readsFields() const override { return false; }
    void begin(const CaptureFacts& f) override {
        tallies_.clear();
        last_tally_ = nullptr;
        std::string binds;
        for (const auto& b : f.bindings)
            binds += fmt::format(" {}.{}={}", b.instance, b.role, b.signal);
        put(out_, fmt::format("# {} ({}, {} timebase){}\n", f.file, f.format,
                              rateText(f.timebase.sampleRateHz()), binds));
    }
    void onEvent(const Event& e, const CaptureFacts& f) override {
        line_.clear();
        appendEventText(line_, e, f.timebase);
        line_ += '\n';
        put(out_, line_);
        // Runs of one instance and type are the rule: skip the map look-ups for them.
        const std::string& inst = e.instance.empty() ? e.proto : e.instance;
        if (!last_tally_ || inst != last_inst_ || e.type != last_type_) {
            last_inst_ = inst;
            last_type_ = e.type;
            last_tally_ = &tallies_[inst];
            last_count_ = &last_tally_->by_type[e.type];
        }
        Tally& t = *last_tally_;
        ++*last_count_;
        if (!e.errors.empty()) t.faulty++;
        for (const auto& err : e.errors)
            t.by_error[err]++;
    }
    void end(const CaptureFacts& f) override {
        const double dur = double(f.timebase.toNs(f.end - f.start));
        put(out_, fmt::format("# summary: {} edges in {}\n", f.edges, formatDuration(dur)));
        for (const auto& inst : f.protos) {
            const auto& t = tallies_[inst];
            std::string types, errs;
            for (const auto& [k, n] : t.by_type)
                types += fmt::format("{}{} {}", types.empty() ? "" : ", ", n, k);
            for (const auto& [k, n] : t.by_error)
                errs += fmt::format("{}{} {}", errs.empty() ? "" : ", ", n, k);
            put(out_, fmt::format("# {}: {}; {} with errors{}\n", inst,
                                  types.empty() ? "no events" : types, t.faulty,
                                  errs.empty() ? "" : " (" + errs + ")"));
        }
        for (const auto& a : f.advice)
            put(out_, fmt::format("# hint: {}\n", a));
        flush(out_);
    }

private:
    std::FILE* out_;
    std::map<std::string, Tally> tallies_;
    std::string line_;  // reused for every event
    std::string last_inst_, last_type_;
    Tally* last_tally_ = nullptr;
    std::uint64_t* last_count_ = nullptr;
};

class JsonlSink : public OutputSink {
public:
    JsonlSink(std::FILE* out, bool name_capture) : out_(out), name_capture_(name_capture) {}
    bool readsSummaries() const override { return false; }  // jsonl has fields, no summary
    void begin(const CaptureFacts& f) override { capture_ = captureJsonFields(f, name_capture_); }
    void onEvent(const Event& e, const CaptureFacts& f) override {
        line_.clear();
        appendEventJson(line_, e, f.timebase, capture_);
        line_ += '\n';
        put(out_, line_);
    }
    void end(const CaptureFacts&) override { flush(out_); }

private:
    std::FILE* out_;
    bool name_capture_;
    std::string capture_;  // the capture fields of every line (captureJsonFields)
    std::string line_;     // reused for every event
};

}  // namespace

std::unique_ptr<OutputSink> makeTextSink(std::FILE* out) {
    return std::make_unique<TextSink>(out);
}
std::unique_ptr<OutputSink> makeJsonlSink(std::FILE* out, bool name_capture) {
    return std::make_unique<JsonlSink>(out, name_capture);
}

}  // namespace busdecode
