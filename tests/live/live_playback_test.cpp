// A recorded session played back as a device (--device playback:file=X.sr): the real
// Renishaw BiSS-C captures give exactly the frames decoding the file gives, and the
// frames published on LCM meanwhile reach a subscriber, followed by the run's "end".
#include <gtest/gtest.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <lcm/lcm-cpp.hpp>
#include <set>
#include <thread>

#include "busdecode_lcm/bissc_frame_t.hpp"
#include "busdecode_lcm/decode_status_t.hpp"
#include "support/paths.h"

namespace busdecode::test {
namespace {

std::string renishaw(const std::string& rate) {
    return realCaptures() + "/biss-renishaw/sr/renishaw_biss_" + rate + ".sr";
}

const std::vector<std::string> kBissc{"--proto", "bissc", "--opt", "bits=32", "--format", "jsonl"};

class RenishawPlayback : public ::testing::TestWithParam<std::string> {};

TEST_P(RenishawPlayback, DecodesTheFramesTheFileGives) {
    const std::string capture = renishaw(GetParam());
    std::vector<std::string> file_args{capture}, live_args{"--device", "playback:file=" + capture};
    file_args.insert(file_args.end(), kBissc.begin(), kBissc.end());
    live_args.insert(live_args.end(), kBissc.begin(), kBissc.end());
    const RunResult file = runDecode(file_args);
    ASSERT_EQ(file.status, 0) << file.err;
    ASSERT_NE(file.out.find("\"type\":\"frame\""), std::string::npos);
    const RunResult live = runDecode(live_args);
    EXPECT_EQ(live.status, 0) << live.err;
    EXPECT_EQ(live.out, file.out);
}

INSTANTIATE_TEST_SUITE_P(Rates, RenishawPlayback,
                         ::testing::Values("250kHz", "1MHz", "2MHz", "5MHz", "10MHz"));

struct Received {
    std::vector<std::int64_t> positions;
    std::vector<std::string> states;
    busdecode_lcm::decode_status_t last{};
    void onFrame(const lcm::ReceiveBuffer*, const std::string&,
                 const busdecode_lcm::bissc_frame_t* m) {
        positions.push_back(m->position);
    }
    void onStatus(const lcm::ReceiveBuffer*, const std::string&,
                  const busdecode_lcm::decode_status_t* m) {
        states.push_back(m->state);
        last = *m;
    }
};

// "position":N of every jsonl line, in order.
std::vector<std::int64_t> positionsIn(const std::string& jsonl) {
    std::vector<std::int64_t> out;
    for (std::size_t at = jsonl.find("\"position\":"); at != std::string::npos;
         at = jsonl.find("\"position\":", at + 1))
        out.push_back(std::stoll(jsonl.substr(at + 11)));
    return out;
}

TEST(LivePlayback, PublishesTheFramesOnLcmToASubscriber) {
    // A port of this process's own: tests running at once do not hear each other.
    const std::string url =
        "udpm://239.255.76.67:" + std::to_string(20000 + getpid() % 20000) + "?ttl=0";
    lcm::LCM lc(url);
    if (!lc.good()) GTEST_SKIP() << "no LCM on " << url << " (no multicast route)";
    Received got;
    lc.subscribe("DECODE_BISSC_FRAME", &Received::onFrame, &got);
    lc.subscribe("DECODE_STATUS", &Received::onStatus, &got);
    // Multicast must loop back to this machine, or no subscriber can hear it.
    busdecode_lcm::decode_status_t probe{};
    probe.state = "probe";
    lc.publish("DECODE_STATUS", &probe);
    lc.handleTimeout(1000);
    if (got.states.empty()) GTEST_SKIP() << "multicast on " << url << " does not loop back";
    got.states.clear();

    const std::string capture = renishaw("1MHz");
    std::atomic<bool> done{false};
    RunResult live;
    std::thread decode([&] {
        live = runDecode({"--device", "playback:file=" + capture, "--proto", "bissc", "--opt",
                          "bits=32", "--format", "jsonl", "--lcm", url});
        done = true;
    });
    const auto until = std::chrono::steady_clock::now() + std::chrono::seconds(20);
    while (std::chrono::steady_clock::now() < until &&
           (got.states.empty() || got.states.back() != "end"))
        lc.handleTimeout(50);
    decode.join();
    ASSERT_EQ(live.status, 0) << live.err;
    const std::vector<std::int64_t> decoded = positionsIn(live.out);
    ASSERT_EQ(decoded.size(), 3u);
    EXPECT_EQ(got.positions, decoded);
    ASSERT_FALSE(got.states.empty());
    EXPECT_EQ(got.states.back(), "end");
    // The acquisition's counts: the whole session, nothing dropped.
    EXPECT_EQ(got.last.live_samples, 1'000'000);
    EXPECT_EQ(got.last.live_dropped, 0);
    EXPECT_GE(got.last.live_behind, 0);
    EXPECT_EQ(got.last.format, "sigrok-playback");
}

}  // namespace
}  // namespace busdecode::test
