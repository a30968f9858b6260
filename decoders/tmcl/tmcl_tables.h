#pragma once
// TMCL data tables: commands, status codes, TMCM-1690 axis and global parameters, and
// the symbolic names of type fields. The tables themselves are generated from the
// manual's text (tables/generate_tables.py) or written as plain data
// (tmcl_type_names.cpp); this header only declares them and their look-ups.
#include <string>
#include <string_view>
#include <vector>

namespace busdecode::tmcl {

struct CommandInfo {
    int number;
    const char* mnemonic;
    // How the TMCL-IDE writes the fields: "T" type, "M" motor/bank, "V" value, separated
    // by ", "; "T:<set>" writes the type as a symbol of that set (typeSymbol()).
    const char* layout;
    const char* parameters;  // "axis", "global" or "": which table names the type field
    const char* description;
};

struct StatusInfo {
    int code;
    const char* text;
};

struct ParameterInfo {
    int number;
    const char* name;
    const char* unit;
    const char* access;
};

struct TypeSymbol {
    const char* set;
    int type;
    const char* symbol;
};

const std::vector<CommandInfo>& commandTable();
const std::vector<StatusInfo>& statusTable();
const std::vector<ParameterInfo>& axisParameterTable();
const std::vector<ParameterInfo>& globalParameterTable();  // bank 0
const std::vector<TypeSymbol>& typeSymbolTable();

const CommandInfo* findCommand(int number);
const StatusInfo* findStatus(int code);
const ParameterInfo* findAxisParameter(int number);
// Bank 0 from the table; bank 2 are the TMCL user variables ("User variable #n").
std::string globalParameterName(int bank, int number);
const char* typeSymbol(std::string_view set, int type);  // nullptr when none

}  // namespace busdecode::tmcl
