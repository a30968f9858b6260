// The errors and the decoder requests every entry point shares.
#include <fmt/format.h>

#include "app/decode_args.h"
#include "app/plugin_loader.h"
#include "bindings.h"
#include "event_dict.h"

namespace busdecode::py {

std::vector<DecoderRequest> requestsFor(const std::vector<std::string>& protos,
                                        const std::vector<std::string>& maps,
                                        const std::vector<std::string>& opts) {
    try {
        loadPlugins(protos);
        return buildRequests(protos, maps, opts);  // option values checked there
    } catch (const InputError& e) {
        throw UsageError(e.what());
    }
}

void bindErrors(pyb::module_& m) {
    static pyb::exception<std::runtime_error> base(m, "Error");
    base.doc() = "Base of busdecode's errors: str(e) is the line `decode` prints.";
    static pyb::exception<InputError> input(m, "InputError", base.ptr());
    input.doc() = "Bad input: an unreadable capture or rules file, an unbound role.";
    static pyb::exception<UsageError> usage(m, "UsageError", base.ptr());
    usage.doc() = "A wrong call: unknown decoder, option, role or argument value.";
    // The message as text even where it quotes bytes that are not UTF-8 (a Latin-1 file
    // name): pybind11's own translation would leave str(e) empty.
    pyb::register_exception_translator([](std::exception_ptr p) {
        auto raise = [](PyObject* type, const char* what) {
            PyErr_SetObject(type, textToPython(what).ptr());
        };
        try {
            if (p) std::rethrow_exception(p);
        } catch (const InputError& e) {
            raise(input.ptr(), e.what());
        } catch (const UsageError& e) {
            raise(usage.ptr(), e.what());
        }
    });
}

}  // namespace busdecode::py
