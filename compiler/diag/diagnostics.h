// DiagnosticEngine: collects the diagnostics every compiler stage reports (front end, lowering,
// the driver), and renders them.
//
// The library never prints. Stages call report(); the CLI asks for the rendered text (render,
// render_all): `file:line:col: error: message`, the source line, a caret `^~~~` under the
// range, then `note:` lines. A caller without the SourceManager (the runtime, and through it a
// renderer plugin) gets resolve_all(): each diagnostic with its id, severity, file, line,
// column, message and rendered text. An error cap stops collection after too many errors (the
// stages check stopped() and bail out early, which also bounds the time spent on garbage input).
#pragma once

#include "diag/diag_ids.h"
#include "diag/source_location.h"

#include <functional>
#include <string>
#include <string_view>
#include <vector>

namespace lobe::diag {
// A function's signature as oslc words it in messages: `float f (float)` for `float f(float)`.
inline std::string oslc_signature(std::string s) {
  if (size_t at = s.find('('); at != std::string::npos && at > 0 && s[at - 1] != ' ')
    s.insert(s.begin() + std::ptrdiff_t(at), ' ');
  return s;
}
} // namespace lobe::diag

namespace lobe::diag {

class SourceManager;

struct Diagnostic {
  DiagId id;
  Severity severity;
  SourceRange range;
  std::string message;
  // How many times oslc prints it (a warning raised inside argument i of a call: oslc checks
  // argument i i + 1 times, nested calls multiplying); Lobe's own rendering prints it once.
  int oslc_repeat = 1;
};

class DiagnosticEngine {
public:
  explicit DiagnosticEngine(int max_errors = 50) : max_errors_(max_errors) {}

  // Reports a diagnostic. A note attaches to the diagnostic before it and is dropped when that
  // one was (after the error cap).
  void report(DiagId id, SourceRange range, std::vector<std::string> args = {});
  void report(DiagId id, SourceLoc loc, std::vector<std::string> args = {}) {
    report(id, SourceRange(loc), std::move(args));
  }

  // Warnings for which `quiet` returns true are dropped, with their notes (`#pragma osl
  // nowarn`: the front end installs it for the duration of a compile). Null: keep all.
  void set_warning_filter(std::function<bool(SourceRange)> quiet) { quiet_ = std::move(quiet); }

  const std::vector<Diagnostic>& diagnostics() const { return diags_; }
  int error_count() const { return errors_; }
  int warning_count() const { return warnings_; }
  bool has_errors() const { return errors_ > 0; }
  bool stopped() const { return stopped_; } // the error cap was reached
  void clear();
  // -Werror: warnings reported from now on are errors (and counted as errors).
  void set_warnings_as_errors(bool on) { werror_ = on; }
  // Diagnostic::oslc_repeat of what is reported from now on (the type checker sets it while it
  // checks a format call's arguments).
  void set_oslc_repeat(int n) { oslc_repeat_ = n; }
  int oslc_repeat() const { return oslc_repeat_; }

private:
  std::vector<Diagnostic> diags_;
  std::function<bool(SourceRange)> quiet_;
  int max_errors_;
  int errors_ = 0, warnings_ = 0;
  bool stopped_ = false;
  bool last_dropped_ = false;
  bool werror_ = false;
  int oslc_repeat_ = 1;
};

// One diagnostic as text: include trail, location line, source line, caret line, and an
// "expanded from macro" note when the location lies in a macro expansion. Ends with '\n'.
std::string render(const Diagnostic& d, const SourceManager& sm);
// All diagnostics of the engine, in order.
std::string render_all(const DiagnosticEngine& engine, const SourceManager& sm);

// "note", "warning", "error" or "fatal error", as the rendered text words a severity.
const char* severity_word(Severity s);

// The caret form under one line of text: the line, then `^` at 0-based `column` followed by
// `~` to cover `length` characters (tabs before the caret kept, so it lines up), each line
// ending in '\n'. The one caret renderer: render() uses it, and so does a tool that reports a
// place in a line of its own (`lobe brdf`'s closure expressions).
std::string caret_under(std::string_view line, size_t column, size_t length = 1);
// A diagnostic resolved for a caller that does not hold the SourceManager: where it is as a
// person reads it (the presumed file, 1-based line and column, after #line; "" and 0 when it
// has no location), the message alone, and render()'s text.
struct Report {
  DiagId id = DiagId::err_file_not_found;
  Severity severity = Severity::Error;
  std::string file;
  int line = 0, column = 0;
  std::string message;
  std::string text;    // rendered, ending in '\n'
  int oslc_repeat = 1; // Diagnostic::oslc_repeat
};
// One Report per diagnostic of the engine, in order (notes are Severity::Note entries).
std::vector<Report> resolve_all(const DiagnosticEngine& engine, const SourceManager& sm);
// A Report about a whole file (no line), rendered `file: error: message`; `file` "" renders
// as render() renders a diagnostic without a location.
Report file_report(DiagId id, const std::string& file, const std::vector<std::string>& args = {});

} // namespace lobe::diag
