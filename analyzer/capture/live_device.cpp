#include "live_device.h"

#include <fmt/format.h>

#include "core/options.h"

namespace busdecode {

LiveSettings parseDeviceSpec(const std::string& spec) {
    LiveSettings s;
    s.spec = spec;
    std::size_t at = spec.find(':');
    s.driver = spec.substr(0, at);
    if (s.driver.empty())
        throw InputError(fmt::format("--device '{}': expected DRIVER[:key=value...]", spec));
    while (at != std::string::npos) {
        const std::size_t next = spec.find(':', at + 1);
        const std::string piece =
            spec.substr(at + 1, next == std::string::npos ? next : next - at - 1);
        const std::size_t eq = piece.find('=');
        if (eq != std::string::npos && eq > 0)
            s.options.emplace_back(piece.substr(0, eq), piece.substr(eq + 1));
        else if (!s.options.empty())  // a ':' inside a value (a file path)
            s.options.back().second += ":" + piece;
        else
            throw InputError(fmt::format(
                "--device {}: '{}': expected key=value (conn=..., file=...)", spec, piece));
        at = next;
    }
    return s;
}

}  // namespace busdecode
