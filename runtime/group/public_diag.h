// Diagnostics as the public API gives them (lobe/shadingsys.h, Diagnostic): the compiler's
// reports converted, and the runtime's own, which are rows of the same table
// (compiler/diag/diag_ids.cpp). Part of lobe_grouptext, so group text reports through it too.
#pragma once

#include "diag/diagnostics.h"
#include "lobe/shadingsys.h"

#include <optional>
#include <string>

namespace lobe::group {

// The compiler's diagnostic as the public API gives it (shadingsys.h, Diagnostic).
Diagnostic to_public(const diag::Report& r);
// A runtime diagnostic through the one table (compiler/diag/diag_ids.cpp): `id`'s row gives its
// name and wording (the runtime's rows are "%0" or fixed text; `arg` fills %0). The severity is
// the row's unless given; `file` and `line` place it (text `file:line: error: message`).
Diagnostic runtime_diag(diag::DiagId id, const std::string& arg = "",
                        std::optional<diag::Severity> severity = std::nullopt,
                        const std::string& file = "", int line = 0);
// An error of a later stage (code generation) as text, `file:line:col: error: message` when it
// names its place (file, line, column and message then filled in), else `message` (the text
// gets "error: ").
Diagnostic located_error(const std::string& text, diag::DiagId id);

} // namespace lobe::group
