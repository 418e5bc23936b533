// Text helpers shared by the text writers (FEBio, SOFA, legacy VTK): exact numbers and safe XML.
#pragma once

#include <string>

namespace tissuemesh {

/// Shortest decimal that reads back to the same double (std::to_chars: exact, locale-free);
/// -0 is written "0".
std::string shortest_decimal(double v);

/// Attribute / element text: markup characters escaped, non-ASCII (UTF-8 decoded; an invalid byte
/// is taken as Latin-1) as character references, characters XML forbids replaced by '?'. Valid
/// whatever encoding the file declares.
std::string xml_escape(const std::string& s);

/// Comment text: ASCII only (references are not expanded in comments), no "--", no trailing '-'.
std::string xml_comment(const std::string& s);

}  // namespace tissuemesh
