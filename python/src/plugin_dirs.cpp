#include "plugin_dirs.h"

#include <dlfcn.h>

#include <cstdlib>
#include <filesystem>
#include <string>

namespace busdecode::py {

namespace {

std::filesystem::path moduleDir() {
    Dl_info info{};
    if (!dladdr(reinterpret_cast<void*>(&addModulePluginDir), &info) || !info.dli_fname) return {};
    return std::filesystem::weakly_canonical(info.dli_fname).parent_path();
}

}  // namespace

void addModulePluginDir() {
    namespace fs = std::filesystem;
    const fs::path here = moduleDir();
    std::error_code ec;
    const bool in_build_tree = fs::equivalent(here, BUSDECODE_BUILD_MODULE_DIR, ec);
    const fs::path dir = in_build_tree ? fs::path(BUSDECODE_BUILD_PLUGIN_DIR)
                                       : (here / BUSDECODE_INSTALLED_PLUGIN_DIR).lexically_normal();
    std::string path;
    if (const char* env = std::getenv("BUSDECODE_PLUGIN_PATH"); env && *env)
        path = std::string(env) + ":";
    path += dir.string();
    setenv("BUSDECODE_PLUGIN_PATH", path.c_str(), 1);
}

}  // namespace busdecode::py
