#include "report_sink.h"

#include <algorithm>
#include <cctype>

#include "capture_stats.h"
#include "core/atomic_file.h"
#include "html_report.h"
#include "text_report.h"

namespace busdecode {

namespace {

bool wantsHtml(const std::string& path) {
    auto dot = path.rfind('.');
    if (dot == std::string::npos) return false;
    std::string ext = path.substr(dot + 1);
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return char(std::tolower(c)); });
    return ext == "html" || ext == "htm";
}

// Streams the events into CaptureStats; renders and writes the file at the end.
class ReportSink : public OutputSink {
public:
    // The report is written once the capture is decoded: a bad path fails before that.
    explicit ReportSink(std::string path) : path_(std::move(path)), html_(wantsHtml(path_)) {
        checkWritable(path_);
        stats_.keepWaveforms(html_);
    }
    void begin(const CaptureFacts& facts) override { stats_.begin(facts); }
    // The HTML report draws the captured edges of a few events.
    bool wantsEdges() const override { return html_; }
    void onEdges(const Edge* first, const Edge* last) override { stats_.addEdges(first, last); }
    void onVolts(const std::vector<VoltSample>& volts,
                 const std::vector<LineThreshold>& thresholds) override {
        stats_.addVolts(volts, thresholds);
    }
    void onEvent(const Event& e, const CaptureFacts&) override { stats_.add(e); }
    void end(const CaptureFacts& facts) override {
        stats_.end(facts);
        writeFileAtomically(path_, html_ ? renderHtmlReport(stats_) : renderTextReport(stats_));
    }

private:
    std::string path_;
    bool html_;
    CaptureStats stats_;
};

}  // namespace

std::unique_ptr<OutputSink> makeReportSink(const std::string& path) {
    return std::make_unique<ReportSink>(path);
}

}  // namespace busdecode
