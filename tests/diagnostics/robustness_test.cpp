// The front end on hostile input: truncated shaders, random bytes, 10 000-deep nesting of every
// nestable construct, and a 5 MB file. Each must give diagnostics (or compile), never crash or
// hang.
#include "diag/source_manager.h"
#include "frontend.h"

#include <gtest/gtest.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

using namespace lobe;
namespace fs = std::filesystem;

namespace {

struct Compiled {
  diag::DiagnosticEngine diags;
  std::unique_ptr<ast::TranslationUnit> tu;
  frontend::FrontendTimings timings;
  explicit Compiled(const std::string& src, bool stdlib = true) {
    frontend::FrontendOptions o;
    o.include_stdlib = stdlib;
    tu = frontend::compile_to_ast({"r.osl", src}, o, diags, &timings);
  }
  bool has(diag::DiagId id) const {
    for (auto& d : diags.diagnostics())
      if (d.id == id) return true;
    return false;
  }
};

std::string repeat(const std::string& s, int n) {
  std::string r;
  r.reserve(s.size() * size_t(n));
  for (int i = 0; i < n; ++i) r += s;
  return r;
}

std::string read(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

const std::string kShader =
    "struct S { float a; color c[2]; closure color cl; };\n"
    "S make(float x) { S s; s.a = x; s.c[0] = color(x); s.cl = x * diffuse(N); return s; }\n"
    "surface t [[ string help = \"h\" ]] (float k = 0.5 [[ float min = 0, float max = 1 ]],\n"
    "  output color o = 0, string m = \"ggx\")\n"
    "{\n"
    "  S s = make(k);\n"
    "  for (int i = 0; i < 3; ++i) { if (i == 1) continue; o += color(i) * noise(P * i); }\n"
    "  Ci = s.cl + o * microfacet(m, N, 0.2, 1.5, 0) + 0.1 * oren_nayar_diffuse_bsdf(N, o, k, "
    "\"label\", \"x\");\n"
    "}\n";

} // namespace

TEST(Robustness, ReferenceShaderCompiles) {
  Compiled r(kShader);
  EXPECT_FALSE(r.diags.has_errors());
}

TEST(Robustness, EveryTruncationOfAShader) {
  for (size_t n = 0; n < kShader.size(); ++n) {
    Compiled r(kShader.substr(0, n), false);
    (void)r;
  }
}

// A truncated file (no final newline) reports its errors inside the file, never at the
// preprocessed text: each diagnostic names r.osl at a line and column of the truncated text
// (the end of the file at the latest), and an unterminated comment is reported once.
TEST(Robustness, TruncationErrorsPointIntoTheFile) {
  const std::string src = kShader + "float f() { /* unterminated\n return 1; }\n";
  for (size_t n = 1; n < src.size(); n += 7) {
    std::string text = src.substr(0, n);
    Compiled r(text, false);
    std::vector<std::string> lines;
    std::istringstream in(text + "\n");
    for (std::string l; std::getline(in, l);) lines.push_back(l);
    int comments = 0;
    for (auto& d : r.diags.diagnostics()) {
      comments += d.id == diag::DiagId::err_unterminated_comment;
      diag::PresumedLoc p = r.tu->sources->presumed(d.range.begin);
      ASSERT_STREQ(p.file, "r.osl") << "at " << n << ": " << d.message;
      ASSERT_GE(p.line, 1);
      ASSERT_LE(size_t(p.line), lines.size()) << "at " << n << ": " << d.message;
      ASSERT_LE(size_t(p.column), lines[size_t(p.line - 1)].size() + 1)
          << "at " << n << ": " << d.message;
    }
    EXPECT_LE(comments, 1) << "at " << n;
  }
}

TEST(Robustness, EndOfFileErrorsAtTheEndOfTheFile) {
  Compiled a("shader t() {\n  float x = 1 +", false);
  EXPECT_EQ(diag::render_all(a.diags, *a.tu->sources),
            "r.osl:2:16: error: expected expression, found 'end of file'\n"
            "  float x = 1 +\n"
            "               ^\n"
            "r.osl:2:16: error: expected '}', found 'end of file'\n"
            "  float x = 1 +\n"
            "               ^\n"
            "r.osl:1:12: note: to match this '{'\n"
            "shader t() {\n"
            "           ^\n");
  Compiled b("shader t() {\n  /* comment", false);
  EXPECT_EQ(diag::render_all(b.diags, *b.tu->sources),
            "r.osl:2:3: error: unterminated /* comment\n"
            "  /* comment\n"
            "  ^~\n"
            "r.osl:2:13: error: expected '}', found 'end of file'\n"
            "  /* comment\n"
            "            ^\n"
            "r.osl:1:12: note: to match this '{'\n"
            "shader t() {\n"
            "           ^\n");
  // With a final newline the end of the file is the start of the line after the last.
  Compiled c("shader t() {\n", false);
  EXPECT_NE(diag::render_all(c.diags, *c.tu->sources)
                .find("r.osl:2:1: error: expected '}', found 'end of file'"),
            std::string::npos)
      << diag::render_all(c.diags, *c.tu->sources);
}

TEST(Robustness, TruncatedCorpusFiles) {
  fs::path dir = fs::path(LOBE_SOURCE_DIR) / "tests" / "parse" / "materials";
  int files = 0;
  for (const auto& e : fs::directory_iterator(dir)) {
    if (e.path().extension() != ".osl") continue;
    ++files;
    std::string src = read(e.path());
    for (size_t n = 0; n < src.size(); n += 13) Compiled r(src.substr(0, n), false);
  }
  EXPECT_GT(files, 0);
}

TEST(Robustness, RandomBytes) {
  uint32_t state = 2463534242u;
  for (int round = 0; round < 100; ++round) {
    std::string s(4096, '\0');
    for (auto& c : s) {
      state ^= state << 13;
      state ^= state >> 17;
      state ^= state << 5;
      c = char(state & 0xff);
    }
    Compiled r(s, false);
    EXPECT_TRUE(r.diags.has_errors());
  }
}

TEST(Robustness, RandomTokens) {
  const char* toks[] = {"surface", "s",    "(",     ")",       "{",      "}",      "[[",      "]]",
                        "]",       "[",    "float", "x",       "=",      "1",      ";",       ",",
                        "if",      "else", "for",   "struct",  "return", "color",  "\"str\"", "+",
                        "*",       "?",    ":",     "#define", "\n",     "output", "closure", "."};
  uint32_t state = 7;
  for (int round = 0; round < 200; ++round) {
    std::string s;
    for (int i = 0; i < 300; ++i) {
      state = state * 1103515245u + 12345u;
      s += toks[(state >> 16) % (sizeof(toks) / sizeof(toks[0]))];
      s += ' ';
    }
    Compiled r(s, false);
    (void)r;
  }
}

TEST(Robustness, DeepNestingOfEveryKind) {
  const int n = 10000;
  const std::string body_open = "shader s() { float x = 1; ";
  struct Case {
    const char* what;
    std::string src;
  } cases[] = {
      {"parentheses", body_open + "x = " + repeat("(", n) + "1" + repeat(")", n) + "; }"},
      {"blocks", body_open + repeat("{", n) + repeat("}", n) + " }"},
      {"unary minus", body_open + "x = " + repeat("-", n) + "1; }"},
      {"not", body_open + "x = " + repeat("!", n) + "1; }"},
      {"init lists", body_open + "float a[1] = " + repeat("{", n) + "1" + repeat("}", n) + "; }"},
      {"ternaries", body_open + "x = " + repeat("x ? 1 : ", n) + "2; }"},
      {"if chains", body_open + repeat("if (x) ", n) + "x = 2; }"},
      {"else-if chains", body_open + "if (x) x = 1;" + repeat(" else if (x) x = 1;", n) + " }"},
      {"subscripts",
       body_open + "float a[2]; x = " + repeat("a[", n) + "0" + repeat("]", n) + "; }"},
      {"calls", body_open + "x = " + repeat("sin(", n) + "1" + repeat(")", n) + "; }"},
      {"operator chain", body_open + "x = 1" + repeat(" + 1", n) + "; }"},
      {"assignment chain", body_open + "x = " + repeat("x = ", n) + "1; }"},
      {"nested functions", body_open + repeat("float f() { ", n) + repeat("}", n) + " }"},
      {"macro arguments",
       "#define F(a) (a)\n" + body_open + "x = " + repeat("F(", n) + "1" + repeat(")", n) + "; }"},
      {"conditionals", repeat("#if 1\n", n) + "shader s() {}\n" + repeat("#endif\n", n)},
  };
  for (const auto& c : cases) {
    auto t0 = std::chrono::steady_clock::now();
    Compiled r(c.src, false);
    std::printf(
        "%-18s %6.1f ms\n", c.what,
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
    if (std::string(c.what) != "conditionals")
      EXPECT_TRUE(r.diags.has_errors()) << c.what;
    else
      EXPECT_FALSE(r.diags.has_errors()) << c.what;
  }
}

TEST(Robustness, FiveMegabyteShaderCompiles) {
  std::string src = "surface big(float k = 1) {\n  float x = 0;\n  color c = 0;\n";
  int i = 0;
  while (src.size() < 5u * 1024 * 1024) {
    src += "  x += sin(k * " + std::to_string(i) + ") * 0.5; c += color(x, 1, 0) * noise(P * " +
           std::to_string(i % 97) + ".5);\n";
    ++i;
  }
  src += "  Ci = x * c * diffuse(N);\n}\n";
  Compiled r(src);
  std::printf("5 MB shader: preprocess %.0f ms, lex+parse %.0f ms, sema %.0f ms\n",
              r.timings.preprocess_ms, r.timings.parse_ms, r.timings.sema_ms);
  EXPECT_FALSE(r.diags.has_errors());
  ASSERT_NE(r.tu->shader(), nullptr);
  EXPECT_EQ(r.tu->shader()->body->stmts.size(), size_t(2 + 2 * i + 1)); // x, c, the loop, Ci
}

TEST(Robustness, FiveMegabytesOfGarbageStopsAtTheErrorCap) {
  std::string src = repeat("float 1 = @ ; } ) ", 5 * 1024 * 1024 / 18);
  Compiled r(src, false);
  EXPECT_TRUE(r.diags.stopped());
}
