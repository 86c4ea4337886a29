// Tokenizer, argument parser and overload resolution for closure call expressions.
#include "closure_expr.h"

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

// Stores one argument into the block; an error if its type does not fit the parameter.
std::optional<ExprError> bind(const registry::ClosureParam& p, const Arg& a, ParsedClosure& pc) {
  auto mismatch = [&] {
    return ExprError{a.pos, std::string("'") + p.name + "' expects " + type_name(p.type)};
  };
  switch (p.type) {
  case ArgType::Int:
    if (a.kind != Arg::Number || a.number != static_cast<int>(a.number)) return mismatch();
    pc.params.set(p.name, static_cast<int>(a.number));
    return std::nullopt;
  case ArgType::Float:
    if (a.kind != Arg::Number) return mismatch();
    pc.params.set(p.name, static_cast<float>(a.number));
    return std::nullopt;
  case ArgType::Color:
  case ArgType::Vector:
    if (a.kind == Arg::Number && p.type == ArgType::Color) {
      float v = static_cast<float>(a.number);
      pc.params.set(p.name, Vec3{v, v, v});
      return std::nullopt;
    }
    if (a.kind != Arg::Triple) return mismatch();
    pc.params.set(p.name, a.triple);
    return std::nullopt;
  case ArgType::String:
    if (a.kind != Arg::String) return mismatch();
    // The library reads a distribution by its first letter: anything but these is a mistake.
    if (std::string_view(p.name) == "distribution" && a.text != "ggx" && a.text != "beckmann")
      return ExprError{a.pos, "unknown distribution \"" + a.text + "\" (\"ggx\" or \"beckmann\")"};
    pc.strings->push_back(a.text);
    pc.params.set(p.name, pc.strings->back().c_str());
    return std::nullopt;
  case ArgType::Closure:
    return ExprError{a.pos, "closure arguments are not supported here"};
  }
  return mismatch();
}

// Binds all arguments against one registry entry.
std::optional<ExprError> bind_entry(const registry::ClosureEntry& e, const std::vector<Arg>& args,
                                    size_t close_pos, ParsedClosure& pc) {
  std::vector<const registry::ClosureParam*> positional;
  for (const auto& p : e.params)
    if (!p.keyword) positional.push_back(&p);
  if (args.size() < positional.size())
    return ExprError{close_pos, std::string(e.name) + " expects " +
                                    std::to_string(positional.size()) + " arguments, got " +
                                    std::to_string(args.size())};
  for (size_t k = 0; k < positional.size(); ++k)
    if (auto err = bind(*positional[k], args[k], pc)) return err;
  for (size_t k = positional.size(); k < args.size(); k += 2) {
    const Arg& name = args[k];
    if (name.kind != Arg::String)
      return ExprError{name.pos, "too many arguments (keywords are \"name\", value pairs)"};
    const registry::ClosureParam* kw = nullptr;
    for (const auto& p : e.params)
      if (p.keyword && name.text == p.name) kw = &p;
    if (!kw) return ExprError{name.pos, "unknown keyword \"" + name.text + "\" for " + e.name};
    if (k + 1 >= args.size()) return ExprError{close_pos, "keyword without a value"};
    if (auto err = bind(*kw, args[k + 1], pc)) return err;
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
  std::optional<ExprError> first_error;
  for (const registry::ClosureEntry& e : registry::closures()) {
    if (name != e.name) continue;
    ParsedClosure pc{e.key, closures::Params(e.key), 1.0,
                     std::make_shared<std::deque<std::string>>()};
    std::optional<ExprError> err = bind_entry(e, args, close_pos, pc);
    if (!err) {
      if (e.flags & registry::kTransmit)
        for (const auto& p : e.params)
          if (p.type == ArgType::Float &&
              (std::string_view(p.name) == "ior" || std::string_view(p.name) == "eta")) {
            float v;
            std::memcpy(
                &v, pc.params.data() + registry::param_offset(e.params, &p - e.params.data()), 4);
            pc.eta_below = v;
          }
      return {std::move(pc), {}};
    }
    if (!first_error || err->pos > first_error->pos) first_error = err;
  }
  if (!first_error) return {std::nullopt, {name_pos, "unknown closure '" + name + "'"}};
  return {std::nullopt, *first_error};
}

} // namespace lobe::verify
