#pragma once
// ZIP captures (sigrok .sr, DSView .dsl) through libzip: opening with one-line errors,
// small members read whole, large ones streamed. Messages name the file and the member.
#include <cstdint>
#include <optional>
#include <string>

struct zip;
struct zip_file;

namespace busdecode {

class ZipArchive {
public:
    // Opens `path`, or when fd >= 0 that descriptor (owned from here on); `name` is what
    // messages call the file, `what` what it was expected to be ("a sigrok session").
    ZipArchive(const std::string& path, int fd, std::string name, const std::string& what);
    ~ZipArchive();
    ZipArchive(const ZipArchive&) = delete;
    ZipArchive& operator=(const ZipArchive&) = delete;

    const std::string& name() const { return name_; }
    zip* handle() { return zip_; }
    // Uncompressed size of `member`, or nullopt when there is no such member.
    std::optional<std::uint64_t> size(const std::string& member);
    bool has(const std::string& member) { return size(member).has_value(); }
    // The whole of a small member (at most `max` bytes are read); nullopt when absent.
    std::optional<std::string> readText(const std::string& member, std::size_t max = 1 << 20);

private:
    std::string name_;
    zip* zip_ = nullptr;
};

// One member read front to back.
class ZipMember {
public:
    ZipMember(ZipArchive& archive, const std::string& member);
    ~ZipMember();
    ZipMember(const ZipMember&) = delete;
    ZipMember& operator=(const ZipMember&) = delete;
    // Fills out[0, n) entirely; throws InputError naming file and member if the member
    // is corrupt (its CRC checked once it is read to its end) or ends first.
    void readExactly(void* out, std::size_t n);

private:
    [[noreturn]] void throwCorrupt() const;
    ZipArchive& archive_;
    std::string member_;
    zip_file* file_ = nullptr;
    std::uint64_t left_ = 0;  // bytes of the member not read yet
};

}  // namespace busdecode
