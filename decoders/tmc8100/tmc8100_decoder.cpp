#include "tmc8100_decoder.h"

#include <algorithm>
#include <limits>

#include <fmt/format.h>

#include "core/bit_word.h"
#include "core/event_window.h"
#include "core/gray.h"
#include "spi_info.h"

namespace busdecode {

using namespace tmc8100;

namespace {
std::optional<std::uint64_t> wordOf(const Event& e, const char* key) {
    const Value* v = e.get(key);
    if (!v || isNull(*v)) return std::nullopt;
    return std::uint64_t(asInt(*v));
}
}  // namespace

Tmc8100Decoder::Tmc8100Decoder(const Options& o)
    : BlockDecoder("tmc8100"),
      stack_("spi", o, {kSpiCs, kSpiSclk, kSpiMosi, kSpiMiso, -1},
             [this](Event&& e) { onTransfer(std::move(e)); }),
      mode_option_(o.text("mode")) {
    const std::string& enc = o.text("encoder");
    protocol_fixed_ = enc != "auto";
    if (enc == "ssi") protocol_ = EncoderProtocol::Ssi;
    if (enc == "biss") protocol_ = EncoderProtocol::Biss;
}

void Tmc8100Decoder::start(const DecoderContext& ctx) {
    Decoder::start(ctx);
    stack_.start(ctx);
    const int lv = kTmcAvail < int(ctx.initial_levels.size()) ? ctx.initial_levels[kTmcAvail] : -1;
    avail_bound_ = lv >= 0;
    avail_level_ = lv == 1;
    miso_bound_ = kTmcMiso < int(ctx.initial_levels.size()) && ctx.initial_levels[kTmcMiso] >= 0;
    firmware_ = mode_option_ == "app"          ? Firmware::App
                : mode_option_ == "bootloader" ? Firmware::Bootloader
                                               : Firmware::Unknown;
}

void Tmc8100Decoder::edge(Tick t, int role, bool level) {
    if (role != kTmcAvail) {
        stack_.edge(t, role, level);
        updateBusy();
        return;
    }
    // Let the SPI layer finish every word that ended before this GPIO6 edge first.
    stack_.advance(t);
    if (level && !avail_level_) {
        bool someone_waits = false;
        for (auto& w : waiting_) {
            someone_waits = true;
            if (w.avail_rise == kNoTick) w.avail_rise = t;
        }
        if (!someone_waits && firmware_ == Firmware::App && miso_bound_) {
            // The firmware raises SPI_DATA_AVAILABLE when it queues replies; nothing asked.
            EventPtr owned = newEvent("avail", t, t);
            Event& e = *owned;
            e.set("level", std::int64_t(1));
            e.error("unexpected_avail");
            e.summary = "GPIO6 (SPI_DATA_AVAILABLE) rose with no command waiting for replies";
            emit(std::move(owned));
        }
    }
    avail_level_ = level;
    updateBusy();
}

void Tmc8100Decoder::advance(Tick now) {
    stack_.advance(now);
    updateBusy();
}

void Tmc8100Decoder::glitch(Tick t, int role) {
    stack_.glitch(t, role);
}

Tick Tmc8100Decoder::watermark(Tick now) const {
    return std::min(Decoder::watermark(now), stack_.watermark(now));
}

void Tmc8100Decoder::updateBusy() {
    // Events may still start at the oldest command waiting for replies, or at the first
    // 8/16-bit frame of a datagram still being assembled.
    Tick from = kNoTick;
    if (!waiting_.empty()) from = waiting_.front().start;
    if (acc_bits_ > 0 && (from == kNoTick || acc_start_ < from)) from = acc_start_;
    if (from == kNoTick)
        idle();
    else
        setBusyFrom(from);
}

void Tmc8100Decoder::onTransfer(Event&& spi) {
    const auto mosi = wordOf(spi, "mosi");
    const auto miso = wordOf(spi, "miso");
    const int bits = int(asInt(*spi.get("bits")));
    const bool short_frame = spi.hasError("short_frame");
    if (!short_frame && bits < 32 && 32 % bits == 0) {
        // Hosts that clock 8- or 16-bit frames under one cs (the Landungsbruecke sends
        // four bytes): the datagram is their concatenation, first word most significant.
        if (acc_bits_ == 0) acc_start_ = spi.start;
        acc_mosi_ = (acc_mosi_ << bits) | mosi.value_or(0);
        acc_miso_ = (acc_miso_ << bits) | miso.value_or(0);
        acc_bits_ += bits;
        if (acc_bits_ < 32) {
            updateBusy();
            return;
        }
        Event dg = std::move(spi);
        dg.start = acc_start_;
        if (mosi) dg.set("mosi", acc_mosi_);
        if (miso) dg.set("miso", acc_miso_);
        dg.set("bits", std::int64_t(32));
        acc_bits_ = 0;
        acc_mosi_ = acc_miso_ = 0;
        onTransfer(std::move(dg));
        return;
    }
    if (short_frame || bits != 32) {
        acc_bits_ = 0;
        acc_mosi_ = acc_miso_ = 0;
        // Not a datagram: report what was on MOSI without giving it a meaning.
        EventPtr owned = newEvent("command", spi.start, spi.end);
        Event& e = *owned;
        e.set("code", mosi && bits >= 8 ? Value(std::int64_t((*mosi >> (bits - 8)) & 0xFF))
                                        : Value(Null{}));
        e.set("name", std::string("unknown"));
        e.set("word", mosi ? Value(*mosi) : Value(Null{}));
        e.errors = spi.errors;
        e.summary = fmt::format("{}-bit word, not a 32-bit datagram", bits);
        emit(std::move(owned));
        return;
    }
    if (miso) onMiso(std::uint32_t(*miso), spi);
    if (mosi) onMosi(std::uint32_t(*mosi), spi);
    updateBusy();
}

void Tmc8100Decoder::emitReply(ReplyKind kind, std::uint32_t word, const Event& spi,
                               const Waiting* w, std::vector<std::string> errors) {
    EventPtr owned = newEvent("reply", spi.start, spi.end);
    Event& e = *owned;
    e.set("tag", std::int64_t(word >> 24));
    e.set("value", std::int64_t(word & 0xFFFFFF));
    const std::string text = describeReply(kind, word, protocol_, e);
    e.set("command", w ? Value(w->cmd.name) : Value(Null{}));
    if (w && w->cmd.address) e.set("address", std::int64_t(*w->cmd.address));
    e.set("word", std::uint64_t(word));
    for (auto& x : errors)
        e.error(std::move(x));
    for (const auto& x : spi.errors)
        e.error(x);
    e.summary = w ? fmt::format("{} (reply to {})", text, w->cmd.name) : text;
    emit(std::move(owned));
}

void Tmc8100Decoder::record(Waiting& w, ReplyKind kind, std::uint32_t word) {
    switch (kind) {
        case ReplyKind::RawPosition:
            w.raw = word & 0xFFFF;
            break;
        case ReplyKind::BinaryPosition:
            w.binary = word & 0xFFFF;
            break;
        case ReplyKind::Flags:
            w.flags = word & 0xFFFFFF;
            break;
        case ReplyKind::ClockEdges:
            w.edges = word & 0xFF;
            break;
        case ReplyKind::Protocol:
            if (!protocol_fixed_) {
                const std::string text = asciiOf(word);
                if (text == "SSI ")
                    protocol_ = EncoderProtocol::Ssi;
                else if (text == "BISS")
                    protocol_ = EncoderProtocol::Biss;
            }
            break;
        default:
            break;
    }
}

void Tmc8100Decoder::onMiso(std::uint32_t word, const Event& spi) {
    if (firmware_ == Firmware::Bootloader) {
        // The bootloader answers a query in the very next transfer (the demo sends the
        // query twice: once to ask, once to read); program writes have no answer.
        if (boot_query_) {
            Waiting w;
            w.cmd = *boot_query_;
            emitReply(boot_query_->replies.front(), word, spi, &w, {});
            boot_query_.reset();
        }
        return;
    }
    if (word == 0) return;  // an empty output buffer shifts out zeros: no reply in it

    if (!waiting_.empty() && waiting_.front().only_optional_left) {
        Waiting& w = waiting_.front();
        if (kindFromTag(word) == ReplyKind::ClockEdges) {
            // A fourth word after 0x70: the BiSS demo firmware.
            record(w, ReplyKind::ClockEdges, word);
            w.last_reply_end = spi.end;
            emitReply(ReplyKind::ClockEdges, word, spi, &w, {});
            finishFront(false);
            return;
        }
        finishFront(false);
    }
    if (waiting_.empty()) {
        // Before anything identified the firmware, a stray word is left alone rather
        // than given a meaning; with the application known it is a protocol fault.
        if (firmware_ == Firmware::App)
            emitReply(kindFromTag(word), word, spi, nullptr, {"unsolicited_reply"});
        return;
    }

    Waiting& w = waiting_.front();
    std::vector<std::string> errors;
    if (w.next == 0 && avail_bound_ && (w.avail_rise == kNoTick || w.avail_rise > spi.start))
        errors.push_back("avail_low");
    ReplyKind kind = w.cmd.replies[w.next];
    if (!matches(kind, word)) {
        errors.push_back("unexpected_reply");
        const ReplyKind got = kindFromTag(word);
        auto later =
            std::find(w.cmd.replies.begin() + std::ptrdiff_t(w.next) + 1, w.cmd.replies.end(), got);
        if (later == w.cmd.replies.end()) {
            emitReply(got, word, spi, nullptr, std::move(errors));
            return;
        }
        // A reply went missing: continue with the one that arrived.
        w.next = std::size_t(later - w.cmd.replies.begin());
        kind = got;
    }
    record(w, kind, word);
    if (w.first_reply_start == kNoTick) w.first_reply_start = spi.start;
    w.last_reply_end = spi.end;
    emitReply(kind, word, spi, &w, std::move(errors));
    if (++w.next == w.cmd.replies.size()) {
        if (w.cmd.name == "read_encoder" && protocol_ == EncoderProtocol::Unknown)
            w.only_optional_left = true;  // a 0x71 word may follow (BiSS demo)
        else
            finishFront(false);
    }
}

void Tmc8100Decoder::onMosi(std::uint32_t word, const Event& spi) {
    const std::uint8_t code = std::uint8_t(word >> 24);
    if (mode_option_ == "auto" && firmware_ != Firmware::Bootloader) {
        // The bootloader is recognised by its chip queries or by a run of program writes
        // to consecutive addresses; a single 0x08.. word proves nothing.
        if (isBootloaderQuery(code) || (isProgramWrite(code) && last_write_address_ &&
                                        programAddress(word) == *last_write_address_ + 1))
            firmware_ = Firmware::Bootloader;
        else if (code == 0x80 || code == 0xFE || code == 0xFF)
            firmware_ = Firmware::App;
    }
    if (isProgramWrite(code))
        last_write_address_ = programAddress(word);
    else
        last_write_address_.reset();

    const bool boot = firmware_ == Firmware::Bootloader;
    Command c = boot ? bootloaderCommand(word) : appCommand(word, protocol_);
    EventPtr owned = newEvent("command", spi.start, spi.end);
    Event& e = *owned;
    e.set("code", std::int64_t(code));
    e.set("name", c.name);
    e.set("word", std::uint64_t(word));
    if (c.address) e.set("address", std::int64_t(*c.address));
    if (c.data) e.set("data", std::int64_t(*c.data));
    e.errors = spi.errors;
    std::string text = fmt::format("{} (0x{:08X})", c.name, word);
    if (c.address) text += fmt::format(" address 0x{:03X}", *c.address);
    if (c.data) text += fmt::format(" data 0x{:04X}", *c.data);

    if (boot) {
        boot_query_.reset();
        if (!c.replies.empty()) boot_query_ = c;
        if (c.switches_to_app) firmware_ = Firmware::App;
    } else if (firmware_ == Firmware::App && !c.replies.empty() && miso_bound_) {
        // (Without MISO no reply can be seen: nothing is waited for.)
        if (!waiting_.empty() && waiting_.front().only_optional_left) finishFront(false);
        // The note expects "a new command is not sent before all data from the previous
        // command has been read out".
        if (std::any_of(waiting_.begin(), waiting_.end(),
                        [&](const Waiting& w) { return requiredRepliesLeft(w); }))
            e.error("replies_pending");
        Waiting w;
        w.cmd = c;
        w.start = spi.start;
        w.end = spi.end;
        // GPIO6 still high for earlier replies already says "data available" for a FIFO.
        // With nothing else waiting a high level is left over from the previous reply
        // (it falls when that transfer ends), so only a new rise counts.
        if (avail_level_ && !waiting_.empty()) w.avail_rise = spi.end;
        waiting_.push_back(std::move(w));
        // A host that never reads its replies must not hold the output back forever.
        while (waiting_.size() > kMaxWaiting)
            finishFront(true);
    }
    e.summary = std::move(text);
    emit(std::move(owned));
}

void Tmc8100Decoder::finishFront(bool incomplete) {
    complete(waiting_.front(), incomplete);
    waiting_.pop_front();
}

void Tmc8100Decoder::complete(Waiting& w, bool incomplete) {
    if (w.cmd.name != "read_encoder") return;
    EventPtr owned =
        newEvent("encoder_read", w.start, w.last_reply_end == kNoTick ? w.end : w.last_reply_end);
    Event& e = *owned;
    auto opt = [](const std::optional<std::uint32_t>& v) {
        return v ? Value(std::int64_t(*v)) : Value(Null{});
    };
    e.set("gray", opt(w.raw));
    e.set("binary", opt(w.binary));
    const bool biss = protocol_ == EncoderProtocol::Biss || w.edges.has_value();
    std::optional<std::uint32_t> flags;
    if (w.flags) flags = biss ? (*w.flags >> 16) & 0x03 : (*w.flags >> 16) & 0xFF;
    e.set("flags", opt(flags));
    std::optional<bool> consistent;
    if (w.raw && w.binary) consistent = grayToBinary(*w.raw) == *w.binary;
    e.set("consistent", consistent ? Value(*consistent) : Value(Null{}));
    if (biss) {
        std::optional<std::uint32_t> crc_rx, crc_calc;
        if (w.flags) {
            crc_rx = (*w.flags >> 8) & 0xFF;
            crc_calc = *w.flags & 0xFF;
            e.set("nE", std::int64_t((*flags >> 1) & 1));
            e.set("nW", std::int64_t(*flags & 1));
        }
        e.set("crc_rx", opt(crc_rx));
        e.set("crc_calc", opt(crc_calc));
        e.set("crc_ok", crc_rx ? Value(*crc_rx == *crc_calc) : Value(Null{}));
        e.set("clock_edges", opt(w.edges));
        if (crc_rx && *crc_rx != *crc_calc) e.error("crc");
    }
    e.errors.insert(e.errors.end(), w.errors.begin(), w.errors.end());
    if (incomplete || !w.raw || !w.binary || !w.flags) e.error("incomplete");
    if (consistent && !*consistent) e.error("inconsistent");

    std::string text = "encoder read:";
    if (w.raw) text += fmt::format(" raw 0x{:04X}", *w.raw);
    if (w.binary) text += fmt::format(" binary 0x{:04X} ({})", *w.binary, *w.binary);
    if (flags) text += fmt::format(" flags 0x{:02X}", *flags);
    if (consistent && !*consistent)
        text += fmt::format(" (Gray decode of raw is 0x{:04X})", grayToBinary(*w.raw));
    e.summary = std::move(text);

    e.wants_correlation = true;
    corr_window_[w.start] = w.first_reply_start == kNoTick ? e.end : w.first_reply_start;
    // correlate() consumes these in order; bounded in case a host never calls it.
    while (corr_window_.size() > 256)
        corr_window_.erase(corr_window_.begin());
    emit(std::move(owned));
}

void Tmc8100Decoder::correlate(Event& e, const EventWindow& window) {
    if (e.type != "encoder_read") return;
    auto it = corr_window_.find(e.start);
    if (it == corr_window_.end()) return;
    const Tick to = it->second;
    corr_window_.erase(it);
    const Value* gray = e.get("gray");
    if (!gray || isNull(*gray)) return;

    // The encoder frame the TMC8100 clocked: the first ssi (or bissc) frame that starts
    // between the command and the first reply read.
    std::optional<std::uint64_t> wire;
    std::string proto;
    auto lookFor = [&](const char* p, const char* field) {
        window.forEach(p, "frame", e.start, to, [&](const Event& f) {
            if (auto v = wordOf(f, field)) {
                wire = *v;
                proto = p;
                return false;
            }
            return true;
        });
    };
    lookFor("ssi", "raw");
    if (!wire) lookFor("bissc", "position");
    if (wire) {
        // The firmware reports the last 16 bits it shifted in: the single-turn field as sent.
        const std::uint64_t wire_st = lowBits(*wire, 16);
        const bool match = wire_st == std::uint64_t(asInt(*gray));
        e.set("ssi_match", match);
        e.set("encoder_st", std::int64_t(wire_st));
        if (match) {
            e.summary += fmt::format(" - the {} frame agrees", proto);
        } else {
            e.error("ssi_mismatch");
            e.summary +=
                fmt::format(" - {} frame on the encoder bus carried 0x{:04X}", proto, wire_st);
        }
        return;
    }
    // No frame in the window: only a fault if an encoder decoder runs in this pass at all.
    bool encoder_decoded = false;
    for (const char* p : {"ssi", "bissc"})
        window.forEach(p, "frame", std::numeric_limits<Tick>::min(),
                       std::numeric_limits<Tick>::max(), [&](const Event&) {
                           encoder_decoded = true;
                           return false;
                       });
    if (encoder_decoded) {
        e.set("ssi_match", false);
        e.error("no_encoder_frame");
    }
}

void Tmc8100Decoder::finish(Tick end) {
    stack_.finish(end);
    while (!waiting_.empty())
        finishFront(!waiting_.front().only_optional_left);
    idle();
}

}  // namespace busdecode
