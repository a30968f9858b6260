// subscribe(): the LCM feed of a `decode --lcm` run as event dicts. Each event's
// annotation (DECODE_EVENTS, event_annotation_t, decoded here with the project's own
// generated type) carries the event's jsonl object, which becomes the dict: exactly
// what decode() gives for the same event.
#include <pybind11/stl.h>

#include <chrono>
#include <deque>
#include <lcm/lcm-cpp.hpp>
#include <memory>
#include <optional>
#include <regex>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "bindings.h"
#include "busdecode_lcm/decode_status_t.hpp"
#include "busdecode_lcm/event_annotation_t.hpp"
#include "core/options.h"
#include "lcm/feed_losses.h"
#include "lcm/lcm_channels.h"
#include "lcm/lcm_publisher.h"

namespace busdecode::py {

namespace {

constexpr int kPollMs = 100;

class Subscription {
public:
    Subscription(const std::string& url, const std::vector<std::string>& channels,
                 std::optional<double> timeout_s, bool until_end)
        : lc_(openLcm(url)),
          timeout_s_(timeout_s),
          until_end_(until_end),
          loads_(pyb::module_::import("json").attr("loads")) {
        if (!channels.empty()) {
            try {
                wanted_ = std::regex(fmt::format("({})", fmt::join(channels, ")|(")));
            } catch (const std::regex_error& e) {
                throw UsageError(fmt::format("channels {}: not a regular expression ({})",
                                             fmt::join(channels, ", "), e.what()));
            }
        }
        lc_->subscribe(kLcmEventsChannel, &Subscription::onEvent, this);
        lc_->subscribe(kLcmStatusChannel, &Subscription::onStatus, this);
        last_ = std::chrono::steady_clock::now();
    }

    std::int64_t lost() const { return losses_.lost(); }

    // Stops receiving and closes LCM's socket; the iteration ends. A reader waiting in
    // next() on another thread (its handlers filling pending_) does so when it wakes.
    void close() {
        closed_ = true;
        if (busy_) return;
        pending_.clear();
        lc_.reset();
    }

    pyb::object next() {
        // As a generator: one reader at a time (the wait below releases the GIL).
        if (busy_) throw pyb::value_error("subscribe(): already being read on another thread");
        for (;;) {
            if (closed_) {
                close();
                throw pyb::stop_iteration();
            }
            if (!pending_.empty()) break;
            if (ended_ || timedOut()) throw pyb::stop_iteration();
            busy_ = true;
            // The handlers touch no Python.
            withoutGil([&] { lc_->handleTimeout(kPollMs); }, [] {});
            busy_ = false;
            if (PyErr_CheckSignals() != 0) throw pyb::error_already_set();
        }
        std::string json = std::move(pending_.front());
        pending_.pop_front();
        return loads_(json);
    }

private:
    bool timedOut() const {
        if (!timeout_s_) return false;
        const std::chrono::duration<double> idle = std::chrono::steady_clock::now() - last_;
        return idle.count() >= *timeout_s_;
    }
    void onEvent(const lcm::ReceiveBuffer*, const std::string&,
                 const busdecode_lcm::event_annotation_t* m) {
        last_ = std::chrono::steady_clock::now();
        losses_.onEvent(m->seq);
        if (!wanted_ || std::regex_match(m->channel, *wanted_)) pending_.push_back(m->json);
    }
    void onStatus(const lcm::ReceiveBuffer*, const std::string&,
                  const busdecode_lcm::decode_status_t* m) {
        last_ = std::chrono::steady_clock::now();
        losses_.onStatus(m->state, m->events);
        if (until_end_ && m->state == "done") ended_ = true;  // "end" ends one capture only
    }

    std::shared_ptr<lcm::LCM> lc_;
    std::optional<double> timeout_s_;
    bool until_end_;
    pyb::object loads_;
    FeedLosses losses_;
    std::optional<std::regex> wanted_;
    std::deque<std::string> pending_;
    std::chrono::steady_clock::time_point last_;
    bool ended_ = false;
    bool busy_ = false;  // next() waits in handleTimeout() with the GIL released
    bool closed_ = false;
};

}  // namespace

void bindSubscribe(pyb::module_& m) {
    pyb::class_<Subscription>(m, "Subscription", "Events received from a decode --lcm feed.")
        .def("__iter__", [](Subscription& s) -> Subscription& { return s; })
        .def("__next__", &Subscription::next)
        .def("close", &Subscription::close, "Stops receiving; the iteration then ends.")
        .def("__enter__", [](Subscription& s) -> Subscription& { return s; })
        .def("__exit__", [](Subscription& s, const pyb::args&) { s.close(); })
        .def_property_readonly("lost", &Subscription::lost,
                               "Events of the feed known to be lost so far: gaps in their "
                               "numbering, and events the publisher counted that never came.");
    m.def(
        "subscribe_feed",
        [](const std::string& url, const std::vector<std::string>& channels,
           std::optional<double> timeout_s, bool until_end) {
            return std::make_unique<Subscription>(url, channels, timeout_s, until_end);
        },
        pyb::arg("url"), pyb::arg("channels"), pyb::arg("timeout"), pyb::arg("until_end"));
}

}  // namespace busdecode::py
