// Clang -verify style expectations for diagnostics tests. A comment in a test shader
//
//   x = y;   // expect-error@+0:7 {{undeclared identifier 'y'}}
//
// expects an error on the comment's line (+0; +1 is the next line, -1 the previous) at column 7
// whose message contains the text between {{ and }}. The column may be omitted
// (`expect-error@+0 {{...}}`); `expect-warning` and `expect-note` work alike, and
// `@file.h:3:5` names a line in another file (an included header). Every error and warning
// must be expected; notes are checked only where expected.
#pragma once

#include "diag/diagnostics.h"
#include "diag/source_manager.h"

#include <string>
#include <vector>

namespace lobe::verify {

struct Expectation {
  diag::Severity severity;
  std::string file; // empty: the main file
  int line = 0;
  int column = 0; // 0: any column
  std::string text;
  int source_line = 0; // where the expectation is written
};

// Parses the expectations in `source` (the main file's text).
std::vector<Expectation> parse_expectations(const std::string& source,
                                            std::vector<std::string>& errors);

// Matches diagnostics against expectations; returns a list of problems (empty: all good).
std::vector<std::string> verify(const std::vector<Expectation>& expected,
                                const std::string& main_file, const diag::DiagnosticEngine& diags,
                                const diag::SourceManager& sm);

} // namespace lobe::verify
