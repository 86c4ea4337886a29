// Tokenizer and argument parser for closure call expressions; which closure the call binds to
// is the registry's match (registry/closure_call.h), the one the type checker uses.
#include "closure_expr.h"

#include "closure_call.h"
#include "closure_registry.h"
#include "driver/driver.h"

#include <cctype>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <string_view>
#include <vector>

namespace lobe::verify {
namespace {

using registry::ArgType;

struct Arg {
  enum Kind { Number, Triple, String } kind;
  size_t pos;
  double number = 0;
  Vec3 triple;
  bool is_color = false; // color(...) rather than vector/normal/point/N/U/T
  std::string text;
};

class Parser {
public:
  explicit Parser(std::string_view s) : s_(s) {}

  std::optional<ExprError> parse_call(std::string& name, size_t& name_pos, std::vector<Arg>& args,
                                      size_t& close_pos) {
    skip();
    name_pos = i_;
    name = ident();
    if (name.empty()) return ExprError{i_, "expected a closure name"};
    if (!eat('(')) return ExprError{i_, "expected '(' after '" + name + "'"};
    skip();
    if (!eat(')')) {
      for (;;) {
        Arg a;
        if (auto e = parse_arg(a)) return e;
        args.push_back(a);
        if (eat(',')) continue;
        if (peek() == ')') break;
        return ExprError{i_, "expected ',' or ')'"};
      }
      close_pos = i_;
      eat(')');
    } else {
      close_pos = i_ - 1;
    }
    skip();
    if (i_ < s_.size()) return ExprError{i_, "unexpected text after the closure call"};
    return std::nullopt;
  }

private:
  void skip() {
    while (i_ < s_.size() && std::isspace(static_cast<unsigned char>(s_[i_]))) ++i_;
  }
  char peek() {
    skip();
    return i_ < s_.size() ? s_[i_] : '\0';
  }
  bool eat(char c) {
    if (peek() != c) return false;
    ++i_;
    return true;
  }
  std::string ident() {
    skip();
    size_t b = i_;
    while (i_ < s_.size() && (std::isalnum(static_cast<unsigned char>(s_[i_])) || s_[i_] == '_'))
      ++i_;
    if (b < s_.size() && std::isdigit(static_cast<unsigned char>(s_[b]))) {
      i_ = b;
      return {};
    }
    return std::string(s_.substr(b, i_ - b));
  }
  std::optional<ExprError> number(double& out) {
    skip();
    std::string tail(s_.substr(i_));
    char* end = nullptr;
    out = std::strtod(tail.c_str(), &end);
    if (end == tail.c_str()) return ExprError{i_, "expected a number"};
    // NaN, infinities and numbers a float cannot hold would reach the closure as NaN or Inf.
    if (!std::isfinite(out) || std::fabs(out) > 3.4028234663852886e38)
      return ExprError{i_, "not a finite number (a float)"};
    i_ += static_cast<size_t>(end - tail.c_str());
    return std::nullopt;
  }
  // color(x) / color(x, y, z) and friends, after the constructor name.
  std::optional<ExprError> triple(Arg& a) {
    if (!eat('(')) return ExprError{i_, "expected '('"};
    double v[3];
    if (auto e = number(v[0])) return e;
    if (eat(',')) {
      if (auto e = number(v[1])) return e;
      if (!eat(',')) return ExprError{i_, "expected ',' (a triple takes 1 or 3 numbers)"};
      if (auto e = number(v[2])) return e;
    } else {
      v[1] = v[2] = v[0];
    }
    if (!eat(')')) return ExprError{i_, "expected ')'"};
    a.triple = {float(v[0]), float(v[1]), float(v[2])};
    return std::nullopt;
  }
  std::optional<ExprError> parse_arg(Arg& a) {
    skip();
    a.pos = i_;
    char c = peek();
    if (c == '"') {
      size_t end = s_.find('"', i_ + 1);
      if (end == std::string_view::npos) return ExprError{i_, "unterminated string"};
      a.kind = Arg::String;
      a.text = std::string(s_.substr(i_ + 1, end - i_ - 1));
      i_ = end + 1;
      return std::nullopt;
    }
    if (std::isalpha(static_cast<unsigned char>(c)) || c == '_') {
      std::string id = ident();
      a.kind = Arg::Triple;
      if (id == "N")
        a.triple = {0, 0, 1};
      else if (id == "U" || id == "T")
        a.triple = {1, 0, 0};
      else if (id == "color" || id == "vector" || id == "normal" || id == "point") {
        a.is_color = id == "color";
        return triple(a);
      } else
        return ExprError{a.pos, "unknown name '" + id + "' (use N, U, T, color(), vector())"};
      return std::nullopt;
    }
    a.kind = Arg::Number;
    return number(a.number);
  }

  std::string_view s_;
  size_t i_ = 0;
};

std::string type_name(ArgType t) {
  switch (t) {
  case ArgType::Int:
    return "an int";
  case ArgType::Float:
    return "a float";
  case ArgType::Color:
    return "a color";
  case ArgType::Vector:
    return "a vector";
  case ArgType::String:
    return "a string";
  case ArgType::Closure:
    return "a closure";
  }
  return "?";
}

// Whether a literal of `a`'s kind can set a parameter of type `t` (a number sets an int only
// when it is whole; a number sets a color as a grey). Closure parameters are accepted here and
// refused by bind() with their own message.
bool fits(ArgType t, const Arg& a) {
  switch (t) {
  case ArgType::Int:
    return a.kind == Arg::Number && a.number == static_cast<int>(a.number);
  case ArgType::Float:
    return a.kind == Arg::Number;
  case ArgType::Color:
    return a.kind == Arg::Number || a.kind == Arg::Triple;
  case ArgType::Vector:
    return a.kind == Arg::Triple;
  case ArgType::String:
    return a.kind == Arg::String;
  case ArgType::Closure:
    return true;
  }
  return false;
}

// Stores one argument into the block; an error if its type does not fit the parameter.
std::optional<ExprError> bind(const registry::ClosureParam& p, const Arg& a, ParsedClosure& pc) {
  if (!fits(p.type, a))
    return ExprError{a.pos, std::string("'") + p.name + "' expects " + type_name(p.type)};
  switch (p.type) {
  case ArgType::Int:
    pc.params.set(p.name, static_cast<int>(a.number));
    break;
  case ArgType::Float:
    pc.params.set(p.name, static_cast<float>(a.number));
    break;
  case ArgType::Color:
  case ArgType::Vector:
    if (a.kind == Arg::Number) {
      float v = static_cast<float>(a.number);
      pc.params.set(p.name, Vec3{v, v, v});
    } else {
      pc.params.set(p.name, a.triple);
    }
    break;
  case ArgType::String:
    // The library reads a distribution by its first letter: anything but these is a mistake.
    if (std::string_view(p.name) == "distribution" && a.text != "ggx" && a.text != "beckmann")
      return ExprError{a.pos, "unknown distribution \"" + a.text + "\" (\"ggx\" or \"beckmann\")"};
    pc.strings->push_back(a.text);
    pc.params.set(p.name, pc.strings->back().c_str());
    break;
  case ArgType::Closure:
    return ExprError{a.pos, "closure arguments are not supported here"};
  }
  return std::nullopt;
}

// The registry's match of the call (registry/closure_call.h), asked about literal arguments.
registry::ClosureMatch match(const std::string& name, const std::vector<Arg>& args) {
  registry::CallArgs ca;
  ca.count = args.size();
  ca.cost = [&](size_t i, ArgType t) { return fits(t, args[i]) ? 0 : registry::kNoFit; };
  ca.is_string = [&](size_t i) { return args[i].kind == Arg::String; };
  ca.literal = [&](size_t i) -> std::optional<std::string_view> {
    if (args[i].kind != Arg::String) return std::nullopt;
    return args[i].text;
  };
  return registry::match_closure_call(registry::closures(), name, ca);
}

// The located error for a call no entry fits.
ExprError no_fit(const registry::ClosureMatch& m, const std::string& name,
                 const std::vector<Arg>& args, size_t name_pos, size_t close_pos) {
  const registry::ClosureEntry* e = m.problem_entry;
  using P = registry::CallProblem;
  switch (m.problem) {
  case P::TooFewArguments:
    return {close_pos, std::string(e->name) + " expects " +
                           std::to_string(registry::positional_count(*e)) + " arguments, got " +
                           std::to_string(args.size())};
  case P::ArgumentType: {
    const Arg& a = args[m.problem_arg];
    const registry::ClosureParam& p = e->params[m.problem_arg];
    return {a.pos, std::string("'") + p.name + "' expects " + type_name(p.type)};
  }
  case P::KeywordName:
    return {args[m.problem_arg].pos, "too many arguments (keywords are \"name\", value pairs)"};
  case P::KeywordWithoutValue:
    return {close_pos, "keyword without a value"};
  case P::UnknownClosure:
  case P::None:
    break;
  }
  return {name_pos, "unknown closure '" + name + "'"};
}

// Stores the matched call's arguments into a block for its entry.
std::optional<ExprError> bind_match(const registry::ClosureMatch& m, const std::vector<Arg>& args,
                                    ParsedClosure& pc) {
  const registry::ClosureEntry& e = *m.entry;
  for (size_t k = 0; k < m.positional; ++k)
    if (auto err = bind(e.params[k], args[k], pc)) return err;
  for (const registry::KeywordArg& kw : m.keywords) {
    const Arg& name = args[kw.name_arg];
    if (kw.param < 0)
      return ExprError{name.pos, "unknown keyword \"" + name.text + "\" for " + e.name};
    if (auto err = bind(e.params[size_t(kw.param)], args[kw.name_arg + 1], pc)) return err;
  }
  return std::nullopt;
}

// The closure functions stdosl.h defines in the language by forwarding to a registry closure,
// `closure color f(params) { return g(args); }` with each of g's arguments one of f's
// parameters or a constant (microfacet(dist, N, alpha, eta, refr) is microfacet(dist, N,
// vector(0), alpha, alpha, eta, refr); reflection(N) is reflection(N, 0)). Read once from the
// front end's typed AST of the standard header, so stdosl.h stays the one place they are said.
struct Forward {
  const ast::FunctionDecl* function;
  std::string target;
  struct Slot {
    int param = -1; // f's parameter passed on, or -1: `constant`
    Arg constant{Arg::Number, 0};
  };
  std::vector<Slot> slots;
};

// A constant argument of the forwarding call (after the type checker's conversions), or false.
bool constant_arg(const ast::Expr* e, Arg& out) {
  // The kind the argument has as passed (vector(0) is a cast of the int 0 to a vector).
  out.kind = e->type.is_string() ? Arg::String : e->type.is_triple() ? Arg::Triple : Arg::Number;
  while (e->kind == ast::ExprKind::Cast) e = static_cast<const ast::CastExpr*>(e)->operand.get();
  double v;
  if (e->kind == ast::ExprKind::FloatLit)
    v = static_cast<const ast::FloatLit*>(e)->value;
  else if (e->kind == ast::ExprKind::IntLit)
    v = static_cast<const ast::IntLit*>(e)->value;
  else if (e->kind == ast::ExprKind::StringLit) {
    out.kind = Arg::String;
    out.text = static_cast<const ast::StringLit*>(e)->value;
    return true;
  } else
    return false;
  out.number = v;
  out.triple = {float(v), float(v), float(v)};
  return true;
}

std::vector<Forward> read_forwards(const ast::TranslationUnit& tu) {
  std::vector<Forward> out;
  for (const ast::DeclPtr& d : tu.decls) {
    if (d->kind != ast::DeclKind::Function || !d->from_stdlib) continue;
    const auto* f = static_cast<const ast::FunctionDecl*>(d.get());
    if (!f->return_type.is_closure() || !f->body || f->body->stmts.size() != 1 ||
        f->body->stmts[0]->kind != ast::StmtKind::Return)
      continue;
    const ast::Expr* v = static_cast<const ast::ReturnStmt*>(f->body->stmts[0].get())->value.get();
    if (!v || v->kind != ast::ExprKind::Call) continue;
    const auto* call = static_cast<const ast::CallExpr*>(v);
    if (call->callee.kind != ast::CalleeKind::Closure || !call->keywords.empty()) continue;
    Forward fw{f, call->name, {}};
    bool plain = true;
    for (const ast::ExprPtr& a : call->args) {
      const ast::Expr* e = a.get();
      while (e->kind == ast::ExprKind::Cast && static_cast<const ast::CastExpr*>(e)->implicit)
        e = static_cast<const ast::CastExpr*>(e)->operand.get();
      Forward::Slot slot;
      if (e->kind == ast::ExprKind::Ident) {
        for (size_t k = 0; k < f->params.size(); ++k)
          if (static_cast<const ast::IdentExpr*>(e)->decl == f->params[k].get())
            slot.param = int(k);
        plain &= slot.param >= 0;
      } else {
        plain &= constant_arg(a.get(), slot.constant);
      }
      fw.slots.push_back(slot);
    }
    if (plain) out.push_back(std::move(fw));
  }
  return out;
}

const std::vector<Forward>& stdosl_forwards() {
  static const std::vector<Forward> forwards = [] {
    static driver::Loaded loaded = driver::compile_source(
        "<lobe brdf: stdosl.h>", "shader lobe_brdf_forms() {}\n", driver::Options{});
    return loaded.tu ? read_forwards(*loaded.tu) : std::vector<Forward>{};
  }();
  return forwards;
}

// The call rewritten through a forwarding function of stdosl.h whose parameters the arguments
// fit (strings for strings, triples for triples, numbers for numbers), or false. Arguments
// past the function's parameters (keyword pairs) follow the forwarded ones.
bool forward_stdosl(std::string& name, std::vector<Arg>& args, size_t name_pos) {
  for (const Forward& fw : stdosl_forwards()) {
    const auto& params = fw.function->params;
    if (fw.function->name != name || args.size() < params.size()) continue;
    bool fits = true;
    for (size_t k = 0; k < params.size() && fits; ++k) {
      const ast::Type& t = params[k]->type;
      Arg::Kind want = t.is_string() ? Arg::String : t.is_triple() ? Arg::Triple : Arg::Number;
      fits = args[k].kind == want && (t.is_string() || t.is_triple() || t.is_float() || t.is_int());
    }
    if (!fits) continue;
    std::vector<Arg> out;
    for (const Forward::Slot& s : fw.slots) {
      if (s.param >= 0) {
        out.push_back(args[size_t(s.param)]);
      } else {
        out.push_back(s.constant);
        out.back().pos = name_pos;
      }
    }
    out.insert(out.end(), args.begin() + std::ptrdiff_t(params.size()), args.end());
    name = fw.target;
    args = std::move(out);
    return true;
  }
  return false;
}

} // namespace

ExprResult parse_closure_expr(std::string_view text) {
  Parser parser(text);
  std::string name;
  size_t name_pos = 0, close_pos = 0;
  std::vector<Arg> args;
  if (auto e = parser.parse_call(name, name_pos, args, close_pos)) return {std::nullopt, *e};
  registry::ClosureMatch m = match(name, args);
  if (!m.entry) { // maybe a form stdosl.h forwards to a registry closure
    std::string fwd_name = name;
    std::vector<Arg> fwd_args = args;
    if (forward_stdosl(fwd_name, fwd_args, name_pos)) {
      registry::ClosureMatch fm = match(fwd_name, fwd_args);
      if (fm.entry) name = std::move(fwd_name), args = std::move(fwd_args), m = fm;
    }
  }
  if (!m.entry) return {std::nullopt, no_fit(m, name, args, name_pos, close_pos)};
  const registry::ClosureEntry& e = *m.entry;
  ParsedClosure pc{e.key, closures::Params(e.key), 1.0,
                   std::make_shared<std::deque<std::string>>()};
  if (auto err = bind_match(m, args, pc)) return {std::nullopt, *err};
  if (e.flags & registry::kTransmit)
    for (const auto& p : e.params)
      if (p.type == ArgType::Float &&
          (std::string_view(p.name) == "ior" || std::string_view(p.name) == "eta")) {
        float v;
        std::memcpy(&v, pc.params.data() + registry::param_offset(e.params, &p - e.params.data()),
                    4);
        pc.eta_below = v;
      }
  return {std::move(pc), {}};
}

} // namespace lobe::verify
