#include "zip_archive.h"

#include <algorithm>

#include <unistd.h>
#include <zip.h>

#include <fmt/format.h>

#include "core/options.h"

namespace busdecode {

ZipArchive::ZipArchive(const std::string& path, int fd, std::string name, const std::string& what)
    : name_(std::move(name)) {
    int err = 0;
    if (fd >= 0) {
        zip_ = zip_fdopen(fd, ZIP_RDONLY, &err);
        if (!zip_) ::close(fd);
    } else {
        zip_ = zip_open(path.c_str(), ZIP_RDONLY, &err);
    }
    if (!zip_) {
        zip_error_t ze;
        zip_error_init_with_code(&ze, err);
        const std::string msg = zip_error_strerror(&ze);
        zip_error_fini(&ze);
        throw InputError(fmt::format("{}: not a readable {}: {}", name_, what, msg));
    }
}

ZipArchive::~ZipArchive() {
    if (zip_) zip_discard(zip_);
}

std::optional<std::uint64_t> ZipArchive::size(const std::string& member) {
    zip_stat_t st;
    zip_stat_init(&st);
    if (zip_stat(zip_, member.c_str(), 0, &st) != 0 || !(st.valid & ZIP_STAT_SIZE))
        return std::nullopt;
    return st.size;
}

std::optional<std::string> ZipArchive::readText(const std::string& member, std::size_t max) {
    const auto n = size(member);
    if (!n) return std::nullopt;
    std::string text(std::size_t(std::min<std::uint64_t>(*n, max)), '\0');
    ZipMember(*this, member).readExactly(text.data(), text.size());
    return text;
}

ZipMember::ZipMember(ZipArchive& archive, const std::string& member)
    : archive_(archive),
      member_(member),
      file_(zip_fopen(archive.handle(), member.c_str(), 0)),
      left_(archive.size(member).value_or(0)) {
    if (!file_) throw InputError(fmt::format("{}: cannot read {}", archive_.name(), member_));
}

ZipMember::~ZipMember() {
    zip_fclose(file_);
}

void ZipMember::readExactly(void* out, std::size_t n) {
    auto* p = static_cast<char*>(out);
    while (n > 0) {
        const zip_int64_t got = zip_fread(file_, p, n);
        if (got < 0) throwCorrupt();
        if (got == 0) throw InputError(fmt::format("{}: {} ends early", archive_.name(), member_));
        p += got;
        n -= std::size_t(got);
        left_ -= std::min<std::uint64_t>(left_, std::uint64_t(got));
    }
    // libzip checks a member's CRC only on a read at its end: one more, for nothing.
    char past;
    if (left_ == 0 && zip_fread(file_, &past, 1) < 0) throwCorrupt();
}

void ZipMember::throwCorrupt() const {
    throw InputError(fmt::format("{}: {} is corrupt: {}", archive_.name(), member_,
                                 zip_error_strerror(zip_file_get_error(file_))));
}

}  // namespace busdecode
