#include "live_module.h"

#include <dlfcn.h>

#include <QCoreApplication>
#include <QDir>
#include <QFileInfo>

#include <fmt/format.h>

#include "core/options.h"

namespace busdecode {

namespace {

#define BUSDECODE_STRINGIFY2(x) #x
#define BUSDECODE_STRINGIFY(x) BUSDECODE_STRINGIFY2(x)

// Beside the core library, in the build tree and installed (Debian's multiarch too).
std::vector<std::string> moduleCandidates() {
    const QString app =
        QCoreApplication::instance() ? QCoreApplication::applicationDirPath() : QString(".");
    std::vector<std::string> out;
    for (const char* rel :
         {"/../lib/busdecode", "/../lib/x86_64-linux-gnu/busdecode", "/../lib64/busdecode"})
        out.push_back(QDir::cleanPath(app + rel + "/busdecode_live.so").toStdString());
    return out;
}

const LiveModule* load(const std::string& option) {
    std::string tried;
    for (const auto& path : moduleCandidates()) {
        if (!QFileInfo::exists(QString::fromStdString(path))) {
            tried += (tried.empty() ? "" : ", ") + path;
            continue;
        }
        void* handle = ::dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
        if (!handle)
            throw InputError(fmt::format("{}: cannot load {}: {}", option, path, ::dlerror()));
        using Entry = const LiveModule* (*)();
        auto entry =
            reinterpret_cast<Entry>(::dlsym(handle, BUSDECODE_STRINGIFY(BUSDECODE_LIVE_ENTRY)));
        const LiveModule* m = entry ? entry() : nullptr;
        if (!m || m->abi != kLiveModuleAbi)
            throw InputError(
                fmt::format("{}: {} is not this decode's live module (reinstall "
                            "busdecode)",
                            option, path));
        return m;
    }
    throw InputError(fmt::format(
        "{}: the live module busdecode_live.so is not installed (looked for {})", option, tried));
}

}  // namespace

const LiveModule& liveModule(const std::string& option) {
    static const LiveModule* module = nullptr;
    if (!module) module = load(option);
    return *module;
}

}  // namespace busdecode
