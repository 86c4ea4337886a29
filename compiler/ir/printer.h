// The IR's text form: print a Shader as stable, readable text (docs/ir.md, "Text form"),
// which ir_parse (parser.h) reads back: print(parse(print(ir))) == print(ir).
#pragma once

#include "ir/ir.h"

#include <string>

namespace lobe::ir {

std::string print(const Shader& shader);

// Pieces, shared with the parser's tests and the `lobe info` output.
std::string format_float(float f);          // shortest text that reads back to the same float
std::string quote(const std::string& s);    // "text" with \" \\ \n \t \xNN escapes
std::string format_name(const std::string& s); // bare if a plain name, else quoted
std::string format_values(const Type& t, const std::vector<ConstValue>& v); // "1 0 0"
std::string format_metadata(const std::vector<Metadata>& md); // "[[ float min = 0 ]]" or ""
std::string format_loc(const SourceLoc& loc);                // "@file:3:7" or ""

} // namespace lobe::ir
