// Implements verify(): symbol checks, then per-op structural checks (table arity, written
// operands, jumps), then the type rules of docs/ir.md for the core opcode classes. Library
// functions are checked only structurally: their overloads are codegen's to resolve.
#include "ir/verifier.h"
#include "ir/opcodes.h"
#include "ir/printer.h"

#include <unordered_set>

namespace lobe::ir {
namespace {

class Verifier {
public:
  explicit Verifier(const Shader& sh) : sh_(sh) {}
  std::vector<std::string> run();

private:
  void symbols();
  void structs();
  void op(int index);
  void jumps(int index, const OpcodeInfo& info);
  void types(const Op& op);
  void error(std::string msg) { errors_.push_back(prefix_ + msg); }
  const Type& ty(const Op& op, int i) const { return sh_.symbols[op.args[i]].type; }
  void expect(bool ok, const std::string& msg) {
    if (!ok) error(msg);
  }

  const Shader& sh_;
  std::string prefix_;
  std::vector<std::string> errors_;
};

bool scalar(const Type& t, BaseType b) { return !t.is_array() && t.base == b; }
bool numeric(const Type& t) { return scalar(t, BaseType::Int) || scalar(t, BaseType::Float); }
bool float_based(const Type& t) { return !t.is_array() && (numeric(t) || t.is_triple()); }

// Whether a value of type `src` converts to `dst` under docs/ir.md's implicit arithmetic rules.
bool promotes(const Type& src, const Type& dst) {
  if (src.is_array() || dst.is_array()) return false;
  if (src == dst) return true;
  if (dst.base == BaseType::Float) return src.base == BaseType::Int;
  if (dst.is_triple()) return numeric(src) || src.is_triple();
  if (dst.base == BaseType::Matrix) return numeric(src);
  return false;
}

bool assignable(const Type& src, const Type& dst) {
  if (promotes(src, dst)) return true;
  if (src.is_array() || dst.is_array()) return false;
  if (dst.base == BaseType::Int) return src.base == BaseType::Float;   // (int) cast
  if (dst.base == BaseType::Closure) return src.base == BaseType::Int; // the null closure
  return false;
}

void Verifier::symbols() {
  std::unordered_set<std::string> names;
  for (size_t i = 0; i < sh_.symbols.size(); ++i) {
    const Symbol& s = sh_.symbols[i];
    prefix_ = "symbol '" + s.name + "': ";
    if (s.name.empty()) error("empty name");
    if (!names.insert(s.name).second) error("duplicate name");
    size_t n = size_t(s.type.components()) * size_t(s.type.arraylen > 0 ? s.type.arraylen : 1);
    if (s.kind == SymKind::Const && s.init.size() != n && s.type.arraylen >= 0)
      error("constant has " + std::to_string(s.init.size()) + " values, type " + to_string(s.type) +
            " needs " + std::to_string(n));
    bool is_param = s.kind == SymKind::Param || s.kind == SymKind::OutputParam;
    if (is_param && !s.init.empty() && s.type.arraylen >= 0 && s.init.size() != n)
      error("default has " + std::to_string(s.init.size()) + " values, needs " + std::to_string(n));
    if (s.folded && (!is_param || s.init.empty()))
      error("'folded' only on parameters with a constant default");
    if (s.default_len != 0 && (!is_param || s.type.arraylen >= 0 || s.default_len < 0))
      error("len=" + std::to_string(s.default_len) + " only on unsized array parameters");
    if (s.init_begin >= 0 || s.init_end >= 0) {
      if (!is_param) error("init ops on a symbol that is not a parameter");
      if (s.init_begin < 0 || s.init_begin > s.init_end || s.init_end > sh_.main_begin)
        error("init range " + std::to_string(s.init_begin) + ":" + std::to_string(s.init_end) +
              " outside the init region 0:" + std::to_string(sh_.main_begin));
    }
  }
}

void Verifier::jumps(int index, const OpcodeInfo& info) {
  const Op& o = sh_.ops[index];
  size_t want = 0;
  if (o.opcode == Opcode::Br) want = 1;
  if (o.opcode == Opcode::Cbr) want = 2;
  if (o.jumps.size() != want)
    error("has " + std::to_string(o.jumps.size()) + " jump targets, needs " + std::to_string(want));
  bool in_init = index < sh_.main_begin;
  int lo = in_init ? 0 : sh_.main_begin;
  int hi = in_init ? sh_.main_begin : int(sh_.ops.size());
  for (int j : o.jumps)
    if (j < lo || j > hi)
      error("jump target " + std::to_string(j) + " outside its region " + std::to_string(lo) +
            ".." + std::to_string(hi));
}

void Verifier::op(int index) {
  const Op& o = sh_.ops[index];
  if (size_t(o.opcode) >= kOpcodeCount) {
    prefix_ = "op " + std::to_string(index) + ": ";
    return error("unknown opcode");
  }
  prefix_ = "op " + std::to_string(index) + " (" + to_string(o.opcode);
  std::string l = format_loc(o.loc);
  prefix_ += (l.empty() ? "" : " " + l) + "): ";
  const OpcodeInfo* info = &ir::info(o.opcode);
  int n = int(o.args.size());
  if (n < info->min_args || (info->max_args != kVariadic && n > info->max_args))
    return error("has " + std::to_string(n) + " operands, needs " + std::to_string(info->min_args) +
                 (info->max_args == info->min_args ? std::string()
                  : info->max_args == kVariadic    ? "+"
                                                   : ".." + std::to_string(info->max_args)));
  for (int i = 0; i < n; ++i) {
    int a = o.args[i];
    if (a < 0 || a >= int(sh_.symbols.size()))
      return error("operand " + std::to_string(i) + " is not a symbol");
    if (o.writes(i) && sh_.symbols[a].kind == SymKind::Const)
      error("writes the constant '" + sh_.symbols[a].name + "'");
  }
  if (n < 32 && (o.written_mask >> n) != 0) error("written mask names missing operands");
  jumps(index, *info);
  types(o);
}

// The type rules of docs/ir.md for the core opcodes.
void Verifier::types(const Op& o) {
  const Opcode c = o.opcode;
  auto t = [&](int i) -> const Type& { return ty(o, i); };
  auto name = [&](int i) {
    return "'" + sh_.symbols[o.args[i]].name + "' (" + to_string(t(i)) + ")";
  };
  auto is_const_string = [&](int i) {
    const Symbol& s = sh_.symbols[o.args[i]];
    return s.kind == SymKind::Const && scalar(s.type, BaseType::String);
  };
  if (c == Opcode::Assign) {
    expect(assignable(t(1), t(0)), "cannot assign " + name(1) + " to " + name(0));
  } else if (c == Opcode::Add || c == Opcode::Sub || c == Opcode::Mul || c == Opcode::Div ||
             c == Opcode::Mod || c == Opcode::Neg) {
    int n = int(o.args.size());
    if (scalar(t(0), BaseType::Closure)) {
      int closures = 0;
      for (int i = 1; i < n; ++i) {
        bool cl = scalar(t(i), BaseType::Closure);
        closures += cl;
        if (!cl)
          expect(numeric(t(i)) || scalar(t(i), BaseType::Color),
                 "closure weight " + name(i) + " must be float or color");
      }
      if (c == Opcode::Add)
        expect(closures == 2, "closure add needs two closures");
      else if (c == Opcode::Mul)
        expect(closures == 1, "closure mul needs one closure and one weight");
      else if (c == Opcode::Neg)
        expect(closures == 1, "closure neg needs a closure");
      else
        error("closures support only add, mul, neg");
      return;
    }
    for (int i = 1; i < n; ++i)
      expect(promotes(t(i), t(0)), "operand " + name(i) + " does not convert to " + name(0));
  } else if (c == Opcode::Eq || c == Opcode::Neq || c == Opcode::Lt || c == Opcode::Le ||
             c == Opcode::Gt || c == Opcode::Ge) {
    expect(scalar(t(0), BaseType::Int), "result " + name(0) + " must be int");
    bool ordered = c != Opcode::Eq && c != Opcode::Neq;
    for (int i = 1; i < 3; ++i) {
      if (ordered)
        expect(numeric(t(i)), "ordered comparison of " + name(i));
      else
        expect(!t(i).is_array() && t(i).base != BaseType::Closure, "cannot compare " + name(i));
    }
    expect(promotes(t(1), t(2)) || promotes(t(2), t(1)),
           "incomparable " + name(1) + " and " + name(2));
  } else if (c == Opcode::Not) {
    expect(scalar(t(0), BaseType::Int), "result must be int");
    expect(numeric(t(1)) || scalar(t(1), BaseType::Closure), "operand " + name(1));
  } else if (c == Opcode::Compl || c == Opcode::BitAnd || c == Opcode::BitOr || c == Opcode::Xor ||
             c == Opcode::Shl || c == Opcode::Shr) {
    for (size_t i = 0; i < o.args.size(); ++i)
      expect(scalar(t(int(i)), BaseType::Int), "operand " + name(int(i)) + " must be int");
  } else if (c == Opcode::CompRef) {
    expect(scalar(t(0), BaseType::Float) && t(1).is_triple() && !t(1).is_array() &&
               scalar(t(2), BaseType::Int),
           "needs float = triple[int]");
  } else if (c == Opcode::CompAssign) {
    expect(t(0).is_triple() && !t(0).is_array() && scalar(t(1), BaseType::Int) && numeric(t(2)),
           "needs triple[int] = float");
  } else if (c == Opcode::MxCompRef) {
    expect(scalar(t(0), BaseType::Float) && scalar(t(1), BaseType::Matrix) &&
               scalar(t(2), BaseType::Int) && scalar(t(3), BaseType::Int),
           "needs float = matrix[int][int]");
  } else if (c == Opcode::MxCompAssign) {
    expect(scalar(t(0), BaseType::Matrix) && scalar(t(1), BaseType::Int) &&
               scalar(t(2), BaseType::Int) && numeric(t(3)),
           "needs matrix[int][int] = float");
  } else if (c == Opcode::ARef || c == Opcode::AAssign) {
    int arr = c == Opcode::ARef ? 1 : 0, elem = c == Opcode::ARef ? 0 : 2,
        idx = c == Opcode::ARef ? 2 : 1;
    expect(t(arr).is_array(), name(arr) + " is not an array");
    expect(scalar(t(idx), BaseType::Int), "index " + name(idx) + " must be int");
    Type e = t(arr);
    e.arraylen = 0;
    expect(c == Opcode::ARef ? t(elem) == e : promotes(t(elem), e),
           "element " + name(elem) + " does not match " + name(arr));
  } else if (c == Opcode::ArrayCopy) {
    auto triple = [](BaseType b) {
      return b == BaseType::Color || b == BaseType::Point || b == BaseType::Vector ||
             b == BaseType::Normal;
    };
    expect(t(0).is_array() && t(1).is_array() &&
               (t(0).base == t(1).base || (triple(t(0).base) && triple(t(1).base))),
           "needs two arrays of one element type (or of two triple kinds)");
  } else if (c == Opcode::ArrayLength) {
    expect(scalar(t(0), BaseType::Int) && t(1).is_array(), "needs int = arraylength(array)");
  } else if (c == Opcode::Construct) {
    expect(t(0).is_triple() || scalar(t(0), BaseType::Matrix),
           "constructs only triples and matrices");
  } else if (c == Opcode::Closure) {
    expect(scalar(t(0), BaseType::Closure), "result must be a closure");
    expect(is_const_string(1), "second operand must be the registry key (a string constant)");
  } else if (c == Opcode::DeclaredClosure) {
    expect(scalar(t(0), BaseType::Closure), "result must be a closure");
    expect(is_const_string(1), "second operand must be the closure's name (a string constant)");
    expect(o.args.size() >= 3 && scalar(t(2), BaseType::Int) &&
               sh_.symbols[o.args[2]].kind == SymKind::Const,
           "third operand must be the number of positional arguments (an int constant)");
  } else if (c == Opcode::Cbr) {
    expect(numeric(t(0)), "condition " + name(0) + " must be int or float");
  } else if (c == Opcode::UseParam) {
    for (size_t i = 0; i < o.args.size(); ++i) {
      SymKind k = sh_.symbols[o.args[i]].kind;
      expect(k == SymKind::Param || k == SymKind::OutputParam,
             name(int(i)) + " is not a parameter");
    }
  } else if (c == Opcode::Dx || c == Opcode::Dy || c == Opcode::Dz || c == Opcode::FilterWidth) {
    expect(float_based(t(0)) && float_based(t(1)), "needs float or triple operands");
  } else if (c == Opcode::Printf || c == Opcode::Format || c == Opcode::Error ||
             c == Opcode::Warning) {
    int f = c == Opcode::Format ? 1 : 0;
    expect(scalar(t(f), BaseType::String), "format " + name(f) + " must be a string");
  }
}

// The struct table: unique names, each struct-typed field naming a struct listed before it.
void Verifier::structs() {
  std::unordered_set<std::string> seen;
  for (const StructType& st : sh_.structs) {
    prefix_ = "struct '" + st.name + "': ";
    for (const StructField& f : st.fields)
      if (!f.struct_name.empty() && !seen.count(f.struct_name))
        error("field '" + f.name + "' of struct type '" + f.struct_name + "' not listed before");
    if (!seen.insert(st.name).second) error("duplicate struct");
  }
}

std::vector<std::string> Verifier::run() {
  structs();
  symbols();
  if (sh_.main_begin < 0 || sh_.main_begin > int(sh_.ops.size()))
    errors_.push_back("main_begin " + std::to_string(sh_.main_begin) + " out of range");
  for (int i = 0; i < int(sh_.ops.size()); ++i) op(i);
  return errors_;
}

} // namespace

std::vector<std::string> verify(const Shader& shader) { return Verifier(shader).run(); }

} // namespace lobe::ir
