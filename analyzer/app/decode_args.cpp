#include "decode_args.h"

#include <chrono>
#include <thread>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "capture/prefetch_reader.h"
#include "core/registry.h"
#include "plugin_loader.h"

namespace busdecode {

namespace {

std::pair<std::string, std::string> splitAssignment(const std::string& what, const std::string& s) {
    auto eq = s.find('=');
    if (eq == std::string::npos || eq == 0)
        throw InputError(fmt::format("{} '{}': expected KEY=VALUE", what, s));
    return {s.substr(0, eq), s.substr(eq + 1)};
}

bool declaresOption(const DecoderInfo& info, const std::string& key) {
    if (key == "glitch_ns") return true;
    for (const auto& o : info.options)
        if (o.key == key) return true;
    return false;
}

bool declaresRole(const DecoderInfo& info, const std::string& role) {
    for (const auto& r : info.roles)
        if (r.name == role) return true;
    return false;
}

}  // namespace

std::vector<DecoderRequest> buildRequests(const std::vector<std::string>& protos,
                                          const std::vector<std::string>& maps,
                                          const std::vector<std::string>& opts) {
    std::vector<DecoderRequest> reqs;
    std::vector<const DecoderInfo*> infos;
    for (const auto& p : protos) {
        const DecoderFactory* f = Registry::instance().find(p);
        if (!f) {
            loadPlugins();  // every plugin: one may provide it without saying so
            f = Registry::instance().find(p);
        }
        if (!f)
            Registry::instance().create(p, {});  // throws "unknown decoder ... (available: ...)"
        reqs.push_back({p, {}, {}});
        infos.push_back(&f->info());
    }
    // A `proto.` prefix scopes a key to one decoder id; otherwise it goes to every
    // requested decoder that declares it.
    auto apply = [&](const std::string& what, const std::string& text, bool is_map) {
        auto [key, value] = splitAssignment(what, text);
        std::string scope;
        if (auto dot = key.find('.'); dot != std::string::npos) {
            std::string prefix = key.substr(0, dot);
            for (const auto& p : protos)
                if (p == prefix) scope = prefix;
            if (!scope.empty()) key = key.substr(dot + 1);
        }
        bool used = false;
        for (std::size_t i = 0; i < reqs.size(); ++i) {
            if (!scope.empty() && reqs[i].proto != scope) continue;
            const bool known =
                is_map ? declaresRole(*infos[i], key) : declaresOption(*infos[i], key);
            if (!known && (scope.empty() && reqs.size() > 1)) continue;
            if (!known) {
                // Let the decoder's own validation produce the error listing valid keys.
                if (is_map) {
                    std::vector<std::string> roles;
                    for (const auto& r : infos[i]->roles)
                        roles.push_back(r.name);
                    throw InputError(
                        fmt::format("decoder {}: unknown role '{}' in --map (roles: {})",
                                    reqs[i].proto, key, fmt::join(roles, ", ")));
                }
                Options::resolve(*infos[i], {{key, value}});
            }
            (is_map ? reqs[i].map : reqs[i].options)[key] = value;
            used = true;
        }
        if (!used) {
            std::vector<std::string> keys;
            for (const auto* info : infos) {
                if (is_map)
                    for (const auto& r : info->roles)
                        keys.push_back(info->id + "." + r.name);
                else
                    for (const auto& o : info->options)
                        keys.push_back(info->id + "." + o.key);
            }
            throw InputError(fmt::format("{} {}: no chosen decoder has '{}' (valid: {})", what,
                                         text, key, fmt::join(keys, ", ")));
        }
    };
    for (const auto& m : maps)
        apply("--map", m, true);
    for (const auto& o : opts)
        apply("--opt", o, false);
    return reqs;
}

namespace {

// --realtime: hands out blocks no faster than the capture's own time runs.
class PacedReader : public CaptureReader {
public:
    PacedReader(std::unique_ptr<CaptureReader> inner, const std::atomic<bool>* stop)
        : in_(std::move(inner)), stop_(stop) {}
    const std::vector<SignalInfo>& signals() const override { return in_->signals(); }
    Timebase timebase() const override { return in_->timebase(); }
    std::string formatName() const override { return in_->formatName(); }
    void select(const std::vector<LineRef>& l) override { in_->select(l); }
    std::vector<std::uint8_t> initialLevels() override {
        auto v = in_->initialLevels();
        t0_ = std::chrono::steady_clock::now();
        return v;
    }
    Tick startTick() const override { return in_->startTick(); }
    bool next(EdgeBlock& b) override {
        if (!in_->next(b)) return false;
        Tick last = b.edges.empty() ? b.known_until : b.edges.back().t;
        if (last != kNoTick) {
            const double s = double(last - in_->startTick()) * in_->timebase().secondsPerTick();
            sleepUntil(t0_ + std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                                 std::chrono::duration<double>(s)));
        }
        return true;
    }
    Tick endTick() const override { return in_->endTick(); }
    std::uint64_t bytesRead() const override { return in_->bytesRead(); }
    std::uint64_t bytesTotal() const override { return in_->bytesTotal(); }

private:
    // In short slices: a stop request (Ctrl-C) ends a long pause at once.
    void sleepUntil(std::chrono::steady_clock::time_point when) const {
        constexpr auto kSlice = std::chrono::milliseconds(20);
        while (!(stop_ && *stop_)) {
            const auto now = std::chrono::steady_clock::now();
            if (now >= when) return;
            std::this_thread::sleep_for(
                std::min<std::chrono::steady_clock::duration>(when - now, kSlice));
        }
    }

    std::unique_ptr<CaptureReader> in_;
    const std::atomic<bool>* stop_;
    std::chrono::steady_clock::time_point t0_;
};

}  // namespace

std::string hintLine(const std::string& capture, const std::string& hint) {
    return fmt::format("decode: {}: hint: {}\n", capture, hint);
}

CaptureFacts decodeCapture(const std::string& path, const std::vector<DecoderRequest>& requests,
                           const OpenOptions& open, const std::vector<OutputSink*>& sinks) {
    return decodeCapture(path, requests, open, sinks, false, nullptr);
}

CaptureFacts decodeCapture(const std::string& path, const std::vector<DecoderRequest>& requests,
                           const OpenOptions& open, const std::vector<OutputSink*>& sinks,
                           bool realtime, const std::atomic<bool>* stop) {
    // Read ahead on a second thread while this one decodes (two cores, pipelined), unless
    // told to keep to one (--threads 1: several decodes side by side, one core each). A
    // file read to its end, never waiting for input, is handed over a few blocks at a
    // time: one whose size the reader knows (a regular file; a pipe's is unknown), not
    // followed.
    std::unique_ptr<CaptureReader> reader = openCapture(path, open);
    if (open.read_ahead && !reader->readsAhead()) {
        const bool whole_file = !open.follow && reader->bytesTotal() > 0;
        reader =
            prefetchReader(std::move(reader), kReadAheadBlocks, whole_file ? kWholeFileBatch : 1);
    }
    if (realtime) reader = std::make_unique<PacedReader>(std::move(reader), stop);
    Session session(requests, *reader, path);
    session.setPieceSpeculation(open.decode_ahead);
    if (stop) session.setStopFlag(stop);
    // Stopped before its end, a capture that is not followed is not reported at all.
    if (stop && !open.follow) session.abandonWhenStopped();
    for (auto* s : sinks)
        session.addSink(s);
    session.run();
    return session.facts();
}

}  // namespace busdecode
