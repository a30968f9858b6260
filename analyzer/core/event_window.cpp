#include "event_window.h"

namespace busdecode {

void EventWindow::forEach(std::string_view proto, std::string_view type, Tick from, Tick to,
                          const std::function<bool(const Event&)>& fn) const {
    auto visit = [&](const Event& e) {
        if (e.start < from || e.start > to) return true;
        if (!proto.empty() && e.proto != proto) return true;
        if (!type.empty() && e.type != type) return true;
        return fn(e);
    };
    for (const auto& e : released_)
        if (!visit(*e)) return;
    if (pending_)
        for (const auto& e : *pending_)
            if (!visit(*e)) return;
}

void EventWindow::remember(EventPtr e, std::size_t keep) {
    released_.push_back(std::move(e));
    while (released_.size() > keep)
        released_.pop_front();
}

}  // namespace busdecode
