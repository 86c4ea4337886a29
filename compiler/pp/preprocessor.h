// The preprocessor: #include, #define (object-like, function-like, variadic, # and ##),
// #undef, #if/#ifdef/#ifndef/#elif/#else/#endif, #line, #pragma error/warning/once/osl nowarn,
// and the predefined OSL_VERSION macros. It works on text: its output is one buffer of preprocessed
// text added to the SourceManager, with segments that map every output byte back to the file and
// line it came from (through includes and macro expansions), so later stages report errors at
// the original location.
//
//   Preprocessor pp(sm, diags, options);
//   pp.process_buffer(stdlib_id);   // the standard header, included automatically
//   pp.process_file("shader.osl");
//   int out = pp.finish();          // the SourceManager buffer the lexer reads
#pragma once

#include "diag/diagnostics.h"
#include "diag/source_manager.h"
#include "pp/pp_token.h"

#include <ctime>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <unordered_map>
#include <vector>

namespace lobe::pp {

struct PPOptions {
  std::vector<std::string> include_dirs; // -I
  std::vector<std::string> defines;      // -D: "NAME" or "NAME=value"
  std::vector<std::string> undefines;    // -U
  int max_include_depth = 64;
  // Reads a file; null to use the file system. Tests give a virtual file system.
  std::function<std::optional<std::string>(const std::string& path)> read_file;
  // Headers built into the compiler, asked by the name as written when no file is found on the
  // search path (the last place searched, as oslc's own shader folder is); null for none.
  std::function<std::optional<std::string>(const std::string& name)> builtin_header;
};

struct Macro {
  std::string name;
  bool function_like = false;
  bool variadic = false; // last parameter is __VA_ARGS__
  std::vector<std::string> params;
  std::vector<PPToken> body;
  diag::SourceLoc def_loc;
};

// Reads a whole file from the file system (nullopt if it is not a readable regular file).
std::optional<std::string> read_file_from_disk(const std::string& path);

// The lines after a `#pragma osl nowarn` (as oslc: that line of that file, as #line numbers
// it), whose warnings are dropped.
struct NowarnLines {
  std::set<std::pair<std::string, int>> lines; // (file, line)
  bool covers(const diag::PresumedLoc& loc) const {
    return loc.valid() && lines.count({loc.file, loc.line}) > 0;
  }
};

// __DATE__ and __TIME__'s tokens for the moment `tm` (local time), quoted, as C spells them
// whatever the locale: "Dec  7 2026" (the day padded with a space), "13:06:11".
std::string date_macro(const std::tm& tm);
std::string time_macro(const std::tm& tm);

class Preprocessor {
public:
  Preprocessor(diag::SourceManager& sm, diag::DiagnosticEngine& diags, PPOptions options);
  ~Preprocessor();

  // Preprocesses a buffer already in the SourceManager, appending to the output.
  void process_buffer(int buffer_id);
  // Reads and preprocesses a file; reports err_file_not_found and returns false if unreadable.
  bool process_file(const std::string& path);
  // Adds the output to the SourceManager and returns its buffer id.
  int finish();

  const Macro* find_macro(const std::string& name) const;
  // The lines whose warnings `#pragma osl nowarn` silences.
  const NowarnLines& nowarn_lines() const { return nowarn_; }
  // The SourceManager buffers of the built-in headers included so far (PPOptions::builtin_header).
  const std::vector<int>& builtin_buffers() const { return builtin_buffers_; }

private:
  struct Cursor {
    const std::vector<PPToken>* toks;
    size_t pos = 0;
    int buffer = -1;
    const PPToken& peek() const { return (*toks)[pos]; }
    bool at_eof() const { return (*toks)[pos].kind == PPKind::Eof; }
  };
  struct Conditional {
    diag::SourceLoc loc;
    bool parent_active, taking, taken, seen_else;
  };
  // Macro expansion input: tokens pushed back by expansions (a stack, back is next), then the
  // file (null when expanding a macro argument on its own).
  struct Input {
    std::vector<PPToken> pending;
    Cursor* file = nullptr;
  };

  // preprocessor.cpp: files, directives, output
  void run(Cursor& cur);
  void directive(Cursor& cur);
  std::vector<PPToken> take_line(Cursor& cur);
  void conditional_directive(const std::string& name, const std::vector<PPToken>& line);
  void do_include(const std::vector<PPToken>& line, Cursor& cur);
  void do_define(const std::vector<PPToken>& line);
  void do_undef(const std::vector<PPToken>& line);
  void do_pragma(const std::vector<PPToken>& line, bool c_style);
  void do_line(const std::vector<PPToken>& line, Cursor& cur);
  bool eval_condition(const std::vector<PPToken>& line, size_t from);
  bool active() const { return conds_.empty() || conds_.back().taking; }
  void define_predefined();
  std::optional<std::string> read(const std::string& path) const;
  void emit_file_token(const PPToken& t);
  void emit_expanded(const std::vector<PPToken>& toks);

  // macro_expander.cpp
  void expand_from_file(Cursor& cur);
  std::vector<PPToken> expand_list(std::vector<PPToken> toks);
  void expand_loop(Input& in, std::vector<PPToken>& out);
  bool try_expand(const PPToken& t, Input& in);
  bool next_is_lparen(Input& in);
  bool collect_args(const Macro& m, const PPToken& name, Input& in,
                    std::vector<std::vector<PPToken>>& args, std::vector<PPToken>& consumed);
  std::vector<PPToken> substitute(const Macro& m, const PPToken& name,
                                  const std::vector<std::vector<PPToken>>& args);
  void define_macro(std::unique_ptr<Macro> m);

  diag::SourceManager& sm_;
  diag::DiagnosticEngine& diags_;
  PPOptions opts_;
  std::unordered_map<std::string, std::unique_ptr<Macro>> macros_;
  std::vector<std::unique_ptr<Macro>> retired_; // redefined/undefined: tokens may point at them
  std::vector<Conditional> conds_;
  std::vector<std::string> include_stack_; // paths of files being processed
  std::set<std::string> once_;             // files with #pragma once
  NowarnLines nowarn_;
  std::vector<int> builtin_buffers_;
  int expand_depth_ = 0;
  long expansion_budget_ = 0;

  std::string out_;
  std::vector<diag::SourceManager::Segment> segs_;
  bool contiguous_ = false; // the next file token may copy the text since the last one
  uint32_t last_end_ = 0;
};

} // namespace lobe::pp
