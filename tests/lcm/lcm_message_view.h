#pragma once
// Test helpers: decode any busdecode LCM message (by channel) into a field-name -> value
// view, so tests compare messages with events and with `--format jsonl` output by name,
// and collect what an LCM instance receives.
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "core/value.h"

namespace lcm {
class LCM;
class ReceiveBuffer;
}  // namespace lcm

namespace busdecode::test {

// One decoded event message (typed or event_fields_t), as fields by name.
struct MessageView {
    std::string channel;
    std::int64_t utime = 0, seq = -1, start_ns = 0, end_ns = 0;
    std::string instance;
    std::vector<std::string> errors;
    std::map<std::string, Value> fields;  // null fields (null_fields, has_X = false) are Null
};

// Decodes a message published on DECODE_<PROTO>_<TYPE>; nullopt (with a gtest failure)
// when the bytes do not decode as the channel's type.
std::optional<MessageView> viewEventMessage(const std::string& channel, const void* data, int size);

// Everything one LCM instance received, per channel, in arrival order.
class Collector {
public:
    explicit Collector(lcm::LCM& lc);
    // Handles whatever is pending (memq:// delivers on handle()).
    void drain(lcm::LCM& lc);
    void add(const std::string& channel, const void* data, int size);
    std::map<std::string, std::vector<std::vector<std::uint8_t>>> byChannel;
    std::vector<std::string> order;  // channel of each message, in arrival order

    template <class Msg>
    std::vector<Msg> decodeAll(const std::string& channel) const;

private:
    void onMessage(const lcm::ReceiveBuffer* rb, const std::string& channel);
};

template <class Msg>
std::vector<Msg> Collector::decodeAll(const std::string& channel) const {
    std::vector<Msg> out;
    auto it = byChannel.find(channel);
    if (it == byChannel.end()) return out;
    for (const auto& bytes : it->second) {
        Msg m;
        if (m.decode(bytes.data(), 0, int(bytes.size())) < 0) continue;
        out.push_back(std::move(m));
    }
    return out;
}

}  // namespace busdecode::test
