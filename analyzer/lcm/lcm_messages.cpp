#include "lcm_messages.h"

#include <chrono>
#include <cmath>
#include <functional>
#include <lcm/lcm-cpp.hpp>
#include <limits>
#include <map>
#include <utility>
#include <vector>

#include "busdecode_lcm/bissc_command_t.hpp"
#include "busdecode_lcm/bissc_frame_t.hpp"
#include "busdecode_lcm/bissc_register_t.hpp"
#include "busdecode_lcm/event_annotation_t.hpp"
#include "busdecode_lcm/event_fields_t.hpp"
#include "busdecode_lcm/spi_transfer_t.hpp"
#include "busdecode_lcm/ssi_frame_t.hpp"
#include "busdecode_lcm/tmc8100_command_t.hpp"
#include "busdecode_lcm/tmc8100_encoder_read_t.hpp"
#include "busdecode_lcm/tmc8100_reply_t.hpp"
#include "busdecode_lcm/tmcl_command_t.hpp"
#include "busdecode_lcm/tmcl_reply_t.hpp"
#include "busdecode_lcm/uart_byte_t.hpp"
#include "lcm_channels.h"
#include "sinks/event_format.h"

namespace busdecode {

namespace {

// Reads contract fields by name and remembers which ones were null or missing (or of a
// kind that can't be represented, e.g. a string where a number is expected).
class FieldReader {
public:
    explicit FieldReader(const Event& e) : e_(e) {}

    std::int64_t integer(const char* key) {
        const Value* v = numeric(key);
        if (!v) return 0;
        if (auto d = std::get_if<double>(v)) return std::isfinite(*d) ? std::int64_t(*d) : 0;
        return asInt(*v);  // bool 0/1; a uint64 keeps its bit pattern
    }
    double real(const char* key) {
        const Value* v = numeric(key);
        return v ? asDouble(*v) : std::numeric_limits<double>::quiet_NaN();
    }
    bool flag(const char* key) {
        const Value* v = numeric(key);
        return v && asDouble(*v) != 0.0;
    }
    std::string text(const char* key) {
        const Value* v = e_.get(key);
        if (auto s = v ? std::get_if<std::string>(v) : nullptr) return *s;
        nulls_.push_back(key);
        return {};
    }
    // A list of integers; a single number becomes a one-element list.
    std::vector<std::int64_t> list(const char* key) {
        const Value* v = e_.get(key);
        if (auto l = v ? std::get_if<std::vector<std::int64_t>>(v) : nullptr) return *l;
        if (v && !isNull(*v) && !std::holds_alternative<std::string>(*v)) return {asInt(*v)};
        nulls_.push_back(key);
        return {};
    }
    // Whether the field holds a value; no null_fields entry (for has_X flags).
    bool present(const char* key) const {
        const Value* v = e_.get(key);
        return v && !isNull(*v);
    }

    const std::vector<std::string>& nulls() const { return nulls_; }

private:
    const Value* numeric(const char* key) {
        const Value* v = e_.get(key);
        if (!v || isNull(*v) || std::holds_alternative<std::string>(*v) ||
            std::holds_alternative<std::vector<std::int64_t>>(*v)) {
            nulls_.push_back(key);
            return nullptr;
        }
        return v;
    }

    const Event& e_;
    std::vector<std::string> nulls_;
};

struct Stamp {
    const Event& e;
    const Timebase& tb;
    std::int64_t seq;
    std::int64_t utime;
    std::string_view capture_fields = {};
};

// The stamp every message carries: times, sequence, instance, errors.
template <class Msg>
void fillStamp(Msg& m, const Stamp& s) {
    m.utime = s.utime;
    m.seq = s.seq;
    m.start_ns = s.tb.toNs(s.e.start);
    m.end_ns = s.tb.toNs(s.e.end);
    m.instance = s.e.instance.empty() ? s.e.proto : s.e.instance;
    m.errors = s.e.errors;
    m.num_errors = static_cast<std::int16_t>(m.errors.size());
}

// The leading fields every typed message shares.
template <class Msg>
void fillCommon(Msg& m, const Stamp& s, const FieldReader& r) {
    fillStamp(m, s);
    m.null_fields = r.nulls();
    m.num_null_fields = static_cast<std::int16_t>(m.null_fields.size());
}

using Publisher = std::function<int(lcm::LCM&, const std::string&, const Stamp&)>;

template <class Msg, class Fill>
Publisher typed(Fill fill) {
    return [fill](lcm::LCM& lc, const std::string& channel, const Stamp& s) {
        Msg m{};
        FieldReader r(s.e);
        fill(m, r);
        fillCommon(m, s, r);
        return lc.publish(channel, &m);
    };
}

// The message fields of each typed event, one filler per LCM type.
void fillSsiFrame(busdecode_lcm::ssi_frame_t& m, FieldReader& r) {
    m.raw = r.integer("raw");
    m.bits = int32_t(r.integer("bits"));
    m.position = r.integer("position");
    m.st = r.integer("st");
    m.mt = r.integer("mt");
    m.angle = r.real("angle");
    m.repeats = int32_t(r.integer("repeats"));
    m.repeat_match = r.flag("repeat_match");
    m.clock_hz = r.real("clock_hz");
    m.has_tm_ns = r.present("tm_ns");
    m.tm_ns = r.real("tm_ns");
}

void fillBisscFrame(busdecode_lcm::bissc_frame_t& m, FieldReader& r) {
    m.position = r.integer("position");
    m.st = r.integer("st");
    m.mt = r.integer("mt");
    m.nE = int8_t(r.integer("nE"));
    m.nW = int8_t(r.integer("nW"));
    m.crc_rx = int8_t(r.integer("crc_rx"));
    m.crc_ok = r.flag("crc_ok");
    m.cds = int8_t(r.integer("cds"));
    m.cdm = int8_t(r.integer("cdm"));
    m.line_delay_ns = r.real("line_delay_ns");
    m.proc_cycles = int32_t(r.integer("proc_cycles"));
    m.clock_hz = r.real("clock_hz");
    m.timeout_ns = r.real("timeout_ns");
}

void fillBisscRegister(busdecode_lcm::bissc_register_t& m, FieldReader& r) {
    m.op = r.text("op");
    m.id = int32_t(r.integer("id"));
    m.address = int32_t(r.integer("address"));
    m.data = r.list("data");
    m.num_data = int16_t(m.data.size());
    m.crc_ok = r.flag("crc_ok");
}

void fillBisscCommand(busdecode_lcm::bissc_command_t& m, FieldReader& r) {
    m.id = int32_t(r.integer("id"));
    m.command = int32_t(r.integer("command"));
    m.crc_ok = r.flag("crc_ok");
}

void fillSpiTransfer(busdecode_lcm::spi_transfer_t& m, FieldReader& r) {
    m.mosi = r.integer("mosi");
    m.miso = r.integer("miso");
    m.bits = int32_t(r.integer("bits"));
}

void fillTmc8100Command(busdecode_lcm::tmc8100_command_t& m, FieldReader& r) {
    m.code = int32_t(r.integer("code"));
    m.name = r.text("name");
}

void fillTmc8100Reply(busdecode_lcm::tmc8100_reply_t& m, FieldReader& r) {
    m.tag = int32_t(r.integer("tag"));
    m.value = r.integer("value");
    m.meaning = r.text("meaning");
}

void fillTmc8100EncoderRead(busdecode_lcm::tmc8100_encoder_read_t& m, FieldReader& r) {
    m.gray = r.integer("gray");
    m.binary = r.integer("binary");
    m.flags = r.integer("flags");
    m.consistent = r.flag("consistent");
    // ssi_match exists only when the SSI side is decoded in the same pass:
    // its absence is not a fault, so it is not listed in null_fields.
    m.has_ssi_match = r.present("ssi_match");
    if (m.has_ssi_match) m.ssi_match = r.flag("ssi_match");
}

void fillUartByte(busdecode_lcm::uart_byte_t& m, FieldReader& r) {
    m.value = int32_t(r.integer("value"));
    m.line = r.text("line");
}

void fillTmclCommand(busdecode_lcm::tmcl_command_t& m, FieldReader& r) {
    m.address = int32_t(r.integer("address"));
    m.command = int32_t(r.integer("command"));
    m.mnemonic = r.text("mnemonic");
    m.type_no = int32_t(r.integer("type_no"));
    m.motor = int32_t(r.integer("motor"));
    m.value = int32_t(r.integer("value"));
    m.checksum_ok = r.flag("checksum_ok");
}

void fillTmclReply(busdecode_lcm::tmcl_reply_t& m, FieldReader& r) {
    m.reply_address = int32_t(r.integer("reply_address"));
    m.module_address = int32_t(r.integer("module_address"));
    m.status = int32_t(r.integer("status"));
    m.status_text = r.text("status_text");
    m.command = int32_t(r.integer("command"));
    m.value = int32_t(r.integer("value"));
    m.checksum_ok = r.flag("checksum_ok");
}

const std::map<std::pair<std::string_view, std::string_view>, Publisher>& typedPublishers() {
    namespace M = busdecode_lcm;
    static const std::map<std::pair<std::string_view, std::string_view>, Publisher> table{
        {{"ssi", "frame"}, typed<M::ssi_frame_t>(fillSsiFrame)},
        {{"bissc", "frame"}, typed<M::bissc_frame_t>(fillBisscFrame)},
        {{"bissc", "register"}, typed<M::bissc_register_t>(fillBisscRegister)},
        {{"bissc", "command"}, typed<M::bissc_command_t>(fillBisscCommand)},
        {{"spi", "transfer"}, typed<M::spi_transfer_t>(fillSpiTransfer)},
        {{"tmc8100", "command"}, typed<M::tmc8100_command_t>(fillTmc8100Command)},
        {{"tmc8100", "reply"}, typed<M::tmc8100_reply_t>(fillTmc8100Reply)},
        {{"tmc8100", "encoder_read"}, typed<M::tmc8100_encoder_read_t>(fillTmc8100EncoderRead)},
        {{"uart", "byte"}, typed<M::uart_byte_t>(fillUartByte)},
        {{"tmcl", "command"}, typed<M::tmcl_command_t>(fillTmclCommand)},
        {{"tmcl", "reply"}, typed<M::tmcl_reply_t>(fillTmclReply)},
    };
    return table;
}

busdecode_lcm::event_field_t genericField(const Field& f) {
    using F = busdecode_lcm::event_field_t;
    F out{};
    out.key = f.key;
    out.json = valueToJson(f.value);
    out.number = asDouble(f.value);
    out.integer = 0;
    std::visit(
        [&](const auto& v) {
            using T = std::decay_t<decltype(v)>;
            if constexpr (std::is_same_v<T, Null>) {
                out.kind = F::KIND_NULL;
            } else if constexpr (std::is_same_v<T, bool>) {
                out.kind = F::KIND_BOOL;
                out.integer = v ? 1 : 0;
            } else if constexpr (std::is_same_v<T, std::int64_t>) {
                out.kind = F::KIND_INT;
                out.integer = v;
            } else if constexpr (std::is_same_v<T, std::uint64_t>) {
                out.kind = F::KIND_UINT;
                out.integer = static_cast<std::int64_t>(v);
            } else if constexpr (std::is_same_v<T, double>) {
                out.kind = F::KIND_DOUBLE;
            } else if constexpr (std::is_same_v<T, std::string>) {
                out.kind = F::KIND_STRING;
                out.text = v;
            } else {
                out.kind = F::KIND_INT_LIST;
            }
        },
        f.value);
    return out;
}

int publishGeneric(lcm::LCM& lc, const std::string& channel, const Stamp& s) {
    busdecode_lcm::event_fields_t m{};
    fillStamp(m, s);
    m.proto = s.e.proto;
    m.type = s.e.type;
    for (const Field& f : s.e.fields)
        m.fields.push_back(genericField(f));
    m.num_fields = static_cast<std::int16_t>(m.fields.size());
    return lc.publish(channel, &m);
}

int publishAnnotation(lcm::LCM& lc, const std::string& typed_channel, const Stamp& s) {
    busdecode_lcm::event_annotation_t m{};
    fillStamp(m, s);
    m.proto = s.e.proto;
    m.type = s.e.type;
    m.channel = typed_channel;
    m.text = eventToText(s.e, s.tb);
    m.json = eventToJson(s.e, s.tb, s.capture_fields);
    return lc.publish(kLcmEventsChannel, &m);
}

}  // namespace

bool hasTypedLcmMessage(std::string_view proto, std::string_view type) {
    return typedPublishers().count({proto, type}) != 0;
}

std::int64_t lcmUtimeNow() {
    using namespace std::chrono;
    return duration_cast<microseconds>(system_clock::now().time_since_epoch()).count();
}

LcmPublishResult publishEventToLcm(lcm::LCM& lc, const Event& e, const Timebase& tb,
                                   std::int64_t seq, std::string_view capture_fields) {
    Stamp s{e, tb, seq, lcmUtimeNow(), capture_fields};
    LcmPublishResult out;
    out.channel = lcmChannelFor(e.proto, e.type);
    const auto& table = typedPublishers();
    auto it = table.find({e.proto, e.type});
    int rc =
        it != table.end() ? it->second(lc, out.channel, s) : publishGeneric(lc, out.channel, s);
    if (rc != 0) ++out.failures;
    if (publishAnnotation(lc, out.channel, s) != 0) ++out.failures;
    return out;
}

}  // namespace busdecode
