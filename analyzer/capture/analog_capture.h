#pragma once
// A capture of sampled voltages (scope CSVs, sigrok analog channels) as a CaptureReader:
// a SampleSource hands out rows of samples, analogReader() turns them into edges with a
// Schmitt trigger per line (analog_lines.h). The tick is a power of ten at most a
// hundredth of the sample period (1 ns to 1 ps), so edges interpolated between samples
// keep their sub-sample time. The first rows are held back (a bounded number) to find
// each line's levels and the sample period.
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "capture_reader.h"

namespace busdecode {

struct AnalogChannel {
    std::string name, full_name;
    std::size_t slot = 0;  // its value in a row of samples
    int bit = -1;          // >= 0: a logic line, this bit of the value (a byte column)
};

class SampleSource {
public:
    virtual ~SampleSource() = default;
    virtual const std::vector<AnalogChannel>& channels() const = 0;
    virtual std::size_t slots() const = 0;  // values per row
    virtual std::string formatName() const = 0;
    virtual std::string fileName() const = 0;  // for messages
    // Seconds between samples when the file states it; 0: found from the rows.
    virtual double period() const { return 0; }
    // When the capture began by the wall clock, as the file says (wall_clock.h), or "".
    virtual std::string wallClockStart() const { return {}; }
    // The next row: its time in seconds and slots() values. False at the end. Throws
    // InputError naming the file and line.
    virtual bool next(double& t, float* values) = 0;
    // After next(): the number (2, 3, ...) of the segment of a sequence capture that the
    // row just read begins, after dead time the scope did not record; 0 for any other row.
    virtual std::uint64_t segmentBegun() const { return 0; }
    // After next() returned false: true when that was no end but a followed file with no
    // new row for a while; next() may be called again.
    virtual bool waiting() const { return false; }
    // Throws InputError naming the file and the row last read.
    [[noreturn]] virtual void fail(const std::string& what) const = 0;
    virtual std::uint64_t bytesRead() const { return 0; }
    virtual std::uint64_t bytesTotal() const { return 0; }
};

std::unique_ptr<CaptureReader> analogReader(std::unique_ptr<SampleSource> src,
                                            const OpenOptions& opts);

}  // namespace busdecode
