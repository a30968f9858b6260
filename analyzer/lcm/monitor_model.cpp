#include "monitor_model.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "sinks/event_format.h"

namespace busdecode {

double BusView::frameRateHz() const {
    if (recent_starts.size() < 2) return 0;
    double span_ns = double(recent_starts.back() - recent_starts.front());
    return span_ns > 0 ? double(recent_starts.size() - 1) * 1e9 / span_ns : 0;
}

BusView& MonitorModel::bus(const std::string& instance, std::int64_t utime) {
    BusView& b = buses_[instance];
    if (b.instance.empty()) {
        b.instance = instance;
        auto hash = instance.find('#');
        b.proto = instance.substr(0, hash);
    }
    b.last_utime = std::max(b.last_utime, utime);
    messages_++;
    return b;
}

void MonitorModel::frame(BusView& b, std::int64_t start_ns, std::int64_t position, std::int64_t st,
                         std::int64_t mt) {
    b.frames++;
    b.has_position = true;
    b.position = position;
    b.st = st;
    b.mt = mt;
    b.recent_starts.push_back(start_ns);
    if (b.recent_starts.size() > kRateWindow) b.recent_starts.pop_front();
}

void MonitorModel::onSsiFrame(const lcm::ReceiveBuffer*, const std::string&,
                              const busdecode_lcm::ssi_frame_t* m) {
    BusView& b = bus(m->instance, m->utime);
    frame(b, m->start_ns, m->position, m->st, m->mt);
    if (m->repeats > 1) {
        b.checked++;
        if (!m->repeat_match) b.check_errors++;
    }
}

void MonitorModel::onBisscFrame(const lcm::ReceiveBuffer*, const std::string&,
                                const busdecode_lcm::bissc_frame_t* m) {
    BusView& b = bus(m->instance, m->utime);
    frame(b, m->start_ns, m->position, m->st, m->mt);
    bool crc_known =
        std::find(m->null_fields.begin(), m->null_fields.end(), "crc_ok") == m->null_fields.end();
    if (crc_known) {
        b.checked++;
        if (!m->crc_ok) b.check_errors++;
    }
    if (std::isfinite(m->line_delay_ns)) {
        double d = m->line_delay_ns;
        b.line_delay_min = b.has_line_delay ? std::min(b.line_delay_min, d) : d;
        b.line_delay_max = b.has_line_delay ? std::max(b.line_delay_max, d) : d;
        b.line_delay = d;
        b.has_line_delay = true;
    }
}

void MonitorModel::onBisscRegister(const lcm::ReceiveBuffer*, const std::string&,
                                   const busdecode_lcm::bissc_register_t* m) {
    BusView& b = bus(m->instance, m->utime);
    (m->op == "write" ? b.reg_writes : b.reg_reads)++;
    std::string data;
    for (std::size_t i = 0; i < m->data.size(); ++i)
        data += fmt::format("{}0x{:02X}", i ? " " : "", m->data[i]);
    recent_registers_.push_back(fmt::format("{:<10} {:<5} id {} addr 0x{:02X} = {}{}", m->instance,
                                            m->op, m->id, m->address, data.empty() ? "-" : data,
                                            m->crc_ok ? "" : "  CRC ERROR"));
    if (recent_registers_.size() > kRecentRegisters) recent_registers_.pop_front();
}

void MonitorModel::onBisscCommand(const lcm::ReceiveBuffer*, const std::string&,
                                  const busdecode_lcm::bissc_command_t* m) {
    bus(m->instance, m->utime).commands++;
}

void MonitorModel::onEncoderRead(const lcm::ReceiveBuffer*, const std::string&,
                                 const busdecode_lcm::tmc8100_encoder_read_t* m) {
    BusView& b = bus(m->instance, m->utime);
    frame(b, m->start_ns, m->binary, m->binary, 0);
    b.checked++;
    // The encoder frame's CRC, relayed by the chip, shows only among the errors.
    const bool crc_bad = std::find(m->errors.begin(), m->errors.end(), "crc") != m->errors.end();
    if (!m->consistent || crc_bad) b.check_errors++;
}

void MonitorModel::onTmclReply(const lcm::ReceiveBuffer*, const std::string&,
                               const busdecode_lcm::tmcl_reply_t* m) {
    BusView& b = bus(m->instance, m->utime);
    b.checked++;
    if (!m->checksum_ok) b.check_errors++;
}

void MonitorModel::onAnnotation(const lcm::ReceiveBuffer*, const std::string&,
                                const busdecode_lcm::event_annotation_t* m) {
    losses_.onEvent(m->seq);
    BusView& b = bus(m->instance.empty() ? m->proto : m->instance, m->utime);
    b.events++;
    for (const auto& e : m->errors)
        b.errors[e]++;
}

void MonitorModel::onStatus(const lcm::ReceiveBuffer*, const std::string&,
                            const busdecode_lcm::decode_status_t* m) {
    losses_.onStatus(m->state, m->events);
    if (m->state == "start") return;
    if (m->state == "done") {  // after the run's last capture
        runs_ended_++;
        state_ = "ended";
        return;
    }
    // Buses are kept across runs: several decoders may publish at once, and a capture
    // decoded again simply continues its bus's counts.
    state_ = m->state == "begin" ? "decoding" : m->state == "live" ? "live" : "ended";
    file_ = m->file;
    capture_ns_ = m->capture_ns;
    dropped_ = m->dropped;
    live_samples_ = m->live_samples;
    live_dropped_ = m->live_dropped;
}

namespace {

std::string fit(std::string s, std::size_t width) {
    if (s.size() > width) s.resize(width);
    return s;
}

std::string rateText(double hz) {
    if (hz <= 0) return "-";
    if (hz >= 1e6) return fmt::format("{:.2f} MHz", hz / 1e6);
    if (hz >= 1e3) return fmt::format("{:.2f} kHz", hz / 1e3);
    return fmt::format("{:.1f} Hz", hz);
}

// One dashboard row: the header and every bus line share the column widths.
std::string row(const std::string& bus, const std::string& pos, const std::string& frames,
                const std::string& rate, const std::string& crc, const std::string& delay,
                const std::string& regs, const std::string& errors) {
    return fmt::format("{:<12} {:<24} {:>9} {:>11} {:>16} {:>23} {:>9}  {}", bus, pos, frames, rate,
                       crc, delay, regs, errors);
}

}  // namespace

// A live run's acquisition: the samples taken, and those decoding fell behind on.
std::string MonitorModel::liveText() const {
    if (live_samples_ == 0) return "";
    return fmt::format("   samples {}", live_samples_) +
           (live_dropped_ ? fmt::format("   SAMPLES DROPPED {}", live_dropped_) : "");
}

std::vector<std::string> MonitorModel::render(const std::string& url, std::int64_t now_utime,
                                              std::size_t width) const {
    std::vector<std::string> out;
    out.push_back(fit(fmt::format("busdecode monitor  {}  [{}]{}", url, state_,
                                  file_.empty() ? "" : "  capture " + file_),
                      width));
    out.push_back(
        fit(fmt::format(
                "capture time {}   messages {}{}", formatDuration(double(capture_ns_)), messages_,
                (dropped_ ? fmt::format("   DROPPED {}", dropped_) : "") +
                    (losses_.lost() ? fmt::format("   LOST {}", losses_.lost()) : "") + liveText()),
            width));
    out.emplace_back();
    out.push_back(fit(row("BUS", "POSITION (MT:ST)", "FRAMES", "FRAME RATE", "CRC ERRORS",
                          "LINE DELAY last/min/max", "REG R/W", "ERRORS"),
                      width));
    if (buses_.empty()) out.push_back("  (no events yet)");
    for (const auto& [name, b] : buses_) {
        std::string pos = !b.has_position ? "-"
                          : b.mt          ? fmt::format("{} ({}:{})", b.position, b.mt, b.st)
                                          : std::to_string(b.position);
        std::string crc =
            b.checked
                ? fmt::format("{:.2f}% ({})", 100.0 * double(b.check_errors) / double(b.checked),
                              b.check_errors)
                : "-";
        std::string delay = b.has_line_delay ? fmt::format("{:.0f}/{:.0f}/{:.0f} ns", b.line_delay,
                                                           b.line_delay_min, b.line_delay_max)
                                             : "-";
        std::string regs =
            b.reg_reads || b.reg_writes ? fmt::format("{}/{}", b.reg_reads, b.reg_writes) : "-";
        std::string errs;
        for (const auto& [e, n] : b.errors)
            errs += fmt::format("{}{}:{}", errs.empty() ? "" : " ", e, n);
        std::string frames = b.frames ? std::to_string(b.frames) : fmt::format("{} ev", b.events);
        std::string age;
        if (now_utime && b.last_utime && now_utime - b.last_utime > 2'000'000)
            age = fmt::format("  (quiet {:.0f} s)", double(now_utime - b.last_utime) / 1e6);
        out.push_back(fit(row(name, pos, frames, rateText(b.frameRateHz()), crc, delay, regs,
                              (errs.empty() ? "-" : errs) + age),
                          width));
    }
    if (!recent_registers_.empty()) {
        out.emplace_back();
        out.push_back("Recent register accesses:");
        for (const auto& r : recent_registers_)
            out.push_back(fit("  " + r, width));
    }
    return out;
}

}  // namespace busdecode
