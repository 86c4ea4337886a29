// Parsing and matching of -verify style diagnostic expectations.
#include "verify.h"

#include <regex>
#include <sstream>

namespace lobe::verify {

std::vector<Expectation> parse_expectations(const std::string& source,
                                            std::vector<std::string>& errors) {
  static const std::regex kRe(
      R"(expect-(error|warning|note)@(?:([+-]\d+)|([\w./-]+):(\d+))(?::(\d+))?\s*\{\{(.*?)\}\})");
  std::vector<Expectation> out;
  std::istringstream in(source);
  std::string line;
  for (int n = 1; std::getline(in, line); ++n) {
    auto pos = line.find("expect-");
    if (pos == std::string::npos) continue;
    bool any = false;
    for (std::sregex_iterator it(line.begin(), line.end(), kRe), end; it != end; ++it) {
      const std::smatch& m = *it;
      Expectation e;
      e.severity = m[1] == "error"     ? diag::Severity::Error
                   : m[1] == "warning" ? diag::Severity::Warning
                                       : diag::Severity::Note;
      if (m[2].matched) {
        e.line = n + std::stoi(m[2]);
      } else {
        e.file = m[3];
        e.line = std::stoi(m[4]);
      }
      e.column = m[5].matched ? std::stoi(m[5]) : 0;
      e.text = m[6];
      e.source_line = n;
      out.push_back(e);
      any = true;
    }
    if (!any) errors.push_back("line " + std::to_string(n) + ": malformed expectation: " + line);
  }
  return out;
}

namespace {

const char* word(diag::Severity s) {
  switch (s) {
  case diag::Severity::Note:
    return "note";
  case diag::Severity::Warning:
    return "warning";
  default:
    return "error";
  }
}

bool ends_with(const std::string& s, const std::string& suffix) {
  return s.size() >= suffix.size() &&
         s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

} // namespace

std::vector<std::string> verify(const std::vector<Expectation>& expected,
                                const std::string& main_file, const diag::DiagnosticEngine& diags,
                                const diag::SourceManager& sm) {
  std::vector<std::string> problems;
  std::vector<bool> used(expected.size(), false);
  for (const auto& d : diags.diagnostics()) {
    diag::Severity sev = d.severity == diag::Severity::Fatal ? diag::Severity::Error : d.severity;
    diag::PresumedLoc p = sm.presumed(d.range.begin);
    std::string file = p.valid() ? p.file : "";
    bool matched = false;
    for (size_t i = 0; i < expected.size() && !matched; ++i) {
      const Expectation& e = expected[i];
      if (used[i] || e.severity != sev || e.line != p.line) continue;
      bool file_ok = e.file.empty() ? file == main_file : ends_with(file, e.file);
      if (!file_ok || (e.column && e.column != p.column)) continue;
      if (d.message.find(e.text) == std::string::npos) continue;
      used[i] = matched = true;
    }
    if (!matched && sev != diag::Severity::Note)
      problems.push_back("unexpected " + std::string(word(sev)) + " at " + file + ":" +
                         std::to_string(p.line) + ":" + std::to_string(p.column) + ": " +
                         d.message);
  }
  for (size_t i = 0; i < expected.size(); ++i) {
    if (used[i]) continue;
    const Expectation& e = expected[i];
    problems.push_back("expected " + std::string(word(e.severity)) + " not seen (written on line " +
                       std::to_string(e.source_line) + ", for " +
                       (e.file.empty() ? main_file : e.file) + ":" + std::to_string(e.line) +
                       (e.column ? ":" + std::to_string(e.column) : "") + "): " + e.text);
  }
  return problems;
}

} // namespace lobe::verify
