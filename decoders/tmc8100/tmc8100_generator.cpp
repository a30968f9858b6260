#include "tmc8100_generator.h"

#include <cmath>

#include "core/crc.h"
#include "core/gray.h"

namespace busdecode {

Tmc8100Scenario::Tmc8100Scenario(Tmc8100Timing timing)
    : timing_(timing),
      // Idle: cs high, clock high (mode 3), data low, GPIO6 low, encoder clock and data high.
      wb_(Timebase{1, 1'000'000'000},
          {"spi_csn", "spi_sclk", "spi_sdi", "spi_sdo", "gpio6", "clock", "data"},
          {1, 1, 0, 0, 0, 1, 1}),
      spi_(wb_, SpiLines{kCsn, kSclk, kSdi, kSdo}, SpiMode{1, 1, false, false}, timing.spi) {}

const Tmc8100Transfer& Tmc8100Scenario::transfer(std::uint32_t mosi, std::uint32_t miso) {
    Tmc8100Transfer t;
    t.mosi = mosi;
    t.miso = miso;
    t.cs_low_ns = now_;
    t.cs_high_ns = spi_.transfer(now_, mosi, miso, 32);
    now_ = t.cs_high_ns + timing_.transfer_gap_ns;
    transfers_.push_back(t);
    return transfers_.back();
}

void Tmc8100Scenario::setAvail(bool level) {
    wb_.setNs(kGpio6, now_, level);
}

std::uint32_t Tmc8100Scenario::ssiWord(std::uint8_t flags3, std::uint8_t mt6,
                                       std::uint16_t st_binary) {
    return (std::uint32_t(flags3 & 0x7) << 22) | (std::uint32_t(mt6 & 0x3F) << 16) |
           std::uint32_t(binaryToGray(st_binary) & 0xFFFF);
}

void Tmc8100Scenario::ssiFrame(std::uint32_t word, int bits) {
    // First falling edge latches; each rising edge shifts the next bit out, MSB first;
    // the master samples on falling edges 2..bits+1; after the last rising edge data
    // stays low for the monoflop time.
    const double h = timing_.ssi_period_ns / 2;
    const double t0 = now_;
    for (int k = 0; k <= bits; ++k) {
        const double fall = t0 + k * timing_.ssi_period_ns;
        const double rise = fall + h;
        wb_.setNs(kEncClock, fall, false);
        wb_.setNs(kEncClock, rise, true);
        const bool bit = k < bits ? ((word >> (bits - 1 - k)) & 1u) != 0 : false;
        wb_.setNs(kEncData, rise + timing_.ssi_data_delay_ns, bit);
    }
    const double last_rise = t0 + bits * timing_.ssi_period_ns + h;
    wb_.setNs(kEncData, last_rise + timing_.monoflop_ns, true);
    now_ = last_rise;
}

int Tmc8100Scenario::bissFrame(std::uint32_t data, int bits, int ne, int nw,
                               std::uint32_t crc_xor) {
    // Slot k is the SL level after MA rising edge k (1-based): LAT 1, ACK 0, start 1,
    // CDS 0, data MSB first, nE, nW, CRC6 as sent, STP 0.
    const std::uint64_t payload =
        (std::uint64_t(data) << 2) | (std::uint64_t(ne & 1) << 1) | (nw & 1);
    const std::uint32_t crc = bissCrc6(payload, bits + 2) ^ crc_xor;
    std::vector<bool> slots = {true, false, true, false};
    for (int i = bits + 1; i >= 0; --i)
        slots.push_back(((payload >> i) & 1u) != 0);
    for (int i = 5; i >= 0; --i)
        slots.push_back(((crc >> i) & 1u) != 0);
    slots.push_back(false);
    const double h = timing_.ssi_period_ns / 2;
    const double t0 = now_;
    for (std::size_t k = 0; k < slots.size(); ++k) {
        const double fall = t0 + double(k) * timing_.ssi_period_ns;
        wb_.setNs(kEncClock, fall, false);
        wb_.setNs(kEncClock, fall + h, true);
        wb_.setNs(kEncData, fall + h + timing_.ssi_data_delay_ns, slots[k]);
    }
    const double last_rise = t0 + double(slots.size() - 1) * timing_.ssi_period_ns + h;
    wb_.setNs(kEncData, last_rise + timing_.monoflop_ns, true);  // the slave's timeout
    now_ = last_rise;
    return int(slots.size()) * 2;
}

void Tmc8100Scenario::readEncoderBiss(const BissRead& r) {
    transfer(0x80000000u, 0);
    now_ += timing_.command_to_ssi_ns - timing_.transfer_gap_ns;
    const int bits = 13;
    const std::uint16_t cable = r.position & 0x1FFF;
    const std::uint64_t payload =
        (std::uint64_t(cable) << 2) | (std::uint64_t(r.ne & 1) << 1) | (r.nw & 1);
    const std::uint32_t crc_ok = bissCrc6(payload, bits + 2);
    // A corrupted CRC on the cable: the firmware receives it and calculates the right one.
    const std::uint32_t crc_sent = r.corrupt_crc ? crc_ok ^ 1u : crc_ok;
    const int edges = bissFrame(cable, bits, r.ne, r.nw, crc_sent ^ crc_ok);
    const std::uint16_t raw = r.reported_raw.value_or(cable);
    const std::uint16_t binary = r.reported_binary.value_or(std::uint16_t(grayToBinary(raw)));
    now_ += timing_.ssi_to_avail_ns;
    setAvail(true);
    now_ += timing_.avail_to_read_ns;
    const std::uint32_t flags = (std::uint32_t(r.ne & 1) << 1) | std::uint32_t(r.nw & 1);
    reply({0x10000000u | raw, 0x20000000u | binary,
           0x70000000u | (flags << 16) | (crc_sent << 8) | crc_ok,
           0x71000000u | std::uint32_t(edges)},
          true, std::nullopt);
}

void Tmc8100Scenario::reply(const std::vector<std::uint32_t>& words, bool last_drops_avail,
                            std::optional<std::uint32_t> next_command) {
    for (std::size_t i = 0; i < words.size(); ++i) {
        const bool last = i + 1 == words.size();
        const std::uint32_t mosi = last && next_command ? *next_command : 0;
        transfer(mosi, words[i]);
        if (last && last_drops_avail) {
            // The output buffer is empty once the last word has been shifted out.
            const double gap = timing_.transfer_gap_ns;
            now_ -= gap;
            setAvail(false);
            now_ += gap;
        }
    }
}

void Tmc8100Scenario::readEncoder(const EncoderRead& r) {
    transfer(0x80000000u, 0);
    now_ += timing_.command_to_ssi_ns - timing_.transfer_gap_ns;
    ssiFrame(r.ssi_word, 25);
    const std::uint16_t received = std::uint16_t(r.ssi_word & 0xFFFF);
    const std::uint16_t raw = r.reported_raw.value_or(received);
    const std::uint16_t binary = r.reported_binary.value_or(std::uint16_t(grayToBinary(raw)));
    const std::uint8_t flags = std::uint8_t((r.ssi_word >> 22) & 0x7);
    now_ += timing_.ssi_to_avail_ns;
    if (r.avail_rises) setAvail(true);
    now_ += timing_.avail_to_read_ns;
    if (!r.host_waits) now_ -= timing_.avail_to_read_ns + timing_.ssi_to_avail_ns + 1000;
    std::vector<std::uint32_t> words = {0x10000000u | raw, 0x20000000u | binary,
                                        0x70000000u | (std::uint32_t(flags) << 16)};
    words.resize(std::size_t(r.replies_read));
    reply(words, r.avail_rises && r.replies_read >= 3, r.next_command);
}

void Tmc8100Scenario::getVersion(std::uint8_t major, std::uint8_t minor) {
    transfer(0xFF000000u, 0);
    now_ -= timing_.transfer_gap_ns - 1000;
    setAvail(true);
    now_ += timing_.transfer_gap_ns - 1000;
    reply({0xFF000000u | (std::uint32_t(major) << 8) | minor}, true, std::nullopt);
}

void Tmc8100Scenario::getProtocol(const std::string& text) {
    std::uint32_t w = 0;
    for (int i = 0; i < 4; ++i)
        w = (w << 8) | std::uint8_t(i < int(text.size()) ? text[i] : ' ');
    transfer(0xFE000000u, 0);
    now_ -= timing_.transfer_gap_ns - 1000;
    setAvail(true);
    now_ += timing_.transfer_gap_ns - 1000;
    reply({w}, true, std::nullopt);
}

Waveform Tmc8100Scenario::build() const {
    return wb_.build(wb_.ticksFromNs(now_ + 30000));
}

Tick Tmc8100Scenario::firstSampleTick(const Tmc8100Transfer& t) const {
    // Mode 3 samples on the trailing (rising) edge of each clock cycle.
    return Tick(std::llround(t.cs_low_ns + timing_.spi.cs_setup_ns + timing_.spi.period_ns / 2));
}

Tick Tmc8100Scenario::endTick(const Tmc8100Transfer& t) const {
    const double last = t.cs_low_ns + timing_.spi.cs_setup_ns + 31 * timing_.spi.period_ns +
                        timing_.spi.period_ns / 2;
    return Tick(std::llround(last + timing_.spi.period_ns));
}

}  // namespace busdecode
