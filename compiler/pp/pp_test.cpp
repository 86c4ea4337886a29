// Preprocessor tests: macros, conditionals, includes, pragmas, and locations through includes
// and macro expansions. Output text is compared with whitespace collapsed.
#include "pp/preprocessor.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <ctime>
#include <map>
#include <set>

using namespace lobe;
using diag::DiagId;

namespace {

struct PPRun {
  diag::SourceManager sm;
  diag::DiagnosticEngine diags;
  std::map<std::string, std::string> files;
  std::string out;
  int out_id = -1;
  pp::NowarnLines nowarn;

  std::string run(const std::string& main, pp::PPOptions opts = {}) {
    files["main.osl"] = main;
    opts.read_file = [this](const std::string& p) -> std::optional<std::string> {
      auto it = files.find(p);
      if (it == files.end()) return std::nullopt;
      return it->second;
    };
    pp::Preprocessor pp(sm, diags, opts);
    pp.process_file("main.osl");
    out_id = pp.finish();
    nowarn = pp.nowarn_lines();
    out = sm.buffer_text(out_id);
    return collapse(out);
  }
  // The output's tokens joined by single spaces (the spacing of expansions is not specified).
  std::string collapse(const std::string& s) {
    diag::DiagnosticEngine scratch;
    std::string r;
    for (const auto& t : pp::tokenize(s, diag::SourceLoc{1}, scratch)) {
      if (t.kind == pp::PPKind::Newline || t.kind == pp::PPKind::Eof) continue;
      if (!r.empty()) r += ' ';
      r += t.text;
    }
    return r;
  }
  // Presumed location of the n-th occurrence of `needle` in the output.
  diag::PresumedLoc where(const std::string& needle, int n = 0) {
    size_t pos = out.find(needle);
    while (n-- > 0 && pos != std::string::npos) pos = out.find(needle, pos + 1);
    EXPECT_NE(pos, std::string::npos) << needle;
    return sm.presumed(sm.buffer_start(out_id).advanced(uint32_t(pos)));
  }
  bool has(DiagId id) const {
    for (auto& d : diags.diagnostics())
      if (d.id == id) return true;
    return false;
  }
};

} // namespace

TEST(PP, PlainTextPassesThrough) {
  PPRun r;
  EXPECT_EQ(r.run("surface s() { /* c */ Ci = 0; } // x\n"), "surface s ( ) { Ci = 0 ; }");
  EXPECT_FALSE(r.diags.has_errors());
}

TEST(PP, ObjectAndFunctionMacros) {
  PPRun r;
  EXPECT_EQ(r.run("#define N 3\n#define SQ(x) ((x)*(x))\nint a = SQ(N+1);\n"),
            "int a = ( ( 3 + 1 ) * ( 3 + 1 ) ) ;");
}

TEST(PP, NestedAndSelfReferentialMacros) {
  PPRun r;
  EXPECT_EQ(r.run("#define A B\n#define B A\n#define f(x) f(x+1)\nA f(2)\n"), "A f ( 2 + 1 )");
}

TEST(PP, StringizeAndPaste) {
  PPRun r;
  EXPECT_EQ(r.run("#define S(x) #x\n#define CAT(a,b) a##b\nS(a \"q\" b) CAT(foo,bar) CAT(1,2)\n"),
            "\"a \\\"q\\\" b\" foobar 12");
}

TEST(PP, Variadic) {
  PPRun r;
  EXPECT_EQ(r.run("#define P(fmt, ...) printf(fmt, __VA_ARGS__)\nP(\"%d %d\", 1, 2);\n"),
            "printf ( \"%d %d\" , 1 , 2 ) ;");
}

TEST(PP, MacroArgumentsAcrossLinesAndNested) {
  PPRun r;
  EXPECT_EQ(r.run("#define ADD(a,b) (a+b)\nADD(ADD(1,2),\n  (3,4))\n"),
            "( ( 1 + 2 ) + ( 3 , 4 ) )");
}

TEST(PP, FunctionMacroNameWithoutParensIsNotExpanded) {
  PPRun r;
  EXPECT_EQ(r.run("#define f(x) x\nint f;\n"), "int f ;");
}

TEST(PP, Conditionals) {
  PPRun r;
  std::string src = "#define X 2\n"
                    "#if X > 1 && defined(X) && !defined Y\na\n#elif 1\nb\n#else\nc\n#endif\n"
                    "#ifdef Y\nd\n#else\ne\n#endif\n"
                    "#ifndef Y\nf\n#endif\n"
                    "#if 0\n#if 1\ng\n#endif\n#bogus\n#elif X == 2\nh\n#endif\n"
                    "#if (1 ? 0 : 1) || (7 % 4 != 3) || (1 << 3) != 8 || -1 >= 0\ni\n#endif\n";
  EXPECT_EQ(r.run(src), "a e f h");
  EXPECT_FALSE(r.diags.has_errors());
}

TEST(PP, PredefinedAndCommandLine) {
  PPRun r;
  pp::PPOptions o;
  o.defines = {"FOO", "BAR=7", "GONE=1"};
  o.undefines = {"GONE"};
  EXPECT_EQ(
      r.run("OSL_VERSION OSL_VERSION_MAJOR OSL_VERSION_MINOR OSL_VERSION_PATCH FOO BAR GONE\n", o),
      "11312 1 13 12 1 7 GONE"); // OSL 1.13.12 (oslc -E)
}

TEST(PP, ConditionalErrors) {
  PPRun r;
  r.run("#endif\n#else\n#if 1\n#else\n#else\n#endif\n#if 1 +\n#endif\n#if 1/0\n#endif\n#if 1\n");
  EXPECT_TRUE(r.has(DiagId::err_endif_without_if));
  EXPECT_TRUE(r.has(DiagId::err_else_without_if));
  EXPECT_TRUE(r.has(DiagId::err_else_after_else));
  EXPECT_TRUE(r.has(DiagId::err_pp_expr));
  EXPECT_TRUE(r.has(DiagId::err_unterminated_conditional));
}

// A chain of conditional operators used to recurse once per `?` without a depth limit, so a
// long chain overflowed the stack; now it is an error like deep parentheses.
TEST(PP, LongConditionalChainIsAnErrorNotAStackOverflow) {
  PPRun r;
  std::string chain;
  for (int i = 0; i < 100000; ++i) chain += "1 ? 1 : ";
  r.run("#if " + chain + "1\nyes\n#endif\n#if 1 ? 2 : 1 ? 0 : 1\nok\n#endif\n");
  EXPECT_TRUE(r.has(DiagId::err_pp_expr));
  ASSERT_EQ(r.diags.diagnostics().size(), 1u);
  EXPECT_EQ(r.collapse(r.out), "ok");
}

TEST(PP, IncludesWithSearchPathsAndGuards) {
  PPRun r;
  r.files["main.osl"] = "";
  r.files["inc/h.h"] = "#ifndef H\n#define H\nint h;\n#endif\n";
  r.files["sub/q.h"] = "#include \"r.h\"\nq\n";
  r.files["sub/r.h"] = "r\n";
  pp::PPOptions o;
  o.include_dirs = {"inc", "sub/"};
  EXPECT_EQ(r.run("#include \"h.h\"\n#include <h.h>\n#include <q.h>\nmain\n", o),
            "int h ; r q main");
  EXPECT_FALSE(r.diags.has_errors());
  // Locations: `q` is line 2 of sub/q.h; `main` line 4 of main.osl.
  auto q = r.where("q\n");
  EXPECT_STREQ(q.file, "sub/q.h");
  EXPECT_EQ(q.line, 2);
  auto m = r.where("main");
  EXPECT_STREQ(m.file, "main.osl");
  EXPECT_EQ(m.line, 4);
  EXPECT_EQ(m.column, 1);
}

// Built-in headers come last, as oslc's shader folder does: the including file's folder and the
// -I paths win, for "" and <> alike; built-in headers may include each other.
TEST(PP, BuiltinHeadersAreSearchedLast) {
  std::map<std::string, std::string> builtin = {
      {"lib.h", "builtin_lib\n"},
      {"shadowed.h", "builtin_shadowed\n"},
      {"outer.h", "#pragma once\n#include \"lib.h\"\nouter\n"}};
  pp::PPOptions o;
  o.include_dirs = {"inc"};
  o.builtin_header = [&](const std::string& name) -> std::optional<std::string> {
    auto it = builtin.find(name);
    if (it == builtin.end()) return std::nullopt;
    return it->second;
  };
  PPRun r;
  r.files["inc/shadowed.h"] = "user_shadowed\n";
  EXPECT_EQ(r.run("#include \"lib.h\"\n#include <shadowed.h>\n#include \"outer.h\"\n"
                  "#include <outer.h>\n",
                  o),
            "builtin_lib user_shadowed builtin_lib outer");
  EXPECT_FALSE(r.diags.has_errors());
  EXPECT_STREQ(r.where("outer").file, "outer.h");
  PPRun local;
  local.files["shadowed.h"] = "beside_main\n"; // the including file's folder ("" only)
  EXPECT_EQ(local.run("#include \"shadowed.h\"\n", o), "beside_main");
  PPRun missing;
  missing.run("#include \"none.h\"\n", o);
  EXPECT_TRUE(missing.has(DiagId::err_include_not_found));
}

TEST(PP, IncludeErrors) {
  PPRun r;
  r.files["a.h"] = "#include \"b.h\"\n";
  r.files["b.h"] = "#include \"a.h\"\n";
  r.run("#include \"missing.h\"\n#include \"a.h\"\n#include nothing\n");
  EXPECT_TRUE(r.has(DiagId::err_include_not_found));
  EXPECT_TRUE(r.has(DiagId::err_include_cycle));
  EXPECT_TRUE(r.has(DiagId::err_include_syntax));
}

TEST(PP, IncludeDepthCap) {
  PPRun r;
  r.files["d.h"] = "#define DEPTH\n"; // unused
  // A chain of distinct files deeper than the cap.
  for (int i = 0; i < 10; ++i)
    r.files[std::string("f") + std::to_string(i) + ".h"] =
        std::string("#include \"f") + std::to_string(i + 1) + ".h\"\n";
  r.files["f10.h"] = "end\n";
  pp::PPOptions o;
  o.max_include_depth = 5;
  r.run("#include \"f0.h\"\n", o);
  EXPECT_TRUE(r.has(DiagId::err_include_depth));
}

TEST(PP, PragmaErrorWarningOnce) {
  PPRun r;
  r.files["o.h"] = "#pragma once\nonce\n";
  std::string out =
      r.run("#pragma error \"bad thing\"\n#pragma warning \"careful\"\n#pragma osl nowarn\n"
            "#include \"o.h\"\n#include \"o.h\"\n");
  EXPECT_EQ(out, "once");
  ASSERT_EQ(r.diags.diagnostics().size(), 2u);
  EXPECT_EQ(r.diags.diagnostics()[0].message, "bad thing");
  EXPECT_EQ(r.diags.diagnostics()[0].severity, diag::Severity::Error);
  EXPECT_EQ(r.diags.diagnostics()[1].message, "careful");
  EXPECT_EQ(r.diags.diagnostics()[1].severity, diag::Severity::Warning);
  EXPECT_EQ(r.sm.presumed(r.diags.diagnostics()[1].range.begin).line, 2);
}

// oslc's own pragmas (`#pragma osl NAME`, "osl" in any case): an unknown NAME is a warning;
// other pragmas are ignored. (oslc 1.13: `#pragma osl NoWarn` gives "Unknown pragma 'NoWarn'",
// `#pragma foo nowarn` nothing.)
TEST(PP, PragmaOslNames) {
  PPRun r;
  r.run("#pragma OSL nowarn\n#pragma osl nowarn x y\n#pragma foo nowarn\n#pragma osl NoWarn\n");
  ASSERT_EQ(r.diags.diagnostics().size(), 1u);
  EXPECT_EQ(r.diags.diagnostics()[0].id, DiagId::warn_unknown_pragma);
  EXPECT_EQ(r.diags.diagnostics()[0].message, "Unknown pragma 'NoWarn'");
  EXPECT_EQ(r.sm.presumed(r.diags.diagnostics()[0].range.begin).line, 4);
  // The lines after the two nowarn pragmas, as the file numbers them.
  using Lines = std::set<std::pair<std::string, int>>;
  EXPECT_EQ(r.nowarn.lines, (Lines{{"main.osl", 2}, {"main.osl", 3}}));
  // The name is the word's leading letters (oslc 1.13.12: `#pragma osl bogus2` warns "Unknown
  // pragma 'bogus'", `Foo_Bar` 'Foo', `9abc` '', and `nowarn2` is nowarn).
  PPRun q;
  q.run("#pragma osl bogus2\n#pragma osl Foo_Bar\n#pragma osl 9abc\n#pragma osl nowarn2\n");
  ASSERT_EQ(q.diags.diagnostics().size(), 3u);
  EXPECT_EQ(q.diags.diagnostics()[0].message, "Unknown pragma 'bogus'");
  EXPECT_EQ(q.diags.diagnostics()[1].message, "Unknown pragma 'Foo'");
  EXPECT_EQ(q.diags.diagnostics()[2].message, "Unknown pragma ''");
  EXPECT_EQ(q.nowarn.lines, (Lines{{"main.osl", 5}}));
}

TEST(PP, LineDirective) {
  PPRun r;
  r.run("a\n#line 50 \"other.osl\"\nb\nc\n");
  auto b = r.where("b");
  EXPECT_EQ(b.line, 50);
  EXPECT_STREQ(b.file, "other.osl");
  EXPECT_EQ(r.where("c").line, 51);
  EXPECT_EQ(r.where("a").line, 1);
}

TEST(PP, LocationsThroughMacros) {
  PPRun r;
  r.run("#define TWICE(x) (x + x)\n\n   y = TWICE(zz);\n");
  // Body tokens map to the invocation (line 3 col 8); argument tokens to their spelling.
  auto paren = r.where("(");
  EXPECT_EQ(paren.line, 3);
  EXPECT_EQ(paren.column, 8);
  auto zz = r.where("zz", 1);
  EXPECT_EQ(zz.line, 3);
  EXPECT_EQ(zz.column, 14);
  auto y = r.where("y");
  EXPECT_EQ(y.line, 3);
  EXPECT_EQ(y.column, 4);
}

// __DATE__ and __TIME__ are when the preprocessor ran, in C's forms, as oslc expands them (OSL
// 1.13.12 printed `Dec  7 2026|13:06:11` for `printf("%s|%s\n", __DATE__, __TIME__)` at that
// moment; Lobe refused them as undeclared).
TEST(PP, DateAndTimeMacros) {
  std::tm tm{};
  tm.tm_year = 2026 - 1900, tm.tm_mon = 11, tm.tm_mday = 7;
  tm.tm_hour = 13, tm.tm_min = 6, tm.tm_sec = 11;
  EXPECT_EQ(pp::date_macro(tm), "\"Dec  7 2026\"");
  EXPECT_EQ(pp::time_macro(tm), "\"13:06:11\"");
  tm.tm_mon = 0, tm.tm_mday = 31, tm.tm_hour = 0, tm.tm_min = 0, tm.tm_sec = 0;
  EXPECT_EQ(pp::date_macro(tm), "\"Jan 31 2026\"");
  EXPECT_EQ(pp::time_macro(tm), "\"00:00:00\"");
  // Expanded: the moment of the run, in those forms.
  std::time_t before = std::time(nullptr);
  PPRun r;
  std::string out = r.run("__DATE__ __TIME__\n");
  std::time_t after = std::time(nullptr);
  auto at = [](std::time_t when) {
    std::tm t{};
    localtime_r(&when, &t);
    return pp::date_macro(t) + " " + pp::time_macro(t);
  };
  EXPECT_TRUE(out == at(before) || out == at(after)) << out;
}

// __LINE__ in the main file is one more than its line, as oslc's (OSL 1.13.12: a shader whose
// line 2 prints __LINE__ prints 3, `oslc s.osl; testshade s`); in an included file it is the
// line (tests/shade/line_macro.osl). After `#line N` the next line is N, with or without a
// file name, in the GNU form too (OSL 1.13.12 prints 3, 100, 200 other.osl, 300 third.osl for
// `printf("%d %s\n", __LINE__, __FILE__)` on lines 2, 4, 6, 8 of a shader with `#line 100`,
// `#line 200 "other.osl"` and `# 300 "third.osl"` before the last three).
TEST(PP, LineAndFileMacros) {
  PPRun r;
  EXPECT_EQ(r.run("\n\n__LINE__ __FILE__\n"), "4 \"main.osl\"");
  PPRun l;
  EXPECT_EQ(l.run("__LINE__\n#line 100\n__LINE__\n#line 200 \"other.osl\"\n__LINE__ __FILE__\n"
                  "# 300 \"third.osl\"\n__LINE__ __FILE__\n"),
            "2 100 200 \"other.osl\" 300 \"third.osl\"");
}

TEST(PP, MacroErrors) {
  PPRun r;
  r.run("#define\n#define F(a,b) a\nF(1)\n#define G(x) #y\n#define H(x) ## x\n#foo\nF(1,\n");
  EXPECT_TRUE(r.has(DiagId::err_macro_unterminated_call));
  EXPECT_TRUE(r.has(DiagId::err_macro_name_missing));
  EXPECT_TRUE(r.has(DiagId::err_macro_arg_count));
  EXPECT_TRUE(r.has(DiagId::err_hash_not_param));
  EXPECT_TRUE(r.has(DiagId::err_paste_at_edge));
  EXPECT_TRUE(r.has(DiagId::err_unknown_directive));
}

TEST(PP, RedefinitionWarnsWithNote) {
  PPRun r;
  r.run("#define A 1\n#define A 1\n#define A 2\n");
  ASSERT_EQ(r.diags.diagnostics().size(), 2u);
  EXPECT_EQ(r.diags.diagnostics()[0].id, DiagId::warn_macro_redefined);
  EXPECT_EQ(r.sm.presumed(r.diags.diagnostics()[0].range.begin).line, 3);
  EXPECT_EQ(r.diags.diagnostics()[1].id, DiagId::note_previous_definition);
  EXPECT_EQ(r.sm.presumed(r.diags.diagnostics()[1].range.begin).line, 2); // the latest one
}

TEST(PP, ExplosiveExpansionIsAnError) {
  PPRun r;
  // Each level doubles: 2^40 tokens if unbounded.
  std::string src = "#define L0 x\n";
  for (int i = 1; i <= 40; ++i)
    src += std::string("#define L") + std::to_string(i) + " L" + std::to_string(i - 1) + " L" +
           std::to_string(i - 1) + "\n";
  src += "L40\n";
  r.run(src);
  EXPECT_TRUE(r.has(DiagId::err_macro_expansion_too_large));
}

TEST(PP, UnterminatedComment) {
  PPRun r;
  r.run("a /* never closed\n");
  EXPECT_TRUE(r.has(DiagId::err_unterminated_comment));
}
