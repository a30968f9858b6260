#pragma once
// Events as Python dicts with exactly the keys and values of `decode --format jsonl`
// (the mapping of sinks/event_format.h): Python ints for integers and whole doubles,
// floats for other doubles, None for nulls and non-finite numbers, lists for lists.
#include <pybind11/pybind11.h>

#include <cstdint>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

#include "core/event.h"
#include "field_order.h"

namespace busdecode::py {

namespace pyb = pybind11;

// A field value as jsonl writes it.
pyb::object valueToPython(const Value& v);

// Text out of a capture as a str; bytes that are not UTF-8 become U+FFFD, as in jsonl.
pyb::str textToPython(const std::string& s);
// A file's name as os.fsdecode() makes it (bytes that are not UTF-8 as surrogates), so
// that it opens the same file again.
pyb::str pathToPython(const std::string& path);

// What a dict is made of: an event's proto, type, fields and errors (not its summary),
// with its times already in ns (the session's timebase applied).
struct TimedEvent {
    Event event;
    std::int64_t start_ns = 0, end_ns = 0;

    // Copies what a dict needs of `e` into this one's storage, kept from an earlier
    // event: no allocation once the strings and vectors have grown.
    void set(const Event& e, std::int64_t start, std::int64_t end);
};

// Makes the dicts; keeps the key and name strings it made, so that the millions of
// events of a capture share them instead of each making its own. Needs the GIL.
class DictMaker {
public:
    pyb::dict operator()(const TimedEvent& e);
    // The capture's wall-clock start, put in every dict as jsonl puts it in every line
    // ("" for none: no key).
    void setCaptureStart(const std::string& start);

private:
    pyb::str name(const std::string& s);
    // The key of the field at `position` among the event's own fields (kCommonKey for a key
    // every event has, put first): events of one kind list their fields in one order.
    PyObject* fieldKey(const std::string& key, std::size_t position);
    // The name of `s`, looked up only when it is not `last` (most events repeat it).
    PyObject* repeatedName(const std::string& s, std::pair<std::string, pyb::str>& last);
    static constexpr PyObject* kCommonKey = nullptr;
    // The keys every event has, made once (with the GIL: DictMaker is made from Python).
    const pyb::str proto_ = pyb::str("proto"), type_ = pyb::str("type"),
                   start_ns_ = pyb::str("start_ns"), end_ns_ = pyb::str("end_ns"),
                   errors_ = pyb::str("errors"), capture_start_key_ = pyb::str("capture_start");
    pyb::object capture_start_;  // null: none
    std::pair<std::string, pyb::str> last_proto_, last_type_;
    std::unordered_map<std::string, pyb::str> names_;
    FieldOrder<pyb::str> keys_at_;
};

}  // namespace busdecode::py
