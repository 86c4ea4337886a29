// Parser tests: every construct (checked through the AST dump), recovery with several errors
// per file, and the nesting cap.
#include "ast/ast_dump.h"
#include "parse/parser.h"

#include <gtest/gtest.h>

using namespace lobe;
using diag::DiagId;

namespace {

struct ParseRun {
  diag::SourceManager sm;
  diag::DiagnosticEngine diags{1000};
  ast::TranslationUnit tu;
  explicit ParseRun(const std::string& src, parse::ParseOptions o = {}) {
    int id = sm.add_file("t.osl", src);
    auto ts = lex::lex_buffer(sm, diags, id);
    parse::parse(ts, diags, tu, o);
  }
  std::string dump() const { return ast::dump(tu); }
  int count(DiagId id) const {
    int n = 0;
    for (auto& d : diags.diagnostics()) n += d.id == id;
    return n;
  }
  int line_of(size_t i) const { return sm.presumed(diags.diagnostics()[i].range.begin).line; }
};

// Parses `surface s() { <body> }` and returns the dump of the body's statements.
std::string body(const std::string& stmts) {
  ParseRun r("surface s() { " + stmts + " }");
  EXPECT_FALSE(r.diags.has_errors()) << stmts;
  std::string d = r.dump();
  // "(surface s () { ... })\n" -> "..."
  auto b = d.find("{ ");
  auto e = d.rfind(" })");
  return b == std::string::npos || e == std::string::npos || e < b ? d : d.substr(b + 2, e - b - 2);
}

} // namespace

TEST(Parser, ShaderWithParamsMetadataAndTrailingComma) {
  ParseRun r(R"(
    surface plastic [[ string help = "A " "plastic", int version = 2 ]] (
        float Kd = 0.5 [[ float min = 0, float max = 1, string widget = "slider" ]],
        color Cs = color(1, 0.5, 0),
        normal Nn = N,
        output float out = 0,
        float arr[3] = {1, 2, 3},
        string opts = "a|b" [[ string options = "a|b", ]],
    ) { Ci = Kd * Cs * diffuse(Nn); })");
  EXPECT_FALSE(r.diags.has_errors()) << ast::dump(r.tu);
  EXPECT_EQ(
      r.dump(),
      "(surface plastic [[ string help = \"A plastic\" int version = 2 ]] ("
      "(var float Kd 0.5 [[ float min = 0 float max = 1 string widget = \"slider\" ]]) "
      "(var color Cs (construct color 1 0.5 0)) (var normal Nn N) (var output float out 0) "
      "(var float[3] arr ({} 1 2 3)) (var string opts \"a|b\" [[ string options = \"a|b\" ]])) "
      "{ (= Ci (* (* Kd Cs) (call diffuse Nn))); })\n");
  auto* s = r.tu.shader();
  ASSERT_NE(s, nullptr);
  EXPECT_EQ(s->shader_type, ast::ShaderType::Surface);
  EXPECT_TRUE(s->params[3]->is_output);
}

TEST(Parser, AllShaderTypes) {
  ParseRun r("displacement d() {} volume v() {} shader g() {}");
  EXPECT_FALSE(r.diags.has_errors());
  EXPECT_EQ(r.dump(), "(displacement d () { })\n(volume v () { })\n(shader g () { })\n");
}

TEST(Parser, StructsNestedArraysAndConstructors) {
  ParseRun r("struct A { float x, y[2]; color c; };\n"
             "struct B { A a; A arr[3]; closure color cl; };\n"
             "shader s() { B b; A a = A(1, {2, 3}, color(1)); b.a.y[1] = a.x; b.arr[2].c.r = 1; }");
  EXPECT_FALSE(r.diags.has_errors()) << ast::dump(r.tu);
  EXPECT_EQ(r.dump(), "(struct A ((var float x) (var float[2] y) (var color c)))\n"
                      "(struct B ((var A a) (var A[3] arr) (var closure color cl)))\n"
                      "(shader s () { (var B b) (var A a (call A 1 ({} 2 3) (construct color 1))) "
                      "(= ([] (. y (. a b)) 1) (. x a)); (= (. r (. c ([] (. arr b) 2))) 1); })\n");
}

TEST(Parser, FunctionsPrototypesNestedAndOperators) {
  ParseRun r("float sq(float x) { return x * x; }\n"
             "void setit(output float a[], float v) { a[0] = v; }\n"
             "closure color myclosure(normal N, float r) [[ int builtin = 1 ]];\n"
             "struct V2 { float x, y; };\n"
             "V2 __operator__add__(V2 a, V2 b) { return V2(a.x + b.x, a.y + b.y); }\n"
             "shader s() { float inner(float q) { return q + 1; } float z = inner(sq(2)); }\n");
  EXPECT_FALSE(r.diags.has_errors()) << ast::dump(r.tu);
  auto* proto = static_cast<ast::FunctionDecl*>(r.tu.decls[2].get());
  EXPECT_TRUE(proto->is_builtin);
  EXPECT_EQ(proto->body, nullptr);
  EXPECT_EQ(proto->return_type.base, ast::BaseType::Closure);
  auto* setit = static_cast<ast::FunctionDecl*>(r.tu.decls[1].get());
  EXPECT_TRUE(setit->params[0]->is_output);
  EXPECT_EQ(setit->params[0]->type.arraylen, -1);
  std::string d = r.dump();
  EXPECT_NE(d.find("(function V2 __operator__add__ ((var V2 a) (var V2 b)) { (return (call V2 "
                   "(+ (. x a) (. x b)) (+ (. y a) (. y b)))) })"),
            std::string::npos)
      << d;
  EXPECT_NE(d.find("{ (function float inner ((var float q)) { (return (+ q 1)) }) "
                   "(var float z (call inner (call sq 2))) }"),
            std::string::npos)
      << d;
}

TEST(Parser, Precedence) {
  EXPECT_EQ(body("x = a + b * c - d / e % f;"), "(= x (- (+ a (* b c)) (% (/ d e) f)));");
  EXPECT_EQ(body("x = a || b && c | d ^ e & f == g < h << i + j;"),
            "(= x (|| a (&& b (| c (^ d (& e (== f (< g (<< h (+ i j))))))))));");
  EXPECT_EQ(body("x = a and b or not c;"), "(= x (|| (&& a b) (! c)));");
  EXPECT_EQ(body("x = y = c ? d : e ? f : g;"), "(= x (= y (? c d (? e f g))));");
  EXPECT_EQ(body("x = -a[1].r++ + ~--b;"), "(= x (+ (- (post++ (. r ([] a 1)))) (~ (pre-- b))));");
  EXPECT_EQ(body("a += 1, b <<= 2, c ^= d;"), "(, (+= a 1) (<<= b 2) (^= c d));");
}

TEST(Parser, CastsConstructorsAndGrouping) {
  EXPECT_EQ(body("v = (vector) P + (a + b) * vector(P);"),
            "(= v (+ (cast vector P) (* (+ a b) (construct vector P))));");
  EXPECT_EQ(body("c = color(\"hsv\", h, s, v); m = matrix(\"shader\", 1); p = point(\"object\", 0, "
                 "0, 1);"),
            "(= c (construct color \"hsv\" h s v)); (= m (construct matrix \"shader\" 1)); "
            "(= p (construct point \"object\" 0 0 1));");
  EXPECT_EQ(body("float f = float(i); int k = (int) f;"),
            "(var float f (construct float i)) (var int k (cast int f))");
}

TEST(Parser, Statements) {
  EXPECT_EQ(body("if (a) b = 1; else if (c) { b = 2; } else ;"),
            "(if a (= b 1); (if c { (= b 2); } ;))");
  EXPECT_EQ(body("for (int i = 0; i < 3; ++i) { if (i == 1) continue; break; }"),
            "(for (var int i 0) (< i 3) (pre++ i) { (if (== i 1) continue) break })");
  EXPECT_EQ(body("for (;;) break;"), "(for _ _ _ break)");
  EXPECT_EQ(body("for (i = 0; i < 2; i++) x;"), "(for (= i 0); (< i 2) (post++ i) x;)");
  EXPECT_EQ(body("while (x < 3) x += 1; do { x--; } while (x);"),
            "(while (< x 3) (+= x 1);) (do { (post-- x); } x)");
  EXPECT_EQ(body("return; exit();"), "(return) (call exit);");
  EXPECT_EQ(body("float a[] = {1, 2,}, b = 3; closure color c = 0;"),
            "(var float[] a ({} 1 2)) (var float b 3) (var closure color c 0)");
}

TEST(Parser, ClosureKeywordArgumentsAreOrdinaryArguments) {
  EXPECT_EQ(body("Ci = 0.5 * diffuse(N, \"label\", \"base\") + color(1) * microfacet(\"ggx\", N, "
                 "0.1, 1.5, 0);"),
            "(= Ci (+ (* 0.5 (call diffuse N \"label\" \"base\")) (* (construct color 1) "
            "(call microfacet \"ggx\" N 0.1 1.5 0))));");
}

TEST(Parser, NodeRanges) {
  ParseRun r("shader s() {\n  x = foo(1, 2);\n}");
  auto* sh = r.tu.shader();
  auto* st = static_cast<ast::ExprStmt*>(sh->body->stmts[0].get());
  auto* as = static_cast<ast::AssignExpr*>(st->expr.get());
  auto b = r.sm.presumed(as->rhs->range.begin);
  auto e = r.sm.presumed(as->rhs->range.end);
  EXPECT_EQ(b.line, 2);
  EXPECT_EQ(b.column, 7);
  EXPECT_EQ(e.column, 16); // one past ')'
}

TEST(Parser, RecoveryReportsSeveralErrors) {
  ParseRun r("shader s() {\n"
             "  float a = ;\n" // 2: expected expression
             "  b = (1 + 2;\n" // 3: expected ')'
             "  c = 3\n"       // 4-5: expected ';' (found 'd')
             "  d = 4;\n"
             "  if x) y = 1;\n" // 6: expected '('
             "  e = 5;\n"
             "}\n"
             "float f( { }\n"          // 9: bad parameter
             "surface t() { g = ; }\n" // 10
             "int 123;\n");            // 11
  EXPECT_GE(r.diags.error_count(), 6);
  std::vector<int> lines;
  for (size_t i = 0; i < r.diags.diagnostics().size(); ++i)
    if (r.diags.diagnostics()[i].severity == diag::Severity::Error) lines.push_back(r.line_of(i));
  for (int want : {2, 3, 5, 6, 9, 10, 11})
    EXPECT_NE(std::find(lines.begin(), lines.end(), want), lines.end())
        << "no error on line " << want;
  // The second shader is still in the tree.
  bool found_t = false;
  for (auto& d : r.tu.decls) found_t |= d->name == "t";
  EXPECT_TRUE(found_t);
}

TEST(Parser, MissingDefaultAndBadMetadata) {
  ParseRun r("surface s(float a, float b = 1 [[ string x = \"y\" ) {}");
  EXPECT_EQ(r.count(DiagId::err_param_needs_default), 1);
  EXPECT_GE(r.diags.error_count(), 2);
}

TEST(Parser, DeepNestingIsAnErrorNotACrash) {
  std::string src = "shader s() { x = ";
  for (int i = 0; i < 10000; ++i) src += "(";
  src += "1";
  for (int i = 0; i < 10000; ++i) src += ")";
  src += "; ";
  for (int i = 0; i < 10000; ++i) src += "{";
  for (int i = 0; i < 10000; ++i) src += "}";
  src += "}";
  ParseRun r(src);
  EXPECT_EQ(r.count(DiagId::err_nesting_too_deep), 1);
  std::string neg = "shader s() { x = ";
  for (int i = 0; i < 10000; ++i) neg += "-";
  ParseRun r2(neg + "1; }");
  EXPECT_EQ(r2.count(DiagId::err_nesting_too_deep), 1);
}

TEST(Parser, ModerateNestingIsFine) {
  std::string src = "shader s() { x = ";
  for (int i = 0; i < 50; ++i) src += "(";
  src += "1";
  for (int i = 0; i < 50; ++i) src += ")";
  src += "; }";
  ParseRun r(src);
  EXPECT_FALSE(r.diags.has_errors());
}

TEST(Parser, TruncatedInputsNeverCrash) {
  std::string src =
      "struct P { float a; color c[2]; };\n"
      "float f(output float x, P p[]) [[ int builtin = 0 ]] { x = p[0].a; return x; }\n"
      "surface s [[ string help = \"h\" ]] (float k = 1 [[ float min = 0 ]], output color o = 0)\n"
      "{ for (int i = 0; i < 3; ++i) { o += color(k) * f(k, {}); } Ci = o * diffuse(N); }\n";
  for (size_t n = 0; n <= src.size(); ++n) {
    ParseRun r(src.substr(0, n));
    (void)r;
  }
  ParseRun full(src);
  EXPECT_FALSE(full.diags.has_errors()) << ast::dump(full.tu);
}
