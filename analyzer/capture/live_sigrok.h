#pragma once
// The analyser, through libsigrok's C API: opens one device (or a recorded session played
// back as one), configures it and runs the acquisition, handing every logic packet to a
// callback on the thread that calls run().
#include <atomic>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "live_device.h"

namespace busdecode {

class SigrokAcquisition {
public:
    // Opens and configures the device. Throws InputError ("--device demo: ...").
    explicit SigrokAcquisition(const LiveSettings& settings);
    ~SigrokAcquisition();
    SigrokAcquisition(const SigrokAcquisition&) = delete;
    SigrokAcquisition& operator=(const SigrokAcquisition&) = delete;

    // The enabled logic channels, in the order of their bits in a sample word.
    const std::vector<std::string>& channelNames() const;
    std::uint64_t samplerate() const;
    bool isPlayback() const;

    // Logic packet: n words of `unit` bytes. Returns false to end the acquisition.
    using LogicPacket = std::function<bool(const std::uint8_t* data, std::size_t n, unsigned unit)>;
    // Runs the acquisition until the device ends it or stop(). A recorded session is paced
    // at its sample rate. Returns "" or why the device could not start.
    std::string run(const LogicPacket& on_logic);
    // From any thread: ends run() soon.
    void stop();
    // The last error libsigrok logged ("" if none), to say why a device went away.
    std::string lastLibraryError() const;

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

// `decode --scan`: one line per attached device, the demo device included:
// "DRIVER<TAB>VENDOR MODEL<TAB>CONNECTION<TAB>CHANNELS".
std::vector<std::string> scanSigrokDevices();

}  // namespace busdecode
