// _busdecode: the compiled half of the Python package `busdecode` (python/busdecode/
// holds the documented functions that call it).
#include <pybind11/pybind11.h>

#include "bindings.h"
#include "plugin_dirs.h"

PYBIND11_MODULE(_busdecode, m) {
    using namespace busdecode::py;
    m.doc() = "busdecode's decoders, verify and LCM feed (use the busdecode package)";
    addModulePluginDir();
    bindErrors(m);
    bindDecoders(m);
    bindDecode(m);
    bindRead(m);
    bindVerify(m);
    bindSubscribe(m);
}
