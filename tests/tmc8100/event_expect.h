#pragma once
// Exact comparison of decoded events with an expected list: type, start, end, the listed
// fields (integers compared by value whatever their signedness) and the errors.
#include <gtest/gtest.h>

#include <string>
#include <utility>
#include <vector>

#include "core/event.h"
#include "core/waveform.h"

namespace busdecode::test {

struct Expected {
    std::string type;
    Tick start = 0, end = 0;
    std::vector<std::pair<std::string, Value>> fields;
    std::vector<std::string> errors = {};
};

std::string show(const Value& v);
// Compares every event of `proto` in `events` with `want`, in order, and says which differ.
void expectEvents(const std::vector<Event>& events, const std::string& proto,
                  const std::vector<Expected>& want);
std::vector<Event> only(const std::vector<Event>& events, const std::string& proto,
                        const std::string& type = "");

// Registers the decoders the tests use (spi, tmc8100 and, when built, ssi).
void registerDecoders();
Value I(std::int64_t v);
Value S(const char* s);

}  // namespace busdecode::test
