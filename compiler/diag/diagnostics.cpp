// DiagnosticEngine and Clang-style rendering.
#include "diag/diagnostics.h"

#include "diag/source_manager.h"

#include <algorithm>

namespace lobe::diag {

void DiagnosticEngine::report(DiagId id, SourceRange range, std::vector<std::string> args) {
  const DiagInfo& info = diag_info(id);
  Severity severity =
      werror_ && info.severity == Severity::Warning ? Severity::Error : info.severity;
  if (severity == Severity::Note) {
    if (last_dropped_ || diags_.empty()) return;
  } else {
    // A warning silenced by `#pragma osl nowarn` is dropped before -Werror could promote it.
    last_dropped_ = stopped_ || (info.severity == Severity::Warning && quiet_ && quiet_(range));
    if (last_dropped_) return;
    if (severity >= Severity::Error && errors_ >= max_errors_) {
      stopped_ = true;
      last_dropped_ = true;
      diags_.push_back({DiagId::fatal_too_many_errors, Severity::Fatal, range,
                        diag_info(DiagId::fatal_too_many_errors).format});
      return;
    }
  }
  if (severity >= Severity::Error) ++errors_;
  if (severity == Severity::Warning) ++warnings_;
  diags_.push_back({id, severity, range, format_message(info.format, args), oslc_repeat_});
}

void DiagnosticEngine::clear() {
  diags_.clear();
  errors_ = warnings_ = 0;
  stopped_ = last_dropped_ = false;
}

const char* severity_word(Severity s) {
  switch (s) {
  case Severity::Note:
    return "note";
  case Severity::Warning:
    return "warning";
  case Severity::Error:
    return "error";
  case Severity::Fatal:
    return "fatal error";
  }
  return "error";
}

namespace {

std::string loc_prefix(const PresumedLoc& p) {
  return std::string(p.file) + ":" + std::to_string(p.line) + ":" + std::to_string(p.column);
}

// The source line and a caret line under [begin, end) (same line only; else a single caret).
std::string caret_lines(const SourceManager& sm, SourceRange r) {
  std::string_view line = sm.line_text(r.begin);
  PresumedLoc b = sm.presumed(r.begin);
  if (!b.valid()) return {};
  size_t col = size_t(b.column - 1), len = 1;
  SourceLoc fb = sm.file_loc(r.begin), fe = sm.file_loc(r.end);
  if (fe.offset > fb.offset + 1 && sm.buffer_of(fb) == sm.buffer_of(fe))
    len = std::min<size_t>(fe.offset - fb.offset, line.size() > col ? line.size() - col : 1);
  return caret_under(line, col, len);
}

// "In file included from a.osl:3:" lines, outermost last (as Clang prints them).
std::string include_trail(const SourceManager& sm, SourceLoc loc) {
  std::string out;
  int guard = 0;
  for (SourceLoc inc = sm.include_loc(loc); inc.valid() && guard < 64;
       inc = sm.include_loc(inc), ++guard) {
    PresumedLoc p = sm.presumed(inc);
    out += "In file included from " + std::string(p.file) + ":" + std::to_string(p.line) + ":\n";
  }
  return out;
}

} // namespace

std::string render(const Diagnostic& d, const SourceManager& sm) {
  std::string out;
  PresumedLoc p = sm.presumed(d.range.begin);
  if (!p.valid()) return std::string(severity_word(d.severity)) + ": " + d.message + "\n";
  if (d.severity != Severity::Note) out += include_trail(sm, d.range.begin);
  out += loc_prefix(p) + ": " + severity_word(d.severity) + ": " + d.message + "\n";
  out += caret_lines(sm, d.range);
  const SourceManager::Segment* seg = nullptr;
  sm.file_loc(d.range.begin, &seg);
  if (seg && !seg->linear && seg->macro_def.valid()) {
    PresumedLoc m = sm.presumed(seg->macro_def);
    out += loc_prefix(m) +
           ": note: " + format_message(diag_info(DiagId::note_expanded_from).format, {seg->macro}) +
           "\n";
    out += caret_lines(sm, SourceRange(seg->macro_def));
  }
  return out;
}

std::string caret_under(std::string_view line, size_t column, size_t length) {
  std::string out(line);
  out += '\n';
  for (size_t i = 0; i < column && i < line.size(); ++i) out += line[i] == '\t' ? '\t' : ' ';
  for (size_t i = line.size(); i < column; ++i) out += ' '; // a place just past the end
  out += '^';
  out.append(length > 1 ? length - 1 : 0, '~');
  out += '\n';
  return out;
}

std::string render_all(const DiagnosticEngine& engine, const SourceManager& sm) {
  std::string out;
  for (const auto& d : engine.diagnostics()) out += render(d, sm);
  return out;
}

std::vector<Report> resolve_all(const DiagnosticEngine& engine, const SourceManager& sm) {
  std::vector<Report> out;
  for (const auto& d : engine.diagnostics()) {
    Report r{d.id, d.severity, "", 0, 0, d.message, render(d, sm), d.oslc_repeat};
    if (PresumedLoc p = sm.presumed(d.range.begin); p.valid()) {
      r.file = p.file;
      r.line = p.line;
      r.column = p.column;
    }
    out.push_back(std::move(r));
  }
  return out;
}

Report file_report(DiagId id, const std::string& file, const std::vector<std::string>& args) {
  const DiagInfo& info = diag_info(id);
  Report r{id, info.severity, file, 0, 0, format_message(info.format, args), ""};
  r.text = (file.empty() ? "" : file + ": ") + severity_word(r.severity) + ": " + r.message + "\n";
  return r;
}

} // namespace lobe::diag
