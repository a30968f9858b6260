// _busdecode: the compiled half of the Python package `busdecode` (python/busdecode/
// holds the documented functions that call it).
#include <pybind11/pybind11.h>

#include "bindings.h"
#include "plugin_dirs.h"

namespace busdecode::py {

namespace {
unsigned long main_thread = 0;
}

void noteMainThread() {
    main_thread =
        pyb::module_::import("threading").attr("main_thread")().attr("ident").cast<unsigned long>();
}

bool onMainThread() {
    return PyThread_get_thread_ident() == main_thread;
}

}  // namespace busdecode::py

PYBIND11_MODULE(_busdecode, m) {
    using namespace busdecode::py;
    m.doc() = "busdecode's decoders, verify and LCM feed (use the busdecode package)";
    noteMainThread();
    addModulePluginDir();
    bindErrors(m);
    bindDecoders(m);
    bindDecode(m);
    bindRead(m);
    bindVerify(m);
    bindSubscribe(m);
}
