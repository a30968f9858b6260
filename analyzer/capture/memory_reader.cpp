// A CaptureReader over an in-memory Waveform: how generated captures reach the session
// in unit tests without a file in between.
#include <algorithm>

#include "capture_reader.h"
#include "core/waveform.h"

namespace busdecode {

namespace {

class MemoryReader : public CaptureReader {
public:
    explicit MemoryReader(const Waveform& w) : w_(w) {
        for (const auto& n : w.names) {
            auto dot = n.rfind('.');
            signals_.push_back({dot == std::string::npos ? n : n.substr(dot + 1), n, 1});
        }
    }
    const std::vector<SignalInfo>& signals() const override { return signals_; }
    Timebase timebase() const override { return w_.timebase; }
    std::string formatName() const override { return "memory"; }
    void select(const std::vector<LineRef>& lines) override {
        checkSelection(lines);
        map_.assign(w_.names.size(), -1);
        for (int i = 0; i < int(lines.size()); ++i)
            map_[lines[i].signal] = i;
        selected_ = lines;
    }
    std::vector<std::uint8_t> initialLevels() override {
        std::vector<std::uint8_t> out;
        for (const auto& l : selected_)
            out.push_back(w_.initial[l.signal]);
        return out;
    }
    Tick startTick() const override { return w_.start; }
    bool next(EdgeBlock& block) override {
        block.clear();
        while (pos_ < w_.edges.size() && block.edges.size() < kEdgeBlockSize) {
            const Edge& e = w_.edges[pos_++];
            if (map_[e.line] >= 0)
                block.edges.push_back({e.t, std::uint32_t(map_[e.line]), std::uint8_t(e.level)});
        }
        block.known_until = pos_ < w_.edges.size()
                                ? (block.edges.empty() ? kNoTick : block.edges.back().t)
                                : w_.end;
        return !block.edges.empty() || pos_ < w_.edges.size();
    }
    Tick endTick() const override { return w_.end; }

private:
    const Waveform& w_;
    std::vector<SignalInfo> signals_;
    std::vector<LineRef> selected_;
    std::vector<int> map_;
    std::size_t pos_ = 0;
};

}  // namespace

std::unique_ptr<CaptureReader> memoryReader(const Waveform& w) {
    return std::make_unique<MemoryReader>(w);
}

}  // namespace busdecode
