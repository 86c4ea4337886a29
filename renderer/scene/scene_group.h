// OSL shader-group text for scene files: the runtime's one reader (runtime/group/group_text.h),
// with its diagnostics joined into the scene loader's error string.
#pragma once

#include "group_text.h" // runtime/group

#include <optional>
#include <string>

namespace lobe::scene {

using group::is_param_type;

// `allow_bare`: OSL testrender XML's `color Cs 0.8 0.1 0.1 ;` (a param without the keyword).
// `first_line` > 0: the file line the text starts on, so messages carry file lines.
inline std::optional<ShaderGroup> parse_group_text(const std::string& text,
                                                   const std::string& where, bool allow_bare,
                                                   std::string& error, int first_line = 0) {
  DiagnosticList diags;
  auto g = group::parse_group_text(text, where, diags, {allow_bare, first_line});
  error.clear();
  for (const Diagnostic& d : diags)
    if (d.severity == Diagnostic::Severity::Error) error += (error.empty() ? "" : "\n") + d.text;
  if (!g) return std::nullopt;
  return std::move(*g);
}

} // namespace lobe::scene
