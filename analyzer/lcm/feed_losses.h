#pragma once
// Events of a `decode --lcm` feed that a subscriber never received. UDP multicast drops
// datagrams when a subscriber falls behind; each event's annotation carries its number
// in the run (seq, from 0), and the run's statuses how many it published.
#include <cstdint>
#include <string_view>

namespace busdecode {

class FeedLosses {
public:
    // An event annotation's seq: a gap before it is lost events.
    void onEvent(std::int64_t seq) {
        if (seq > next_seq_) lost_ += seq - next_seq_;
        if (seq >= next_seq_) next_seq_ = seq + 1;
    }
    // A DECODE_STATUS message: "start" begins a run (seq from 0 again); "end" and "done"
    // count what the publisher handed out, so the run's last events that never came count.
    void onStatus(std::string_view state, std::int64_t events) {
        if (state == "start") next_seq_ = 0;
        if ((state == "end" || state == "done") && events > next_seq_) {
            lost_ += events - next_seq_;
            next_seq_ = events;
        }
    }
    std::int64_t lost() const { return lost_; }

private:
    std::int64_t next_seq_ = 0, lost_ = 0;
};

}  // namespace busdecode
