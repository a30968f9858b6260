// Symbolic names of TMCL type fields, as data, from the TMCM-1690 TMCL manual's binary
// representation tables: MVP/MVPA (3.6.4, 3.6.44), CALC (3.6.15), JC and CALL (3.6.17,
// 3.6.43), WAIT (3.6.21), CALCX (3.6.27), CLE (3.6.30), CALCVV..CALCV (3.6.35-3.6.40).
#include "tmcl_tables.h"

namespace busdecode::tmcl {

const std::vector<TypeSymbol>& typeSymbolTable() {
    static const std::vector<TypeSymbol> table = {
        {"move", 0, "ABS"},      {"move", 1, "REL"},       {"move", 2, "COORD"},
        {"calc", 0, "ADD"},      {"calc", 1, "SUB"},       {"calc", 2, "MUL"},
        {"calc", 3, "DIV"},      {"calc", 4, "MOD"},       {"calc", 5, "AND"},
        {"calc", 6, "OR"},       {"calc", 7, "XOR"},       {"calc", 8, "NOT"},
        {"calc", 9, "LOAD"},     {"calcx", 0, "ADD"},      {"calcx", 1, "SUB"},
        {"calcx", 2, "MUL"},     {"calcx", 3, "DIV"},      {"calcx", 4, "MOD"},
        {"calcx", 5, "AND"},     {"calcx", 6, "OR"},       {"calcx", 7, "XOR"},
        {"calcx", 8, "NOT"},     {"calcx", 9, "LOAD"},     {"calcx", 10, "SWAP"},
        {"calcv", 0, "ADD"},     {"calcv", 1, "SUB"},      {"calcv", 2, "MUL"},
        {"calcv", 3, "DIV"},     {"calcv", 4, "MOD"},      {"calcv", 5, "AND"},
        {"calcv", 6, "OR"},      {"calcv", 7, "XOR"},      {"calcv", 8, "NOT"},
        {"calcv", 9, "LOAD"},    {"calcv", 10, "SWAP"},    {"calcv", 11, "COMP"},
        {"condition", 0, "ZE"},  {"condition", 1, "NZ"},   {"condition", 2, "EQ"},
        {"condition", 3, "NE"},  {"condition", 4, "GT"},   {"condition", 5, "GE"},
        {"condition", 6, "LT"},  {"condition", 7, "LE"},   {"condition", 8, "ETO"},
        {"condition", 9, "EAL"}, {"condition", 10, "EDV"}, {"condition", 11, "EPO"},
        {"wait", 0, "TICKS"},    {"wait", 1, "POS"},       {"wait", 2, "REFSW"},
        {"wait", 3, "LIMSW"},    {"flag", 0, "ALL"},       {"flag", 1, "ETO"},
        {"flag", 2, "EAL"},      {"flag", 3, "EDV"},       {"flag", 4, "EPO"},
        {"flag", 5, "ESD"},
    };
    return table;
}

}  // namespace busdecode::tmcl
