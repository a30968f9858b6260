#include "event_dict.h"

#include <type_traits>
#include <variant>

#include "sinks/event_format.h"

namespace busdecode::py {

pyb::object valueToPython(const Value& v) {
    return std::visit(
        [](const auto& x) -> pyb::object {
            using T = std::decay_t<decltype(x)>;
            if constexpr (std::is_same_v<T, Null>) {
                return pyb::none();
            } else if constexpr (std::is_same_v<T, bool>) {
                return pyb::bool_(x);
            } else if constexpr (std::is_same_v<T, std::int64_t> ||
                                 std::is_same_v<T, std::uint64_t>) {
                return pyb::int_(x);
            } else if constexpr (std::is_same_v<T, double>) {
                switch (jsonNumberKind(x)) {
                    case JsonNumber::Null:
                        return pyb::none();
                    case JsonNumber::Integer:
                        return pyb::int_(std::int64_t(x));
                    case JsonNumber::Real:
                        break;
                }
                return pyb::float_(x);
            } else if constexpr (std::is_same_v<T, std::string>) {
                return textToPython(x);
            } else {
                pyb::list out(x.size());
                for (std::size_t i = 0; i < x.size(); ++i)
                    out[i] = pyb::int_(x[i]);
                return out;
            }
        },
        v);
}

void TimedEvent::set(const Event& e, std::int64_t start, std::int64_t end) {
    event.proto = e.proto;
    event.type = e.type;
    event.fields = e.fields;
    event.errors = e.errors;
    start_ns = start;
    end_ns = end;
}

pyb::str textToPython(const std::string& s) {
    PyObject* text = PyUnicode_DecodeUTF8(s.data(), Py_ssize_t(s.size()), "replace");
    if (!text) throw pyb::error_already_set();
    return pyb::reinterpret_steal<pyb::str>(text);
}

pyb::str pathToPython(const std::string& path) {
    PyObject* text = PyUnicode_DecodeFSDefaultAndSize(path.data(), Py_ssize_t(path.size()));
    if (!text) throw pyb::error_already_set();
    return pyb::reinterpret_steal<pyb::str>(text);
}

pyb::str DictMaker::name(const std::string& s) {
    auto it = names_.find(s);
    if (it == names_.end()) it = names_.emplace(s, textToPython(s)).first;
    return it->second;
}

void DictMaker::setCaptureStart(const std::string& start) {
    capture_start_ = start.empty() ? pyb::object() : pyb::object(textToPython(start));
}

PyObject* DictMaker::fieldKey(const std::string& key, std::size_t position) {
    if (const pyb::str* known = keys_at_.find(key, position)) return known->ptr();
    if (isCommonEventKey(key)) return kCommonKey;
    return keys_at_.remember(key, position, name(key)).ptr();
}

PyObject* DictMaker::repeatedName(const std::string& s, std::pair<std::string, pyb::str>& last) {
    if (!last.second || !sameKey(last.first, s)) last = {s, name(s)};
    return last.second.ptr();
}

namespace {

// d[key] = value, through the C API: pybind11's item proxies cost several times more.
void put(PyObject* d, PyObject* key, PyObject* value) {
    if (PyDict_SetItem(d, key, value) < 0) throw pyb::error_already_set();
}
void put(PyObject* d, const pyb::str& key, const pyb::object& value) {
    put(d, key.ptr(), value.ptr());
}

}  // namespace

pyb::dict DictMaker::operator()(const TimedEvent& te) {
    const Event& e = te.event;
    auto d = pyb::reinterpret_steal<pyb::dict>(PyDict_New());
    if (!d) throw pyb::error_already_set();
    put(d.ptr(), proto_.ptr(), repeatedName(e.proto, last_proto_));
    put(d.ptr(), type_.ptr(), repeatedName(e.type, last_type_));
    if (capture_start_) put(d.ptr(), capture_start_key_.ptr(), capture_start_.ptr());
    put(d.ptr(), start_ns_, pyb::int_(te.start_ns));
    put(d.ptr(), end_ns_, pyb::int_(te.end_ns));
    std::size_t position = 0;
    for (const auto& f : e.fields) {
        PyObject* key = fieldKey(f.key, position);
        if (key == kCommonKey) continue;
        ++position;
        put(d.ptr(), key, valueToPython(f.value).ptr());
    }
    pyb::list errors(e.errors.size());
    for (std::size_t i = 0; i < e.errors.size(); ++i)
        errors[i] = name(e.errors[i]);
    put(d.ptr(), errors_, errors);
    return d;
}

}  // namespace busdecode::py
