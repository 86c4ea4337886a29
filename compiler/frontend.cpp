// The front-end pipeline. Type checking runs only when preprocessing and parsing reported no
// error: a partial tree would mostly produce follow-on errors.
#include "frontend.h"

#include "closure_registry.h"
#include "diag/source_manager.h"
#include "lex/lexer.h"
#include "parse/parser.h"
#include "pp/preprocessor.h"
#include "sema/sema.h"
#include "stdlib/stdlib.h"

#include <algorithm>
#include <chrono>

namespace lobe::frontend {

namespace {

using Clock = std::chrono::steady_clock;
double ms_since(Clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}

// Marks the declarations that come from the standard header and the other built-in headers.
void mark_stdlib(ast::TranslationUnit& tu, const diag::SourceManager& sm,
                 const std::vector<int>& ids) {
  if (ids.empty()) return;
  for (auto& d : tu.decls) {
    int b = sm.buffer_of(sm.file_loc(d->range.begin));
    d->from_stdlib = std::find(ids.begin(), ids.end(), b) != ids.end();
  }
}

// Runs the preprocessor over the standard header (unless turned off) and the input; returns
// the output buffer's id and sets `stdlib_id` (-1 without the header) and, when given,
// `nowarn` (the lines `#pragma osl nowarn` silences) and `library` (the buffers of the built-in
// headers the input included, and the standard header's).
int run_preprocessor(const SourceInput& input, const FrontendOptions& options,
                     diag::SourceManager& sm, diag::DiagnosticEngine& diags, int& stdlib_id,
                     pp::NowarnLines* nowarn = nullptr, std::vector<int>* library = nullptr) {
  pp::PPOptions ppo;
  ppo.include_dirs = options.include_dirs;
  ppo.defines = options.defines;
  ppo.undefines = options.undefines;
  ppo.read_file = options.read_file;
  // The built-in headers come last on the search path, as oslc's shader folder does: a file of
  // the same name on the path wins. `#include "stdosl.h"` (which most OSL shaders write) then
  // finds the header already included, and its include guard makes it a no-op.
  ppo.builtin_header = [](const std::string& name) -> std::optional<std::string> {
    if (auto text = stdlib::find_header(name)) return std::string(*text);
    return std::nullopt;
  };
  pp::Preprocessor pp(sm, diags, ppo);
  stdlib_id = -1;
  if (options.include_stdlib) {
    stdlib_id = sm.add_file(stdlib::kStdoslName, std::string(stdlib::stdosl_source()));
    pp.process_buffer(stdlib_id);
  }
  if (input.text)
    pp.process_buffer(sm.add_file(input.path.empty() ? "<source>" : input.path, *input.text));
  else
    pp.process_file(input.path);
  int out = pp.finish();
  if (nowarn) *nowarn = pp.nowarn_lines();
  if (library) {
    *library = pp.builtin_buffers();
    if (stdlib_id >= 0) library->push_back(stdlib_id);
  }
  return out;
}

} // namespace

std::unique_ptr<ast::TranslationUnit> compile_to_ast(const SourceInput& input,
                                                     const FrontendOptions& options,
                                                     diag::DiagnosticEngine& diags,
                                                     FrontendTimings* timings) {
  FrontendTimings t;
  auto tu = std::make_unique<ast::TranslationUnit>();
  tu->sources = std::make_shared<diag::SourceManager>();
  diag::SourceManager& sm = *tu->sources;

  auto t0 = Clock::now();
  int stdlib_id = -1;
  pp::NowarnLines nowarn;
  std::vector<int> library;
  int out = run_preprocessor(input, options, sm, diags, stdlib_id, &nowarn, &library);
  t.preprocess_ms = ms_since(t0);
  // `#pragma osl nowarn` silences the parser's and type checker's warnings on the next line,
  // for this compile only (the filter holds its own copy of the lines).
  diags.set_warning_filter([&sm, nowarn = std::move(nowarn)](diag::SourceRange r) {
    return nowarn.covers(sm.presumed(r.begin));
  });
  struct FilterReset {
    diag::DiagnosticEngine& d;
    ~FilterReset() { d.set_warning_filter(nullptr); }
  } reset{diags};

  t0 = Clock::now();
  lex::TokenStream ts = lex::lex_buffer(sm, diags, out);
  parse::parse(ts, diags, *tu);
  mark_stdlib(*tu, sm, library);
  t.parse_ms = ms_since(t0);

  if (!diags.has_errors()) {
    t0 = Clock::now();
    sema::SemaOptions so;
    so.closures = registry::closures();
    sema::check(*tu, diags, so);
    t.sema_ms = ms_since(t0);
  }
  if (timings) *timings = t;
  return tu;
}

// The output a line at a time, with a `# N "file"` line wherever the next line is not the
// one after the line before in the same file (as cpp marks them).
std::string preprocess(const SourceInput& input, const FrontendOptions& options,
                       diag::DiagnosticEngine& diags, diag::SourceManager& sm) {
  int stdlib_id = -1;
  int out = run_preprocessor(input, options, sm, diags, stdlib_id);
  const std::string& text = sm.buffer_text(out);
  uint32_t base = sm.buffer_start(out).offset;
  std::string result, file;
  int next_line = 0;
  for (size_t b = 0; b < text.size();) {
    size_t e = text.find('\n', b);
    e = e == std::string::npos ? text.size() : e + 1;
    diag::PresumedLoc p = sm.presumed(diag::SourceLoc{base + uint32_t(b)});
    if (p.valid() && (p.file != file || p.line != next_line)) {
      file = p.file;
      result += "# " + std::to_string(p.line) + " \"" + file + "\"\n";
    }
    next_line = p.valid() ? p.line + 1 : next_line + 1;
    result.append(text, b, e - b);
    b = e;
  }
  return result;
}

} // namespace lobe::frontend
