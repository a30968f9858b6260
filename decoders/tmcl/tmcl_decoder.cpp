#include "tmcl_decoder.h"

#include <algorithm>

#include <fmt/format.h>

#include "core/registry.h"
#include "uart_decoder.h"

namespace busdecode {

using namespace tmcl;

namespace {

// Upper roles: host, module, bus. Lower (uart) roles: rx = 0, tx = 1.
constexpr int kUartRx = 0, kUartTx = 1;

// Every field of the contract exists on every command/reply event, null when unknown.
void commandFields(Event& e) {
    for (const char* k :
         {"address", "command", "mnemonic", "type_no", "motor", "value", "checksum_ok"})
        e.set(k, Null{});
}
void replyFields(Event& e) {
    for (const char* k : {"reply_address", "module_address", "status", "status_text", "command",
                          "value", "checksum_ok"})
        e.set(k, Null{});
}

}  // namespace

TmclDecoder::TmclDecoder(const Options& options) : BlockDecoder("tmcl"), options_(options) {
    if (options.has("gap_bytes")) gap_bytes_ = options.number("gap_bytes");
    if (options.has("host_address") && !options.isAuto("host_address"))
        host_address_ = int(options.integer("host_address"));
    if (options.has("module_address") && !options.isAuto("module_address"))
        module_address_ = int(options.integer("module_address"));
}

TmclDecoder::~TmclDecoder() = default;

void TmclDecoder::start(const DecoderContext& ctx) {
    Decoder::start(ctx);
    auto bound = [&](int role) {
        return role < int(ctx.initial_levels.size()) && ctx.initial_levels[role] >= 0;
    };
    // A bus line carries both directions. Automatic binding may also find lines named
    // tx/rx beside it; decoding them too would report every datagram twice, so the bus
    // wins and host/module are ignored when it is bound.
    if (!bound(kBus) && (bound(kHost) || bound(kModule))) {
        lines_ = std::make_unique<LowerStack>(
            "uart", options_, std::vector<int>{kUartTx, kUartRx, -1}, [this](Event&& e) {
                const auto* line = e.get("line");
                const bool tx = line && std::holds_alternative<std::string>(*line) &&
                                std::get<std::string>(*line) == "tx";
                onUartEvent(tx ? kHost : kModule, std::move(e));
            });
        lines_->start(ctx);
    }
    if (bound(kBus)) {
        bus_ = std::make_unique<LowerStack>("uart", options_, std::vector<int>{-1, -1, kUartRx},
                                            [this](Event&& e) { onUartEvent(kBus, std::move(e)); });
        bus_->start(ctx);
    }
}

void TmclDecoder::edge(Tick t, int role, bool level) {
    if (lines_) lines_->edge(t, role, level);
    if (bus_) bus_->edge(t, role, level);
    checkGaps(t);
}

void TmclDecoder::glitch(Tick t, int role) {
    if (lines_) lines_->glitch(t, role);
    if (bus_) bus_->glitch(t, role);
}

void TmclDecoder::advance(Tick now) {
    if (lines_) lines_->advance(now);
    if (bus_) bus_->advance(now);
    checkGaps(now);
}

void TmclDecoder::finish(Tick end) {
    if (lines_) lines_->finish(end);
    if (bus_) bus_->finish(end);
    for (int s = 0; s < 3; ++s)
        if (!partial_[s].empty()) flushShort(Stream(s));
    updateBusy();
}

Tick TmclDecoder::lowerWatermark(Tick now) const {
    Tick w = now;
    if (lines_) w = std::min(w, lines_->watermark(now));
    if (bus_) w = std::min(w, bus_->watermark(now));
    return w;
}

Tick TmclDecoder::watermark(Tick now) const {
    return std::min(Decoder::watermark(now), lowerWatermark(now));
}

void TmclDecoder::onUartEvent(Stream stream, Event&& e) {
    if (e.type != "byte") return;  // breaks and baud reports do not carry datagram bytes
    const Value* v = e.get("value");
    if (!v || isNull(*v)) {  // the capture ended mid-character
        if (!partial_[stream].empty()) flushShort(stream);
        return;
    }
    onByte(stream, ByteIn{std::uint8_t(asInt(*v)), e.start, e.end, !e.errors.empty()});
}

void TmclDecoder::onByte(Stream stream, const ByteIn& b) {
    auto& p = partial_[stream];
    if (!p.empty()) {
        const double gap = gap_bytes_ * double(p.back().end - p.back().start);
        if (double(b.start - p.back().end) > gap) flushShort(stream);
    }
    p.push_back(b);
    if (p.size() == 9) {
        std::vector<ByteIn> bytes;
        bytes.swap(p);
        onDatagram(stream, bytes);
    }
    updateBusy();
}

void TmclDecoder::checkGaps(Tick now) {
    // A datagram that stopped arriving: once the pause exceeds the gap (and no character
    // is under way in the UART below), it will not be completed.
    const Tick settled = lowerWatermark(now);
    for (int s = 0; s < 3; ++s) {
        auto& p = partial_[s];
        if (p.empty()) continue;
        const double gap = gap_bytes_ * double(p.back().end - p.back().start);
        if (double(settled - p.back().end) > gap) flushShort(Stream(s));
    }
    updateBusy();
}

void TmclDecoder::flushShort(Stream stream) {
    auto& p = partial_[stream];
    if (p.empty()) return;
    const bool reply = stream == kModule || (stream == kBus && pending_.awaiting);
    EventPtr owned = newEvent(reply ? "reply" : "command", p.front().start, p.back().end);
    Event& e = *owned;
    reply ? replyFields(e) : commandFields(e);
    std::vector<std::int64_t> bytes;
    for (const auto& b : p)
        bytes.push_back(b.value);
    e.set("bytes", bytes);
    e.set("length", std::int64_t(p.size()));
    e.error("short_frame");
    std::string hex;
    for (const auto& b : p)
        hex += fmt::format(" {:02X}", b.value);
    e.summary = fmt::format("{} cut short after {} of 9 bytes:{}", e.type, p.size(), hex);
    p.clear();
    emit(std::move(owned));
}

bool TmclDecoder::isReplyOnBus(const Datagram& d) const {
    if (host_address_ >= 0 && module_address_ >= 0 && host_address_ != module_address_) {
        if (d[0] == host_address_ && d[1] == module_address_) return true;
        if (d[0] == module_address_) return false;
    }
    const bool reply_shape = looksLikeReply(d) && (host_address_ < 0 || d[0] == host_address_);
    if (pending_.awaiting) {
        // The answer to the command before it: same command number, from the module
        // that was addressed. Failing that, a reply-shaped datagram that is not sent to
        // that module (a next command usually is).
        if (d[3] == pending_.command.command && d[1] == pending_.command.address) return true;
        return reply_shape && d[0] != pending_.command.address;
    }
    // No command to answer (the capture began mid-exchange, or the module did not
    // answer the last one): only a clean reply that reports success.
    return reply_shape && checksumOk(d) && (d[2] == 100 || d[2] == 101);
}

void TmclDecoder::onDatagram(Stream stream, const std::vector<ByteIn>& bytes) {
    Datagram d;
    bool fault = false;
    for (int i = 0; i < 9; ++i) {
        d[i] = bytes[i].value;
        fault = fault || bytes[i].fault;
    }
    const Tick start = bytes.front().start, end = bytes.back().end;
    const bool version_expected =
        pending_.awaiting && pending_.command.command == kGetVersion && pending_.command.type == 0;
    bool reply = stream == kModule;
    if (stream == kBus)
        reply = version_expected ? isVersionString(d) || isReplyOnBus(d) : isReplyOnBus(d);
    if (!reply) {
        emitCommand(d, start, end, fault);
        return;
    }
    // The GetVersion string reply has no checksum; recognise it by what was asked, or by
    // its printable characters where a checksum does not fit.
    if (isVersionString(d) && (version_expected || (!pending_.awaiting && !checksumOk(d))))
        emitVersionReply(d, start, end, fault);
    else
        emitReply(d, start, end, fault);
}

void TmclDecoder::emitCommand(const Datagram& d, Tick start, Tick end, bool fault) {
    const Command c = parseCommand(d);
    EventPtr owned = newEvent("command", start, end);
    Event& e = *owned;
    e.set("address", std::int64_t(c.address));
    e.set("command", std::int64_t(c.command));
    e.set("mnemonic", mnemonicOf(c.command));
    e.set("type_no", std::int64_t(c.type));
    e.set("motor", std::int64_t(c.motor));
    e.set("value", std::int64_t(c.value));
    e.set("checksum_ok", c.checksum_ok);
    e.set("checksum", std::int64_t(d[8]));
    const std::string param = parameterName(c);
    if (!param.empty()) e.set("parameter", param);
    const std::string text = ideLine(c);
    e.set("text", text);
    if (!c.checksum_ok) e.error("checksum");
    if (fault) e.error("framing");
    e.summary = c.address == 1 ? text : fmt::format("{}  (address {})", text, c.address);
    if (!c.checksum_ok)
        e.summary += fmt::format("  [checksum {:02X}, sum {:02X}]", d[8], checksumOf(d));
    pending_ = PendingCommand{c, text, start, end, true};
    emit(std::move(owned));
}

void TmclDecoder::pairWithCommand(Event& e, Tick start, Tick end) {
    if (!pending_.awaiting || pending_.end > start) return;
    e.set("request", pending_.text);
    e.set("request_start_ns", tb().toNs(pending_.start));
    // Differences in ticks first: converting two far-apart times to ns and subtracting
    // could overflow (fuzz finding).
    e.set("rtt_ns", tb().toNs(end - pending_.start));
    e.set("latency_ns", tb().toNs(start - pending_.end));
    pending_.awaiting = false;
}

void TmclDecoder::emitReply(const Datagram& d, Tick start, Tick end, bool fault) {
    const Reply r = parseReply(d);
    EventPtr owned = newEvent("reply", start, end);
    Event& e = *owned;
    e.set("reply_address", std::int64_t(r.reply_address));
    e.set("module_address", std::int64_t(r.module_address));
    e.set("status", std::int64_t(r.status));
    const std::string text = statusText(r.status);
    e.set("status_text", text.empty() ? fmt::format("unknown status {}", r.status) : text);
    e.set("command", std::int64_t(r.command));
    e.set("value", std::int64_t(r.value));
    e.set("checksum_ok", r.checksum_ok);
    e.set("checksum", std::int64_t(d[8]));
    e.set("mnemonic", mnemonicOf(r.command));
    const bool answers = pending_.awaiting && pending_.command.command == r.command;
    pairWithCommand(e, start, end);
    if (!r.checksum_ok) e.error("checksum");
    if (fault) e.error("framing");
    e.summary = fmt::format("reply {} <- {}: {} {}, {} value {}", r.reply_address, r.module_address,
                            r.status, text.empty() ? "unknown status" : text, mnemonicOf(r.command),
                            r.value);
    if (const Value* rtt = e.get("rtt_ns"))
        e.summary += fmt::format("  (rtt {:.3f} ms{})", double(asInt(*rtt)) / 1e6,
                                 answers ? "" : ", answers another command");
    if (!r.checksum_ok)
        e.summary += fmt::format("  [checksum {:02X}, sum {:02X}]", d[8], checksumOf(d));
    emit(std::move(owned));
}

void TmclDecoder::emitVersionReply(const Datagram& d, Tick start, Tick end, bool fault) {
    EventPtr owned = newEvent("reply", start, end);
    Event& e = *owned;
    replyFields(e);
    e.set("reply_address", std::int64_t(d[0]));
    e.set("status_text", std::string("version string"));
    e.set("command", std::int64_t(kGetVersion));
    e.set("mnemonic", std::string("GetVersion"));
    const std::string version(d.begin() + 1, d.end());
    e.set("version", version);
    pairWithCommand(e, start, end);
    if (fault) e.error("framing");
    e.summary = fmt::format("reply {}: GetVersion \"{}\"", d[0], version);
    emit(std::move(owned));
}

void TmclDecoder::updateBusy() {
    Tick busy = kNoTick;
    for (const auto& p : partial_)
        if (!p.empty() && (busy == kNoTick || p.front().start < busy)) busy = p.front().start;
    if (busy == kNoTick)
        idle();
    else
        setBusyFrom(busy);
}

std::vector<std::string> TmclDecoder::advice() const {
    std::vector<std::string> out;
    for (const auto* stack : {lines_.get(), bus_.get()})
        if (stack)
            for (auto& a : stack->lower().advice())
                out.push_back("its UART: " + a);
    return out;
}

}  // namespace busdecode
