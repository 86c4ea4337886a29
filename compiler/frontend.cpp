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
  int stdlib_id = -1;
  if (options.include_stdlib) {
    stdlib_id = sm.add_file(stdlib::kStdoslName, std::string(stdlib::stdosl_source()));
    pp.process_buffer(stdlib_id);
  }
  if (input.text)
    pp.process_buffer(sm.add_file(input.path.empty() ? "<source>" : input.path, *input.text));
  else
    pp.process_file(input.path);
  int out = pp.finish();
  t.preprocess_ms = ms_since(t0);

  t0 = Clock::now();
  lex::TokenStream ts = lex::lex_buffer(sm, diags, out);
  parse::parse(ts, diags, *tu);
  std::vector<int> library = pp.builtin_buffers();
  if (stdlib_id >= 0) library.push_back(stdlib_id);
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

} // namespace lobe::frontend
