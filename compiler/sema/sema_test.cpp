// Type checker tests, through the whole front end (so the standard header is present): types,
// coercions, overloads (also by return type), output arguments, structs, operator overloading,
// closures with keyword arguments against the real registry, and the error cases.
#include "ast/ast_dump.h"
#include "diag/source_manager.h"
#include "frontend.h"
#include "sema/builtins.h"
#include "stdlib/stdlib.h"

#include <gtest/gtest.h>

using namespace lobe;
using diag::DiagId;

namespace {

struct Checked {
  diag::DiagnosticEngine diags{200};
  std::unique_ptr<ast::TranslationUnit> tu;

  explicit Checked(const std::string& src) {
    tu = frontend::compile_to_ast({"t.osl", src}, {}, diags);
  }
  std::string text() const { return diag::render_all(diags, *tu->sources); }
  bool ok() const { return !diags.has_errors(); }
  int count(DiagId id) const {
    int n = 0;
    for (auto& d : diags.diagnostics()) n += d.id == id;
    return n;
  }
  // Dump (with types) of the shader body.
  std::string body() const {
    ast::DumpOptions o;
    o.types = true;
    return ast::dump(tu->shader()->body.get(), o);
  }
  const ast::ShaderDecl* shader() const { return tu->shader(); }
};

std::string body_of(const std::string& stmts) {
  Checked c("shader s() { " + stmts + " }");
  EXPECT_TRUE(c.ok()) << stmts << "\n" << c.text();
  return c.ok() ? c.body() : "";
}

} // namespace

TEST(Sema, StandardHeaderTypeChecks) {
  Checked c("");
  EXPECT_TRUE(c.ok()) << c.text();
}

TEST(Sema, ExplicitIncludeOfTheStandardHeader) {
  for (const char* inc : {"#include \"stdosl.h\"\n", "#include <stdosl.h>\n"}) {
    diag::DiagnosticEngine diags;
    frontend::FrontendOptions o;
    o.include_stdlib = false;
    std::string src = std::string(inc) + "shader s() { float m = mix(0.0, 1.0, 0.5) + M_PI; }";
    auto tu = frontend::compile_to_ast({"t.osl", src}, o, diags);
    EXPECT_FALSE(diags.has_errors()) << inc << diag::render_all(diags, *tu->sources);
  }
}

TEST(Sema, LiteralsAndArithmeticCoercions) {
  EXPECT_EQ(body_of("float f = 1;"), "{ (var float f (icast float:float 1:int)) }");
  EXPECT_EQ(body_of("color c = 0.5 * color(1, 0, 0);"),
            "{ (var color c (*:color (icast color:color 0.5:float) (construct color:color "
            "(icast float:float 1:int) (icast float:float 0:int) (icast float:float 0:int)))) }");
  EXPECT_EQ(body_of("int i = 7 / 2; float g = 7 / 2.0;"),
            "{ (var int i (/:int 7:int 2:int)) (var float g (/:float (icast float:float 7:int) "
            "2.0:float)) }");
  // point - point is a vector
  EXPECT_EQ(
      body_of("vector d = P - P;"),
      "{ (var vector d (-:vector (icast vector:vector P:point) (icast vector:vector P:point))) }");
  // point - vector is a point (oslc's kinds for two triples: tests/shade/triple_kinds_osl.osl)
  EXPECT_EQ(body_of("vector d = P - I;"),
            "{ (var vector d (icast vector:vector (-:point P:point (icast point:point I:vector)))) "
            "}");
  EXPECT_EQ(body_of("int b = 1 < 2.5;"),
            "{ (var int b (<:int (icast float:float 1:int) 2.5:float)) }");
  // a matrix times a number scales it: the number stays a float (tests/shade/matrix_scalar_osl)
  EXPECT_EQ(body_of("matrix m = 2; m = m * 3;"),
            "{ (var matrix m (icast matrix:matrix 2:int)) (=:matrix m:matrix (*:matrix m:matrix "
            "(icast float:float 3:int))); }");
}

TEST(Sema, OneArgumentConstructorsAreCasts) {
  EXPECT_EQ(
      body_of("vector w = vector(P); color c = color(0.5); int k = int(2.7);"),
      "{ (var vector w (cast vector:vector P:point)) (var color c (cast color:color 0.5:float)) "
      "(var int k (cast int:int 2.7:float)) }");
  EXPECT_EQ(
      body_of("color h = color(\"hsv\", 0.1, 1, 1);"),
      "{ (var color h (construct color:color \"hsv\":string 0.1:float (icast float:float 1:int) "
      "(icast float:float 1:int))) }");
}

TEST(Sema, ComponentsMembersAndMatrixElements) {
  EXPECT_EQ(
      body_of(
          "float a = P.x + P[1]; matrix m = 1; m[1][2] = a; float arr[3] = {1, 2, 3}; a = arr[2];"),
      "{ (var float a (+:float (. x:float P:point) ([]:float P:point 1:int))) "
      "(var matrix m (icast matrix:matrix 1:int)) (=:float ([]:float m:matrix 1:int 2:int) "
      "a:float); "
      "(var float[3] arr ({}:float[3] (icast float:float 1:int) (icast float:float 2:int) "
      "(icast float:float 3:int))) (=:float a:float ([]:float arr:float[3] 2:int)); }");
}

TEST(Sema, OverloadsByArgumentsAndReturnType) {
  std::string src =
      "shader s() { float f = noise(P); color c = noise(P); vector w = (vector) noise(u, v);"
      " float g = noise(u); float h = sin(1); int a = abs(-2); }";
  Checked c(src);
  ASSERT_TRUE(c.ok()) << c.text();
  auto& stmts = c.shader()->body->stmts;
  auto call_of = [&](size_t i) {
    auto* v =
        static_cast<ast::VarDecl*>(static_cast<ast::DeclStmt*>(stmts[i].get())->decls[0].get());
    ast::Expr* e = v->init.get();
    while (auto* k = ast::as<ast::CastExpr>(e)) e = k->operand.get();
    return ast::as<ast::CallExpr>(e);
  };
  EXPECT_EQ(call_of(0)->callee.builtin->signature(), "float noise(point)");
  EXPECT_EQ(call_of(1)->callee.builtin->signature(), "color noise(point)");
  EXPECT_EQ(call_of(2)->callee.builtin->signature(), "vector noise(float, float)");
  EXPECT_EQ(call_of(3)->callee.builtin->signature(), "float noise(float)");
  EXPECT_EQ(call_of(4)->callee.builtin->signature(), "float sin(float)");
  EXPECT_EQ(call_of(5)->callee.builtin->signature(), "int abs(int)");
  EXPECT_EQ(call_of(1)->callee.kind, ast::CalleeKind::Builtin);
}

// User functions overload by return type alone, as builtins do: the type the context expects
// picks one (initialiser, cast, assignment, the operands of an operator); without one, float is
// preferred, then int, color, vector, point, normal, with oslc's warning.
TEST(Sema, UserOverloadsByReturnTypeOnly) {
  Checked c("float pick() { return 1; }\ncolor pick() { return 2; }\nint pick() { return 3; }\n"
            "shader s() { float f = pick(); color c = pick(); color k = (color) pick();"
            " int i = pick(); c = pick(); float g = pick() * 2; }");
  ASSERT_TRUE(c.ok()) << c.text();
  std::string b = c.body();
  EXPECT_NE(b.find("(var float f (call pick:float))"), std::string::npos) << b;
  EXPECT_NE(b.find("(var color c (call pick:color))"), std::string::npos) << b;
  EXPECT_NE(b.find("(var color k (cast color:color (call pick:color)))"), std::string::npos) << b;
  EXPECT_NE(b.find("(var int i (call pick:int))"), std::string::npos) << b;
  EXPECT_NE(b.find("(=:color c:color (call pick:color))"), std::string::npos) << b;
  EXPECT_NE(b.find("(*:float (call pick:float)"), std::string::npos) << b; // no context: float

  Checked no_float("int two() { return 2; }\ncolor two() { return 3; }\n"
                   "shader s() { float g = two() * 2; }");
  ASSERT_TRUE(no_float.ok()) << no_float.text();
  EXPECT_NE(no_float.body().find("(*:int (call two:int)"), std::string::npos) << no_float.body();

  Checked tie(
      "point q() { return 1; }\nvector q() { return 2; }\nshader s() { float d = q()[0]; }");
  EXPECT_TRUE(tie.ok()) << tie.text();
  EXPECT_EQ(tie.count(DiagId::warn_ambiguous_call), 1) << tie.text();
  std::string t = tie.text();
  EXPECT_NE(t.find("t.osl:2:8: note: chosen: vector q()"), std::string::npos) << t;
  EXPECT_NE(t.find("t.osl:1:7: note: other candidate: point q()"), std::string::npos) << t;
}

// Same parameters and the same return type is a redefinition: oslc warns, with a note at the
// first, and the new one replaces it (gM:st14, gV:out5).
TEST(Sema, RedefinitionOfAFunctionNeedsTheSameReturnType) {
  Checked c("float pick() { return 1; }\ncolor pick() { return 2; }\ncolor pick() { return 3; }\n"
            "shader s() { color c = pick(); }");
  EXPECT_TRUE(c.ok()) << c.text();
  EXPECT_EQ(c.count(DiagId::warn_function_redefined), 1) << c.text();
  std::string t = c.text();
  EXPECT_NE(t.find("t.osl:3:7: warning: Function 'color pick ()' redefined in the same scope"),
            std::string::npos)
      << t;
  EXPECT_NE(t.find("t.osl:2:7: note: previous definition is here"), std::string::npos) << t;
  auto* d = static_cast<ast::DeclStmt*>(c.shader()->body->stmts[0].get());
  auto* call = ast::as<ast::CallExpr>(static_cast<ast::VarDecl*>(d->decls[0].get())->init.get());
  ASSERT_NE(call, nullptr);
  EXPECT_EQ(c.tu->sources->presumed(call->callee.function->name_range.begin).line, 3); // the last
  // A prototype is completed by the definition of its own return type only.
  Checked proto("color pick();\nfloat pick() { return 1; }\ncolor pick() { return 2; }\n"
                "shader s() { color c = pick(); float f = pick(); }");
  EXPECT_TRUE(proto.ok()) << proto.text();
}

TEST(Sema, UserOverloadsAndCoercionOrder) {
  Checked c("float f(float x) { return 1; }\n"
            "float f(color x) { return 2; }\n"
            "shader s() { float a = f(1); float b = f(P); float d = f(color(1)); }");
  ASSERT_TRUE(c.ok()) << c.text();
  auto& stmts = c.shader()->body->stmts;
  auto callee = [&](size_t i) {
    auto* v =
        static_cast<ast::VarDecl*>(static_cast<ast::DeclStmt*>(stmts[i].get())->decls[0].get());
    return ast::to_string(ast::as<ast::CallExpr>(v->init.get())->callee.function->params[0]->type);
  };
  EXPECT_EQ(callee(0), "float"); // int -> float beats int -> color
  EXPECT_EQ(callee(1), "color"); // point -> color (triple to triple)
  EXPECT_EQ(callee(2), "color");
}

TEST(Sema, UserFunctionOverridesBuiltinWithSameSignature) {
  Checked c("float noise(point p) { return 0.25; }\nshader s() { float n = noise(P); color k = "
            "noise(P); }");
  ASSERT_TRUE(c.ok()) << c.text();
  auto* d0 = static_cast<ast::DeclStmt*>(c.shader()->body->stmts[0].get());
  auto* call = ast::as<ast::CallExpr>(static_cast<ast::VarDecl*>(d0->decls[0].get())->init.get());
  ASSERT_NE(call, nullptr);
  EXPECT_EQ(call->callee.kind, ast::CalleeKind::User);
  auto* d1 = static_cast<ast::DeclStmt*>(c.shader()->body->stmts[1].get());
  auto* call2 = ast::as<ast::CallExpr>(static_cast<ast::VarDecl*>(d1->decls[0].get())->init.get());
  ASSERT_NE(call2, nullptr); // the color builtin matches the expected type exactly
  EXPECT_EQ(call2->callee.kind, ast::CalleeKind::Builtin);
}

TEST(Sema, NoMatchListsCandidates) {
  Checked c("float f(float x) { return x; }\nfloat f(string s) { return 0; }\n"
            "shader s() { f(matrix(1)); }");
  EXPECT_EQ(c.count(DiagId::err_no_matching_call), 1);
  EXPECT_EQ(c.count(DiagId::note_candidate), 2);
  std::string t = c.text();
  EXPECT_NE(t.find("t.osl:3:14: error: no matching function for call to 'f(matrix)'"),
            std::string::npos)
      << t;
  EXPECT_NE(t.find("t.osl:1:7: note: candidate: float f(float)"), std::string::npos) << t;
  EXPECT_NE(t.find("t.osl:2:7: note: candidate: float f(string)"), std::string::npos) << t;
}

// Equal scores and equal return types: the newest declaration, with a warning (gH:k).
TEST(Sema, AmbiguousUserCall) {
  Checked c("float g(float a, color b) { return 0; }\nfloat g(color a, float b) { return 0; }\n"
            "shader s() { g(1.0, 1.0); }");
  EXPECT_TRUE(c.ok()) << c.text();
  EXPECT_EQ(c.count(DiagId::warn_ambiguous_call), 1) << c.text();
  std::string t = c.text();
  EXPECT_NE(t.find("t.osl:3:14: warning: call to 'g(float, float)' is ambiguous"),
            std::string::npos)
      << t;
  EXPECT_NE(t.find("t.osl:2:7: note: chosen: float g(color, float)"), std::string::npos) << t;
  EXPECT_NE(t.find("t.osl:1:7: note: other candidate: float g(float, color)"), std::string::npos)
      << t;
}

TEST(Sema, OutputArguments) {
  Checked ok("void set(output float x) { x = 1; }\nshader s() { float a; set(a); float k, cc; "
             "sincos(0.5, k, cc); }");
  EXPECT_TRUE(ok.ok()) << ok.text();
  // As in oslc: a literal cannot be an output, a value that is no variable (`p + 1`) can (it
  // is written to a temporary), and an int is chosen for `output float` by its score and then
  // rejected (gV:out2, out6, out10).
  Checked bad("void set(float x) { x = 1; }\n" // writes a non-output param
              "void put(output float x) { x = 2; }\n"
              "shader s(float p = 1) { put(1.5); put(p + 1); int i; put(i); }");
  EXPECT_EQ(bad.count(DiagId::warn_write_nonoutput_param), 1) << bad.text(); // oslc warns too
  EXPECT_EQ(bad.count(DiagId::err_output_arg_not_lvalue), 1) << bad.text();
  EXPECT_EQ(bad.count(DiagId::err_output_arg_type), 1) << bad.text();
  // Any triple kind goes to a triple output (gV:out3, out8).
  Checked triples("void put(output color c) { c = 1; }\nshader s() { point q; put(q); }");
  EXPECT_TRUE(triples.ok()) << triples.text();
}

TEST(Sema, GlobalsAndWritability) {
  EXPECT_TRUE(
      Checked("surface s() { P = P + N; N = normalize(N); Ci = 0; float x = u + v + time; }").ok());
  // As oslc 1.13.12 (`oslc g.osl` for each kind of shader): the globals but P, I, N, Ci are
  // non-output parameters, written with a warning; a shader's own input parameter is an error.
  Checked bad("surface s() { Ng = N; u = 1; }\ndisplacement d() { }");
  EXPECT_EQ(bad.count(DiagId::warn_write_nonoutput_param), 2) << bad.text();
  EXPECT_EQ(bad.count(DiagId::err_shader_redefinition), 1);
  Checked disp("displacement d() { P += N; Ci = 0; I = N; }");
  EXPECT_TRUE(disp.ok()) << disp.text();
  EXPECT_EQ(disp.count(DiagId::warn_write_nonoutput_param), 0) << disp.text();
  Checked generic("shader g() { u = 1; }");
  EXPECT_NE(generic.text().find("warning: cannot write to non-output parameter \"u\""),
            std::string::npos)
      << generic.text();
  Checked param("shader t(float p = 1, float a[2] = {1, 2}, output float o = 0)\n"
                "{ p = 2; a[1] = 3; p += 1; o = p; }");
  EXPECT_EQ(param.count(DiagId::err_write_nonoutput_param), 3) << param.text();
  EXPECT_NE(param.text().find("error: cannot write to non-output parameter \"p\""),
            std::string::npos)
      << param.text();
}

TEST(Sema, ShadingFunctions) {
  EXPECT_TRUE(Checked("surface s() { if (backfacing() || raytype(\"shadow\")) exit(); float a = "
                      "surfacearea(); }")
                  .ok());
}

TEST(Sema, OperatorRules) {
  Checked c("shader s() { color a = 1, b = 2; int x = a < b; string q = \"a\" + \"b\"; "
            "closure color c1 = 0, c2 = 0; closure color c3 = c1 * c2; c3 = c1 * vector(1); "
            "int y = 1.5 & 2; }");
  EXPECT_EQ(c.count(DiagId::err_bad_binary), 5) << c.text();
}

TEST(Sema, ClosureArithmeticAndMix) {
  Checked bad("surface s() { closure color c = 0.5 * diffuse(N) - emission(); }");
  EXPECT_EQ(bad.count(DiagId::err_bad_binary), 1) << bad.text(); // no closure subtraction
  Checked ok("surface s() { closure color a = diffuse(N); Ci = a * 2 + color(0.5) * a; Ci *= 0.5;"
             " Ci += -a; Ci = mix(a, transparent(), 0.25); Ci = u > 0.5 ? a : 0; }");
  EXPECT_TRUE(ok.ok()) << ok.text();
}

TEST(Sema, ClosureKeywordArguments) {
  Checked c(
      "surface s() { Ci = oren_nayar_diffuse_bsdf(N, color(1), 0.5, \"energy_compensation\", 1,"
      " \"label\", \"a\", \"label\", \"b\"); }");
  ASSERT_TRUE(c.ok()) << c.text();
  auto* st = static_cast<ast::ExprStmt*>(c.shader()->body->stmts[0].get());
  auto* call = ast::as<ast::CallExpr>(static_cast<ast::AssignExpr*>(st->expr.get())->rhs.get());
  ASSERT_NE(call, nullptr);
  EXPECT_EQ(call->callee.kind, ast::CalleeKind::Closure);
  EXPECT_EQ(call->num_positional, 3);
  ASSERT_EQ(call->keywords.size(), 2u);
  EXPECT_EQ(call->keywords[0].name, "energy_compensation");
  EXPECT_EQ(call->keywords[1].name, "label");
  EXPECT_EQ(ast::as<ast::StringLit>(call->keywords[1].value)->value, "b"); // the last one wins
  // A keyword the closure does not take, or of another type, is kept as written (parameter -1),
  // as oslc keeps it; the group builder drops it.
  Checked kept("surface s() { Ci = diffuse(N, \"nonsense\", 1, \"label\", 3); }");
  ASSERT_TRUE(kept.ok()) << kept.text();
  auto* ks = static_cast<ast::ExprStmt*>(kept.shader()->body->stmts[0].get());
  auto* kc = ast::as<ast::CallExpr>(static_cast<ast::AssignExpr*>(ks->expr.get())->rhs.get());
  ASSERT_NE(kc, nullptr);
  ASSERT_EQ(kc->keywords.size(), 2u);
  EXPECT_EQ(kc->keywords[0].name, "nonsense");
  EXPECT_EQ(kc->keywords[0].param_index, -1);
  EXPECT_EQ(kc->keywords[1].name, "label");
  EXPECT_EQ(kc->keywords[1].param_index, -1);
  EXPECT_EQ(kc->keywords[1].value->type.base, ast::BaseType::Int); // not converted
  Checked bad("surface s() { Ci = diffuse(1, 2); }");
  EXPECT_EQ(bad.count(DiagId::err_no_matching_call), 1) << bad.text();
}

TEST(Sema, ClosureOverloadsFromRegistry) {
  Checked c("surface s() { Ci = microfacet(\"ggx\", N, 0.2, 1.5, 0) + microfacet(\"ggx\", N, dPdu, "
            "0.1, 0.3, 1.5, 0); }");
  EXPECT_TRUE(c.ok()) << c.text();
}

TEST(Sema, StructsConstructorsAndInitLists) {
  Checked c("struct A { float x; color c[2]; };\n"
            "struct B { A a; int n; };\n"
            "shader s() { A a = A(1, {color(1), 2}); B b = { a, 3 }; B b2 = {{1, {0, 0}}, 2};"
            " b.a.c[1].r = b2.a.x; A arr[2] = { a, A(2, {0, 1}) }; float f = arr[1].c[0][2]; }");
  EXPECT_TRUE(c.ok()) << c.text();
  Checked bad(
      "struct A { float x; };\nshader s() { A a = A(1, 2); A b = {1, 2}; float f = a.y; a = 1; }");
  EXPECT_EQ(bad.count(DiagId::err_struct_ctor_args), 1) << bad.text();
  EXPECT_EQ(bad.count(DiagId::err_init_count), 1) << bad.text();
  EXPECT_EQ(bad.count(DiagId::err_no_member), 1) << bad.text();
  EXPECT_EQ(bad.count(DiagId::err_cannot_assign), 1) << bad.text();
}

TEST(Sema, OperatorOverloading) {
  Checked c("struct V2 { float x, y; };\n"
            "V2 __operator__add__(V2 a, V2 b) { return V2(a.x + b.x, a.y + b.y); }\n"
            "V2 __operator__mul__(V2 a, float s) { return V2(a.x * s, a.y * s); }\n"
            "V2 __operator__neg__(V2 a) { return V2(-a.x, -a.y); }\n"
            "int __operator__eq__(V2 a, V2 b) { return a.x == b.x && a.y == b.y; }\n"
            "shader s() { V2 p = V2(1, 2), q = V2(3, 4); V2 r = -(p + q) * 2; int e = p == q; V2 z "
            "= p - q; }");
  EXPECT_EQ(c.count(DiagId::err_bad_binary), 1) << c.text(); // no __operator__sub__
  EXPECT_EQ(c.diags.error_count(), 1) << c.text();
}

TEST(Sema, CompoundAssignmentUsesOperatorOverloads) {
  // OSL rewrites `a op= b` as `a = a op b`, so the struct overloads apply.
  const std::string decls =
      "struct V2 { float x, y; };\n"
      "V2 __operator__add__(V2 a, V2 b) { return V2(a.x + b.x, a.y + b.y); }\n"
      "V2 __operator__mul__(V2 a, float s) { return V2(a.x * s, a.y * s); }\n"
      "float __operator__sub__(V2 a, V2 b) { return a.x - b.x; }\n";
  Checked c(decls + "shader s() { V2 p = V2(1, 2), q = V2(3, 4); p += q; p *= 2; }");
  ASSERT_TRUE(c.ok()) << c.text();
  EXPECT_NE(c.body().find("(+=:V2 p:V2 q:V2)"), std::string::npos) << c.body();
  EXPECT_NE(c.body().find("(*=:V2 p:V2 (icast float:float 2:int))"), std::string::npos) << c.body();
  // No overload (no __operator__div__), and an overload whose result is not the target's type.
  Checked bad(decls + "shader s() { V2 p = V2(1, 2), q = p; p /= q; p -= q; }");
  EXPECT_EQ(bad.count(DiagId::err_bad_binary), 1) << bad.text();
  EXPECT_EQ(bad.count(DiagId::err_cannot_assign), 1) << bad.text();
  EXPECT_NE(bad.text().find("invalid operands to binary '/=' ('V2' and 'V2')"), std::string::npos)
      << bad.text();
  EXPECT_NE(bad.text().find("cannot assign 'float' to 'V2'"), std::string::npos) << bad.text();
}

TEST(Sema, FunctionRules) {
  Checked c("float f(float x) { if (x > 0) x = 1; }\n" // missing return + readonly write
            "float g(float x) { return g(x); }\n"      // recursion
            "float h(float x) { return k(x); }\n"      // undeclared function
            "void w() { return 1; }\n"
            "float r() { return; }\n"
            "shader s() { break; float y = undefined_var; int z = \"s\"; }");
  EXPECT_EQ(c.count(DiagId::err_missing_return), 1) << c.text();
  EXPECT_EQ(c.count(DiagId::warn_write_nonoutput_param), 1) << c.text();
  EXPECT_EQ(c.count(DiagId::err_recursion), 1) << c.text();
  EXPECT_EQ(c.count(DiagId::err_unknown_function), 1) << c.text();
  EXPECT_EQ(c.count(DiagId::err_return_value_in_void), 1) << c.text();
  EXPECT_EQ(c.count(DiagId::err_return_without_value), 1) << c.text();
  EXPECT_EQ(c.count(DiagId::err_break_outside_loop), 1) << c.text();
  EXPECT_EQ(c.count(DiagId::err_undeclared), 1) << c.text();
  EXPECT_EQ(c.count(DiagId::err_cannot_assign), 1) << c.text();
}

TEST(Sema, MutualRecursionAndNestedFunctions) {
  Checked c(
      "float b(float x);\nfloat a(float x) { return b(x); }\nfloat b(float x) { return a(x); }\n"
      "shader s() { float sq(float v) { return v * v; } float t = sq(2); }");
  EXPECT_EQ(c.count(DiagId::err_recursion), 2) << c.text();
  EXPECT_EQ(c.diags.error_count(), 2) << c.text();
}

TEST(Sema, RedefinitionHasNote) {
  Checked c("shader s() { float a = 1;\n int a = 2; }");
  EXPECT_EQ(c.count(DiagId::err_redefinition), 1);
  std::string t = c.text();
  EXPECT_NE(t.find("t.osl:2:6: error: redefinition of 'a'"), std::string::npos) << t;
  EXPECT_NE(t.find("t.osl:1:20: note: previous definition is here"), std::string::npos) << t;
}

TEST(Sema, ScopesLoopsAndConditions) {
  Checked c("shader s() { for (int i = 0; i < 3; ++i) { float i2 = i; } int j = i;"
            " float a[2]; if (a) {} closure color cc = 0; int k = cc ? 1 : 2; }");
  EXPECT_EQ(c.count(DiagId::err_undeclared), 1) << c.text();
  // An array is no condition, nor a closure for ?: (oslc: "Cannot use a closure as a
  // condition"); strings, triples, matrices and closures are (OSL's truth rules, below).
  EXPECT_EQ(c.count(DiagId::err_bad_condition), 2) << c.text();
  Checked ok("shader s() { string s = \"x\"; matrix m = 1; closure color cc = 0;"
             " if (s) {} while (P) {} for (; m; ) {} do {} while (N); if (cc) {} if (!cc) {}"
             " int k = (N && s) || !m; float f = P ? 1 : 0; }");
  EXPECT_TRUE(ok.ok()) << ok.text();
}

TEST(Sema, ShaderParamsDefaultsAndMetadata) {
  Checked c("surface s(normal Nn = N, vector T = normalize(dPdu), float k = 1 [[ float min = 0 ]],"
            " float arr[] = {1, 2}, color tint = k) { Ci = k * diffuse(Nn); }");
  ASSERT_TRUE(c.ok()) << c.text();
  // An unsized parameter stays unsized (an instance value may have another length); its
  // default keeps its own length.
  EXPECT_TRUE(c.shader()->params[3]->type.is_unsized_array());
  EXPECT_EQ(c.shader()->params[3]->init->type.arraylen, 2);
  Checked local("shader s() { float a[] = {1, 2, 3}; int n = arraylength(a); }");
  ASSERT_TRUE(local.ok()) << local.text();
  EXPECT_NE(local.body().find("(var float[3] a"), std::string::npos) << local.body();
  Checked bad("surface s(float k = 1 [[ float min = u ]]) {}");
  EXPECT_EQ(bad.count(DiagId::err_metadata_not_const), 1) << bad.text();
  Checked folded("surface s(float k = 1 [[ float third = 1.0 / 3.0, int n = -(1 + 2) ]]) {}");
  EXPECT_TRUE(folded.ok()) << folded.text();
}

TEST(Sema, BuiltinTableCoversTheStandardLibrary) {
  const char* names[] = {"sin",
                         "cos",
                         "tan",
                         "asin",
                         "acos",
                         "atan",
                         "atan2",
                         "sinh",
                         "cosh",
                         "tanh",
                         "pow",
                         "exp",
                         "exp2",
                         "expm1",
                         "log",
                         "log2",
                         "log10",
                         "logb",
                         "sqrt",
                         "inversesqrt",
                         "cbrt",
                         "abs",
                         "fabs",
                         "sign",
                         "floor",
                         "ceil",
                         "round",
                         "trunc",
                         "fmod",
                         "mod",
                         "min",
                         "max",
                         "select",
                         "isnan",
                         "isinf",
                         "isfinite",
                         "erf",
                         "erfc",
                         "radians",
                         "degrees",
                         "step",
                         "smoothstep",
                         "dot",
                         "cross",
                         "length",
                         "distance",
                         "normalize",
                         "transform",
                         "transformu",
                         "getmatrix",
                         "determinant",
                         "transpose",
                         "luminance",
                         "blackbody",
                         "wavelength_color",
                         "transformc",
                         "noise",
                         "snoise",
                         "pnoise",
                         "psnoise",
                         "cellnoise",
                         "hashnoise",
                         "hash",
                         "printf",
                         "format",
                         "error",
                         "warning",
                         "concat",
                         "strlen",
                         "startswith",
                         "endswith",
                         "stoi",
                         "stof",
                         "substr",
                         "getchar",
                         "regex_search",
                         "regex_match",
                         "arraylength",
                         "exit",
                         "isconnected",
                         "isconstant",
                         "Dx",
                         "Dy",
                         "Dz",
                         "filterwidth",
                         "area",
                         "calculatenormal",
                         "backfacing",
                         "surfacearea",
                         "raytype"};
  for (const char* n : names) EXPECT_FALSE(sema::builtins().lookup(n).empty()) << n;
  // 1-4 D noise with float, color and vector results, as OSL's.
  EXPECT_EQ(sema::builtins().lookup("cellnoise").size(), 12u);
}

TEST(Sema, SplinesAndRendererServices) {
  Checked c(
      "shader s() { float knots[6] = {0, 0, 1, 2, 3, 3}; color ck[4] = {0, 1, 2, 3};"
      " float a = spline(\"catmull-rom\", u, 0, 0, 1, 2, 3, 3);"
      " color b = spline(\"linear\", u, color(0), color(0), color(1), color(1));"
      " float k = spline(\"bspline\", u, knots) + spline(\"bspline\", u, 5, knots);"
      " color d = spline(\"constant\", u, ck); float e = splineinverse(\"linear\", 0.5, knots);"
      " float val; int ok = getattribute(\"object:name\", val) + getattribute(\"obj\", \"n\", val);"
      " string names[2]; ok += getattribute(\"names\", names); setmessage(\"m\", val);"
      " ok += getmessage(\"trace\", \"hitdist\", val) + gettextureinfo(\"t.exr\", \"exists\", ok);"
      " ok += trace(P, N, \"maxdist\", 10.0); fprintf(\"log.txt\", \"%d\\n\", ok);"
      " color env = environment(\"sky.exr\", I, \"blur\", 0.1); float t3 = texture3d(\"v.vdb\", "
      "P); }");
  EXPECT_TRUE(c.ok()) << c.text();
  Checked bad("shader s() { float v; getattribute(\"a\", 1.0); int i = spline(\"linear\", u, 1, 2, "
              "3, 4); }");
  EXPECT_EQ(bad.count(DiagId::err_output_arg_not_lvalue), 1) << bad.text();
  // spline() of floats is a float: assigned to an int it truncates with oslc's warning.
  EXPECT_EQ(bad.count(DiagId::warn_lose_precision), 1) << bad.text();
}

TEST(Sema, StringAndMiscBuiltins) {
  Checked c("shader s() { string f = format(\"%d %s\", 1, \"x\"); printf(\"%g\\n\", P);"
            " int n = strlen(f) + startswith(f, \"a\") + hash(f) + regex_match(f, \"a.*\");"
            " float arr[4]; int len = arraylength(arr); int con = isconnected(n);"
            " color t = texture(\"a.exr\", u, v, \"wrap\", \"periodic\"); float w = filterwidth(u);"
            " float k = clamp(u, 0, 1); color m = mix(color(0), color(1), 0.5); float l = "
            "linearstep(0, 1, u);"
            " float aa = aastep(0.5, u); vector rr = reflect(I, N); float Kr, Kt; fresnel(I, N, "
            "1.5, Kr, Kt);"
            " float pi = M_PI; }");
  EXPECT_TRUE(c.ok()) << c.text();
}

TEST(Sema, RegexWithResultsArray) {
  Checked c("shader s() { int r[4]; int a = regex_search(\"foo1\", r, \"[0-9]\");"
            " int b = regex_match(\"foo1\", r, \"f(o+)1\"); }");
  ASSERT_TRUE(c.ok()) << c.text();
  EXPECT_NE(c.body().find("(call regex_search:int \"foo1\":string r:int[4] \"[0-9]\":string)"),
            std::string::npos)
      << c.body();
  // The results array is written: it must be an int array variable.
  Checked bad("shader s() { float f[2]; int a = regex_search(\"x\", f, \"x\");"
              " int b = regex_match(\"x\", {1, 2}, \"x\"); }");
  EXPECT_EQ(bad.count(DiagId::err_no_matching_call) + bad.count(DiagId::err_output_arg_not_lvalue),
            2)
      << bad.text();
}

// ---- oslc 1.13's overload rules (docs/language.md, "Calls and overload resolution"). The
// cases are the experiments run on oslc 1.13.12; the choices and messages are oslc's.

namespace {

// One overload of f per return type, each returning a value of it (oslc experiment gQ).
const char* const kEveryReturnType =
    "float f() { return 1; }\nint f() { return 1; }\ncolor f() { return 1; }\n"
    "point f() { return 1; }\nvector f() { return 1; }\nnormal f() { return 1; }\n"
    "matrix f() { return 1; }\nstring f() { return \"s\"; }\n";

// The return types of the overloads of `name` the calls in the shader body chose, in order.
std::string chosen(const Checked& c, const std::string& name) {
  std::string b = c.body(), out, key = "(call " + name + ":";
  for (size_t at = b.find(key); at != std::string::npos; at = b.find(key, at + 1)) {
    size_t end = b.find_first_of(" )", at + key.size());
    out += (out.empty() ? "" : " ") + b.substr(at + key.size(), end - at - key.size());
  }
  return out;
}

} // namespace

// The ambiguity is a warning, in Lobe's style: the call, then the chosen candidate and the
// others as notes at their declarations (OSL's pragma-nowarn test shader, without its pragma).
TEST(Sema, AmbiguityWarningNamesTheChosenCandidate) {
  Checked c("normal func () { return 1; }\nvector func () { return 2; }\n"
            "shader test () { point p = func(); }");
  EXPECT_TRUE(c.ok()) << c.text();
  EXPECT_EQ(c.text(), "t.osl:3:28: warning: call to 'func()' is ambiguous\n"
                      "shader test () { point p = func(); }\n"
                      "                           ^~~~\n"
                      "t.osl:2:8: note: chosen: vector func()\n"
                      "vector func () { return 2; }\n"
                      "       ^~~~\n"
                      "t.osl:1:8: note: other candidate: normal func()\n"
                      "normal func () { return 1; }\n"
                      "       ^~~~\n");
  // Builtins have no location: their notes carry none.
  Checked b("shader s() { noise(P); }");
  EXPECT_NE(b.text().find("note: chosen: float noise(point)\nnote: other candidate: color "
                          "noise(point)\nnote: other candidate: vector noise(point)\n"),
            std::string::npos)
      << b.text();
}

// `#pragma osl nowarn` silences the warnings of the next line only (as oslc: that line of that
// file), not errors.
TEST(Sema, PragmaOslNowarn) {
  Checked c("normal func () { return 1; }\nvector func () { return 2; }\nshader test () {\n"
            "    #pragma osl nowarn\n    point p = func();\n    point q = func();\n"
            "    #pragma osl nowarn\n\n    point r = func();\n"
            "    #pragma osl nowarn\n    point s = func(1);\n}");
  EXPECT_EQ(c.count(DiagId::warn_ambiguous_call), 2) << c.text();
  EXPECT_EQ(c.count(DiagId::err_no_matching_call), 1) << c.text();
  std::string t = c.text();
  EXPECT_NE(t.find("t.osl:6:15: warning"), std::string::npos) << t;
  EXPECT_NE(t.find("t.osl:9:15: warning"), std::string::npos) << t;
  EXPECT_EQ(c.diags.warning_count(), 2);
}

// Ties between struct-returning candidates are an error, listing the tied ones by rank (gM:st7);
// one struct among other types takes its rank, and an expected struct type decides (gM:st5).
TEST(Sema, StructReturnTies) {
  Checked c("struct S { float x; };\nstruct T { float x; };\nS f() { S s; return s; }\n"
            "T f() { T t; return t; }\nfloat f() { return 1; }\nshader s() { f(); S s = f(); }");
  EXPECT_EQ(c.count(DiagId::err_ambiguous_call), 1) << c.text();
  std::string t = c.text();
  size_t fl = t.find("note: candidate: float f()"), tt = t.find("note: candidate: T f()"),
         ss = t.find("note: candidate: S f()");
  EXPECT_TRUE(fl < tt && tt < ss) << t;
  Checked one("struct S { float x; };\nS f() { S s; return s; }\nvoid f() { }\n"
              "shader s() { f(); }");
  EXPECT_TRUE(one.ok()) << one.text();
  EXPECT_EQ(one.count(DiagId::warn_ambiguous_call), 1) << one.text();
  EXPECT_NE(one.text().find("note: chosen: S f()"), std::string::npos) << one.text();
}

// No candidate: every overload in sight is listed, newest first, builtins after user functions.
TEST(Sema, NoMatchListsNewestFirst) {
  Checked c("float sqrt(string s) { return 0; }\nshader s() { sqrt(matrix(1)); }");
  std::string t = c.text();
  size_t user = t.find("t.osl:1:7: note: candidate: float sqrt(string)");
  size_t builtin = t.find("note: candidate: float sqrt(float)");
  EXPECT_TRUE(user != std::string::npos && builtin != std::string::npos && user < builtin) << t;
}

// Overloads declared after a call are not candidates (gW:sc1, sc3).
TEST(Sema, LaterOverloadsAreNotSeen) {
  Checked c("float h(point x) { return 1; }\nvoid g() { h(N); }\nfloat h(vector x) { return 2; }\n"
            "shader s() { g(); }");
  EXPECT_TRUE(c.ok()) << c.text();
  EXPECT_EQ(c.count(DiagId::warn_ambiguous_call), 0) << c.text();
  Checked later("shader s() { h(1); }\nfloat h(float x) { return 1; }");
  EXPECT_EQ(later.count(DiagId::err_unknown_function), 1) << later.text();
}

// The shader body is one overload scope with the file (gW:sc4, sc8, sc9); a function body or a
// block hides the outer overloads of a name it declares, builtins included (found on oslc
// 1.13.12: `void g() { float h(normal x) {...} h(P); }` takes h(normal) over a global h(point)).
TEST(Sema, ScopesOfFunctionDeclarations) {
  Checked merged("float h(point x) { return 1; }\n"
                 "shader s() { float h(vector v) { return 2; } h(N); h(P); }");
  EXPECT_TRUE(merged.ok()) << merged.text();
  EXPECT_EQ(merged.count(DiagId::warn_ambiguous_call), 1) << merged.text(); // h(N): a tie
  EXPECT_NE(merged.text().find("t.osl:2:20: note: chosen: float h(vector)"), std::string::npos)
      << merged.text();
  Checked redef("float h(float x) { return 1; }\nshader s() { float h(float x) { return 2; } }");
  EXPECT_EQ(redef.count(DiagId::warn_function_redefined), 1) << redef.text();
  Checked builtin("shader s() { float noise(float x) { return 1; } float a = noise(P); }");
  EXPECT_TRUE(builtin.ok()) << builtin.text();
  EXPECT_EQ(builtin.count(DiagId::warn_function_redefined), 1) << builtin.text();
  EXPECT_NE(builtin.text().find("note: previous definition is built-in: float noise(float)"),
            std::string::npos)
      << builtin.text();

  Checked hidden(
      "float h(point x) { return 1; }\n"
      "void g() { float h(normal x) { return 2; } h(P); }\n"
      "void k() { { float h(normal x) { return 3; } } h(P); }\nshader s() { g(); k(); }");
  EXPECT_TRUE(hidden.ok()) << hidden.text();
  EXPECT_EQ(hidden.count(DiagId::warn_ambiguous_call), 0) << hidden.text();
  Checked no_builtin("void g() { float noise(float x) { return 1; } float a = noise(P); }\n"
                     "shader s() { { float h(float x) { return 1; } } }");
  EXPECT_EQ(no_builtin.count(DiagId::err_no_matching_call), 1) << no_builtin.text();
  // Same signature in a function body: no warning, the inner one is used.
  Checked inner(
      "float h(point x) { return 1; }\nvoid g() { float h(point x) { return 2; } h(P); }\n"
      "shader s() { g(); }");
  EXPECT_TRUE(inner.ok()) << inner.text();
  EXPECT_EQ(inner.diags.warning_count(), 0) << inner.text();
}

// User functions never hide builtins: a redefined builtin signature is replaced alone (bB:u3),
// and a user function ties with builtins like any overload (bB:u11, u17, u18).
TEST(Sema, UserFunctionsMergeWithBuiltins) {
  Checked c("float noise(point x) { return 0.25; }\nfloat length(point x) { return 1; }\n"
            "float texture(string n, float s, float t) { return 0.5; }\n"
            "shader s() { color a = noise(P); float b = noise(P); float l = length(N);"
            " float t = texture(\"x.tx\", u, v); }");
  ASSERT_TRUE(c.ok()) << c.text();
  std::string b = c.body();
  EXPECT_NE(b.find("(var color a (call noise:color P:point))"), std::string::npos) << b;
  EXPECT_EQ(c.count(DiagId::warn_ambiguous_call), 2) << c.text(); // length and texture
  EXPECT_NE(c.text().find("t.osl:2:7: note: chosen: float length(point)"), std::string::npos)
      << c.text();
  EXPECT_NE(c.text().find("t.osl:3:7: note: chosen: float texture(string, float, float)"),
            std::string::npos)
      << c.text();
}

// Where a call finds an expected type, and where not (gQ: the one of eight `T f()` chosen).
TEST(Sema, ExpectedTypeContexts) {
  struct Probe {
    const char* stmts;
    const char* chosen;
  };
  const Probe probes[] = {
      {"float(f());", "float"},
      {"int(f());", "float"},     // int(x) expects nothing
      {"matrix(f());", "float"},  // nor matrix(x)
      {"normal(f());", "normal"}, // a triple's T(x) expects T
      {"color(f(), 0, 0);", "float"},
      {"point(\"world\", 0, f(), 0);", "float"},
      {"(int) f();", "int"},
      {"(string) f();", "string"},
      {"int x = f();", "int"},
      {"matrix x; x = f();", "matrix"},
      {"color x; x += f();", "color"},
      {"int x = 0; x |= f();", "int"},
      {"f();", "float"},
      {"if (f()) {}", "float"},
      {"float x = f() ? 1 : 2;", "int"},
      {"float x = !f();", "float"},
      {"color x = -f();", "color"},
      {"int b = f() == 1;", "int"},
      {"int x = 1 << f();", "int"},
      {"color x = 1 ? f() : color(1);", "color"},
      {"color x = sin(f());", "color"}, // arguments take the call's expected type
      {"float x = length(f());", "float"},
      {"float a[2] = {f(), 1};", "float"},
      {"string s = format(\"%s\", f());", "string"},
  };
  for (const Probe& p : probes) {
    Checked c(std::string(kEveryReturnType) + "shader s() { " + p.stmts + " }");
    EXPECT_TRUE(c.ok()) << p.stmts << "\n" << c.text();
    EXPECT_EQ(chosen(c, "f"), p.chosen) << p.stmts;
  }
  // return, a struct's fields, a struct constructor's arguments (gQ:prR1, prR3).
  Checked r(std::string(kEveryReturnType) +
            "struct SS { color c; float x; };\ncolor g() { return f(); }\n"
            "shader s() { color c = g(); SS a = {f(), f()}; SS b = SS(f(), f()); }");
  EXPECT_TRUE(r.ok()) << r.text();
  EXPECT_EQ(chosen(r, "f"), "color float color float");
  // The argument expects the call's type, not the parameter's (gR:prR6, gP:nest_2).
  Checked arg(std::string(kEveryReturnType) +
              "float g(color c) { return 1; }\nshader s() { float x = g(f()); }");
  EXPECT_TRUE(arg.ok()) << arg.text();
  EXPECT_EQ(chosen(arg, "f"), "float");
  Checked nest(std::string(kEveryReturnType) +
               "color g(float a, float b) { return 1; }\nshader s() { color x = g(f(), 1); }");
  EXPECT_EQ(nest.count(DiagId::err_no_matching_call), 1) << nest.text();
  EXPECT_NE(nest.text().find("'g(color, int)'"), std::string::npos) << nest.text();
}

// Builtins resolve by the same rules (oslc 1.13.12's choices, read from its .oso: bA, bC, bD).
// The first shader checked as one line with `oslc -q bi.osl`: its .oso runs noise (vector
// result), transformv from stdosl.h:262 for t and k, mix, min of two ints, texture into the
// vector x, the float and the int clamp (stdosl.h:141, 142); the only warning is "Ambiguous
// call to 'transform (string, int)'" (chosen vector, others point :263, normal :261).
TEST(Sema, BuiltinsByOslcRules) {
  Checked c("shader s() { point a = noise(P) + 0; vector t = transform(\"world\", 1);"
            " color k = transform(\"world\", 1); point m = mix(P, N, 0.5);"
            " float n = min(1, 2); vector x = texture(\"a.tx\", u, v); float y = clamp(u, 0, 1);"
            " int z = clamp(1, 0, 1); }");
  ASSERT_TRUE(c.ok()) << c.text();
  EXPECT_EQ(chosen(c, "noise"), "vector"); // 32 for point: vector noise (OSL has no point one)
  EXPECT_EQ(chosen(c, "transform"), "vector vector");
  EXPECT_EQ(chosen(c, "min"), "int"); // the arguments first
  EXPECT_EQ(chosen(c, "texture"), "vector");
  EXPECT_EQ(chosen(c, "clamp"), "float int");
  EXPECT_EQ(c.count(DiagId::warn_ambiguous_call), 1) << c.text(); // color k = transform(...)
  Checked mix("shader s() { mix(P, N, 0.5); }");
  EXPECT_NE(mix.text().find("note: chosen: point mix(point, point, float)"), std::string::npos)
      << mix.text();
}

// Every header built into the compiler (OSL's shader folder: color2.h ... oslutil.h) is found
// without -I and compiles without a diagnostic.
TEST(Sema, BuiltinHeadersCompileCleanly) {
  int n = 0;
  for (const stdlib::Header& h : stdlib::headers()) {
    Checked c("#include \"" + std::string(h.name) + "\"\nshader s() {}");
    EXPECT_TRUE(c.diags.diagnostics().empty()) << h.name << "\n" << c.text();
    ++n;
  }
  EXPECT_EQ(n, 7);
  Checked use("#include <color4.h>\n#include \"vector2.h\"\n#include \"matrix33.h\"\n"
              "shader s(color4 p = color4({0.5, 1.5, 2.5}, 3.5)) {"
              " color4 q = 2 / p + mix(p, p, 0.5); vector2 w = normalize(vector2(3, 4)) * 2;"
              " matrix33 m = matrix44To33(matrix(2)); point x = transform(m / 2, P); }");
  EXPECT_TRUE(use.ok()) << use.text();
}

// A shader's own definition of a function the built-in headers define replaces it with a
// warning, as in OSL; two definitions in the shader's file are still an error.
TEST(Sema, RedefiningALibraryFunctionWarns) {
  Checked c("#include \"color2.h\"\n"
            "float hypot(float a, float b) { return a + b; }\n"
            "color2 abs(color2 a) { return a; }\n"
            "int iscameraray() { return 42; }\n"
            "shader s() { float h = hypot(1, 2); color2 a = abs(color2(-1, 1));"
            " int r = iscameraray(); }");
  EXPECT_TRUE(c.ok()) << c.text();
  EXPECT_EQ(c.count(DiagId::warn_function_redefined), 3) << c.text();
  EXPECT_NE(c.body().find("hypot"), std::string::npos);
}

// {x}, {x, y, z} and {"space", x, y, z} for a triple, and the matrix forms, are the type's
// constructor (OSL): in declarations, parameter defaults, arguments, struct fields, returns.
TEST(Sema, InitListsForTriplesAndMatrices) {
  Checked c("struct S { color c; float f; };\n"
            "color twice(color x) { return 2 * x; }\n"
            "point origin() { return {0, 0, 0}; }\n"
            "shader s(vector d = {1, 2, 3}, matrix M = {\"shader\", 1}) {"
            " color a = {1, 2, 3}; color g = {0.5}; point p = {\"common\", 4, 5, 6};"
            " matrix m = {1}; matrix n = {1,0,0,0, 0,1,0,0, 0,0,1,0, 0,0,0,1};"
            " S st = {{1, 2, 3}, 4}; color t = twice({3, 2, 1}); color arr[2] = {{1}, {2, 3, 4}};"
            " a = {u, v, 1}; }");
  EXPECT_TRUE(c.ok()) << c.text();
  EXPECT_NE(c.body().find("(var color a (construct color:color (icast float:float 1:int)"),
            std::string::npos)
      << c.body();
  Checked bad("shader s() { color a = {1, 2}; vector b = {\"x\"}; }");
  EXPECT_EQ(bad.count(DiagId::err_bad_constructor), 2) << bad.text();
}

// The standard library beyond the core set: split, dictionaries, point clouds, int fabs,
// vector-returning textures and the explicit-derivative and UDIM forms.
TEST(Sema, MoreStandardLibraryForms) {
  Checked c(
      "shader s() { string r[3]; int n = split(\"a b\", r) + split(\"a,b\", r, \",\")"
      " + split(\"a,b\", r, \",\", 2); int d = dict_find(\"<a/>\", \"//a\");"
      " int e = dict_find(d, \"b\") + dict_next(d); color cv; matrix mv; string sv;"
      " int f = dict_value(d, \"x\", cv) + dict_value(d, \"y\", mv) + dict_value(d, \"\", sv);"
      " int idx[2]; float dist[2]; point pos[2];"
      " int g = pointcloud_search(\"p.ptc\", P, 1, 2, \"index\", idx, \"distance\", dist)"
      " + pointcloud_search(\"p.ptc\", P, 1, 2, 1, \"position\", pos)"
      " + pointcloud_get(\"p.ptc\", idx, 2, \"position\", pos)"
      " + pointcloud_write(\"p.ptc\", P, \"u\", u); int h = fabs(-3);"
      " vector tv = texture(\"t.tx\", u, v); vector ev = environment(\"e.tx\", I, I, I);"
      " color t3 = texture3d(\"t.tx\", P, I, I, I, \"blur\", 0.1); int res[2];"
      " int k = gettextureinfo(\"t.<UDIM>.tx\", u, v, \"resolution\", res);"
      " matrix W; int w = getmatrix(\"world\", W); color ior, ext;"
      " artistic_ior(color(0.9), color(0.5), ior, ext); int q = iscameraray(); }");
  EXPECT_TRUE(c.ok()) << c.text();
  // Point-cloud results are written: they must be variables.
  Checked bad("shader s() { int n = pointcloud_search(\"p.ptc\", P, 1, 2, \"index\", 3); }");
  EXPECT_EQ(bad.count(DiagId::err_output_arg_not_lvalue), 1) << bad.text();
}
