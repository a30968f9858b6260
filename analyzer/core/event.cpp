#include "event.h"

#include <algorithm>

namespace busdecode {

Event& Event::set(std::string key, Value v) {
    for (auto& f : fields) {
        if (f.key == key) {
            f.value = std::move(v);
            return *this;
        }
    }
    return add(key, std::move(v));
}

const Value* Event::get(std::string_view key) const {
    for (const auto& f : fields)
        if (f.key == key) return &f.value;
    return nullptr;
}

Event& Event::error(std::string e) {
    if (!hasError(e)) errors.push_back(std::move(e));
    return *this;
}

void Event::reset() {
    proto.clear();
    type.clear();
    start = end = 0;
    fields.clear();
    errors.clear();
    summary.clear();
    instance.clear();
    wants_correlation = false;
}

bool Event::hasError(std::string_view e) const {
    return std::find(errors.begin(), errors.end(), e) != errors.end();
}

}  // namespace busdecode
