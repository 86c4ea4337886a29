// Diagnostics as the public API gives them (public_diag.h).
#include "public_diag.h"

namespace lobe::group {

Diagnostic to_public(const diag::Report& r) {
  Diagnostic d;
  d.severity = r.severity == diag::Severity::Note      ? Diagnostic::Severity::Note
               : r.severity == diag::Severity::Warning ? Diagnostic::Severity::Warning
                                                       : Diagnostic::Severity::Error;
  d.text = r.text;
  // One line: no trailing newline, as the runtime's own diagnostics.
  if (d.text.ends_with('\n') && d.text.find('\n') == d.text.size() - 1) d.text.pop_back();
  d.id = diag::diag_name(r.id);
  d.file = r.file;
  d.line = r.line;
  d.column = r.column;
  d.message = r.message;
  d.oslc_repeat = r.oslc_repeat;
  return d;
}

Diagnostic runtime_diag(diag::DiagId id, const std::string& arg,
                        std::optional<diag::Severity> severity, const std::string& file, int line) {
  const diag::DiagInfo& info = diag::diag_info(id);
  diag::Report r{id, severity.value_or(info.severity),         file, line,
                 0,  diag::format_message(info.format, {arg}), ""};
  std::string place = file.empty() ? "" : line > 0 ? file + ":" + std::to_string(line) : file;
  r.text = (place.empty() ? "" : place + ": ") + diag::severity_word(r.severity) + ": " + r.message;
  return to_public(r);
}

Diagnostic located_error(const std::string& text, diag::DiagId id) {
  Diagnostic d{Diagnostic::Severity::Error, text, diag::diag_name(id)};
  size_t at = text.find(": error: ");
  if (at == std::string::npos) {
    d.text = "error: " + text;
    d.message = text;
    return d;
  }
  d.message = text.substr(at + 9);
  // `file:line:col` (the file may hold colons itself: split from the right).
  std::string place = text.substr(0, at);
  size_t c2 = place.rfind(':');
  size_t c1 = c2 == std::string::npos || c2 == 0 ? std::string::npos : place.rfind(':', c2 - 1);
  auto number = [](const std::string& s) {
    return !s.empty() && s.find_first_not_of("0123456789") == std::string::npos ? std::stoi(s) : 0;
  };
  if (c1 != std::string::npos && number(place.substr(c1 + 1, c2 - c1 - 1)) > 0) {
    d.file = place.substr(0, c1);
    d.line = number(place.substr(c1 + 1, c2 - c1 - 1));
    d.column = number(place.substr(c2 + 1));
  } else {
    d.file = place;
  }
  return d;
}

} // namespace lobe::group
