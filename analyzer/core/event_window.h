#pragma once
// Events of all decoders in one pass, by time: the general cross-decoder correlation
// mechanism (a TMC8100 encoder read looks up the SSI frame clocked between its command
// and its reply). Bounded: old events fall out once far behind the release point.
#include <deque>
#include <functional>
#include <string_view>

#include "event.h"

namespace busdecode {

class EventWindow {
public:
    // Calls fn for every held event of `proto`/`type` (empty = any) whose start lies in
    // [from, to]. Stops early when fn returns false.
    void forEach(std::string_view proto, std::string_view type, Tick from, Tick to,
                 const std::function<bool(const Event&)>& fn) const;
    // Session side.
    void remember(EventPtr e, std::size_t keep);
    void setPending(const std::deque<EventPtr>* pending) { pending_ = pending; }

private:
    std::deque<EventPtr> released_;
    const std::deque<EventPtr>* pending_ = nullptr;
};

}  // namespace busdecode
