// DiagnosticEngine: collects the diagnostics every front-end stage reports, and renders them.
//
// The library never prints. Stages call report(); the CLI (or a renderer plugin) asks for the
// rendered text: `file:line:col: error: message`, the source line, a caret `^~~~` under the
// range, then `note:` lines. An error cap stops collection after too many errors (the stages
// check stopped() and bail out early, which also bounds the time spent on garbage input).
#pragma once

#include "diag/diag_ids.h"
#include "diag/source_location.h"

#include <functional>
#include <string>
#include <vector>

namespace lobe {
struct Diagnostic; // lobe/shadingsys.h
}

namespace lobe::diag {

class SourceManager;

struct Diagnostic {
  DiagId id;
  Severity severity;
  SourceRange range;
  std::string message;
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

private:
  std::vector<Diagnostic> diags_;
  std::function<bool(SourceRange)> quiet_;
  int max_errors_;
  int errors_ = 0, warnings_ = 0;
  bool stopped_ = false;
  bool last_dropped_ = false;
  bool werror_ = false;
};

// One diagnostic as text: include trail, location line, source line, caret line, and an
// "expanded from macro" note when the location lies in a macro expansion. Ends with '\n'.
std::string render(const Diagnostic& d, const SourceManager& sm);
// All diagnostics of the engine, in order.
std::string render_all(const DiagnosticEngine& engine, const SourceManager& sm);
// The runtime API's form (one entry per diagnostic, notes as Severity::Note entries).
std::vector<lobe::Diagnostic> to_runtime(const DiagnosticEngine& engine, const SourceManager& sm);

} // namespace lobe::diag
