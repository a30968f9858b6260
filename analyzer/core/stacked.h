#pragma once
// Stacking (SPI -> TMC8100, UART -> TMCL): an upper decoder owns a lower one created
// through the registry, forwards the edges of the roles it maps onto the lower one's
// roles, and receives the lower decoder's events instead of the output.
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "decoder.h"

namespace busdecode {

class LowerStack : public EventSink {
public:
    using Handler = std::function<void(Event&&)>;
    // role_map[upper role index] = lower role index, or -1 when not forwarded.
    // Options of the upper decoder whose keys the lower decoder declares are passed on.
    LowerStack(const std::string& lower_id, const Options& upper_options, std::vector<int> role_map,
               Handler on_lower_event);
    ~LowerStack() override;

    void start(const DecoderContext& upper_ctx);
    void edge(Tick t, int upper_role, bool level);
    void advance(Tick now);
    void finish(Tick end);
    void glitch(Tick t, int upper_role);
    Tick watermark(Tick now) const;
    Decoder& lower() { return *lower_; }
    const Decoder& lower() const { return *lower_; }

    void onEvent(Event&& e) override { handler_(std::move(e)); }

private:
    std::unique_ptr<Decoder> lower_;
    std::vector<int> role_map_;
    Handler handler_;
    int lower_roles_ = 0;
};

}  // namespace busdecode
