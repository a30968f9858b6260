// Scope CSVs (scope_csv_layout.h) as rows of samples for analogReader(): the time from
// the file's own time base (a time column and its unit, or start + index * increment),
// one value per channel column; the logic analyser byte columns of a mixed-signal Rigol
// are values whose bits are the lines.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <optional>

#include <fmt/format.h>

#include "analog_capture.h"
#include "core/options.h"
#include "readers.h"
#include "scope_csv_layout.h"
#include "wall_clock.h"

namespace busdecode {

namespace {

bool blank(std::string_view f) {
    return f.find_first_not_of(" \t") == std::string_view::npos;
}

class ScopeCsvSamples : public SampleSource {
public:
    ScopeCsvSamples(std::unique_ptr<TextSource> src, ScopeLayout layout, const OpenOptions& opts)
        : src_(std::move(src)), lay_(std::move(layout)), opts_(opts) {
        for (const auto& c : lay_.channels) {
            auto at = std::find(slot_field_.begin(), slot_field_.end(), c.field);
            if (at == slot_field_.end()) {
                slot_scale_.insert(slot_scale_.begin() + (at - slot_field_.begin()), c.scale);
                at = slot_field_.insert(at, c.field);
            }
            channels_.push_back(
                {c.name, c.full_name, std::size_t(at - slot_field_.begin()), c.bit});
        }
        std::string_view line;
        for (std::size_t i = 0; i < lay_.header_lines; ++i) {
            if (!nextLine(line)) break;
            if (wall_clock_.empty()) wall_clock_ = wallClockOfLecroySegment(line);
        }
    }

    const std::vector<AnalogChannel>& channels() const override { return channels_; }
    std::size_t slots() const override { return slot_field_.size(); }
    std::string formatName() const override { return lay_.format; }
    std::string fileName() const override { return src_->name(); }
    double period() const override { return lay_.time_is_index ? lay_.increment : 0; }
    std::string wallClockStart() const override { return wall_clock_; }
    std::uint64_t bytesRead() const override { return src_->bytesRead(); }
    std::uint64_t bytesTotal() const override { return src_->bytesTotal(); }
    [[noreturn]] void fail(const std::string& what) const override {
        throw InputError(src_->at(what));
    }

    // Blank rows and rows whose every value is empty (Keysight's last) are skipped.
    bool next(double& t, float* values) override {
        begun_ = 0;
        std::string_view line;
        while (nextLine(line, opts_.follow))
            if (parseRow(line, t, values)) return true;
        return false;
    }
    bool waiting() const override { return waiting_; }
    std::uint64_t segmentBegun() const override { return begun_; }

private:
    // `may_stall`: a followed file that has no new row for kStall is `waiting()`.
    bool nextLine(std::string_view& line, bool may_stall = false) {
        constexpr auto kStall = std::chrono::milliseconds(50);
        waiting_ = false;
        // A writer may add bytes without ending a row: the stall is timed, not counted.
        // The clock is read only once a row is not there (not once a row).
        std::optional<std::chrono::steady_clock::time_point> since;
        for (;;) {
            const auto st = src_->nextLine(line);
            if (st == TextSource::Status::Line) return true;
            if (st == TextSource::Status::Eof || (opts_.stop && opts_.stop->load())) return false;
            if (!since) since = std::chrono::steady_clock::now();
            if (may_stall && std::chrono::steady_clock::now() - *since >= kStall) {
                waiting_ = true;
                return false;
            }
            src_->waitForData(5);
        }
    }

    void split(std::string_view line) {
        fields_.clear();
        for (std::size_t b = 0;;) {
            const std::size_t e = line.find(lay_.sep, b);
            fields_.push_back(line.substr(b, e == std::string_view::npos ? e : e - b));
            if (e == std::string_view::npos) return;
            b = e + 1;
        }
    }

    bool parseRow(std::string_view line, double& t, float* values) {
        if (blank(line)) return false;
        split(line);
        if (std::all_of(fields_.begin(), fields_.end(), blank)) return false;  // ",,"
        const bool trailing = fields_.size() == lay_.fields + 1 && blank(fields_.back());
        if (fields_.size() != lay_.fields && !trailing)
            fail(fmt::format("expected {} fields, found {} (a ragged row)", lay_.fields,
                             fields_.size()));
        double x;
        if (!parseScopeNumber(fields_[lay_.time_field], lay_.decimal_comma, x) || !std::isfinite(x))
            fail(fmt::format("expected a {} in column {}, found '{}'",
                             lay_.time_is_index ? "sample index" : "time", lay_.time_field + 1,
                             printable(fields_[lay_.time_field])));
        t = lay_.time_is_index ? lay_.start + x * lay_.increment : x * lay_.time_scale;
        if (lay_.segment_rows) t += segmentStart();
        std::size_t empty = 0;
        for (std::size_t s = 0; s < slot_field_.size(); ++s) {
            const std::string_view f = fields_[slot_field_[s]];
            double v = 0;
            if (blank(f))
                ++empty;
            else if (!parseScopeNumber(f, lay_.decimal_comma, v) ||
                     !(std::abs(v * slot_scale_[s]) <= std::numeric_limits<float>::max()))
                fail(fmt::format("expected a number in column {}, found '{}'", slot_field_[s] + 1,
                                 printable(f)));
            values[s] = float(v * slot_scale_[s]);
        }
        if (empty == slot_field_.size()) return false;
        if (empty) fail("an empty value in a row that has others");
        return true;
    }

    // The trigger time of the segment this data row belongs to.
    double segmentStart() {
        const std::uint64_t k = rows_ / lay_.segment_rows;
        if (k > 0 && rows_ % lay_.segment_rows == 0) begun_ = k + 1;
        ++rows_;
        if (k >= lay_.segment_starts.size())
            fail(fmt::format("more rows than {} segments of {}", lay_.segment_starts.size(),
                             lay_.segment_rows));
        return lay_.segment_starts[k];
    }

    std::unique_ptr<TextSource> src_;
    ScopeLayout lay_;
    std::uint64_t rows_ = 0;
    std::uint64_t begun_ = 0;  // segmentBegun()
    OpenOptions opts_;
    std::vector<AnalogChannel> channels_;
    std::vector<std::size_t> slot_field_;  // the field of each value slot
    std::vector<double> slot_scale_;       // and its volts per unit
    std::vector<std::string_view> fields_;
    std::string wall_clock_;  // LeCroy's first segment's trigger time
    bool waiting_ = false;
};

}  // namespace

std::unique_ptr<CaptureReader> openScopeCsvIfScope(std::unique_ptr<TextSource>& src,
                                                   const OpenOptions& opts) {
    const std::string_view head = src->peek(16384);
    auto layout = recogniseScopeCsv(head, head.size() < 16384, src->name());
    if (!layout) return nullptr;
    return analogReader(std::make_unique<ScopeCsvSamples>(std::move(src), std::move(*layout), opts),
                        opts);
}

}  // namespace busdecode
