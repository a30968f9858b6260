#include "sample_rows_reader.h"

#include <cctype>
#include <cmath>

#include <fmt/format.h>

#include "core/options.h"
#include "readers.h"

namespace busdecode {

Timebase rowTimebase(const std::string& file, const std::string& dialect, double rate_hz) {
    if (!(rate_hz > 0))
        throw InputError(fmt::format(
            "{}: a {} has no time column or sample rate: give the sample rate with --rate HZ", file,
            dialect));
    if (rate_hz == std::floor(rate_hz) && rate_hz < 9e18) return Timebase{1, std::int64_t(rate_hz)};
    return Timebase{1'000'000, std::int64_t(std::llround(rate_hz * 1e6))};
}

namespace {

int digitValue(char c) {
    if (c >= '0' && c <= '9') return c - '0';
    if (c >= 'a' && c <= 'f') return c - 'a' + 10;
    if (c >= 'A' && c <= 'F') return c - 'A' + 10;
    return -1;
}

class SampleRowsReader : public CaptureReader {
public:
    SampleRowsReader(std::unique_ptr<TextSource> src, SampleColumns c, double rate_hz)
        : src_(std::move(src)),
          c_(std::move(c)),
          tb_(rowTimebase(src_->name(), c_.dialect, rate_hz)),
          last_row_(lastTickOf(tb_)) {}

    const std::vector<SignalInfo>& signals() const override { return c_.signals; }
    Timebase timebase() const override { return tb_; }
    std::string formatName() const override {  // "Vivado ILA CSV" -> "vivado-ila-csv"
        std::string out;
        for (char ch : c_.dialect)
            out += ch == ' ' ? '-' : char(std::tolower(static_cast<unsigned char>(ch)));
        return out;
    }
    std::uint64_t bytesRead() const override { return src_->bytesRead(); }
    std::uint64_t bytesTotal() const override { return src_->bytesTotal(); }
    bool changesOnly() const override { return true; }

    void select(const std::vector<LineRef>& lines) override {
        checkSelection(lines);
        lines_ = lines;
        for (const auto& l : lines_)
            if (l.signal < 0 || l.signal >= int(c_.signals.size()))
                throw std::out_of_range("SampleRowsReader::select");
        levels_.assign(lines_.size(), 0);
    }

    std::vector<std::uint8_t> initialLevels() override {
        if (!started_) {
            started_ = true;
            have_row_ = readRow(levels_);
        }
        return levels_;
    }
    Tick startTick() const override { return 0; }
    Tick endTick() const override { return rows_ > 0 ? Tick(rows_ - 1) : 0; }

    bool next(EdgeBlock& block) override {
        block.clear();
        if (!started_) initialLevels();
        if (!have_row_) return false;
        row_levels_.resize(lines_.size());
        while (block.edges.size() + lines_.size() <= kEdgeBlockSize) {
            if (!readRow(row_levels_)) {
                have_row_ = false;
                break;
            }
            for (std::size_t i = 0; i < lines_.size(); ++i)
                if (row_levels_[i] != levels_[i]) {
                    levels_[i] = row_levels_[i];
                    block.edges.push_back(Edge(Tick(rows_ - 1), std::uint32_t(i), levels_[i]));
                }
        }
        block.known_until = Tick(rows_ - 1);
        return have_row_ || !block.edges.empty();
    }

private:
    // The next row's levels of the selected lines; false at the end.
    bool readRow(std::vector<std::uint8_t>& out) {
        std::string_view line;
        for (;;) {
            const auto st = src_->nextLine(line);
            if (st == TextSource::Status::Eof) return false;
            if (st == TextSource::Status::NoData) {
                src_->waitForData(50);
                continue;
            }
            if (line.find_first_not_of(" \t") != std::string_view::npos) break;
        }
        split(line);
        if (fields_.size() != c_.fields)
            throw InputError(src_->at(fmt::format("{}: a row of {} fields, the first had {}",
                                                  c_.dialect, fields_.size(), c_.fields)));
        if (rows_ >= std::uint64_t(last_row_))
            throw InputError(src_->at(fmt::format(
                "{}: more than {} rows, past 2^55 or what times in ns can hold at this rate",
                c_.dialect, last_row_)));
        ++rows_;
        for (std::size_t i = 0; i < lines_.size(); ++i) {
            const int s = lines_[i].signal;
            out[i] = bitOf(fields_[c_.columns[std::size_t(s)]], c_.radix[std::size_t(s)],
                           lines_[i].bit < 0 ? 0 : lines_[i].bit);
        }
        return true;
    }

    void split(std::string_view line) {
        fields_.clear();
        if (c_.comma_only) {
            for (std::size_t at = 0;;) {
                const std::size_t comma = line.find(',', at);
                fields_.push_back(trim(line.substr(at, comma - at)));
                if (comma == std::string_view::npos) break;
                at = comma + 1;
            }
            return;
        }
        // Runs of separators are one; leading and trailing ones (ChipScope's TAB before
        // the line end) separate nothing.
        std::size_t at = 0;
        while (at < line.size()) {
            const std::size_t b = line.find_first_not_of(" \t,", at);
            if (b == std::string_view::npos) break;
            const std::size_t e = std::min(line.find_first_of(" \t,", b), line.size());
            fields_.push_back(line.substr(b, e - b));
            at = e;
        }
    }

    static std::string_view trim(std::string_view s) {
        while (!s.empty() && (s.front() == ' ' || s.front() == '\t'))
            s.remove_prefix(1);
        while (!s.empty() && (s.back() == ' ' || s.back() == '\t'))
            s.remove_suffix(1);
        return s;
    }

    // Bit `bit` of a field written in `radix`.
    std::uint8_t bitOf(std::string_view v, SampleColumns::Radix radix, int bit) const {
        auto bad = [&](const char* what) {
            return InputError(
                src_->at(fmt::format("{}: '{}' is not {}", c_.dialect, printable(v), what)));
        };
        if (radix == SampleColumns::Radix::Unsigned) {
            if (v.empty() || v.size() > 19 || v.find_first_not_of("0123456789") != v.npos)
                throw bad("an unsigned number");
            std::uint64_t x = 0;
            for (char ch : v)
                x = x * 10 + std::uint64_t(ch - '0');
            return bit < 64 ? std::uint8_t((x >> bit) & 1) : 0;
        }
        const bool hex = radix == SampleColumns::Radix::Hex;
        if (v.empty()) throw bad(hex ? "a hex value" : "a binary value");
        const std::size_t per = hex ? 4 : 1;
        for (char ch : v) {
            const int d = digitValue(ch);
            if (d < 0 || (!hex && d > 1)) throw bad(hex ? "a hex value" : "0 or 1 (binary)");
        }
        const std::size_t digit = std::size_t(bit) / per;
        if (digit >= v.size()) return 0;
        return std::uint8_t((digitValue(v[v.size() - 1 - digit]) >> (std::size_t(bit) % per)) & 1);
    }

    std::unique_ptr<TextSource> src_;
    SampleColumns c_;
    Timebase tb_;
    Tick last_row_;
    std::vector<LineRef> lines_;
    std::vector<std::uint8_t> levels_, row_levels_;
    std::vector<std::string_view> fields_;
    std::uint64_t rows_ = 0;
    bool started_ = false, have_row_ = false;
};

}  // namespace

std::unique_ptr<CaptureReader> sampleRowsReader(std::unique_ptr<TextSource> src,
                                                SampleColumns columns, double rate_hz) {
    return std::make_unique<SampleRowsReader>(std::move(src), std::move(columns), rate_hz);
}

}  // namespace busdecode
