#include "lcm_message_view.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <lcm/lcm-cpp.hpp>

#include "busdecode_lcm/bissc_command_t.hpp"
#include "busdecode_lcm/bissc_frame_t.hpp"
#include "busdecode_lcm/bissc_register_t.hpp"
#include "busdecode_lcm/event_fields_t.hpp"
#include "busdecode_lcm/spi_transfer_t.hpp"
#include "busdecode_lcm/ssi_frame_t.hpp"
#include "busdecode_lcm/tmc8100_command_t.hpp"
#include "busdecode_lcm/tmc8100_encoder_read_t.hpp"
#include "busdecode_lcm/tmc8100_reply_t.hpp"
#include "busdecode_lcm/tmcl_command_t.hpp"
#include "busdecode_lcm/tmcl_reply_t.hpp"
#include "busdecode_lcm/uart_byte_t.hpp"

namespace busdecode::test {

namespace {

Value I(std::int64_t v) {
    return Value{v};
}
Value D(double v) {
    return std::isfinite(v) ? Value{v} : Value{Null{}};
}
Value B(bool v) {
    return Value{v};
}
Value S(const std::string& v) {
    return Value{v};
}

template <class Msg>
bool decodeInto(Msg& m, const void* data, int size) {
    return m.decode(data, 0, size) >= 0;
}

// The header every typed message shares; null_fields become Null.
template <class Msg>
void common(MessageView& v, const Msg& m) {
    v.utime = m.utime;
    v.seq = m.seq;
    v.start_ns = m.start_ns;
    v.end_ns = m.end_ns;
    v.instance = m.instance;
    v.errors = m.errors;
}
template <class Msg>
void applyNulls(MessageView& v, const Msg& m) {
    for (const auto& k : m.null_fields)
        v.fields[k] = Null{};
}

template <class Msg, class Fill>
std::optional<MessageView> typed(const std::string& ch, const void* data, int size, Fill fill) {
    Msg m;
    if (!decodeInto(m, data, size)) {
        ADD_FAILURE() << "message on " << ch << " does not decode as " << Msg::getTypeName();
        return std::nullopt;
    }
    MessageView v;
    v.channel = ch;
    common(v, m);
    fill(v.fields, m);
    applyNulls(v, m);
    return v;
}

using Viewer = std::function<std::optional<MessageView>(const std::string&, const void*, int)>;
using Viewers = std::map<std::string, Viewer>;
namespace M = busdecode_lcm;
using F = std::map<std::string, Value>;

// A channel's typed message, its fields set by `fill`.
template <class Msg, class Fill>
Viewer viewAs(Fill fill) {
    return [fill](const std::string& ch, const void* data, int size) {
        return typed<Msg>(ch, data, size, fill);
    };
}

void addEncoderViewers(Viewers& v) {
    v["DECODE_SSI_FRAME"] = viewAs<M::ssi_frame_t>([](F& f, const M::ssi_frame_t& m) {
        f = {{"raw", I(m.raw)},
             {"bits", I(m.bits)},
             {"position", I(m.position)},
             {"st", I(m.st)},
             {"mt", I(m.mt)},
             {"angle", D(m.angle)},
             {"repeats", I(m.repeats)},
             {"repeat_match", B(m.repeat_match)},
             {"clock_hz", D(m.clock_hz)},
             {"tm_ns", m.has_tm_ns ? D(m.tm_ns) : Value{Null{}}}};
    });
    v["DECODE_BISSC_FRAME"] = viewAs<M::bissc_frame_t>([](F& f, const M::bissc_frame_t& m) {
        f = {{"position", I(m.position)},
             {"st", I(m.st)},
             {"mt", I(m.mt)},
             {"nE", I(m.nE)},
             {"nW", I(m.nW)},
             {"crc_rx", I(m.crc_rx)},
             {"crc_ok", B(m.crc_ok)},
             {"cds", I(m.cds)},
             {"cdm", I(m.cdm)},
             {"line_delay_ns", D(m.line_delay_ns)},
             {"proc_cycles", I(m.proc_cycles)},
             {"clock_hz", D(m.clock_hz)},
             {"timeout_ns", D(m.timeout_ns)}};
    });
    v["DECODE_BISSC_REGISTER"] =
        viewAs<M::bissc_register_t>([](F& f, const M::bissc_register_t& m) {
            f = {{"op", S(m.op)},
                 {"id", I(m.id)},
                 {"address", I(m.address)},
                 {"data", Value{m.data}},
                 {"crc_ok", B(m.crc_ok)}};
        });
    v["DECODE_BISSC_COMMAND"] = viewAs<M::bissc_command_t>([](F& f, const M::bissc_command_t& m) {
        f = {{"id", I(m.id)}, {"command", I(m.command)}, {"crc_ok", B(m.crc_ok)}};
    });
}

void addDriveViewers(Viewers& v) {
    v["DECODE_SPI_TRANSFER"] = viewAs<M::spi_transfer_t>([](F& f, const M::spi_transfer_t& m) {
        f = {{"mosi", I(m.mosi)}, {"miso", I(m.miso)}, {"bits", I(m.bits)}};
    });
    v["DECODE_TMC8100_COMMAND"] =
        viewAs<M::tmc8100_command_t>([](F& f, const M::tmc8100_command_t& m) {
            f = {{"code", I(m.code)}, {"name", S(m.name)}};
        });
    v["DECODE_TMC8100_REPLY"] = viewAs<M::tmc8100_reply_t>([](F& f, const M::tmc8100_reply_t& m) {
        f = {{"tag", I(m.tag)}, {"value", I(m.value)}, {"meaning", S(m.meaning)}};
    });
    v["DECODE_TMC8100_ENCODER_READ"] =
        viewAs<M::tmc8100_encoder_read_t>([](F& f, const M::tmc8100_encoder_read_t& m) {
            f = {{"gray", I(m.gray)},
                 {"binary", I(m.binary)},
                 {"flags", I(m.flags)},
                 {"consistent", B(m.consistent)}};
            if (m.has_ssi_match) f["ssi_match"] = B(m.ssi_match);
        });
    v["DECODE_UART_BYTE"] = viewAs<M::uart_byte_t>([](F& f, const M::uart_byte_t& m) {
        f = {{"value", I(m.value)}, {"line", S(m.line)}};
    });
    v["DECODE_TMCL_COMMAND"] = viewAs<M::tmcl_command_t>([](F& f, const M::tmcl_command_t& m) {
        f = {{"address", I(m.address)},
             {"command", I(m.command)},
             {"mnemonic", S(m.mnemonic)},
             {"type_no", I(m.type_no)},
             {"motor", I(m.motor)},
             {"value", I(m.value)},
             {"checksum_ok", B(m.checksum_ok)}};
    });
    v["DECODE_TMCL_REPLY"] = viewAs<M::tmcl_reply_t>([](F& f, const M::tmcl_reply_t& m) {
        f = {{"reply_address", I(m.reply_address)},
             {"module_address", I(m.module_address)},
             {"status", I(m.status)},
             {"status_text", S(m.status_text)},
             {"command", I(m.command)},
             {"value", I(m.value)},
             {"checksum_ok", B(m.checksum_ok)}};
    });
}

// A channel without a typed message: the generic key/value message.
std::optional<MessageView> viewGenericMessage(const std::string& ch, const void* data, int size) {
    M::event_fields_t m;
    if (!decodeInto(m, data, size)) {
        ADD_FAILURE() << "message on " << ch << " does not decode as event_fields_t";
        return std::nullopt;
    }
    MessageView v;
    v.channel = ch;
    common(v, m);
    for (const auto& f : m.fields) {
        using K = M::event_field_t;
        switch (f.kind) {
            case K::KIND_NULL:
                v.fields[f.key] = Null{};
                break;
            case K::KIND_BOOL:
                v.fields[f.key] = f.integer != 0;
                break;
            case K::KIND_INT:
                v.fields[f.key] = f.integer;
                break;
            case K::KIND_UINT:
                v.fields[f.key] = std::uint64_t(f.integer);
                break;
            case K::KIND_DOUBLE:
                v.fields[f.key] = f.number;
                break;
            case K::KIND_STRING:
                v.fields[f.key] = S(f.text);
                break;
            default:
                v.fields[f.key] = S(f.json);
                break;  // lists: their JSON text
        }
    }
    return v;
}

}  // namespace

std::optional<MessageView> viewEventMessage(const std::string& ch, const void* data, int size) {
    static const Viewers viewers = [] {
        Viewers v;
        addEncoderViewers(v);
        addDriveViewers(v);
        return v;
    }();
    const auto it = viewers.find(ch);
    return it != viewers.end() ? it->second(ch, data, size) : viewGenericMessage(ch, data, size);
}

Collector::Collector(lcm::LCM& lc) {
    lc.subscribe(".*", &Collector::onMessage, this);
}

void Collector::drain(lcm::LCM& lc) {
    while (lc.handleTimeout(0) > 0) {
    }
}

void Collector::add(const std::string& channel, const void* data, int size) {
    auto p = static_cast<const std::uint8_t*>(data);
    byChannel[channel].emplace_back(p, p + size);
    order.push_back(channel);
}

void Collector::onMessage(const lcm::ReceiveBuffer* rb, const std::string& channel) {
    add(channel, rb->data, int(rb->data_size));
}

}  // namespace busdecode::test
