// two_cores_probe: what passing data between two threads costs on this machine, now.
//
//     two_cores_probe            prints "round trip N ns, handover G GB/s"
//
// On the bench VM the host places the two virtual cores sometimes on one die (a shared
// L3) and sometimes on two, for minutes at a time; a cache line written on one core and
// then read or written on the other costs several times as much on two dies, while each
// core alone runs as fast. decode's two threads hand each other data, single-thread
// programs do not: so bench/run.sh prints this beside its timings (bench/README.md, "Two
// dies"). Two figures:
// - round trip: one cache line passed back and forth, 200 000 times (latency);
// - handover: 256 KiB blocks written by one thread and summed by the other, eight in
//   flight, 500 MiB in all (the rate at which written data crosses).
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <thread>
#include <vector>

namespace {

using Clock = std::chrono::steady_clock;

double roundTripNs() {
    constexpr int kTrips = 200000;
    alignas(64) std::atomic<int> turn{0};  // 1: the other thread's turn
    std::thread other([&] {
        for (int i = 0; i < kTrips; ++i) {
            while (turn.load(std::memory_order_acquire) != 1) {
            }
            turn.store(0, std::memory_order_release);
        }
    });
    const auto t0 = Clock::now();
    for (int i = 0; i < kTrips; ++i) {
        turn.store(1, std::memory_order_release);
        while (turn.load(std::memory_order_acquire) != 0) {
        }
    }
    const auto t1 = Clock::now();
    other.join();
    return std::chrono::duration<double, std::nano>(t1 - t0).count() / kTrips;
}

constexpr std::size_t kBlock = 256 << 10, kInFlight = 8;
constexpr int kBlocks = 2000;

double handoverGBs(std::uint64_t& checksum) {
    std::vector<std::uint64_t> buf(kBlock * kInFlight / 8);
    alignas(64) std::atomic<int> written{0};
    alignas(64) std::atomic<int> read{0};
    const auto t0 = Clock::now();
    std::thread writer([&] {
        for (int b = 0; b < kBlocks; ++b) {
            while (b - read.load(std::memory_order_acquire) >= int(kInFlight)) {
            }
            std::uint64_t* p = &buf[(std::size_t(b) % kInFlight) * kBlock / 8];
            std::fill(p, p + kBlock / 8, std::uint64_t(b));
            written.store(b + 1, std::memory_order_release);
        }
    });
    std::uint64_t sum = 0;
    for (int b = 0; b < kBlocks; ++b) {
        while (written.load(std::memory_order_acquire) <= b) {
        }
        const std::uint64_t* p = &buf[(std::size_t(b) % kInFlight) * kBlock / 8];
        for (std::size_t i = 0; i < kBlock / 8; ++i)
            sum += p[i];
        read.store(b + 1, std::memory_order_release);
    }
    const auto t1 = Clock::now();
    writer.join();
    checksum = sum;
    return double(kBlock) * kBlocks / std::chrono::duration<double>(t1 - t0).count() / 1e9;
}

}  // namespace

int main(int argc, char**) {
    if (argc != 1) {
        std::fprintf(stderr, "usage: two_cores_probe (no arguments)\n");
        return 2;
    }
    const double ns = roundTripNs();
    std::uint64_t checksum = 0;
    const double gbs = handoverGBs(checksum);
    // Block b holds kBlock / 8 copies of b: the sum proves every block was read whole.
    const std::uint64_t expected =
        std::uint64_t(kBlock / 8) * (std::uint64_t(kBlocks) * (kBlocks - 1) / 2);
    if (checksum != expected) {
        std::fprintf(stderr, "two_cores_probe: read %llu, expected %llu\n",
                     static_cast<unsigned long long>(checksum),
                     static_cast<unsigned long long>(expected));
        return 1;
    }
    std::printf("round trip %.0f ns, handover %.1f GB/s\n", ns, gbs);
    return 0;
}
