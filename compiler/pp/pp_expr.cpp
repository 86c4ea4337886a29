// #if expression evaluator: precedence climbing over the C operators.
#include "pp/pp_expr.h"

#include <cstdlib>

namespace lobe::pp {
namespace {

// Binary operators by precedence (higher binds tighter); 0: not a binary operator.
int precedence(const PPToken& t) {
  if (t.kind != PPKind::Punct) return 0;
  static const struct {
    const char* op;
    int prec;
  } kOps[] = {{"||", 1}, {"&&", 2}, {"|", 3}, {"^", 4},  {"&", 5},  {"==", 6},
              {"!=", 6}, {"<", 7},  {">", 7}, {"<=", 7}, {">=", 7}, {"<<", 8},
              {">>", 8}, {"+", 9},  {"-", 9}, {"*", 10}, {"/", 10}, {"%", 10}};
  for (auto& o : kOps)
    if (t.text == o.op) return o.prec;
  return 0;
}

class Evaluator {
public:
  explicit Evaluator(const std::vector<PPToken>& t) : toks_(t) {}

  PPExprResult run() {
    PPExprResult r;
    long long v = ternary();
    if (ok_ && pos_ < toks_.size()) fail("unexpected '" + toks_[pos_].text + "'");
    if (ok_) r.value = v;
    r.error = error_;
    r.where = where_;
    return r;
  }

private:
  const PPToken* peek() const { return pos_ < toks_.size() ? &toks_[pos_] : nullptr; }
  bool accept(const char* p) {
    if (peek() && peek()->is_punct(p)) {
      ++pos_;
      return true;
    }
    return false;
  }
  void fail(const std::string& msg) {
    if (!ok_) return;
    ok_ = false;
    error_ = msg;
    where_ = peek() ? peek()->loc : (toks_.empty() ? diag::SourceLoc{} : toks_.back().loc);
  }

  long long ternary() {
    long long c = binary(1);
    if (!accept("?")) return c;
    // `1 ? 1 : 1 ? 1 : ...` nests here without passing unary()'s depth check on the way down.
    if (++depth_ > 200) {
      fail("expression nested too deeply");
      return 0;
    }
    long long a = ternary();
    if (!accept(":")) {
      fail("expected ':' in conditional expression");
      return 0;
    }
    long long b = ternary();
    --depth_;
    return c ? a : b;
  }

  long long binary(int min_prec) {
    long long lhs = unary();
    while (ok_ && peek() && precedence(*peek()) >= min_prec) {
      std::string op = peek()->text;
      int prec = precedence(*peek());
      ++pos_;
      long long rhs = binary(prec + 1);
      lhs = apply(op, lhs, rhs);
    }
    return lhs;
  }

  long long apply(const std::string& op, long long a, long long b) {
    if ((op == "/" || op == "%") && b == 0) {
      fail("division by zero");
      return 0;
    }
    if (op == "||") return a || b;
    if (op == "&&") return a && b;
    if (op == "|") return a | b;
    if (op == "^") return a ^ b;
    if (op == "&") return a & b;
    if (op == "==") return a == b;
    if (op == "!=") return a != b;
    if (op == "<") return a < b;
    if (op == ">") return a > b;
    if (op == "<=") return a <= b;
    if (op == ">=") return a >= b;
    if (op == "<<") return (b < 0 || b > 63) ? 0 : (long long)((unsigned long long)a << b);
    if (op == ">>") return (b < 0 || b > 63) ? 0 : a >> b;
    if (op == "+") return (long long)((unsigned long long)a + (unsigned long long)b);
    if (op == "-") return (long long)((unsigned long long)a - (unsigned long long)b);
    if (op == "*") return (long long)((unsigned long long)a * (unsigned long long)b);
    if (op == "/") return (a == (-9223372036854775807LL - 1) && b == -1) ? a : a / b;
    return (b == -1) ? 0 : a % b;
  }

  long long unary() {
    if (++depth_ > 200) {
      fail("expression nested too deeply");
      return 0;
    }
    long long v = unary_inner();
    --depth_;
    return v;
  }

  long long unary_inner() {
    const PPToken* t = peek();
    if (!t) {
      fail("missing operand");
      return 0;
    }
    if (accept("!")) return !unary();
    if (accept("~")) return ~unary();
    if (accept("-")) return (long long)(0ull - (unsigned long long)unary());
    if (accept("+")) return unary();
    if (accept("(")) {
      long long v = ternary();
      if (!accept(")")) fail("expected ')'");
      return v;
    }
    ++pos_;
    if (t->kind == PPKind::Ident) return 0; // an undefined identifier is 0
    if (t->kind == PPKind::Number) return number(*t);
    fail("unexpected '" + t->text + "'");
    return 0;
  }

  long long number(const PPToken& t) {
    std::string s = t.text;
    while (!s.empty() && (s.back() == 'u' || s.back() == 'U' || s.back() == 'l' || s.back() == 'L'))
      s.pop_back();
    char* end = nullptr;
    unsigned long long v = std::strtoull(s.c_str(), &end, 0);
    if (s.empty() || *end != '\0') {
      fail("invalid integer '" + t.text + "'");
      return 0;
    }
    return (long long)v;
  }

  const std::vector<PPToken>& toks_;
  size_t pos_ = 0;
  int depth_ = 0;
  bool ok_ = true;
  std::string error_;
  diag::SourceLoc where_;
};

} // namespace

PPExprResult evaluate_pp_expr(const std::vector<PPToken>& toks) {
  if (toks.empty()) {
    PPExprResult r;
    r.error = "#if with no expression";
    return r;
  }
  return Evaluator(toks).run();
}

} // namespace lobe::pp
