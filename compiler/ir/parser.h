// Reads the IR text form written by print() (printer.h; grammar in docs/ir.md). Also meant for
// hand-written IR in tests: blank lines and `#` comment lines are ignored, labels may have any
// name (`Lloop:`), and the written mask defaults to the opcode table's.
#pragma once

#include "ir/ir.h"

#include <optional>
#include <string>
#include <string_view>

namespace lobe::ir {

struct ParseError {
  int line = 0;
  int column = 0;
  std::string message;
  std::string to_string() const; // "line:col: message"
};

struct ParseResult {
  std::optional<Shader> shader; // set on success
  ParseError error;             // set on failure
};

ParseResult parse(std::string_view text);

} // namespace lobe::ir
