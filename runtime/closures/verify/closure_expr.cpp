// Tokenizer and argument parser for closure call expressions; which closure the call binds to
// is the registry's match (registry/closure_call.h), the one the type checker uses.
#include "closure_expr.h"

#include "closure_call.h"
#include "closure_registry.h"

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

// The two overloads that stdosl.h defines in the language by forwarding to a registry closure:
// microfacet(dist, N, alpha, eta, refr) is microfacet(dist, N, vector(0), alpha, alpha, eta,
// refr) and reflection(N) is reflection(N, 0).
void expand_stdosl_forms(const std::string& name, std::vector<Arg>& args) {
  if (name == "microfacet" && args.size() >= 5 && args[2].kind == Arg::Number) {
    Arg u = args[2];
    u.kind = Arg::Triple;
    u.triple = {0, 0, 0};
    Arg alpha = args[2];
    args.insert(args.begin() + 2, u);
    args.insert(args.begin() + 4, alpha);
  } else if (name == "reflection" && args.size() == 1) {
    Arg eta = args[0];
    eta.kind = Arg::Number;
    eta.number = 0;
    args.push_back(eta);
  }
}

} // namespace

ExprResult parse_closure_expr(std::string_view text) {
  Parser parser(text);
  std::string name;
  size_t name_pos = 0, close_pos = 0;
  std::vector<Arg> args;
  if (auto e = parser.parse_call(name, name_pos, args, close_pos)) return {std::nullopt, *e};
  expand_stdosl_forms(name, args);
  registry::ClosureMatch m = match(name, args);
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
