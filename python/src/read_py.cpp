// read(): decodes a whole capture into columns (event_columns.h) with the GIL released,
// then hands each column to Python as one buffer (numpy arrays over the C++ vectors,
// no copy) plus its null mask; busdecode/__init__.py makes the DataFrames.
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <bit>
#include <cmath>
#include <type_traits>

#include "app/decode_args.h"
#include "bindings.h"
#include "decode_args_py.h"
#include "event_columns.h"
#include "event_dict.h"

namespace busdecode::py {

namespace {

// A 1-D array viewing `v` (a std::vector or LaneBuffer), which it then owns.
template <class Buffer>
pyb::array ownedArray(Buffer&& v, const char* dtype) {
    using T = std::remove_cv_t<std::remove_reference_t<decltype(*v.data())>>;
    auto* owner = new Buffer(std::move(v));
    pyb::capsule free_it(owner, [](void* p) { delete static_cast<Buffer*>(p); });
    static const T none{};
    const T* data = owner->empty() ? &none : owner->data();
    return pyb::array(pyb::dtype(dtype), {owner->size()}, {sizeof(T)}, data, free_it);
}

pyb::list objectColumn(const std::vector<Value>& values) {
    pyb::list out(values.size());
    for (std::size_t i = 0; i < values.size(); ++i)
        out[i] = valueToPython(values[i]);
    return out;
}

// (key, kind, values, mask): kind names the pandas array to make.
pyb::tuple columnToPython(Column& c) {
    using K = Column::Kind;
    switch (c.kind) {
        case K::Int:
        case K::UInt:
            return pyb::make_tuple(
                c.key, c.kind == K::Int ? "Int64" : "UInt64",
                ownedArray(std::move(c.lanes), c.kind == K::Int ? "int64" : "uint64"),
                ownedArray(std::move(c.nulls), "bool"));
        case K::Bool: {
            std::vector<std::uint8_t> bits(c.lanes.begin(), c.lanes.end());
            c.lanes = {};
            return pyb::make_tuple(c.key, "boolean", ownedArray(std::move(bits), "bool"),
                                   ownedArray(std::move(c.nulls), "bool"));
        }
        case K::Real:
            for (std::size_t i = 0; i < c.nulls.size(); ++i)
                if (c.nulls[i]) c.lanes[i] = std::bit_cast<std::uint64_t>(std::nan(""));
            c.nulls = {};
            return pyb::make_tuple(c.key, "float64", ownedArray(std::move(c.lanes), "float64"),
                                   pyb::none());
        case K::Text: {
            std::vector<pyb::object> texts;
            for (const auto& t : c.texts)
                texts.push_back(pyb::str(t));
            // The CPython calls directly: pybind11's item proxies cost several times more a row.
            pyb::list out(c.lanes.size());
            for (std::size_t i = 0; i < c.lanes.size(); ++i) {
                PyObject* item = c.nulls[i] ? Py_None : texts[c.lanes[i]].ptr();
                Py_INCREF(item);
                PyList_SET_ITEM(out.ptr(), Py_ssize_t(i), item);
            }
            return pyb::make_tuple(c.key, "object", out, pyb::none());
        }
        case K::Empty:
            return pyb::make_tuple(c.key, "object",
                                   objectColumn(std::vector<Value>(c.nulls.size())), pyb::none());
        case K::Object:
            break;
    }
    return pyb::make_tuple(c.key, "object", objectColumn(c.objects), pyb::none());
}

// Each row's errors as a list of its own (a fresh list: rows may be changed apart).
pyb::list errorColumn(const Table& t) {
    std::vector<std::vector<pyb::str>> sets;
    for (const auto& set : t.error_sets)
        sets.emplace_back(set.begin(), set.end());
    pyb::list out(t.errors.size());
    for (std::size_t i = 0; i < t.errors.size(); ++i) {
        const auto& set = sets[t.errors[i]];
        PyObject* row = PyList_New(Py_ssize_t(set.size()));
        if (!row) throw pyb::error_already_set();
        for (std::size_t j = 0; j < set.size(); ++j) {
            Py_INCREF(set[j].ptr());
            PyList_SET_ITEM(row, Py_ssize_t(j), set[j].ptr());
        }
        PyList_SET_ITEM(out.ptr(), Py_ssize_t(i), row);  // steals the reference
    }
    return out;
}

pyb::dict tablesToPython(std::vector<Table>& tables) {
    pyb::dict out;
    for (auto& t : tables) {
        pyb::list columns;
        columns.append(pyb::make_tuple("start_ns", "int64",
                                       ownedArray(std::move(t.start_ns), "int64"), pyb::none()));
        columns.append(pyb::make_tuple("end_ns", "int64", ownedArray(std::move(t.end_ns), "int64"),
                                       pyb::none()));
        for (auto& c : t.columns)
            columns.append(columnToPython(c));
        columns.append(pyb::make_tuple("errors", "object", errorColumn(t), pyb::none()));
        out[pyb::str(t.proto + "/" + t.type)] = columns;
    }
    return out;
}

pyb::dict readColumns(const CaptureArgs& a) {
    const DecodeJob job = jobFor(a, false);
    TableSink sink;
    {
        pyb::gil_scoped_release nogil;
        decodeCapture(job.path, job.requests, job.open, {&sink});
    }
    return tablesToPython(sink.tables);
}

}  // namespace

void bindRead(pyb::module_& m) {
    m.def("read_columns", &readColumns, pyb::arg("args"));
}

}  // namespace busdecode::py
