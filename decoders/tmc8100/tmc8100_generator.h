#pragma once
// Generator for the whole TMC8100 scenario: the host (Landungsbruecke) on SPI mode 3
// sending 32-bit datagrams, SPI_DATA_AVAILABLE on GPIO6, and the encoder cable the
// firmware clocks (SSI: 26 clocks at 1 MHz for a 25-bit word, sampled on falling edges).
// It plays the SSI demo firmware's dialogue ([D1], docs/protocols.md §3.1) and lets a
// test inject faults: a firmware that reports the wrong binary, a TMC8100 answer that
// differs from what crossed the encoder cable, a host that reads before GPIO6, GPIO6
// rising for nothing.
//
// Lines: spi_csn, spi_sclk, spi_sdi (MOSI), spi_sdo (MISO), gpio6, clock, data (the
// encoder's clock and data: bound automatically by both tmc8100 and ssi).
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "core/waveform.h"
#include "spi_generator.h"

namespace busdecode {

struct Tmc8100Timing {
    SpiTiming spi{376, 500, 500, 30};  // Landungsbruecke: about 2.66 MHz
    double transfer_gap_ns = 4000;     // between two datagrams of the host
    double ssi_period_ns = 1000;       // 1 MHz, as in the SSI demo
    double ssi_data_delay_ns = 100;    // encoder output delay after a rising clock edge
    double monoflop_ns = 20000;        // data low after the word
    double command_to_ssi_ns = 2000;   // firmware reacts to the command
    double ssi_to_avail_ns = 1500;     // Gray conversion and buffer writes
    double avail_to_read_ns = 3000;    // host notices GPIO6
};

// One host transfer, as the generator drove it (times in ns).
struct Tmc8100Transfer {
    std::uint32_t mosi = 0, miso = 0;
    double cs_low_ns = 0, cs_high_ns = 0;
};

class Tmc8100Scenario {
public:
    enum Line : int { kCsn = 0, kSclk, kSdi, kSdo, kGpio6, kEncClock, kEncData, kLineCount };

    explicit Tmc8100Scenario(Tmc8100Timing timing = {});

    // One 32-bit datagram now; returns when cs was released.
    const Tmc8100Transfer& transfer(std::uint32_t mosi, std::uint32_t miso);
    void pause(double ns) { now_ += ns; }
    void setAvail(bool level);
    // One SSI read of `bits` bits (bits + 1 clocks), data low for the monoflop time after.
    void ssiFrame(std::uint32_t word, int bits = 25);

    // One BiSS-C frame of the BiSS demo (docs/protocols.md §4.2): MA clocks LAT, ACK, start,
    // CDS, `bits` data bits, nE, nW, CRC6 (inverted) and stop; SL answers after each rising
    // edge, stays low for the timeout, then idles high. crc_xor corrupts the CRC sent.
    // Returns the MA edges clocked.
    int bissFrame(std::uint32_t data, int bits, int ne, int nw, std::uint32_t crc_xor = 0);

    // The SSI demo's encoder word: 3 flag bits, 6 multi-turn bits, 16 single-turn bits
    // Gray coded.
    static std::uint32_t ssiWord(std::uint8_t flags3, std::uint8_t mt6, std::uint16_t st_binary);

    struct EncoderRead {
        std::uint32_t ssi_word = 0;                    // what the encoder sends
        std::optional<std::uint16_t> reported_raw;     // TMC8100's 0x10 word (default: as received)
        std::optional<std::uint16_t> reported_binary;  // 0x20 word (default: Gray decode of raw)
        bool avail_rises = true;                       // GPIO6 signals the replies
        bool host_waits = true;                        // host reads only after GPIO6
        int replies_read = 3;                          // dummy reads the host does
        std::optional<std::uint32_t> next_command;     // sent with the last read
    };
    // 0x80 command, SSI frame, GPIO6, dummy reads of 0x10 / 0x20 / 0x70.
    void readEncoder(const EncoderRead& r);
    // The BiSS demo's read: 0x80, BiSS-C frame, GPIO6, dummy reads of 0x10 (raw), 0x20
    // (the firmware's Gray decode), 0x70 (nE:nW, CRC received, CRC calculated) and 0x71 (edges).
    struct BissRead {
        std::uint16_t position = 0;                    // 13-bit single-turn (Gray) on the cable
        int ne = 1, nw = 1;                            // as sent (1 = no error / warning)
        std::optional<std::uint16_t> reported_raw;     // default: as received
        std::optional<std::uint16_t> reported_binary;  // default: Gray decode of the raw value
        bool corrupt_crc = false;                      // the cable carries a wrong CRC
    };
    void readEncoderBiss(const BissRead& r);
    // 0xFF -> FF 00 major minor; 0xFE -> four ASCII bytes ("SSI ").
    void getVersion(std::uint8_t major = 1, std::uint8_t minor = 0);
    void getProtocol(const std::string& text = "SSI ");

    double now() const { return now_; }
    const std::vector<Tmc8100Transfer>& transfers() const { return transfers_; }
    Waveform build() const;

    // Tick of the first sampling edge of a transfer and the SPI layer's end estimate (one
    // bit period after the last sampling edge), in the 1 ns timebase: the truth a test
    // compares event times with.
    Tick firstSampleTick(const Tmc8100Transfer& t) const;
    Tick endTick(const Tmc8100Transfer& t) const;

private:
    void reply(const std::vector<std::uint32_t>& words, bool last_drops_avail,
               std::optional<std::uint32_t> next_command);

    Tmc8100Timing timing_;
    WaveBuilder wb_;
    SpiGenerator spi_;
    double now_ = 1000;
    std::vector<Tmc8100Transfer> transfers_;
};

}  // namespace busdecode
