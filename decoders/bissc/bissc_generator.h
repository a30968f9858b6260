#pragma once
// BiSS-C signal generator (the Saleae SimulationDataGenerator idea): MA and SL as a
// logic analyser at the master would see them, with the truth beside the waveform.
// Models clock rate, data width, line delay (SL answers d after each MA rising edge),
// processing time (extra ACK clocks), CDM in the timeout (with or without Hold-CDM),
// clocks past the stop bit, corrupted CRCs, clock jitter, truncated frames and glitches.
// buildControlSequence() turns a list of register accesses and commands (with the
// slave's answers) into the per-frame CDM/CDS bits that carry them.
#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include "core/time.h"
#include "core/waveform.h"

namespace busdecode {

struct BisscGenConfig {
    Timebase timebase{1, 1'000'000'000};  // 1 ns ticks; fromSampleRate() for sampled captures
    double clock_hz = 1e6;
    int bits = 26;
    std::uint32_t crc_poly = 0x43;  // full notation
    std::uint32_t crc_init = 0;
    bool crc_inverted = true;
    double line_delay_ns = 0;   // MA rising edge -> SL change, as seen at the master
    double timeout_ns = 20000;  // slave: SL low this long after the last MA rising edge
    double idle_ns = 10000;     // master: pause after SL rises before the next frame
    double lead_ns = 5000;      // idle before the first frame
    double jitter_ns = 0;       // each MA edge moves by up to +-jitter (uniform)
    bool hold_cdm = false;      // CDM = 1: keep MA low until the next frame (no idle)
    // Slave ready this long after the stop bit even while the master clocks on (>= 0):
    // it raises SL and answers the remaining clocks as a new request (LAT, ACK, busy),
    // as the Renishaw RESOLUTE does behind an iC-Haus MB5U. -1: SL low until the timeout.
    double ready_after_stop_ns = -1;
    std::uint32_t seed = 1;
    std::vector<std::string> names{"MA", "SLO"};
};

struct BisscFrameSpec {
    std::uint64_t data = 0;  // `bits` wide, MSB sent first
    int ne = 1, nw = 1;      // as sent (1 = no error / warning)
    int cds = 0;
    int cdm = 0;
    int proc_cycles = 0;       // busy clocks between ACK and start
    int extra_clocks = 0;      // master clocks past the stop bit
    bool corrupt_crc = false;  // flip the last CRC bit
    int truncate_after = -1;   // master stops after this many rising edges (short frame)
};

struct BisscFrameTruth {
    BisscFrameSpec spec;
    Tick start = 0;  // first MA edge of the frame (fall, or LAT rise with Hold-CDM)
    Tick end = 0;    // SL rises (end of the slave's timeout)
    std::uint32_t crc_sent = 0;
    bool crc_ok = true;
    bool truncated = false;
    int rises = 0;             // MA rising edges clocked
    bool retriggered = false;  // the slave took clocks past the stop bit for a new request
    double clock_hz = 0;
};

class BisscGenerator {
public:
    explicit BisscGenerator(BisscGenConfig cfg);

    const BisscFrameTruth& addFrame(const BisscFrameSpec& f);
    // Idle time with no frame (both lines keep their level).
    void pause(double ns) { now_ns_ += ns; }
    // A pulse of width_ns on line 0 (MA) or 1 (SL) at at_ns, added when building.
    void addGlitch(int line, double at_ns, double width_ns);
    Waveform build() const;

    const std::vector<BisscFrameTruth>& frames() const { return frames_; }
    const BisscGenConfig& config() const { return cfg_; }
    double nowNs() const { return now_ns_; }
    // The CRC as sent for data+nE+nW under this configuration.
    std::uint32_t crcFor(std::uint64_t data, int ne, int nw) const;
    int crcBits() const;

private:
    double jitter();
    void setMa(double ns, bool level);
    void setSl(double ns, bool level);

    BisscGenConfig cfg_;
    WaveBuilder wb_;
    std::mt19937 rng_;
    double now_ns_ = 0;
    double last_ma_ns_ = 0, last_sl_ns_ = 0;
    bool ma_ = true;
    std::vector<BisscFrameTruth> frames_;
    struct Glitch {
        int line;
        double at_ns, width_ns;
    };
    std::vector<Glitch> glitches_;
};

// ---- Control communication (CDM/CDS over many frames) ----

struct ControlItemSpec {
    enum class Kind { Read, Write, Command } kind = Kind::Read;
    int id = 0;       // register access: slave ID (0..7)
    int address = 0;  // 0..127
    // Read: the slave's bytes; write: the master's bytes. More than one = sequential.
    std::vector<std::uint8_t> data;
    std::vector<int> busy;  // per byte: frames the slave delays its S (master repeats S)
    bool refuse = false;    // the slave inverts the W echo
    bool corrupt_header_crc = false;
    bool corrupt_data_crc = false;  // first byte's data CRC (slave's on read, master's on write)
    int idle_before = 14;           // CDM zeros before the S
    // Command: IDS mask (bit i = IDSi), CMD, the slaves' IDA answer, EX or cancel.
    int ids = 0, command = 0, ida = 0;
    bool execute = true;
    int ex_gap = 8;  // frames from the second S to EX
    // Master abandons the access: stops repeating S after this many busy frames (-1: no).
    int abandon_after_busy = -1;
};

struct ControlEventTruth {
    std::string type;                     // "register" / "command"
    int first_frame = 0, last_frame = 0;  // frame indices that carried it
    std::string op;
    int id = 0, address = 0;
    int data = -1;  // -1: none
    bool crc_ok = true;
    bool refused = false;
    int busy = 0;
    bool executed = false;
    std::string error;  // expected error string, empty when clean
};

struct ControlSequence {
    std::vector<int> cdm, cds;  // per frame
    std::vector<ControlEventTruth> events;
};

// Builds the per-frame bits for `items` one after another, then `trailing_idle` zero
// frames so the last access completes.
ControlSequence buildControlSequence(const std::vector<ControlItemSpec>& items,
                                     int trailing_idle = 16);

}  // namespace busdecode
