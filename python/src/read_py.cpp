// read(): decodes a whole capture into columns (event_columns.h) with the GIL released,
// then hands each column to Python as one buffer (numpy arrays over the C++ vectors,
// no copy) plus its null mask; busdecode/__init__.py makes the DataFrames.
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <bit>
#include <cmath>
#include <set>
#include <type_traits>

#include "app/decode_args.h"
#include "bindings.h"
#include "capture/capture_events.h"
#include "core/registry.h"
#include "decode_args_py.h"
#include "event_columns.h"
#include "event_dict.h"
#include "sinks/counting_sink.h"

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

// A numpy array of `n` objects, row i holding the new reference `item(i)`. Made here and
// not from a list by numpy, which looks into each row (a list of errors may be a
// sequence to it) and took longer than the whole DataFrame.
template <class Item>
pyb::array objectArray(std::size_t n, Item&& item) {
    // numpy fills a new object array with nulls.
    pyb::array out(pyb::dtype("O"), std::vector<pyb::ssize_t>{pyb::ssize_t(n)});
    auto** rows = static_cast<PyObject**>(out.mutable_data());
    for (std::size_t i = 0; i < n; ++i)
        rows[i] = item(i);
    return out;
}

pyb::array objectColumn(const std::vector<Value>& values) {
    return objectArray(values.size(),
                       [&](std::size_t i) { return valueToPython(values[i]).release().ptr(); });
}

// A column without a value in any row, typed by the field's declaration (FieldSpec), so
// that a table's columns and their types do not depend on what one capture held.
pyb::tuple nullColumn(const std::string& key, FieldSpec::Kind kind, std::size_t rows) {
    using K = FieldSpec::Kind;
    auto all_null = [rows] { return ownedArray(std::vector<std::uint8_t>(rows, 1), "bool"); };
    switch (kind) {
        case K::Int:
            return pyb::make_tuple(
                key, "Int64", ownedArray(std::vector<std::int64_t>(rows), "int64"), all_null());
        case K::Bool:
            return pyb::make_tuple(key, "boolean",
                                   ownedArray(std::vector<std::uint8_t>(rows), "bool"), all_null());
        case K::Number:
            return pyb::make_tuple(key, "float64",
                                   ownedArray(std::vector<double>(rows, std::nan("")), "float64"),
                                   pyb::none());
        default:
            return pyb::make_tuple(
                key, "object", objectArray(rows, [](std::size_t) { return Py_NewRef(Py_None); }),
                pyb::none());
    }
}

// (key, kind, values, mask): kind names the pandas array to make. `declared` types a
// column that no row gave a value.
pyb::tuple columnToPython(Column& c, FieldSpec::Kind declared) {
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
            auto out = objectArray(c.lanes.size(), [&](std::size_t i) {
                return Py_NewRef(c.nulls[i] ? Py_None : texts[c.lanes[i]].ptr());
            });
            return pyb::make_tuple(c.key, "object", out, pyb::none());
        }
        case K::Empty:
            return nullColumn(c.key, declared, c.rows());
        case K::Object:
            break;
    }
    return pyb::make_tuple(c.key, "object", objectColumn(c.objects), pyb::none());
}

// Each row's errors as a list of its own (a fresh list: rows may be changed apart).
pyb::array errorColumn(const Table& t) {
    std::vector<std::vector<pyb::str>> sets;
    for (const auto& set : t.error_sets)
        sets.emplace_back(set.begin(), set.end());
    return objectArray(t.errors.size(), [&](std::size_t i) {
        const auto& set = sets[t.errors[i]];
        PyObject* row = PyList_New(Py_ssize_t(set.size()));
        if (!row) throw pyb::error_already_set();
        for (std::size_t j = 0; j < set.size(); ++j)
            PyList_SET_ITEM(row, Py_ssize_t(j), Py_NewRef(set[j].ptr()));  // steals the reference
        return row;
    });
}

// What the decoder (or the capture layer, proto "capture") declares of t's events.
const EventTypeSpec* declarationOf(const Table& t) {
    if (t.proto == "capture") {
        for (const auto& type : captureEventTypes())
            if (type.type == t.type) return &type;
        return nullptr;
    }
    const DecoderFactory* decoder = Registry::instance().find(t.proto);
    return decoder ? findEventType(decoder->info(), t.type) : nullptr;
}

// The columns of `t`: its times, the capture's start (when the file gave one), the fields
// the events gave, the declared fields no event had, and the errors.
pyb::list tableColumns(Table& t, const std::string& capture_start) {
    const EventTypeSpec* declared = declarationOf(t);
    auto declaredKind = [&](const std::string& key) {
        if (declared)
            for (const auto& f : declared->fields)
                if (f.name == key) return f.kind;
        return FieldSpec::Kind::Any;
    };
    const std::size_t rows = t.start_ns.size();
    pyb::list columns;
    columns.append(pyb::make_tuple("start_ns", "int64", ownedArray(std::move(t.start_ns), "int64"),
                                   pyb::none()));
    columns.append(
        pyb::make_tuple("end_ns", "int64", ownedArray(std::move(t.end_ns), "int64"), pyb::none()));
    if (!capture_start.empty()) {
        const pyb::str start = textToPython(capture_start);
        columns.append(pyb::make_tuple(
            "capture_start", "object",
            objectArray(rows, [&](std::size_t) { return Py_NewRef(start.ptr()); }), pyb::none()));
    }
    std::set<std::string> seen;
    for (auto& c : t.columns) {
        seen.insert(c.key);
        columns.append(columnToPython(c, declaredKind(c.key)));
    }
    if (declared)
        for (const auto& f : declared->fields)
            if (!f.name.starts_with('<') && !seen.count(f.name))
                columns.append(nullColumn(f.name, f.kind, rows));
    columns.append(pyb::make_tuple("errors", "object", errorColumn(t), pyb::none()));
    return columns;
}

pyb::dict tablesToPython(TableSink& sink) {
    pyb::dict out;
    for (auto& t : sink.tables)
        out[pyb::str(t.proto + "/" + t.type)] = tableColumns(t, sink.capture_start);
    return out;
}

// A whole capture into `sink`, the GIL released and Ctrl-C heard: read_columns'
// decoding, and its floor's.
void decodeWithoutGil(const CaptureArgs& a, OutputSink& sink) {
    const DecodeJob job = jobFor(a, false);
    runInterruptibly([&](const std::atomic<bool>& stop) {
        decodeCapture(job.path, job.requests, job.open, {&sink}, false, &stop);
    });
}

pyb::dict readColumns(const CaptureArgs& a) {
    TableSink sink;
    decodeWithoutGil(a, sink);
    return tablesToPython(sink);
}

// bench/python_read.py's floors: read_columns' decoding, each event counted and dropped,
// which tells the columns' share of read()'s time from the decoding's; with `fields`
// false the decoders leave out the fields too, which tells theirs. Summaries are never
// read, as by TableSink.
std::uint64_t countEvents(const CaptureArgs& a, bool fields) {
    CountingSink sink({.fields = fields, .summaries = false});
    decodeWithoutGil(a, sink);
    return sink.events();
}

}  // namespace

void bindRead(pyb::module_& m) {
    m.def("read_columns", &readColumns, pyb::arg("args"));
    m.def("count_events", &countEvents, pyb::arg("args"), pyb::arg("fields") = true);
}

}  // namespace busdecode::py
