#pragma once
// Escaping for XML and HTML output (JUnit, HTML reports): markup characters become
// entities, line breaks and tabs are encoded, other control characters (not allowed in
// XML 1.0) are dropped.
#include <string>

namespace busdecode {

std::string xmlEscape(const std::string& s);

}  // namespace busdecode
