#include "batch.h"

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdio>
#include <mutex>
#include <optional>
#include <thread>

#include <fmt/format.h>

#include "app/decode_args.h"
#include "app/standard_streams.h"
#include "core/options.h"
#include "rule_checker.h"

namespace busdecode {

namespace {

// "[##########----------]  12/40 captures" redrawn in place on stderr.
void drawProgress(std::size_t done, std::size_t total) {
    constexpr int kWidth = 30;
    const int filled = total ? int(double(done) / double(total) * kWidth) : kWidth;
    printError(fmt::format("\r[{}{}] {:>{}}/{} captures", std::string(std::size_t(filled), '#'),
                           std::string(std::size_t(kWidth - filled), '-'), done,
                           fmt::formatted_size("{}", total), total));
}

void clearProgress() {
    printError("\r\033[K");
}

std::string keyOf(const std::string& assignment) {
    auto eq = assignment.find('=');
    return eq == std::string::npos ? assignment : assignment.substr(0, eq);
}

// Whether the command line's `top` sets what the rules file's `base` sets: the same key,
// for the same decoder or for any (`bits` and `bissc.bits`).
bool sameSetting(const std::string& top, const std::string& base) {
    const std::string t = keyOf(top), b = keyOf(base);
    const auto td = t.find('.'), bd = b.find('.');
    const bool either_unscoped = td == std::string::npos || bd == std::string::npos;
    return either_unscoped ? t.substr(td == std::string::npos ? 0 : td + 1) ==
                                 b.substr(bd == std::string::npos ? 0 : bd + 1)
                           : t == b;
}

std::vector<std::string> overlay(const std::vector<std::string>& base,
                                 const std::vector<std::string>& top) {
    std::vector<std::string> out;
    for (const auto& b : base) {
        bool replaced = false;
        for (const auto& t : top)
            replaced = replaced || sameSetting(t, b);
        if (!replaced) out.push_back(b);
    }
    out.insert(out.end(), top.begin(), top.end());
    return out;
}

}  // namespace

DecodeChoice combineDecodeChoice(const Rules& rules, const std::vector<std::string>& cli_protos,
                                 const std::vector<std::string>& cli_maps,
                                 const std::vector<std::string>& cli_opts) {
    DecodeChoice c;
    c.protos = !cli_protos.empty() ? cli_protos : rules.decode.protos;
    if (c.protos.empty())
        for (const auto& t : rules.tables)
            if (t.proto != kSignalTable) c.protos.push_back(t.proto);  // not a decoder
    c.maps = overlay(rules.decode.maps, cli_maps);
    c.opts = overlay(rules.decode.opts, cli_opts);
    return c;
}

CaptureVerdict verifyCapture(const std::string& capture, const Rules& rules,
                             const std::vector<DecoderRequest>& requests, const OpenOptions& open) {
    CaptureVerdict v;
    v.capture = capture;
    const auto t0 = std::chrono::steady_clock::now();
    try {
        RuleChecker checker(rules);
        v.hints = decodeCapture(capture, requests, open, {&checker}, false, open.stop).advice;
        v.outcomes = checker.outcomes();
        v.events = checker.eventSummary();
    } catch (const InputError& e) {
        v.input_error = true;
        v.error = oneLine(e.what());
    } catch (const std::exception& e) {
        v.input_error = true;
        v.error = fmt::format("internal error: {}", oneLine(e.what()));
    }
    v.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    return v;
}

std::vector<CaptureVerdict> verifyCaptures(
    const std::vector<std::string>& captures, const Rules& rules,
    const std::vector<DecoderRequest>& requests, const OpenOptions& open, const BatchOptions& batch,
    const std::function<void(const CaptureVerdict&)>& on_verdict) {
    const std::size_t n = captures.size();
    std::vector<std::optional<CaptureVerdict>> slots(n);
    std::mutex mu;
    std::condition_variable cv;
    std::atomic<std::size_t> next{0};
    std::size_t finished = 0;
    OpenOptions job_open = open;  // set below, before the workers start

    auto worker = [&] {
        for (;;) {
            const std::size_t i = next.fetch_add(1);
            if (i >= n) return;
            CaptureVerdict v;
            if (open.stop && *open.stop) {  // interrupted: the rest are not started
                v.capture = captures[i];
                v.input_error = true;
                v.error = "not verified: interrupted";
            } else {
                v = verifyCapture(captures[i], rules, requests, job_open);
            }
            {
                std::lock_guard<std::mutex> lock(mu);
                slots[i] = std::move(v);
                ++finished;
            }
            cv.notify_one();
        }
    };
    // jobs <= 0: one per core.
    const std::size_t wanted = batch.jobs > 0 ? std::size_t(batch.jobs)
                                              : std::max(1u, std::thread::hardware_concurrency());
    const std::size_t threads = std::min(wanted, std::max<std::size_t>(n, 1));
    // Captures decoded side by side keep the cores busy already: pieces decoded ahead on
    // top would only add work (bench/README.md, "BiSS-C's pieces decoded ahead").
    if (threads > 1) job_open.decode_ahead = false;
    std::vector<std::thread> pool;
    for (std::size_t t = 0; t < threads; ++t)
        pool.emplace_back(worker);

    // Report in input order on this thread while the workers run.
    std::vector<CaptureVerdict> out;
    out.reserve(n);
    if (batch.progress) drawProgress(0, n);
    for (std::size_t i = 0; i < n; ++i) {
        std::unique_lock<std::mutex> lock(mu);
        std::size_t drawn = finished;
        cv.wait(lock, [&] {
            if (batch.progress && finished != drawn) {
                drawn = finished;
                drawProgress(drawn, n);
            }
            return slots[i].has_value();
        });
        out.push_back(std::move(*slots[i]));
        const std::size_t done_now = finished;
        lock.unlock();
        if (batch.progress) clearProgress();
        if (on_verdict) on_verdict(out.back());
        if (batch.progress) drawProgress(done_now, n);
    }
    for (auto& t : pool)
        t.join();
    if (batch.progress) clearProgress();
    return out;
}

}  // namespace busdecode
