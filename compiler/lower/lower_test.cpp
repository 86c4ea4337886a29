// Lowering tests on hand-built, already type-checked ASTs (what sema produces), checked
// against expected IR text written by hand: inlining with output arguments and return,
// struct flattening, control flow, closures with keywords, parameter init ops, useparam.
#include "lower/lower.h"

#include "closure_registry.h"
#include "ir/printer.h"

#include <gtest/gtest.h>

using namespace lobe;
using namespace lobe::ast;

namespace {

// Builds AST nodes with their sema-filled types.
struct Builder {
  TranslationUnit tu;
  ShaderDecl* shader = nullptr;

  Builder() {
    auto s = std::make_unique<ShaderDecl>();
    s->name = "test";
    s->body = std::make_unique<CompoundStmt>();
    shader = s.get();
    tu.decls.push_back(std::move(s));
  }
  VarDecl* global(const char* name, BaseType b) {
    auto v = std::make_unique<VarDecl>();
    v->name = name;
    v->type = Type(b);
    v->storage = Storage::Global;
    tu.globals.push_back(std::move(v));
    return tu.globals.back().get();
  }
  VarDecl* param(const char* name, Type t, ExprPtr init, bool output = false) {
    auto v = std::make_unique<VarDecl>();
    v->name = name;
    v->type = t;
    v->storage = Storage::ShaderParam;
    v->is_output = output;
    v->init = std::move(init);
    shader->params.push_back(std::move(v));
    return shader->params.back().get();
  }
  static ExprPtr flit(float f) {
    auto e = std::make_unique<FloatLit>();
    e->value = f;
    e->type = Type(BaseType::Float);
    return e;
  }
  static ExprPtr slit(const char* s) {
    auto e = std::make_unique<StringLit>();
    e->value = s;
    e->type = Type(BaseType::String);
    return e;
  }
  static ExprPtr ident(VarDecl* d) {
    auto e = std::make_unique<IdentExpr>();
    e->name = d->name;
    e->decl = d;
    e->type = d->type;
    e->lvalue = true;
    return e;
  }
  static ExprPtr bin(BinaryOp op, ExprPtr a, ExprPtr b, Type t) {
    auto e = std::make_unique<BinaryExpr>();
    e->op = op;
    e->lhs = std::move(a);
    e->rhs = std::move(b);
    e->type = t;
    return e;
  }
  static ExprPtr assign(ExprPtr l, ExprPtr r) {
    auto e = std::make_unique<AssignExpr>();
    e->type = l->type;
    e->lhs = std::move(l);
    e->rhs = std::move(r);
    return e;
  }
  static ExprPtr member(ExprPtr base, const char* name, int field, Type t) {
    auto e = std::make_unique<MemberExpr>();
    e->base = std::move(base);
    e->name = name;
    e->field = field;
    e->type = t;
    return e;
  }
  static StmtPtr expr_stmt(ExprPtr e) {
    auto s = std::make_unique<ExprStmt>();
    s->expr = std::move(e);
    return s;
  }
  static StmtPtr decl(VarDecl* owned_elsewhere) = delete;
  // Declares a local in `body`; the VarDecl is owned by the DeclStmt.
  static VarDecl* local(CompoundStmt* body, const char* name, Type t, ExprPtr init = nullptr) {
    auto v = std::make_unique<VarDecl>();
    v->name = name;
    v->type = t;
    v->init = std::move(init);
    VarDecl* raw = v.get();
    auto s = std::make_unique<DeclStmt>();
    s->decls.push_back(std::move(v));
    body->stmts.push_back(std::move(s));
    return raw;
  }
  void add(StmtPtr s) { shader->body->stmts.push_back(std::move(s)); }
  std::string lower_text() {
    diag::DiagnosticEngine diags;
    lower::LowerResult r = lower::lower(tu, diags);
    for (const diag::Diagnostic& d : diags.diagnostics()) ADD_FAILURE() << d.message;
    return r.shader ? ir::print(*r.shader) : "";
  }
};

const Type kFloat(BaseType::Float);
const Type kColor(BaseType::Color);
const Type kClosure(BaseType::Closure);

TEST(Lower, ClosureWithKeywordScaledByParam) {
  Builder b;
  VarDecl* N = b.global("N", BaseType::Normal);
  VarDecl* Ci = b.global("Ci", BaseType::Closure);
  VarDecl* kd = b.param("Kd", kFloat, Builder::flit(0.5f));
  // Ci = Kd * diffuse(N, "label", "base");
  auto call = std::make_unique<CallExpr>();
  call->name = "diffuse";
  call->type = kClosure;
  call->args.push_back(Builder::ident(N));
  call->args.push_back(Builder::slit("label"));
  call->args.push_back(Builder::slit("base"));
  call->num_positional = 1;
  call->keywords.push_back(KeywordArg{"label", -1, call->args[2].get()});
  call->callee.kind = CalleeKind::Closure;
  call->callee.closure = registry::find_by_key("diffuse");
  ASSERT_NE(call->callee.closure, nullptr);
  b.add(Builder::expr_stmt(
      Builder::assign(Builder::ident(Ci),
                      Builder::bin(BinaryOp::Mul, Builder::ident(kd), std::move(call), kClosure))));
  EXPECT_EQ(b.lower_text(), R"(lobe-ir 1
surface test
symbols
  param float Kd = 0.5
  global closure Ci
  temp closure $t0
  const string $c0 = "diffuse"
  global normal N
  const string $c1 = "label"
  const string $c2 = "base"
main
  closure $t0 $c0 N $c1 $c2
  useparam Kd
  mul Ci Kd $t0
end
)");
}

// float twice(float x, output float y) { y = x * 2; return x + 1; }
// shader: float a; float r = twice(u, a);
// The body's ops carry %infn (ir::Op::in_function): OSL counts them as conditional. The result
// is returned into r from inside the body, as oslc returns it.
TEST(Lower, InliningAliasesOutputArgsAndJumpsToEndOnReturn) {
  Builder b;
  VarDecl* u = b.global("u", BaseType::Float);
  auto f = std::make_unique<FunctionDecl>();
  f->name = "twice";
  f->return_type = kFloat;
  for (auto [name, out] : {std::pair{"x", false}, std::pair{"y", true}}) {
    auto p = std::make_unique<VarDecl>();
    p->name = name;
    p->type = kFloat;
    p->storage = Storage::FuncParam;
    p->is_output = out;
    f->params.push_back(std::move(p));
  }
  VarDecl* x = f->params[0].get();
  VarDecl* y = f->params[1].get();
  f->body = std::make_unique<CompoundStmt>();
  f->body->stmts.push_back(Builder::expr_stmt(
      Builder::assign(Builder::ident(y),
                      Builder::bin(BinaryOp::Mul, Builder::ident(x), Builder::flit(2), kFloat))));
  auto ret = std::make_unique<ReturnStmt>();
  ret->value = Builder::bin(BinaryOp::Add, Builder::ident(x), Builder::flit(1), kFloat);
  f->body->stmts.push_back(std::move(ret));
  FunctionDecl* fn = f.get();
  b.tu.decls.insert(b.tu.decls.begin(), std::move(f));

  VarDecl* a = Builder::local(b.shader->body.get(), "a", kFloat);
  auto call = std::make_unique<CallExpr>();
  call->name = "twice";
  call->type = kFloat;
  call->args.push_back(Builder::ident(u));
  call->args.push_back(Builder::ident(a));
  call->callee.kind = CalleeKind::User;
  call->callee.function = fn;
  Builder::local(b.shader->body.get(), "r", kFloat, std::move(call));
  EXPECT_EQ(b.lower_text(), R"(lobe-ir 1
surface test
symbols
  local float a
  local float r
  global float u
  const float $c0 = 2
  const float $c1 = 1
main
  mul a u $c0 %infn
  add r u $c1 %infn
  br -> L3 %infn
L3:
end
)");
}

// struct S { float a; color c; };  S s; s.c = s.a; with a struct param S p = {1, 2}.
TEST(Lower, StructsFlattenIntoFieldSymbols) {
  Builder b;
  auto sd = std::make_unique<StructDecl>();
  sd->name = "S";
  for (auto [name, t] : {std::pair{"a", kFloat}, std::pair{"c", kColor}}) {
    auto fld = std::make_unique<VarDecl>();
    fld->name = name;
    fld->type = t;
    fld->storage = Storage::Field;
    sd->fields.push_back(std::move(fld));
  }
  Type st(BaseType::Struct, 0, sd.get());
  auto init = std::make_unique<InitListExpr>();
  init->type = st;
  init->elems.push_back(Builder::flit(1));
  auto cast = std::make_unique<CastExpr>();
  cast->target = kColor;
  cast->type = kColor;
  cast->implicit = true;
  cast->operand = Builder::flit(2);
  init->elems.push_back(std::move(cast));
  b.param("p", st, std::move(init));
  VarDecl* s = Builder::local(b.shader->body.get(), "s", st);
  auto cast2 = std::make_unique<CastExpr>();
  cast2->target = kColor;
  cast2->type = kColor;
  cast2->implicit = true;
  cast2->operand = Builder::member(Builder::ident(s), "a", 0, kFloat);
  b.add(Builder::expr_stmt(
      Builder::assign(Builder::member(Builder::ident(s), "c", 1, kColor), std::move(cast2))));
  b.tu.decls.insert(b.tu.decls.begin(), std::move(sd));
  EXPECT_EQ(b.lower_text(), R"(lobe-ir 1
surface test
struct S { float a, color c }
symbols
  param float p.a = 1 struct=S
  param color p.c = 2 2 2 struct=S
  local float s.a struct=S
  local color s.c struct=S
main
  assign s.c s.a
end
)");
}

// normal Nn = N (computed default -> init ops); if (Kd > 0.5) Cout = Kd; else Cout = 0;
TEST(Lower, ParamInitOpsAndIfElse) {
  Builder b;
  VarDecl* N = b.global("N", BaseType::Normal);
  b.param("Nn", Type(BaseType::Normal), Builder::ident(N));
  VarDecl* kd = b.param("Kd", kFloat, Builder::flit(0.25f));
  VarDecl* out = b.param("Cout", kFloat, Builder::flit(0), true);
  auto ifs = std::make_unique<IfStmt>();
  ifs->cond =
      Builder::bin(BinaryOp::Gt, Builder::ident(kd), Builder::flit(0.5f), Type(BaseType::Int));
  ifs->then_stmt = Builder::expr_stmt(Builder::assign(Builder::ident(out), Builder::ident(kd)));
  ifs->else_stmt = Builder::expr_stmt(Builder::assign(Builder::ident(out), Builder::flit(0)));
  b.add(std::move(ifs));
  EXPECT_EQ(b.lower_text(), R"(lobe-ir 1
surface test
symbols
  param normal Nn init=0:1
  global normal N
  param float Kd = 0.25
  oparam float Cout = 0
  const float $c0 = 0.5
  temp int $t0
  const float $c1 = 0
init
  assign Nn N
main
  useparam Kd
  gt $t0 Kd $c0
  cbr $t0 -> L4 L7
L4:
  useparam Kd
  assign Cout Kd
  br -> L8
L7:
  assign Cout $c1
L8:
end
)");
}

} // namespace
