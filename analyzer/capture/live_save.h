#pragma once
// --save FILE.sr: the samples acquired, written as a sigrok session beside the decode.
// They are spooled to an unlinked file next to the target (constant memory whatever the
// run's length) and packed into the session, atomically, when the run ends.
#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

namespace busdecode {

class LiveSaver {
public:
    // names: the lines by bit. Throws InputError naming the file when it cannot be written.
    LiveSaver(std::string path, std::vector<std::string> names, std::uint64_t samplerate);
    ~LiveSaver();
    LiveSaver(const LiveSaver&) = delete;
    LiveSaver& operator=(const LiveSaver&) = delete;

    // n words of `unit` bytes, as the device sent them (on the acquisition thread).
    void add(const std::uint8_t* data, std::size_t n, unsigned unit);
    // Writes the session; false (nothing written) when no sample came. Throws InputError
    // naming the file (a full disk included).
    bool finish();
    std::uint64_t samples() const { return samples_; }

private:
    std::string path_;
    std::vector<std::string> names_;
    std::uint64_t rate_;
    unsigned unit_;
    std::FILE* spool_ = nullptr;
    std::uint64_t samples_ = 0;
    std::vector<std::uint8_t> repacked_;
};

}  // namespace busdecode
