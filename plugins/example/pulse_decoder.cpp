#include "pulse_decoder.h"

#include <string>

namespace pulse {

using namespace busdecode;

class PulseDecoder : public Decoder {
public:
    explicit PulseDecoder(const Options& o)
        : Decoder("pulse"), active_high_(o.text("active") == "high"), min_ns_(o.number("min_ns")) {}

    void edge(Tick t, int, bool level) override {
        if (level == active_high_) {
            since_ = t;
            busyFrom(t);
            return;
        }
        if (since_ == kNoTick) return;  // the capture started inside a pulse
        EventPtr e = newEvent("pulse", since_, t);
        const double width = tb().toNsF(double(t - since_));
        e->add("width_ns", width);
        if (width < min_ns_) e->error("short");
        e->summary = "width " + std::to_string(width) + " ns";
        emit(std::move(e));
        since_ = kNoTick;
        idle();
    }
    void finish(Tick) override { idle(); }

private:
    bool active_high_;
    double min_ns_;
    Tick since_ = kNoTick;
};

std::shared_ptr<const DecoderFactory> makePulseFactory() {
    DecoderInfo d;
    d.id = "pulse";
    d.name = "Pulse widths (example plugin)";
    d.description = "Reports each active pulse on one line with its width.";
    d.roles = {{"line", true, {"line", "in", "sig"}, "the line to watch"}};
    d.options = {choiceOption("active", {"high", "low"}, "which level is a pulse"),
                 numberOption("min_ns", "0", 0, 1e300, "flag pulses shorter than this as `short`")};
    d.events = {{"pulse", "one active pulse", {{"width_ns", FieldSpec::Kind::Number}}}};
    return std::make_shared<SimpleFactory<PulseDecoder>>(std::move(d));
}

}  // namespace pulse
