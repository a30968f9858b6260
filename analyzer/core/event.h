#pragma once
// A decoded event: one frame, word, transfer, register access... Protocol faults are
// events with `errors`, never exceptions.
#include <cstdint>
#include <memory>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "time.h"
#include "value.h"

namespace busdecode {

class EventHome;

struct Field {
    Field() = default;
    template <class V>
    Field(std::string_view k, V&& v) : key(k), value(std::forward<V>(v)) {}
    std::string key;
    Value value;
};

struct Event {
    std::string proto;  // decoder id ("ssi", "bissc", ...)
    std::string type;   // event kind ("frame", "register", ...)
    Tick start = 0;
    Tick end = 0;
    std::vector<Field> fields;        // in the order they should be printed
    std::vector<std::string> errors;  // short stable strings ("crc", "short_frame", ...)
    std::string summary;              // one-line human text, without time and proto
    std::string instance;             // set by the session: which --proto slot emitted it
    // Ask the session to call Decoder::correlate() on this event before it is output,
    // once every other decoder's events up to `end` are known.
    bool wants_correlation = false;

    Event& set(std::string key, Value v);  // replaces an existing key
    // Appends a key the event does not have yet, without searching: for decoders filling
    // a fresh event (a BiSS-C frame has 20 fields; set() would compare keys 190 times).
    // Built in place, without a temporary Value or Field: decoders call this for every
    // field of every frame.
    template <class V>
    Event& add(std::string_view key, V&& v) {
        if (fields.capacity() == 0) fields.reserve(8);  // one allocation, not a growth series
        fields.emplace_back(key, std::forward<V>(v));
        return *this;
    }
    const Value* get(std::string_view key) const;
    bool has(std::string_view key) const { return get(key) != nullptr; }
    Event& error(std::string e);  // adds once
    bool hasError(std::string_view e) const;
    // Back to a fresh Event's contents, keeping the storage of its strings and vectors
    // (the session hands released events back to decoders: no allocation per event).
    void reset();

private:
    // The event pools' bookkeeping, not part of what was decoded (event_pool.h, EventHome):
    // whose storage this is. reset() keeps it.
    friend class EventHome;
    std::uint8_t home_ = 0;
};

// An event in storage of its own: handed from decoder to session to sink by pointer, so
// that its strings and vectors are not moved member by member on the way (three moves
// and three destructions per event: 8 % of BiSS-C's decoding thread's instructions by
// callgrind).
using EventPtr = std::unique_ptr<Event>;

// Where a decoder sends what it decodes.
class EventSink {
public:
    virtual ~EventSink() = default;
    virtual void onEvent(Event&& e) = 0;
    // An event filled in storage from freshEvent(). By default it goes to onEvent, and
    // its storage is kept for the next freshEvent().
    virtual void onOwnedEvent(EventPtr e) {
        onEvent(std::move(*e));
        e->reset();
        spare_ = std::move(e);
    }
    // An empty event to fill, possibly in storage left from one already output.
    virtual EventPtr freshEvent() { return spare_ ? std::move(spare_) : std::make_unique<Event>(); }

private:
    EventPtr spare_;
};

}  // namespace busdecode
