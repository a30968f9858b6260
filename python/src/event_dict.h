#pragma once
// Events as Python dicts with exactly the keys and values of `decode --format jsonl`
// (the mapping of sinks/event_format.h): Python ints for integers and whole doubles,
// floats for other doubles, None for nulls and non-finite numbers, lists for lists.
#include <pybind11/pybind11.h>

#include <cstdint>
#include <string>
#include <unordered_map>

#include "core/event.h"

namespace busdecode::py {

namespace pyb = pybind11;

// A field value as jsonl writes it.
pyb::object valueToPython(const Value& v);

// An event whose times are already in ns (the session's timebase applied).
struct TimedEvent {
    Event event;
    std::int64_t start_ns = 0, end_ns = 0;
};

// Makes the dicts; keeps the key and name strings it made, so that the millions of
// events of a capture share them instead of each making its own. Needs the GIL.
class DictMaker {
public:
    pyb::dict operator()(const TimedEvent& e);

private:
    pyb::str name(const std::string& s);
    std::unordered_map<std::string, pyb::str> names_;
};

}  // namespace busdecode::py
