// The errors and the decoder requests every entry point shares.
#include <fmt/format.h>

#include "app/decode_args.h"
#include "app/plugin_loader.h"
#include "bindings.h"
#include "core/options.h"
#include "core/registry.h"

namespace busdecode::py {

std::vector<DecoderRequest> requestsFor(const std::vector<std::string>& protos,
                                        const std::vector<std::string>& maps,
                                        const std::vector<std::string>& opts) {
    try {
        loadPlugins(protos);
        auto requests = buildRequests(protos, maps, opts);
        // Option values too, here rather than when the capture is open: a wrong call.
        for (const auto& r : requests) {
            auto options = r.options;
            options.erase("glitch_ns");  // the session's own option, checked there
            Options::resolve(Registry::instance().find(r.proto)->info(), options);
        }
        return requests;
    } catch (const InputError& e) {
        throw UsageError(e.what());
    }
}

void bindErrors(pyb::module_& m) {
    static pyb::exception<std::runtime_error> base(m, "Error");
    base.doc() = "Base of busdecode's errors: str(e) is the line `decode` prints.";
    pyb::register_exception<InputError>(m, "InputError", base.ptr()).doc() =
        "Bad input: an unreadable capture or rules file, an unbound role.";
    pyb::register_exception<UsageError>(m, "UsageError", base.ptr()).doc() =
        "A wrong call: unknown decoder, option, role or argument value.";
}

}  // namespace busdecode::py
