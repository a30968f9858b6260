#pragma once
// A sink that counts the events and drops them: a decode's floor, for the benchmarks.
// What it says it reads decides what the decoders build (the session's hints), so a
// floor can be taken with or without the fields and the summaries.
#include <cstdint>

#include "core/session.h"

namespace busdecode {

class CountingSink final : public OutputSink {
public:
    struct Reads {
        bool fields = true;
        bool summaries = true;
    };
    CountingSink() : CountingSink(Reads{}) {}
    explicit CountingSink(Reads reads) : reads_(reads) {}
    void onEvent(const Event&, const CaptureFacts&) override { ++events_; }
    bool readsFields() const override { return reads_.fields; }
    bool readsSummaries() const override { return reads_.summaries; }
    std::uint64_t events() const { return events_; }

private:
    Reads reads_;
    std::uint64_t events_ = 0;
};

}  // namespace busdecode
