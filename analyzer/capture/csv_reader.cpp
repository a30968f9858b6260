// CSV readers. One parser covers the dialects logic analysers write; the header row
// decides which one a file is:
// - sigrok dense CSV: `;` comment lines (`; Channels (2/8): MA, SLO` names the columns,
//   `; Samplerate: 24 MHz` gives the rate), a `logic,logic` header, one row per sample.
// - time column, one row per change or per sample: Saleae Logic 2 (`Time [s],A,B`),
//   Logic 1.x (`Time[s], Channel 0, ...`), USBee (`Time,0,1,...`, per sample, starting
//   at a negative time), ScanaStudio (`Times;CH1 MOSI;...` with `;` separators and
//   times like `4.860 530 ms`). Times are seconds unless a unit follows them.
// - plain: a header of names and one row per sample; needs the rate (--rate).
// Dense formats count one tick per sample (sample 0 = tick 0). Time-column formats
// use ticks of 10^-R s, R = the finest decimal place in the first rows but at least
// 9 (1 ns) and at most 12 (1 ps), so times as written are exact; finer digits later in
// the file are rounded to that tick. Times may be negative.
// Values are 0 or 1; fields may be padded with spaces or quoted.
#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstring>
#include <deque>
#include <optional>
#include <string>
#include <unordered_set>
#include <vector>

#include <fmt/format.h>

#include "capture_events.h"
#include "core/options.h"
#include "core/own_cache_lines.h"
#include "core/sample_rate.h"
#include "csv_fields.h"
#include "decimal_scan.h"
#include "readers.h"
#include "wall_clock.h"

namespace busdecode {

namespace {

// Splits at `sep` into `out` (views into `line`); no allocation once `out` has grown.
void split(std::string_view line, char sep, std::vector<std::string_view>& out) {
    out.clear();
    std::size_t b = 0;
    for (;;) {
        std::size_t e = line.find(sep, b);
        if (e == std::string_view::npos) {
            out.push_back(trimField(line.substr(b)));
            return;
        }
        out.push_back(trimField(line.substr(b, e - b)));
        b = e + 1;
    }
}

// The header's fields: a separator inside double quotes ("RX, module") is part of a name.
void splitHeader(std::string_view line, char sep, std::vector<std::string_view>& out) {
    out.clear();
    bool quoted = false;
    for (std::size_t i = 0, b = 0; i <= line.size(); ++i) {
        if (i < line.size() && line[i] == '"') quoted = !quoted;
        if (i == line.size() || (line[i] == sep && !quoted)) {
            out.push_back(trimField(line.substr(b, i - b)));
            b = i + 1;
        }
    }
}

// A time as written ("-0.000000250", "4.860 530 ms", "1.5e-06", "0 ns"): an exact
// decimal mantissa and a power of ten of seconds. False if it is not a time.
struct Decimal {
    __int128 mantissa = 0;
    int exp10 = 0;  // value = mantissa * 10^exp10 seconds
};
bool parseTime(std::string_view s, Decimal& out) {
    std::size_t i = 0;
    bool neg = false;
    if (i < s.size() && (s[i] == '-' || s[i] == '+')) neg = s[i++] == '-';
    __int128 m = 0;
    int digits = 0, frac = 0;
    bool dot = false;
    for (; i < s.size(); ++i) {
        const char c = s[i];
        if (c >= '0' && c <= '9') {
            if (digits < 30) {
                m = m * 10 + (c - '0');
                ++digits;
                if (dot) ++frac;
            } else if (!dot) {
                return false;  // absurdly large
            }
        } else if (c == '.' && !dot) {
            dot = true;
        } else if (c == ' ' && i + 1 < s.size() && s[i + 1] >= '0' && s[i + 1] <= '9' &&
                   digits > 0) {
            continue;  // digit groups: "4.860 530"
        } else {
            break;
        }
    }
    if (digits == 0) return false;
    int exp = 0;
    if (i < s.size() && (s[i] == 'e' || s[i] == 'E')) {
        ++i;
        if (i < s.size() && s[i] == '+') ++i;  // "1.5e+0": from_chars takes '-' only
        auto [p, ec] = std::from_chars(s.data() + i, s.data() + s.size(), exp);
        if (ec != std::errc() || exp < -30 || exp > 30) return false;
        i = std::size_t(p - s.data());
    }
    while (i < s.size() && s[i] == ' ')
        ++i;
    const std::string_view unit = s.substr(i);
    int unit_exp = 0;
    if (unit.empty() || unit == "s")
        unit_exp = 0;
    else if (unit == "ms")
        unit_exp = -3;
    else if (unit == "us" || unit == "\xc2\xb5s" || unit == "\xce\xbcs")
        unit_exp = -6;
    else if (unit == "ns")
        unit_exp = -9;
    else if (unit == "ps")
        unit_exp = -12;
    else
        return false;
    out.mantissa = neg ? -m : m;
    out.exp10 = exp - frac + unit_exp;
    return true;
}

// value * 10^(exp10 + R) rounded to an integer tick.
bool toTicks(const Decimal& d, int resolution, Tick& t) {
    __int128 v = d.mantissa;
    int e = d.exp10 + resolution;
    for (; e > 0; --e) {
        v *= 10;
        if (v > (__int128)INT64_MAX * 10 || v < (__int128)INT64_MIN * 10) return false;
    }
    if (e < 0) {
        __int128 div = 1;
        for (; e < 0; ++e)
            div *= 10;
        __int128 q = v / div, r = v % div;
        if (2 * (r < 0 ? -r : r) >= div) q += v < 0 ? -1 : 1;
        v = q;
    }
    if (v > kMaxEdgeTick || v < kMinEdgeTick) return false;  // what an Edge holds
    t = Tick(v);
    return true;
}

// In cache lines of its own: its state is written as it reads (own_cache_lines.h).
class alignas(kOwnLineBytes) CsvReader : public CaptureReader {
public:
    CsvReader(std::unique_ptr<TextSource> src, const OpenOptions& opts)
        : src_(std::move(src)), opts_(opts) {
        parseHeader();
    }

    const std::vector<SignalInfo>& signals() const override { return signals_; }
    Timebase timebase() const override { return tb_; }
    std::string formatName() const override { return format_; }
    std::string wallClockStart() const override { return wall_clock_; }

    void select(const std::vector<LineRef>& lines) override {
        checkSelection(lines);
        sel_.clear();
        for (std::size_t i = 0; i < lines.size(); ++i) {
            if (lines[i].signal < 0 || lines[i].signal >= int(signals_.size()))
                throw std::out_of_range("CsvReader::select");
            sel_.push_back(std::size_t(lines[i].signal) + first_col_);
        }
        level_.assign(sel_.size(), 1);
        no_data_from_.assign(sel_.size(), kNoTick);
        x_in_row_.assign(sel_.size(), 0);
    }

    std::vector<std::uint8_t> initialLevels() override {
        if (!started_) start();
        return level_.toVector();
    }
    Tick startTick() const override { return start_; }

    bool next(EdgeBlock& block) override {
        block.clear();
        if (!started_) start();
        if (done_) return false;
        int idle_rounds = 0;
        for (;;) {
            if (block.edges.size() + sel_.size() > kEdgeBlockSize) {
                block.known_until = cur_;
                return handNoData(block), true;
            }
            std::string_view line;
            auto st = nextRow(line);
            if (st == TextSource::Status::Eof) {
                done_ = true;
                block.known_until = cur_;
                if (open_no_data_) closeNoData(cur_, true);
                handNoData(block);
                return !block.edges.empty() || !block.findings.empty();
            }
            if (st == TextSource::Status::NoData) {
                if (!block.edges.empty() || ++idle_rounds > 20) {
                    block.known_until = cur_;
                    return handNoData(block), true;
                }
                src_->waitForData(5);
                continue;
            }
            row(line, &block);
            // A dense capture holds its levels for many samples: the rows that repeat
            // the last one whole are only counted (a sample's row is compared in one
            // load, not found by memchr and compared as a line). `line` is still the row
            // just read: nothing was read into the buffer since.
            if (!timed_ && rows_ > 0) {
                if (const std::uint64_t n = src_->skipLinesEqualTo(line)) {
                    rows_ += n;
                    cur_ = Tick(rows_ - 1);
                }
            }
        }
    }
    Tick endTick() const override { return cur_; }
    std::uint64_t bytesRead() const override { return src_->bytesRead(); }
    std::uint64_t bytesTotal() const override { return src_->bytesTotal(); }
    bool changesOnly() const override { return true; }  // row() compares with level_
    // Saleae writes a row per change and none where the capture stopped.
    bool endsAtLastChange() const override { return format_ == "saleae-csv"; }

private:
    [[noreturn]] void fail(const std::string& what) const {
        throw InputError(src_->at(line_no_, what));
    }

    // The next data row: rows held back while choosing the timebase first, then the
    // stream. Blank and `;` comment lines are skipped.
    TextSource::Status nextRow(std::string_view& line) {
        if (!held_.empty()) {
            current_ = std::move(held_.front().second);
            line_no_ = held_.front().first;
            held_.pop_front();
            line = current_;
            return TextSource::Status::Line;
        }
        for (;;) {
            auto st = src_->nextLine(line);
            if (st != TextSource::Status::Line) return st;
            line_no_ = src_->lineNo();
            // The usual row starts with its time or value: no trimming to look at it.
            if (!line.empty() && (unsigned(line[0] - '0') < 10 || line[0] == '-')) return st;
            std::string_view t = trimField(line);
            if (t.empty() || t.front() == ';' || t.front() == '#') continue;
            return st;
        }
    }

    // What the comment lines above the header said.
    struct HeaderComments {
        std::vector<std::string> channel_names;
        std::optional<SampleRate> rate;
        std::uint64_t rate_line = 0;
        // `#123` lines and no other comment so far: VCD value changes without their header?
        std::uint64_t vcd_times = 0, other_comments = 0;
    };

    void readHeaderComment(std::string_view t, HeaderComments& c) {
        ++(t.size() > 1 && t[0] == '#' && unsigned(t[1] - '0') < 10 ? c.vcd_times
                                                                    : c.other_comments);
        // sigrok: "; Channels (2/8): MA, SLO" and "; Samplerate: 24 MHz"
        std::string_view body = trimField(t.substr(1));
        const std::string lb = asciiLower(body);
        auto colon = body.find(':');
        if (lb.rfind("channels", 0) == 0 && colon != std::string_view::npos) {
            std::vector<std::string_view> parts;
            split(body.substr(colon + 1), ',', parts);
            c.channel_names.assign(parts.begin(), parts.end());
        } else if (lb.rfind("samplerate", 0) == 0 && colon != std::string_view::npos) {
            c.rate = parseSampleRate(body.substr(colon + 1), true);
            c.rate_line = line_no_;
        } else if (wall_clock_.empty()) {
            wall_clock_ = wallClockOfSigrokComment(body);
        }
    }

    // The first line that is neither blank nor a comment: the header.
    std::string_view skipToHeaderLine(HeaderComments& c) {
        std::string_view line;
        for (;;) {
            auto st = src_->nextLine(line);
            if (st == TextSource::Status::NoData) {
                src_->waitForData(5);
                continue;
            }
            if (st == TextSource::Status::Eof) {
                if (c.vcd_times > 0 && c.other_comments == 0)
                    throw InputError(src_->name() +
                                     ": VCD value changes without a VCD header: a VCD starts "
                                     "with $timescale, $var ... and $enddefinitions");
                throw InputError(src_->name() + ": no CSV header (only comment lines)");
            }
            line_no_ = src_->lineNo();
            std::string_view t = trimField(line);
            if (t.empty()) continue;
            if (t.front() == ';' || t.front() == '#') {
                readHeaderComment(t, c);
                continue;
            }
            return line;
        }
    }

    // The signal names and the dialect (format_, timed_, first_col_) the header fields show.
    std::vector<std::string> columnNames(const std::vector<std::string_view>& f, HeaderComments c) {
        const std::string first = asciiLower(f[0]);
        std::vector<std::string> names;
        // sigrok-cli's csv:trigger=true: a last column of the trigger's samples.
        if (!c.channel_names.empty() && f.size() > 1 && asciiLower(f.back()) == "trigger")
            c.channel_names.push_back(std::string(f.back()));
        // sigrok's header form: a row of channel types, the names only in the comment
        auto isType = [&](std::string_view s) {
            const std::string l = asciiLower(s);
            return l == "logic" || l == "analog" || (l == "trigger" && s == f.back());
        };
        const bool all_logic = std::all_of(f.begin(), f.end(), isType);
        const bool typed_after_time = f.size() > 1 && std::all_of(f.begin() + 1, f.end(), isType);
        // "Time" then the channels' names (label=channel) counts in a unit; "Time" then
        // their types, in seconds (below).
        const auto sigrok_time =
            c.channel_names.size() + 1 == f.size() && (first != "time" || !typed_after_time)
                ? sigrokTimeExp10(first, c)
                : std::nullopt;
        if (sigrok_time) {
            // sigrok-cli's csv:time=true: a time column, then the comment's channels.
            timed_ = true;
            first_col_ = 1;
            format_ = "sigrok-csv";
            time_exp10_ = *sigrok_time;
            names = c.channel_names;
        } else if (first.rfind("time", 0) == 0) {
            timed_ = true;
            first_col_ = 1;
            format_ = first == "times"                            ? "scanastudio-csv"
                      : first == "time [s]" || first == "time[s]" ? "saleae-csv"
                                                                  : "time-csv";
            if (typed_after_time && c.channel_names.size() + 1 == f.size()) {
                names = c.channel_names;
                format_ = "sigrok-csv";
            } else {
                for (std::size_t i = 1; i < f.size(); ++i)
                    names.emplace_back(f[i]);
            }
        } else if (all_logic) {
            format_ = "sigrok-csv";
            if (c.channel_names.size() == f.size()) {
                names = c.channel_names;
            } else {
                for (std::size_t i = 0; i < f.size(); ++i)
                    names.push_back(std::to_string(i));
            }
        } else {
            format_ = c.rate && c.rate->timebase ? "sigrok-csv" : "plain-csv";
            names.assign(f.begin(), f.end());
        }
        return names;
    }

    // The power of ten of seconds sigrok-cli's time column counts in: its title names the
    // unit ("microseconds"), or is "Time" (label=channel) in the unit the sample period is
    // whole in (1 MHz: us, 3 MHz: ns), as sigrok-cli writes it. None for other files.
    static std::optional<int> sigrokTimeExp10(const std::string& title, const HeaderComments& c) {
        if (!c.rate || !c.rate->timebase) return std::nullopt;
        constexpr std::pair<std::string_view, int> kUnits[] = {{"seconds", 0},
                                                               {"milliseconds", -3},
                                                               {"microseconds", -6},
                                                               {"nanoseconds", -9},
                                                               {"picoseconds", -12}};
        for (const auto& [word, exp10] : kUnits)
            if (title == word) return exp10;
        if (title != "time") return std::nullopt;
        // label=channel titles the columns with the comment's names.
        const double period = double(c.rate->timebase->num) / double(c.rate->timebase->den);
        int exp10 = 0;
        while (exp10 > -12 && period < std::pow(10.0, exp10) * (1 - 1e-9))
            exp10 -= 3;
        return exp10;
    }

    void addSignals(const std::vector<std::string>& names) {
        std::unordered_set<std::string_view> seen;  // linear in columns: 10^5 are not rare
        seen.reserve(names.size());
        signals_.reserve(names.size());
        for (std::size_t i = 0; i < names.size(); ++i) {
            if (names[i].empty())
                fail(fmt::format("empty column name (column {})", i + 1 + first_col_));
            if (!seen.insert(names[i]).second)
                fail(fmt::format("duplicate column name '{}'", printable(names[i])));
            signals_.push_back(signalFor(names[i]));
        }
    }

    void parseHeader() {
        HeaderComments comments;
        const std::string_view line = skipToHeaderLine(comments);
        if (looksLikeVcdChange(line) && ((comments.vcd_times > 0 && comments.other_comments == 0) ||
                                         src_->name().ends_with(".vcd")))
            fail(
                "VCD value changes without a VCD header: a VCD starts with $timescale, "
                "$var ... and $enddefinitions");
        header_line_ = line_no_;
        // Separator: `;` (ScanaStudio), else `,`, else tab.
        sep_ = line.find(';') != std::string_view::npos    ? ';'
               : line.find(',') != std::string_view::npos  ? ','
               : line.find('\t') != std::string_view::npos ? '\t'
                                                           : ',';
        std::vector<std::string_view> f;
        splitHeader(line, sep_, f);
        if (f.size() > 1 && f.back().empty()) f.pop_back();  // a trailing separator
        ncols_ = f.size();
        col_level_.assign(ncols_, 0);
        // ",0,0,0,0" in memory order, with this file's separator.
        sep_zero_ =
            std::uint64_t(std::uint8_t(sep_)) * 0x0001000100010001ULL + 0x3000300030003000ULL;
        if (headerless(f, comments)) {
            // sigrok-cli's label=off: the comment names the columns, and this line is
            // the first sample (read again as a row).
            format_ = "sigrok-csv";
            addSignals(comments.channel_names);
            held_.push_back({line_no_, std::string(line)});
        } else {
            addSignals(columnNames(f, comments));
        }
        if (timed_) chooseResolution();  // the timebase is known before the first row
        if (!timed_) denseTimebase(comments.rate, comments.rate_line);
    }

    // A first line of samples only (each field 0 or 1) under a sigrok comment naming as
    // many channels.
    static bool headerless(const std::vector<std::string_view>& f, const HeaderComments& c) {
        return c.channel_names.size() == f.size() &&
               std::all_of(f.begin(), f.end(), [](std::string_view v) {
                   v = trimField(v);
                   return v == "0" || v == "1";
               });
    }

    static bool looksLikeVcdChange(std::string_view line) {
        const std::string_view t = trimField(line);
        return t.size() >= 2 && (t[0] == '0' || t[0] == '1' || t[0] == 'x' || t[0] == 'b') &&
               t.find_first_of(",;\t") == std::string_view::npos;
    }

    // One tick per sample: --rate, else the sigrok comment's rate, exactly.
    void denseTimebase(const std::optional<SampleRate>& comment_rate, std::uint64_t comment_line) {
        if (opts_.rate_hz > 0) {
            const SampleRate r = sampleRateOf(opts_.rate_hz);
            if (!r.timebase)
                throw InputError(fmt::format("--rate {}: {}", opts_.rate_hz, r.problem));
            tb_ = *r.timebase;
            return;
        }
        if (comment_rate && !comment_rate->timebase)
            throw InputError(
                src_->at(comment_line, fmt::format("samplerate {}", comment_rate->problem)));
        if (!comment_rate)
            throw InputError(src_->at(header_line_,
                                      "this CSV has no time column and no samplerate comment: "
                                      "give the sample rate with --rate HZ"));
        tb_ = *comment_rate->timebase;
    }

    // "CH1 MOSI" -> name MOSI (the user's label), "CH5 CH 5" -> CH5; full_name keeps the
    // column title as written.
    static SignalInfo signalFor(const std::string& title) {
        SignalInfo s{title, title, 1};
        auto sp = title.find(' ');
        if (sp != std::string::npos && title.size() > 2 && (title[0] == 'C' || title[0] == 'c') &&
            (title[1] == 'H' || title[1] == 'h') &&
            std::isdigit(static_cast<unsigned char>(title[2]))) {
            std::string rest(trimField(std::string_view(title).substr(sp + 1)));
            std::string lr = asciiLower(rest);
            s.name = lr.rfind("ch ", 0) == 0 || lr.empty() ? title.substr(0, sp) : rest;
        }
        return s;
    }

    void start() {
        started_ = true;
        std::string_view line;
        for (;;) {
            auto st = nextRow(line);
            if (st == TextSource::Status::Eof) {
                done_ = true;
                return;
            }
            if (st == TextSource::Status::NoData) {
                src_->waitForData(5);
                if (opts_.stop && opts_.stop->load()) {
                    done_ = true;
                    return;
                }
                continue;
            }
            row(line, nullptr);
            start_ = cur_;
            return;
        }
    }

    // Holds back the first rows to find the finest decimal place of their times.
    void chooseResolution() {
        int finest = 9;
        std::string_view line;
        while (held_.size() < 2000) {
            auto st = src_->nextLine(line);
            if (st != TextSource::Status::Line) {
                if (st == TextSource::Status::NoData && held_.empty()) {
                    src_->waitForData(5);
                    if (!(opts_.stop && opts_.stop->load())) continue;
                }
                break;
            }
            std::string_view t = trimField(line);
            if (t.empty() || t.front() == ';' || t.front() == '#') continue;
            held_.emplace_back(src_->lineNo(), std::string(line));
            std::string_view tf = trimField(t.substr(0, t.find(sep_)));
            Decimal d;
            if (parseTime(tf, d)) finest = std::max(finest, -(d.exp10 + time_exp10_));
        }
        resolution_ = std::min(finest, 12);
        std::int64_t den = 1;
        for (int k = 0; k < resolution_; ++k)
            den *= 10;
        tb_ = Timebase{1, den};
    }

    void row(std::string_view line, EdgeBlock* block) {
        // A dense capture repeats its previous row most of the time (100 MS/s of a 10 MHz
        // bus): the same text means the same levels, so the row is only counted.
        if (!timed_ && rows_ > 0 && line == last_row_) {
            cur_ = Tick(rows_);
            ++rows_;
            return;
        }
        if (timed_ ? plainTimedRow(line, block) : plainDenseRow(line, block)) return;
        split(line, sep_, fields_);
        if (fields_.size() != ncols_) {
            // A trailing separator is tolerated (some tools end rows with one).
            if (!(fields_.size() == ncols_ + 1 && fields_.back().empty()))
                fail(fmt::format("expected {} fields like the header (line {}), found {}", ncols_,
                                 header_line_, fields_.size()));
        }
        Tick t;
        if (timed_) {
            Decimal d;
            if (!parseTime(fields_[0], d))
                fail(fmt::format("expected a time in seconds, found '{}'", printable(fields_[0])));
            d.exp10 += time_exp10_;
            if (!toTicks(d, resolution_, t))
                fail(fmt::format("time '{}' out of range", printable(fields_[0])));
            if (rows_ > 0 && t < cur_)
                fail(fmt::format("time going backwards ({} after {})", printable(fields_[0]),
                                 previousTime()));
            prev_time_.assign(fields_[0]);
            prev_fast_.valid = false;
        } else {
            t = Tick(rows_);
        }
        for (std::size_t i = 0; i < sel_.size(); ++i) {
            const std::size_t col = sel_[i];
            std::string_view v = fields_[col];
            if (v == "X") {  // no data (Saleae's 2025 export): the level stays
                openNoData(i, t);
                continue;
            }
            if (v.size() != 1 || (v[0] != '0' && v[0] != '1'))
                fail(fmt::format("expected 0 or 1 (or X: no data) in column '{}', found '{}'",
                                 signals_[col - first_col_].full_name, printable(v)));
            col_level_[col] = std::uint8_t(v[0] - '0');
        }
        takeRow(t, block);
        if (!timed_) last_row_.assign(line);
    }

    // The rows of a time-column export as Saleae Logic writes them ("0.000001250,1,0,1"):
    // a time of plain digits with at most one point and no more decimals than the tick,
    // then single 0/1 values, no blanks or quotes. Taken without splitting the row into
    // fields, digits and values eight bytes at a time, without 128-bit arithmetic or
    // division ("The CSV readers" in bench/README.md has what that saves). Anything else,
    // errors included, returns false having changed nothing, and row() takes the row the
    // general way: the results are the same.
    bool plainTimedRow(std::string_view line, EdgeBlock* block) {
        if (time_exp10_) return false;  // times in a unit (sigrok-cli's): the general path
        const char* p = line.data();
        const char* const end = p + line.size();
        const bool neg = p < end && *p == '-';
        p += neg;
        // Two loads where 16 bytes of the row are left (scanDecimal16: 16 digits or more
        // come back as 16, refused below like any time of more than 18).
        const auto scan = [end](const char* q) {
            return end - q >= 16 ? scanDecimal16(q) : scanDecimal(q, end);
        };
        const DecimalScan whole = scan(p);
        p = whole.end;
        std::uint64_t m = whole.value;
        int digits = whole.digits, frac = 0;
        const bool point = p < end && *p == '.';
        if (point) {
            const DecimalScan part = scan(p + 1);
            frac = part.digits;
            digits += frac;
            // Up to 18 digits stay below 10^18 < 2^63; the tick is at most 10^-12 s.
            if (digits > 18 || frac > resolution_) return false;
            m = m * kPow10[frac] + part.value;
            p = part.end;
        }
        if (digits == 0 || whole.digits >= 16) return false;
        std::uint64_t ticks;
        if (__builtin_mul_overflow(m, kPow10[resolution_ - frac], &ticks) ||
            ticks > std::uint64_t(kMaxEdgeTick))
            return false;  // (toTicks() words the error)
        const Tick t = neg ? -Tick(ticks) : Tick(ticks);
        if (rows_ > 0 && t < cur_) return false;  // the general path words the error
        if (!plainValues(p, end, 1)) return false;
        prev_fast_ = {m, std::int8_t(whole.digits), std::int8_t(point ? frac : -1), neg, true};
        takeRow(t, block);
        return true;
    }
    // A dense row ("1,0,1,1") the same way: values only, its time the row's number.
    bool plainDenseRow(std::string_view line, EdgeBlock* block) {
        const char* const p = line.data();
        const char* const end = p + line.size();
        if (line.empty() || unsigned(p[0] - '0') >= 2) return false;
        col_level_[0] = std::uint8_t(p[0] - '0');
        if (!plainValues(p + 1, end, 1)) return false;
        takeRow(Tick(rows_), block);
        // row()'s same-text test is for the general path's rows: next() counts this one's
        // repeats from its text in the buffer (no copy per row).
        last_row_.clear();
        return true;
    }
    // Columns `c` on from p to the end of the row: ",0" or ",1" each (with this file's
    // separator), four per 8-byte load, nothing after the last; into col_level_.
    bool plainValues(const char* p, const char* const end, std::size_t c) {
        std::uint8_t* const vals = col_level_.data();
        for (; ncols_ - c >= 4 && end - p >= 8; c += 4, p += 8) {
            std::uint64_t w;
            std::memcpy(&w, p, 8);
            const std::uint64_t x = w ^ sep_zero_;  // 0 where as expected, 1 in a value's bit 0
            if (x & 0xFEFFFEFFFEFFFEFFULL) return false;
            vals[c] = std::uint8_t(x >> 8);
            vals[c + 1] = std::uint8_t(x >> 24);
            vals[c + 2] = std::uint8_t(x >> 40);
            vals[c + 3] = std::uint8_t(x >> 56);
        }
        for (; c < ncols_; ++c, p += 2) {
            if (end - p < 2 || p[0] != sep_ || unsigned(p[1] - '0') >= 2) return false;
            vals[c] = std::uint8_t(p[1] - '0');
        }
        return p == end;
    }
    // A row whose values are in col_level_: its time, and an edge per selected line that
    // changed.
    void takeRow(Tick t, EdgeBlock* block) {
        if (open_no_data_) [[unlikely]]
            closeNoData(t, false);
        cur_ = t;
        ++rows_;
        const std::uint8_t* const vals = col_level_.data();
        for (std::size_t i = 0; i < sel_.size(); ++i) {
            const std::uint8_t level = vals[sel_[i]];
            if (level != level_[i]) {
                level_[i] = level;
                if (block) block->edges.push_back({t, std::uint32_t(i), level});
            }
        }
    }
    // Line i's `X` (no data) at t: a `no_data` stretch opens, closed by its next value.
    void openNoData(std::size_t i, Tick t) {
        x_in_row_[i] = 1;
        if (no_data_from_[i] != kNoTick) return;
        no_data_from_[i] = t;
        ++open_no_data_;
    }
    // The stretches of no data that end at t, where their lines have values again (all
    // of them: the capture ends).
    void closeNoData(Tick t, bool all) {
        for (std::size_t i = 0; i < sel_.size(); ++i) {
            if (no_data_from_[i] != kNoTick && (all || !x_in_row_[i])) {
                no_data_.push_back(
                    noDataEvent(no_data_from_[i], t, signals_[sel_[i] - first_col_].full_name));
                no_data_from_[i] = kNoTick;
                --open_no_data_;
            }
            x_in_row_[i] = 0;
        }
    }
    // The stretches closed so far, and the start of the earliest still open (the session
    // holds later events back until it closes).
    void handNoData(EdgeBlock& block) {
        for (auto& e : no_data_)
            block.findings.push_back(std::move(e));
        no_data_.clear();
        for (std::size_t i = 0; open_no_data_ && i < sel_.size(); ++i)
            if (no_data_from_[i] != kNoTick &&
                (block.findings_from == kNoTick || no_data_from_[i] < block.findings_from))
                block.findings_from = no_data_from_[i];
    }

    // The time of the previous row as written, for "time going backwards": the general
    // path keeps its text in prev_time_; plainTimedRow() keeps its parts, from which its
    // text is made again only for the message (no copy of the text per row).
    struct PlainTime {
        std::uint64_t mantissa = 0;  // the digits, point left out
        std::int8_t whole_digits = 0;
        std::int8_t frac_digits = -1;  // -1: no point
        bool neg = false;
        bool valid = false;  // false: prev_time_ holds the previous time
    };
    PlainTime prev_fast_;
    std::string previousTime() const {
        if (!prev_fast_.valid) return prev_time_;
        const int frac = std::max<int>(prev_fast_.frac_digits, 0);
        std::string digits =
            fmt::format("{:0{}}", prev_fast_.mantissa, prev_fast_.whole_digits + frac);
        std::string out = prev_fast_.neg ? "-" : "";
        out += std::string_view(digits).substr(0, digits.size() - std::size_t(frac));
        if (prev_fast_.frac_digits >= 0) out += '.';
        out += std::string_view(digits).substr(digits.size() - std::size_t(frac));
        return out;
    }

    std::unique_ptr<TextSource> src_;
    OpenOptions opts_;
    std::string format_;
    std::string wall_clock_;  // sigrok's "; from ... on <date>"
    std::vector<SignalInfo> signals_;
    Timebase tb_;
    char sep_ = ',';
    bool timed_ = false;
    std::size_t first_col_ = 0, ncols_ = 0;
    std::uint64_t header_line_ = 0, line_no_ = 0;
    int resolution_ = 9;
    int time_exp10_ = 0;  // the time column's unit, a power of ten of seconds (sigrok-cli's)
    std::deque<std::pair<std::uint64_t, std::string>> held_;
    std::string current_, prev_time_;
    std::string last_row_;  // text of the last parsed untimed row
    std::vector<std::string_view> fields_;
    std::vector<std::size_t> sel_;           // column of each selected line
    OwnLinesArray<std::uint8_t> level_;      // written per edge, on the reading thread
    OwnLinesArray<std::uint8_t> col_level_;  // the row's values, by column (as level_)
    std::uint64_t sep_zero_ = 0;             // plainValues(): the four columns it expects per load
    std::uint64_t rows_ = 0;
    Tick start_ = 0, cur_ = 0;
    bool started_ = false, done_ = false;
    // Stretches of `X` (no data): where each selected line's began (kNoTick: none open),
    // whether the row being read has X there, how many are open, those closed.
    std::vector<Tick> no_data_from_;
    std::vector<std::uint8_t> x_in_row_;
    std::size_t open_no_data_ = 0;
    std::vector<Event> no_data_;
};

}  // namespace

std::unique_ptr<CaptureReader> openCsv(std::unique_ptr<TextSource> src, const OpenOptions& opts) {
    return std::make_unique<CsvReader>(std::move(src), opts);
}

}  // namespace busdecode
