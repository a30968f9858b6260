#include <fmt/format.h>

#include "tmcl_tables.h"

namespace busdecode::tmcl {

namespace {
template <class T, class Key>
const T* findIn(const std::vector<T>& table, Key key, int T::*field) {
    for (const auto& row : table)
        if (row.*field == key) return &row;
    return nullptr;
}
}  // namespace

const CommandInfo* findCommand(int number) {
    return findIn(commandTable(), number, &CommandInfo::number);
}
const StatusInfo* findStatus(int code) {
    return findIn(statusTable(), code, &StatusInfo::code);
}
const ParameterInfo* findAxisParameter(int number) {
    return findIn(axisParameterTable(), number, &ParameterInfo::number);
}

std::string globalParameterName(int bank, int number) {
    if (bank == 0) {
        const auto* p = findIn(globalParameterTable(), number, &ParameterInfo::number);
        return p ? p->name : "";
    }
    if (bank == 2) return fmt::format("User variable #{}", number);
    return "";
}

const char* typeSymbol(std::string_view set, int type) {
    for (const auto& s : typeSymbolTable())
        if (s.type == type && set == s.set) return s.symbol;
    return nullptr;
}

}  // namespace busdecode::tmcl
