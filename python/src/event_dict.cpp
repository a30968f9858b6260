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
                return pyb::str(x);
            } else {
                pyb::list out(x.size());
                for (std::size_t i = 0; i < x.size(); ++i)
                    out[i] = pyb::int_(x[i]);
                return out;
            }
        },
        v);
}

pyb::str DictMaker::name(const std::string& s) {
    auto it = names_.find(s);
    if (it == names_.end()) it = names_.emplace(s, pyb::str(s)).first;
    return it->second;
}

pyb::dict DictMaker::operator()(const TimedEvent& te) {
    const Event& e = te.event;
    pyb::dict d;
    d[name("proto")] = name(e.proto);
    d[name("type")] = name(e.type);
    d[name("start_ns")] = pyb::int_(te.start_ns);
    d[name("end_ns")] = pyb::int_(te.end_ns);
    for (const auto& f : e.fields)
        if (!isCommonEventKey(f.key)) d[name(f.key)] = valueToPython(f.value);
    pyb::list errors(e.errors.size());
    for (std::size_t i = 0; i < e.errors.size(); ++i)
        errors[i] = name(e.errors[i]);
    d[name("errors")] = std::move(errors);
    return d;
}

}  // namespace busdecode::py
