// Library ops that call into the runtime: printf/format/error, strings, closures (registry
// parameter blocks), the noise family, and shading-state queries.
#include "duals.h"
#include "op_tables.h"

#include "closure_registry.h"
#include "env.h"
#include "format.h"
#include "lobe/renderer_services.h"
#include "lobe/shading.h"
#include "shadeop_decls.h"
#include "shadeops.h"

#include <llvm/IR/Constants.h>

#include <algorithm>
#include <array>
#include <climits>
#include <cstddef>
#include <cstdlib>
#include <optional>
#include <sstream>
#include <type_traits>

namespace lobe::codegen {
namespace {

using ir::BaseType;

std::string const_string(const ir::Symbol& s) {
  return (s.kind == ir::SymKind::Const && !s.init.empty()) ? s.init[0].s : std::string();
}
bool is_const_string(const ir::Symbol& s) {
  return s.kind == ir::SymKind::Const && s.type.base == BaseType::String && !s.type.is_array();
}

// ---- printf family --------------------------------------------------------------------------

// Type codes and value pointers for the format shadeops (see shadeops/format.h).
void format_args(LayerEmitter& e, const ir::Op& op, size_t first, std::string& codes,
                 llvm::Value*& argv) {
  std::vector<llvm::Value*> ptrs;
  for (size_t i = first; i < op.args.size(); ++i) {
    const ir::Symbol& s = e.arg(op, int(i));
    char c = 'f';
    switch (s.type.base) {
    case BaseType::Int:
      c = 'i';
      break;
    case BaseType::String:
      c = 's';
      break;
    case BaseType::Closure:
      c = 'c';
      break;
    case BaseType::Matrix:
      c = 'm';
      break;
    case BaseType::Float:
      c = 'f';
      break;
    default:
      c = 't';
    }
    codes += c;
    int n = std::max(1, s.type.arraylen);
    if (s.type.is_array()) { // appended piecewise: "{" + to_string(n) trips GCC 12's -Wrestrict
      codes += '{';
      codes += std::to_string(n);
      codes += '}';
    }
    llvm::Type* t = c == 'i' ? e.i32() : (c == 's' || c == 'c') ? e.ptr() : e.f32();
    std::vector<llvm::Value*> comps;
    for (int k = 0; k < n; ++k)
      for (const Dual& d : e.load(op.args[i], e.iconst(k), false)) comps.push_back(d.v);
    ptrs.push_back(e.spill(comps, t));
  }
  argv = e.spill(ptrs, e.ptr());
}

void op_printf(LayerEmitter& e, const ir::Op& op) {
  const ir::Opcode o = op.opcode;
  bool to_file = o == ir::Opcode::Fprintf, returns = o == ir::Opcode::Format;
  size_t fmt_i = returns || to_file ? 1 : 0;
  std::string codes;
  llvm::Value* argv = nullptr;
  format_args(e, op, fmt_i + 1, codes, argv);
  llvm::Value* fmt = e.load(op.args[fmt_i])[0].v;
  if (returns) {
    // OSL's optimizer folds a format() of constants with C's conversions; run while shading,
    // it rounds exact ties away from zero (shadeops/format.h, FormatRule).
    bool folded = e.group().opt_level > 0;
    for (size_t i = fmt_i; i < op.args.size(); ++i)
      folded = folded && e.arg(op, int(i)).kind == ir::SymKind::Const;
    codes.insert(codes.begin(),
                 folded ? shadeops::kFormatFoldedCode : shadeops::kFormatRuntimeCode);
    e.store(op.args[0],
            Val{Dual{e.call("lobe_format", {e.env_ptr(), fmt, e.string_const(codes), argv})}});
    return;
  }
  if (to_file) {
    e.call("lobe_fprintf",
           {e.sg(), e.env_ptr(), e.load(op.args[0])[0].v, fmt, e.string_const(codes), argv});
    return;
  }
  if (o == ir::Opcode::Printf) {
    e.call("lobe_printf", {e.sg(), e.env_ptr(), fmt, e.string_const(codes), argv});
    return;
  }
  e.call(o == ir::Opcode::Error ? "lobe_error" : "lobe_warning",
         {e.sg(), e.env_ptr(), e.string_const(e.shader().name), fmt, e.string_const(codes), argv});
}

// ---- strings --------------------------------------------------------------------------------

llvm::Value* str(LayerEmitter& e, const ir::Op& op, int i) {
  return e.load(op.args[size_t(i)])[0].v;
}

void op_string(LayerEmitter& e, const ir::Op& op) {
  const ir::Opcode o = op.opcode;
  llvm::Value* r = nullptr;
  if (o == ir::Opcode::Concat) {
    r = str(e, op, 1);
    for (size_t i = 2; i < op.args.size(); ++i)
      r = e.call("lobe_concat", {e.env_ptr(), r, str(e, op, int(i))});
  } else if (o == ir::Opcode::Substr) {
    llvm::Value* len =
        op.args.size() > 3 ? e.load_as(op, 3, BaseType::Int)[0].v : e.iconst(0x7fffffff);
    r = e.call("lobe_substr",
               {e.env_ptr(), str(e, op, 1), e.load_as(op, 2, BaseType::Int)[0].v, len});
  } else if ((o == ir::Opcode::RegexSearch || o == ir::Opcode::RegexMatch) && op.args.size() == 4) {
    // regex_x result results[] subject pattern: the shadeop fills a buffer, copied to results.
    int n = std::max(0, e.arg(op, 1).type.arraylen);
    llvm::Value* buf =
        e.spill(std::vector<llvm::Value*>(size_t(std::max(n, 1)), e.iconst(0)), e.i32());
    r = e.call("lobe_regex_results",
               {str(e, op, 2), str(e, op, 3), e.iconst(o == ir::Opcode::RegexMatch ? 1 : 0), buf,
                e.iconst(n)});
    std::vector<llvm::Value*> got = e.reload(buf, n, e.i32());
    for (int i = 0; i < n; ++i) e.store(op.args[1], Val{Dual{got[size_t(i)]}}, e.iconst(i));
  } else if (o == ir::Opcode::RegexSearch || o == ir::Opcode::RegexMatch) {
    r = e.call("lobe_regex", {str(e, op, 1), str(e, op, int(op.args.size()) - 1),
                              e.iconst(o == ir::Opcode::RegexMatch ? 1 : 0)});
  }
  e.store(op.args[0],
          e.convert(Val{Dual{r}},
                    (o == ir::Opcode::Concat || o == ir::Opcode::Substr) ? BaseType::String
                                                                         : BaseType::Int,
                    e.arg(op, 0).type.base));
}

// ---- library calls (runtime/registry/library_calls.h) ---------------------------------------

// How a library call passes a value: its OSL base type (none for the Env parameter).
template <class T> std::optional<BaseType> library_base() {
  return T::kName ? ir::base_type_from_string(T::kName) : std::nullopt;
}
template <class F> struct LibraryParams;
template <class... P> struct LibraryParams<void(P...)> {
  static std::vector<std::optional<BaseType>> get() { return {library_base<P>()...}; }
};

struct LibraryCall {
  const char* shadeop;
  BaseType result;
  std::vector<std::optional<BaseType>> params; // none: the RuntimeEnv
};

// The row of each library call, indexed by its opcode (null for the other opcodes).
const LibraryCall* library_call(ir::Opcode o) {
  static const std::array<std::optional<LibraryCall>, ir::kOpcodeCount> kByOpcode = [] {
    using namespace ir::library;
    std::array<std::optional<LibraryCall>, ir::kOpcodeCount> a;
#define LOBE_LIBRARY_CODEGEN_ROW(x, e, name, R, P, fn, doc)                                        \
  a[size_t(ir::Opcode::e)] = LibraryCall{#fn, *library_base<R>(), LibraryParams<void P>::get()};
    LOBE_LIBRARY_CALLS(LOBE_LIBRARY_CODEGEN_ROW, _)
#undef LOBE_LIBRARY_CODEGEN_ROW
    return a;
  }();
  const std::optional<LibraryCall>& row = kByOpcode[size_t(o)];
  return row ? &*row : nullptr;
}

// result = shadeop(arguments as C values): ints and floats by value (converted to the
// parameter's type), strings as their pointers, triples as the address of 3 floats.
void op_library_call(LayerEmitter& e, const ir::Op& op) {
  const LibraryCall* c = library_call(op.opcode);
  std::vector<llvm::Value*> args;
  int i = 1;
  for (std::optional<BaseType> p : c->params) {
    BaseType t = p ? *p : BaseType::Int;
    if (!p) {
      args.push_back(e.env_ptr());
    } else if (t == BaseType::Int || t == BaseType::Float || t == BaseType::String) {
      args.push_back(e.load_as(op, i++, t, false)[0].v);
    } else {
      std::vector<llvm::Value*> comps;
      for (const Dual& d : e.load_as(op, i++, t, false)) comps.push_back(d.v);
      args.push_back(e.spill(comps));
    }
  }
  llvm::Value* r = e.call(c->shadeop, std::move(args));
  e.store(op.args[0], e.convert(Val{Dual{r}}, c->result, e.arg(op, 0).type.base));
}

// hash(string) is OIIO's ustring hash, as in OSL (shadeop); hash of numbers is OSL's lookup3
// over the bits of every component (lobe_hash, runtime/mathlib/hashword.h).
void op_hash(LayerEmitter& e, const ir::Op& op) {
  auto& B = e.b();
  if (e.arg(op, 1).type.base == BaseType::String) {
    e.store(op.args[0], Val{Dual{e.call("lobe_strhash", {str(e, op, 1)})}});
    return;
  }
  std::vector<llvm::Value*> words;
  for (size_t i = 1; i < op.args.size(); ++i)
    for (const Dual& d : e.load(op.args[i], nullptr, false))
      words.push_back(d.v->getType()->isFloatTy() ? B.CreateBitCast(d.v, e.i32()) : d.v);
  llvm::Value* h = e.call("lobe_hash", {e.spill(words, e.i32()), e.iconst(int(words.size()))});
  e.store(op.args[0], Val{Dual{h}});
}

// ---- closures -------------------------------------------------------------------------------

// Parses a registry keyword default ("0", "1 1 1", "\"\"") into the block.
void store_default(LayerEmitter& e, llvm::Value* at, const registry::ClosureParam& p) {
  auto& B = e.b();
  std::string text = p.default_value ? p.default_value : "";
  std::istringstream in(text);
  switch (p.type) {
  case registry::ArgType::Int: {
    int v = 0;
    in >> v;
    B.CreateStore(e.iconst(v), at);
    break;
  }
  case registry::ArgType::Float: {
    float v = 0;
    in >> v;
    B.CreateStore(e.fconst(v), at);
    break;
  }
  case registry::ArgType::Color:
  case registry::ArgType::Vector: {
    float v[3] = {0, 0, 0};
    int n = 0;
    while (n < 3 && (in >> v[n])) ++n;
    if (n == 1) v[1] = v[2] = v[0];
    for (int k = 0; k < 3; ++k)
      B.CreateStore(e.fconst(v[k]),
                    B.CreateConstInBoundsGEP1_64(B.getInt8Ty(), at, 4 * unsigned(k)));
    break;
  }
  case registry::ArgType::String: {
    if (text.size() >= 2 && text.front() == '"') text = text.substr(1, text.size() - 2);
    B.CreateStore(e.string_const(text), at);
    break;
  }
  case registry::ArgType::Closure:
    B.CreateStore(llvm::ConstantPointerNull::get(e.b().getPtrTy()), at);
    break;
  }
}

void store_arg(LayerEmitter& e, llvm::Value* at, const registry::ClosureParam& p, const ir::Op& op,
               int i) {
  auto& B = e.b();
  BaseType to = p.type == registry::ArgType::Int      ? BaseType::Int
                : p.type == registry::ArgType::Float  ? BaseType::Float
                : p.type == registry::ArgType::Color  ? BaseType::Color
                : p.type == registry::ArgType::Vector ? BaseType::Vector
                : p.type == registry::ArgType::String ? BaseType::String
                                                      : BaseType::Closure;
  Val v = e.load_as(op, i, to, false);
  for (size_t k = 0; k < v.size(); ++k)
    B.CreateStore(v[k].v, B.CreateConstInBoundsGEP1_64(B.getInt8Ty(), at, 4 * k));
}

void op_closure(LayerEmitter& e, const ir::Op& op) {
  std::string key = const_string(e.arg(op, 1));
  const registry::ClosureEntry* entry = registry::find_by_key(key);
  if (!entry) return e.fail(op, "unknown closure '" + key + "'");
  auto params = entry->params;
  size_t size = registry::param_block_size(params);
  auto* block =
      e.entry_alloca(llvm::ArrayType::get(e.b().getInt8Ty(), unsigned(std::max<size_t>(size, 8))),
                     1, "closure_params");
  auto at = [&](size_t pi) {
    return e.b().CreateConstInBoundsGEP1_64(e.b().getInt8Ty(), block,
                                            registry::param_offset(params, pi));
  };
  size_t argi = 2;
  for (size_t pi = 0; pi < params.size(); ++pi) {
    if (params[pi].keyword) {
      store_default(e, at(pi), params[pi]);
      continue;
    }
    if (argi >= op.args.size()) return e.fail(op, "too few arguments for closure '" + key + "'");
    store_arg(e, at(pi), params[pi], op, int(argi++));
  }
  for (; argi + 1 < op.args.size(); argi += 2) { // "keyword", value pairs; the last one wins
    std::string kw = const_string(e.arg(op, int(argi)));
    size_t pi = 0;
    while (pi < params.size() && !(params[pi].keyword && kw == params[pi].name)) ++pi;
    if (pi == params.size()) continue; // unknown keywords are ignored, as OSL does
    store_arg(e, at(pi), params[pi], op, int(argi + 1));
  }
  llvm::Value* c = e.call("lobe_closure_component",
                          {e.sg(), e.iconst(registry::id_of(key)), block, e.iconst(int(size))});
  e.store(op.args[0], Val{Dual{c}});
}

// A closure the shader declared: each argument is stored as its own type (arrays whole), at its
// natural alignment, and described once in the environment's table, which the closure points
// at so that printing and renderers can read it.
void op_declared_closure(LayerEmitter& e, const ir::Op& op) {
  using Arg = DeclaredClosureArg;
  std::string name = const_string(e.arg(op, 1));
  const ir::Symbol& npos_sym = e.arg(op, 2);
  size_t npos = npos_sym.init.empty() ? 0 : size_t(std::max(0, npos_sym.init[0].i));
  struct Item {
    int symbol;
    Arg arg;
  };
  std::vector<Item> items;
  auto base_of = [](BaseType b) {
    switch (b) {
    case BaseType::Int:
      return Arg::Base::Int;
    case BaseType::Float:
      return Arg::Base::Float;
    case BaseType::Matrix:
      return Arg::Base::Matrix;
    case BaseType::String:
      return Arg::Base::String;
    case BaseType::Closure:
      return Arg::Base::Closure;
    default:
      return Arg::Base::Triple;
    }
  };
  uint32_t offset = 0;
  auto add = [&](const char* keyword, int symbol) {
    const ir::Type& t = e.sym(symbol).type;
    bool pointer = t.base == BaseType::String || t.base == BaseType::Closure;
    uint32_t align = pointer ? 8 : 4, scalar = pointer ? 8 : 4;
    offset = (offset + align - 1) / align * align;
    items.push_back({symbol, {keyword, base_of(t.base), std::max(0, t.arraylen), offset}});
    offset += scalar * uint32_t(t.components()) * uint32_t(std::max(1, t.arraylen));
  };
  size_t argi = 3;
  for (; argi < op.args.size() && argi < 3 + npos; ++argi) add(nullptr, op.args[argi]);
  for (; argi + 1 < op.args.size(); argi += 2) {
    std::string kw = const_string(e.arg(op, int(argi)));
    const char* interned = e.group().env->strings.intern(kw);
    auto same = [&](const Item& it) { return it.arg.keyword == interned; };
    auto it = std::find_if(items.begin(), items.end(), same);
    if (it != items.end()) items.erase(it); // given again: the last one wins
    add(interned, op.args[argi + 1]);
  }
  uint32_t size = (offset + 7) / 8 * 8;
  auto& B = e.b();
  auto* block = e.entry_alloca(llvm::ArrayType::get(B.getInt8Ty(), std::max<uint32_t>(size, 8)), 1,
                               "declared_closure");
  std::vector<Arg> args;
  for (const Item& it : items) {
    const ir::Symbol& s = e.sym(it.symbol);
    bool pointer = s.type.base == BaseType::String || s.type.base == BaseType::Closure;
    int comps = s.type.components(), elems = std::max(1, s.type.arraylen);
    for (int k = 0; k < elems; ++k) {
      Val v = e.load(it.symbol, s.type.is_array() ? e.iconst(k) : nullptr, false);
      for (int c = 0; c < comps; ++c) {
        uint64_t at = it.arg.offset + uint64_t((k * comps + c) * (pointer ? 8 : 4));
        B.CreateStore(v[size_t(c)].v, B.CreateConstInBoundsGEP1_64(B.getInt8Ty(), block, at));
      }
    }
    args.push_back(it.arg);
  }
  const DeclaredClosureInfo* info =
      e.group().env->declared_closures.get(e.group().env->strings.intern(name), args, size);
  llvm::Value* info_ptr = e.host_address(info);
  e.store(op.args[0], Val{Dual{e.call("lobe_closure_declared", {e.sg(), info_ptr, block})}});
}

// ---- noise ----------------------------------------------------------------------------------

void op_noise(LayerEmitter& e, const ir::Op& op) {
  const ir::Opcode o = op.opcode;
  size_t first = 1;
  int kind = o == ir::Opcode::SNoise || o == ir::Opcode::PSNoise ? shadeops::kPerlin
             : o == ir::Opcode::CellNoise                        ? shadeops::kCell
             : o == ir::Opcode::HashNoise                        ? shadeops::kHash
                                                                 : shadeops::kUPerlin;
  // noise("name", ...): a constant known name selects the kind here; a name known only at run
  // time, or an unknown constant, dispatches in lobe_noise_named_d, which reports an unknown
  // name as a run-time error in OSL's words for each (a parameter is constant once specialised,
  // so its wording differs between -O0 and -O2, as OSL's). "gabor" calls lobe_gabor.
  bool periodic = o == ir::Opcode::PNoise || o == ir::Opcode::PSNoise;
  bool named = false, gabor = false, maybe_gabor = false;
  if (e.arg(op, 1).type.base == BaseType::String) {
    first = 2;
    named = true;
    maybe_gabor = true;
    if (is_const_string(e.arg(op, 1))) {
      std::string name = const_string(e.arg(op, 1));
      gabor = name == "gabor";
      maybe_gabor = gabor;
      kind = gabor ? -1 : shadeops::noise_kind_from_name(name, periodic);
      named = !gabor && kind < 0;
    }
  }
  // Coordinates (and periods) up to the first string: the `"keyword", value` options after
  // them (the gabor options; OSL ignores them for the other kinds).
  size_t end = first;
  while (end < op.args.size() && e.arg(op, int(end)).type.base != BaseType::String) ++end;
  size_t nargs = end - first, ncoord = periodic ? nargs / 2 : nargs;
  // OSL evaluates the Dual2 form exactly when the result needs derivatives (its value can
  // differ in the last bits from the value-only form), with the inputs' derivatives or zeros;
  // gabor noise always takes P's derivatives (its filter is the pixel footprint).
  bool derivs = e.wants_derivs(op.args[0]);
  bool in_derivs = derivs || maybe_gabor;
  std::vector<Dual> x;
  std::vector<llvm::Value*> per;
  for (size_t i = 0; i < nargs; ++i) {
    const ir::Symbol& s = e.arg(op, int(first + i));
    Val v = e.load_as(op, int(first + i), s.type.is_triple() ? BaseType::Vector : BaseType::Float,
                      i < ncoord && in_derivs);
    for (const Dual& d : v) {
      if (i < ncoord)
        x.push_back(d);
      else
        per.push_back(d.v);
    }
  }
  int nin = int(x.size()), nout = e.arg(op, 0).type.components();
  auto ptr_null = [&] { return llvm::ConstantPointerNull::get(e.b().getPtrTy()); };
  std::vector<llvm::Value*> xv, dxv, dyv;
  for (const Dual& d : x) {
    xv.push_back(d.v);
    dxv.push_back(d.dx ? d.dx : e.fconst(0));
    dyv.push_back(d.dy ? d.dy : e.fconst(0));
  }
  llvm::Value* in = e.spill(xv);
  llvm::Value* indx = in_derivs ? e.spill(dxv) : ptr_null();
  llvm::Value* indy = in_derivs ? e.spill(dyv) : ptr_null();
  llvm::Value* pp = periodic ? e.spill(per) : ptr_null();
  std::vector<llvm::Value*> zeros(size_t(nout), e.fconst(0));
  llvm::Value* out = e.spill(zeros);
  llvm::Value* odx = derivs || maybe_gabor ? e.spill(zeros) : ptr_null();
  llvm::Value* ody = derivs || maybe_gabor ? e.spill(zeros) : ptr_null();
  // The gabor options, by field offset into shadeops::GaborOptions.
  llvm::Value* opts = ptr_null();
  if (maybe_gabor) {
    auto& B = e.b();
    shadeops::GaborOptions def;
    auto* block = e.entry_alloca(
        llvm::ArrayType::get(B.getInt8Ty(), unsigned(sizeof(shadeops::GaborOptions))), 1,
        "gabor_opts");
    auto at = [&](size_t off) { return B.CreateConstInBoundsGEP1_64(B.getInt8Ty(), block, off); };
    B.CreateStore(e.iconst(def.anisotropic), at(offsetof(shadeops::GaborOptions, anisotropic)));
    B.CreateStore(e.iconst(def.do_filter), at(offsetof(shadeops::GaborOptions, do_filter)));
    for (int k = 0; k < 3; ++k)
      B.CreateStore(e.fconst(def.direction[k]),
                    at(offsetof(shadeops::GaborOptions, direction) + 4 * size_t(k)));
    B.CreateStore(e.fconst(def.bandwidth), at(offsetof(shadeops::GaborOptions, bandwidth)));
    B.CreateStore(e.fconst(def.impulses), at(offsetof(shadeops::GaborOptions, impulses)));
    for (size_t i = end; i + 1 < op.args.size(); i += 2) {
      std::string kw = const_string(e.arg(op, int(i)));
      int vi = int(i + 1);
      if (kw == "anisotropic" || kw == "do_filter") {
        size_t off = kw == "anisotropic" ? offsetof(shadeops::GaborOptions, anisotropic)
                                         : offsetof(shadeops::GaborOptions, do_filter);
        B.CreateStore(e.load_as(op, vi, BaseType::Int, false)[0].v, at(off));
      } else if (kw == "bandwidth" || kw == "impulses") {
        size_t off = kw == "bandwidth" ? offsetof(shadeops::GaborOptions, bandwidth)
                                       : offsetof(shadeops::GaborOptions, impulses);
        B.CreateStore(e.load_as(op, vi, BaseType::Float, false)[0].v, at(off));
      } else if (kw == "direction") {
        Val d = e.load_as(op, vi, BaseType::Vector, false);
        for (size_t k = 0; k < 3; ++k)
          B.CreateStore(d[k].v, at(offsetof(shadeops::GaborOptions, direction) + 4 * k));
      } // other keywords: ignored (sema reports unknown ones)
    }
    opts = block;
  }
  if (gabor)
    e.call("lobe_gabor", {in, indx, indy, e.iconst(nin), pp, opts, out, odx, ody, e.iconst(nout)});
  else if (named) // the place only for a constant name: OSL words the two errors differently
    e.call("lobe_noise_named_d",
           {e.sg(), e.load(op.args[1])[0].v, in, indx, indy, e.iconst(nin), pp, opts, out, odx, ody,
            e.iconst(nout),
            is_const_string(e.arg(op, 1))
                ? e.string_const(op.loc.file.empty() ? e.shader().name : op.loc.file)
                : ptr_null(),
            e.iconst(op.loc.line)});
  else
    e.call("lobe_noise_d",
           {e.iconst(kind), in, indx, indy, e.iconst(nin), pp, out, odx, ody, e.iconst(nout)});
  std::vector<llvm::Value*> ov = e.reload(out, nout), dxo, dyo;
  if (derivs) {
    dxo = e.reload(odx, nout);
    dyo = e.reload(ody, nout);
  }
  Val r;
  for (int j = 0; j < nout; ++j)
    r.push_back(derivs ? Dual{ov[size_t(j)], dxo[size_t(j)], dyo[size_t(j)]} : Dual{ov[size_t(j)]});
  e.store(op.args[0],
          e.convert(r, nout == 1 ? BaseType::Float : BaseType::Color, e.arg(op, 0).type.base));
}

// ---- splines --------------------------------------------------------------------------------

// spline a "basis" x (knots... | knots[] | nknots knots[]); splineinverse likewise (floats).
// Where the result needs derivatives they come from x's and (spline only) the knots' (OSL's
// dual spline shadeops): the knots' derivative planes are passed beside their values when the
// knot array (or a listed knot) carries derivatives.
void op_spline(LayerEmitter& e, const ir::Op& op) {
  auto& B = e.b();
  bool inverse = op.opcode == ir::Opcode::SplineInverse;
  BaseType t =
      inverse || e.arg(op, 0).type.base == BaseType::Float ? BaseType::Float : BaseType::Color;
  int comps = t == BaseType::Float ? 1 : 3;
  bool derivs = e.wants_derivs(op.args[0]);
  Dual x = e.load_as(op, 2, BaseType::Float, derivs)[0];
  size_t k = 3;
  llvm::Value* count = nullptr;
  if (op.args.size() == 5 && e.arg(op, 3).type.base == BaseType::Int &&
      e.arg(op, 4).type.is_array()) {
    count = e.load_as(op, 3, BaseType::Int)[0].v;
    k = 4;
  }
  // splineinverse's derivatives are y's through the curve; OSL's search reads the knots'
  // values only (checked with testshade: knots that vary leave the derivative y' / f'(x)).
  bool knot_derivs = false;
  if (derivs && !inverse)
    for (size_t i = k; i < op.args.size(); ++i) knot_derivs |= e.wants_derivs(op.args[i]);
  std::vector<llvm::Value*> kv, kdx, kdy;
  auto add = [&](const Val& v) {
    for (const Dual& d : v) {
      kv.push_back(d.v);
      if (knot_derivs) {
        kdx.push_back(d.dx ? d.dx : e.fconst(0));
        kdy.push_back(d.dy ? d.dy : e.fconst(0));
      }
    }
  };
  int n = 0;
  if (e.arg(op, int(k)).type.is_array()) {
    const ir::Symbol& a = e.arg(op, int(k));
    n = a.type.arraylen > 0 ? a.type.arraylen : int(a.init.size()) / a.type.components();
    for (int i = 0; i < n; ++i)
      add(e.convert(e.load(op.args[k], e.iconst(i), knot_derivs), a.type.base, t));
  } else {
    for (size_t i = k; i < op.args.size(); ++i, ++n) add(e.load_as(op, int(i), t, knot_derivs));
  }
  llvm::Value* nk = e.iconst(n);
  if (count) nk = B.CreateSelect(B.CreateICmpSLT(count, nk), count, nk);
  llvm::Value* knots = e.spill(kv);
  llvm::Value* null = llvm::ConstantPointerNull::get(B.getPtrTy());
  llvm::Value* knots_dx = knot_derivs ? e.spill(kdx) : null;
  llvm::Value* knots_dy = knot_derivs ? e.spill(kdy) : null;
  bool x_derivs = derivs && (x.dx || x.dy);
  bool chain = x_derivs || knot_derivs;
  llvm::Value* xdx = x.dx ? x.dx : e.fconst(0);
  llvm::Value* xdy = x.dy ? x.dy : e.fconst(0);
  if (inverse) {
    Val r;
    if (chain) {
      llvm::Value* out = e.spill(std::vector<llvm::Value*>(3, e.fconst(0)));
      e.call("lobe_splineinverse_d", {e.load(op.args[1])[0].v, x.v, xdx, xdy, knots, nk, out});
      std::vector<llvm::Value*> o = e.reload(out, 3);
      r.push_back(Dual{o[0], o[1], o[2]});
    } else {
      r.push_back(Dual{e.call("lobe_splineinverse", {e.load(op.args[1])[0].v, x.v, knots, nk})});
    }
    e.store(op.args[0], e.convert(r, BaseType::Float, e.arg(op, 0).type.base));
    return;
  }
  llvm::Value* out = e.spill(std::vector<llvm::Value*>(size_t(comps), e.fconst(0)));
  auto zeros = [&] { return e.spill(std::vector<llvm::Value*>(size_t(comps), e.fconst(0))); };
  llvm::Value* odx = chain ? zeros() : null;
  llvm::Value* ody = chain ? zeros() : null;
  e.call("lobe_spline", {e.load(op.args[1])[0].v, x.v, xdx, xdy, e.iconst(x_derivs ? 1 : 0), knots,
                         knots_dx, knots_dy, nk, e.iconst(comps), out, odx, ody});
  std::vector<llvm::Value*> ov = e.reload(out, comps), gx, gy;
  if (chain) {
    gx = e.reload(odx, comps);
    gy = e.reload(ody, comps);
  }
  Val r;
  for (int c = 0; c < comps; ++c) {
    Dual rc{ov[size_t(c)]};
    if (chain) {
      rc.dx = gx[size_t(c)];
      rc.dy = gy[size_t(c)];
    }
    r.push_back(rc);
  }
  e.store(op.args[0], e.convert(r, t, e.arg(op, 0).type.base));
}

// ---- shading-state queries ------------------------------------------------------------------

llvm::Value* sg_field(LayerEmitter& e, size_t offset, llvm::Type* t) {
  return e.b().CreateLoad(t, e.b().CreateConstInBoundsGEP1_64(e.b().getInt8Ty(), e.sg(), offset));
}

void op_query(LayerEmitter& e, const ir::Op& op) {
  auto& B = e.b();
  const ir::Opcode o = op.opcode;
  Val r;
  if (o == ir::Opcode::RayType) {
    // A constant name's bit is known here; another's is looked up per shade (OSL does too).
    llvm::Value* bit = is_const_string(e.arg(op, 1))
                           ? e.iconst(lobe_raytype_bit(const_string(e.arg(op, 1)).c_str()))
                           : e.call("lobe_raytype_bit", {e.load(op.args[1])[0].v});
    llvm::Value* rt = sg_field(e, offsetof(ShaderGlobals, raytype), e.i32());
    r = Val{Dual{B.CreateZExt(B.CreateICmpNE(B.CreateAnd(rt, bit), e.iconst(0)), e.i32())}};
  } else if (o == ir::Opcode::Backfacing) {
    r = Val{Dual{sg_field(e, offsetof(ShaderGlobals, backfacing), e.i32())}};
  } else if (o == ir::Opcode::SurfaceArea) {
    r = Val{Dual{sg_field(e, offsetof(ShaderGlobals, surfacearea), e.f32())}};
    e.store(op.args[0], e.convert(r, BaseType::Float, e.arg(op, 0).type.base));
    return;
  } else if (o == ir::Opcode::IsConnected) {
    // The group builder answers every isconnected() from the connections as made, before
    // codegen (runtime/group/group_build.cpp, resolve_isconnected); a plan built by hand,
    // without it, has none.
    r = Val{Dual{e.iconst(0)}};
  } else if (o == ir::Opcode::IsConstant) {
    // A constant of the shader as written; specialisation resolves isconstant before it turns
    // params into constants (runtime/group/group_build.cpp), so the answer is the same.
    r = Val{Dual{e.iconst(e.arg(op, 1).kind == ir::SymKind::Const ? 1 : 0)}};
  }
  e.store(op.args[0], e.convert(r, BaseType::Int, e.arg(op, 0).type.base));
}

llvm::Value* null_ptr(LayerEmitter& e) { return llvm::ConstantPointerNull::get(e.b().getPtrTy()); }

llvm::Value* op_file(LayerEmitter& e, const ir::Op& op) {
  return e.string_const(op.loc.file.empty() ? e.shader().name : op.loc.file);
}

// The layer's position in the group as written (messages may only flow downstream).
int layer_index(LayerEmitter& e) { return e.group().layers[size_t(e.layer())].group_index; }

// getattribute r dest ["object"] "name" [index]: the operand types tell the form.
void op_getattribute(LayerEmitter& e, const ir::Op& op) {
  int dest = op.args[1];
  size_t n = op.args.size();
  bool indexed = e.arg(op, int(n) - 1).type.base == BaseType::Int;
  size_t strings = n - 2 - (indexed ? 1 : 0); // 1: name; 2: object and name
  llvm::Value* object = strings == 2 ? e.load(op.args[2])[0].v : null_ptr(e);
  llvm::Value* name = e.load(op.args[strings == 2 ? 3 : 2])[0].v;
  llvm::Value* index = indexed ? e.load(op.args[n - 1])[0].v : e.iconst(INT_MIN); // none
  const std::string& group = e.group().group_name;
  const codegen::LayerPlan& lp = e.group().layers[size_t(e.layer())];
  // The shader:* attributes, for a name known now only (see lobe_getattribute).
  bool known = is_const_string(e.arg(op, strings == 2 ? 3 : 2));
  auto named = [&](const std::string& s) { return known ? e.string_const(s) : null_ptr(e); };
  llvm::Value* r =
      e.call("lobe_getattribute", {e.sg(), e.env_ptr(), object, name, index,
                                   e.iconst(LayerEmitter::type_code(e.sym(dest).type)),
                                   e.iconst(e.wants_derivs(dest) ? 1 : 0), e.storage_address(dest),
                                   named(e.shader().name), named(lp.layer_name), named(group)});
  e.store(op.args[0], e.convert(Val{Dual{r}}, BaseType::Int, e.arg(op, 0).type.base));
}

// getmessage r dest ["source"] "name"
void op_getmessage(LayerEmitter& e, const ir::Op& op) {
  int dest = op.args[1];
  bool sourced = op.args.size() == 4;
  llvm::Value* source = sourced ? e.load(op.args[2])[0].v : null_ptr(e);
  llvm::Value* name = e.load(op.args[sourced ? 3 : 2])[0].v;
  llvm::Value* r =
      e.call("lobe_getmessage", {e.sg(), e.env_ptr(), source, name,
                                 e.iconst(LayerEmitter::type_code(e.sym(dest).type)),
                                 e.iconst(e.wants_derivs(dest) ? 1 : 0), e.storage_address(dest),
                                 op_file(e, op), e.iconst(op.loc.line), e.iconst(layer_index(e))});
  e.store(op.args[0], e.convert(Val{Dual{r}}, BaseType::Int, e.arg(op, 0).type.base));
}

// trace r P R "kw" v...: the ray's origin and direction with their derivatives, and a
// TraceOptions block filled from the keywords.
void op_trace(LayerEmitter& e, const ir::Op& op) {
  auto& B = e.b();
  auto triple = [&](int i, int part) {
    std::vector<llvm::Value*> c;
    for (const Dual& d : e.load_as(op, i, BaseType::Vector)) {
      llvm::Value* v = part == 0 ? d.v : part == 1 ? d.dx : d.dy;
      c.push_back(v ? v : e.fconst(0));
    }
    return e.spill(c);
  };
  auto* block =
      e.entry_alloca(llvm::ArrayType::get(B.getInt8Ty(), sizeof(TraceOptions)), 1, "traceopts");
  auto at = [&](size_t off) { return B.CreateConstInBoundsGEP1_64(B.getInt8Ty(), block, off); };
  TraceOptions defaults;
  B.CreateStore(e.fconst(defaults.mindist), at(offsetof(TraceOptions, mindist)));
  B.CreateStore(e.fconst(defaults.maxdist), at(offsetof(TraceOptions, maxdist)));
  B.CreateStore(B.getInt8(0), at(offsetof(TraceOptions, shade)));
  B.CreateStore(e.string_const(defaults.traceset), at(offsetof(TraceOptions, traceset)));
  for (size_t i = 3; i + 1 < op.args.size(); i += 2) {
    std::string kw = const_string(e.arg(op, int(i)));
    int v = int(i + 1);
    if (kw == "mindist" || kw == "maxdist")
      B.CreateStore(
          e.load_as(op, v, BaseType::Float, false)[0].v,
          at(kw == "mindist" ? offsetof(TraceOptions, mindist) : offsetof(TraceOptions, maxdist)));
    else if (kw == "shade")
      B.CreateStore(
          B.CreateZExt(e.truthy(e.load(op.args[size_t(v)], nullptr, false), e.arg(op, v).type.base),
                       B.getInt8Ty()),
          at(offsetof(TraceOptions, shade)));
    else if (kw == "traceset")
      B.CreateStore(e.load(op.args[size_t(v)])[0].v, at(offsetof(TraceOptions, traceset)));
  }
  llvm::Value* r = e.call("lobe_trace", {e.sg(), triple(1, 0), triple(1, 1), triple(1, 2),
                                         triple(2, 0), triple(2, 1), triple(2, 2), block});
  e.store(op.args[0], e.convert(Val{Dual{r}}, BaseType::Int, e.arg(op, 0).type.base));
}

// gettextureinfo r dest "file" ["s" "t"] "query": with s and t, the UDIM tile there.
void op_gettextureinfo(LayerEmitter& e, const ir::Op& op) {
  int dest = op.args[1];
  bool udim = op.args.size() == 6;
  llvm::Value* s = udim ? e.load_as(op, 3, BaseType::Float, false)[0].v : e.fconst(0);
  llvm::Value* t = udim ? e.load_as(op, 4, BaseType::Float, false)[0].v : e.fconst(0);
  llvm::Value* r = e.call(
      "lobe_gettextureinfo",
      {e.sg(), e.env_ptr(),
       // OSL words a failure by how it looked the file up: a name constant at -O2 as
       // the shader's error (not with s and t), any other through its RendererServices (null
       // here).
       is_const_string(e.arg(op, 2)) && e.group().opt_level >= 2 && !udim
           ? e.string_const(e.shader().name)
           : llvm::ConstantPointerNull::get(e.b().getPtrTy()),
       e.load(op.args[2])[0].v, e.iconst(udim ? 1 : 0), s, t, e.load(op.args[udim ? 5 : 3])[0].v,
       e.iconst(LayerEmitter::type_code(e.sym(dest).type)), e.storage_address(dest)});
  if (e.wants_derivs(dest)) // texture information is constant over the surface
    for (int k = 0; k < std::max(1, e.sym(dest).type.arraylen); ++k)
      e.store(dest, e.load(dest, e.iconst(k), false), e.iconst(k));
  e.store(op.args[0], e.convert(Val{Dual{r}}, BaseType::Int, e.arg(op, 0).type.base));
}

// setmessage "name" value (the value plane only: messages carry no derivatives)
void op_setmessage(LayerEmitter& e, const ir::Op& op) {
  int src = op.args[1];
  e.call("lobe_setmessage",
         {e.sg(), e.load(op.args[0])[0].v, e.iconst(LayerEmitter::type_code(e.sym(src).type)),
          e.storage_address(src), op_file(e, op), e.iconst(op.loc.line), e.iconst(layer_index(e))});
}

// ---- textures -------------------------------------------------------------------------------

// Fills a TextureArgs block from `"keyword", value` pairs starting at operand `first`.
llvm::Value* texture_args(LayerEmitter& e, const ir::Op& op, size_t first) {
  using shadeops::TextureArgs;
  auto& B = e.b();
  const int channels = e.arg(op, 0).type.components(); // the result's
  auto* block =
      e.entry_alloca(llvm::ArrayType::get(B.getInt8Ty(), sizeof(TextureArgs)), 1, "texargs");
  auto at = [&](size_t off) { return B.CreateConstInBoundsGEP1_64(B.getInt8Ty(), block, off); };
  for (size_t k = 0; k < 3; ++k) {
    B.CreateStore(e.fconst(0), at(offsetof(TextureArgs, blur) + 4 * k));
    B.CreateStore(e.fconst(1), at(offsetof(TextureArgs, width) + 4 * k));
  }
  B.CreateStore(e.fconst(0), at(offsetof(TextureArgs, fill)));
  B.CreateStore(e.iconst(0), at(offsetof(TextureArgs, firstchannel)));
  for (size_t k = 0; k < 3; ++k)
    B.CreateStore(llvm::ConstantPointerNull::get(B.getPtrTy()),
                  at(offsetof(TextureArgs, wrap) + sizeof(char*) * k));
  B.CreateStore(llvm::ConstantPointerNull::get(B.getPtrTy()), at(offsetof(TextureArgs, interp)));
  B.CreateStore(e.iconst(0), at(offsetof(TextureArgs, has_missing)));
  for (size_t k = 0; k < 4; ++k)
    B.CreateStore(e.fconst(0), at(offsetof(TextureArgs, missing) + 4 * k));
  B.CreateStore(llvm::ConstantPointerNull::get(B.getPtrTy()),
                at(offsetof(TextureArgs, errormessage)));
  B.CreateStore(e.iconst(0), at(offsetof(TextureArgs, subimage)));
  B.CreateStore(llvm::ConstantPointerNull::get(B.getPtrTy()),
                at(offsetof(TextureArgs, subimagename)));
  const std::vector<ir::Op>& ops = e.shader().ops;
  int op_index = &op >= ops.data() && &op < ops.data() + ops.size() ? int(&op - ops.data()) : 0;
  B.CreateStore(e.iconst(layer_index(e) * 131 + op_index), at(offsetof(TextureArgs, site)));
  for (size_t i = first; i + 1 < op.args.size(); i += 2) {
    std::string kw = const_string(e.arg(op, int(i)));
    int v = int(i + 1);
    // "blur", "width" and "wrap" set the s, t and r values; "sblur", "twidth", ... one.
    std::string axis = kw.size() > 1 && (kw[0] == 's' || kw[0] == 't' || kw[0] == 'r')
                           ? kw.substr(1)
                           : std::string();
    std::string what = axis == "blur" || axis == "width" || axis == "wrap" ? axis : kw;
    if (what == "blur" || what == "width" || what == "wrap") {
      bool text = what == "wrap";
      llvm::Value* x =
          text ? e.load(op.args[size_t(v)])[0].v : e.load_as(op, v, BaseType::Float, false)[0].v;
      size_t base = what == "blur"    ? offsetof(TextureArgs, blur)
                    : what == "width" ? offsetof(TextureArgs, width)
                                      : offsetof(TextureArgs, wrap);
      size_t step = text ? sizeof(char*) : sizeof(float);
      for (size_t k = 0; k < 3; ++k)
        if (kw == what || kw[0] == "str"[k]) B.CreateStore(x, at(base + step * k));
    } else if (kw == "fill")
      B.CreateStore(e.load_as(op, v, BaseType::Float, false)[0].v, at(offsetof(TextureArgs, fill)));
    else if (kw == "firstchannel")
      B.CreateStore(e.load_as(op, v, BaseType::Int, false)[0].v,
                    at(offsetof(TextureArgs, firstchannel)));
    else if (kw == "interp")
      B.CreateStore(e.load(op.args[size_t(v)])[0].v, at(offsetof(TextureArgs, interp)));
    else if (kw == "missingcolor") { // the result's channels (the first for a float)
      Val c = e.load_as(op, v, BaseType::Color, false);
      for (size_t k = 0; k < size_t(channels) && k < 3; ++k)
        B.CreateStore(c[k].v, at(offsetof(TextureArgs, missing) + 4 * k));
      B.CreateStore(e.iconst(1), at(offsetof(TextureArgs, has_missing)));
    } else if (kw == "missingalpha") { // the channel after them; a missing file is no error
      B.CreateStore(e.load_as(op, v, BaseType::Float, false)[0].v,
                    at(offsetof(TextureArgs, missing) + 4 * size_t(std::min(channels, 3))));
      B.CreateStore(e.iconst(1), at(offsetof(TextureArgs, has_missing)));
    } else if (kw == "errormessage" && v < 32 && op.writes(v)) { // the lookup writes it there
      B.CreateStore(e.storage_address(op.args[size_t(v)]), at(offsetof(TextureArgs, errormessage)));
    } else if (kw == "subimage") { // an index, or a name
      if (e.arg(op, v).type.base == BaseType::String)
        B.CreateStore(e.load(op.args[size_t(v)])[0].v, at(offsetof(TextureArgs, subimagename)));
      else
        B.CreateStore(e.load_as(op, v, BaseType::Int, false)[0].v,
                      at(offsetof(TextureArgs, subimage)));
    }
    // "alpha": the lookup's extra channel (alpha_operand); "time": ignored (no motion)
  }
  return block;
}

// The operand a texture lookup's "alpha" keyword writes (lowering marks it written), or -1.
int alpha_operand(LayerEmitter& e, const ir::Op& op, size_t first) {
  for (size_t i = first; i + 1 < op.args.size() && i + 1 < 32; i += 2)
    if (op.writes(int(i + 1)) && const_string(e.arg(op, int(i))) == "alpha") return int(i + 1);
  return -1;
}

// Stores a lookup's extra channel into the "alpha" operand `alpha` of `op`.
void store_alpha(LayerEmitter& e, const ir::Op& op, int alpha, const Dual& a) {
  int sym = op.args[size_t(alpha)];
  e.store(sym, e.convert(Val{a}, BaseType::Float, e.sym(sym).type.base));
}

// texture a "file" s t [dsdx dtdx dsdy dtdy] "kw" v...; derivatives of the result follow s, t.
void op_texture(LayerEmitter& e, const ir::Op& op) {
  auto& B = e.b();
  const ir::Symbol& d = e.arg(op, 0);
  int n = d.type.components();
  bool derivs = e.wants_derivs(op.args[0]);
  Dual s = e.load_as(op, 2, BaseType::Float)[0], t = e.load_as(op, 3, BaseType::Float)[0];
  const size_t first = ir::first_texture_option(e.shader(), op);
  const bool explicit_d = first == 8;
  auto orzero = [&](llvm::Value* v) { return v ? v : e.fconst(0); };
  llvm::Value *dsdx = orzero(s.dx), *dtdx = orzero(t.dx), *dsdy = orzero(s.dy),
              *dtdy = orzero(t.dy);
  if (explicit_d) {
    dsdx = e.load_as(op, 4, BaseType::Float, false)[0].v;
    dtdx = e.load_as(op, 5, BaseType::Float, false)[0].v;
    dsdy = e.load_as(op, 6, BaseType::Float, false)[0].v;
    dtdy = e.load_as(op, 7, BaseType::Float, false)[0].v;
  }
  llvm::Value* args = texture_args(e, op, first);
  // With "alpha", one channel more: the one after the result's.
  int alpha = alpha_operand(e, op, first);
  derivs = derivs || (alpha >= 0 && e.wants_derivs(op.args[size_t(alpha)]));
  int nc = n + (alpha >= 0 ? 1 : 0);
  llvm::Value* out = e.spill(std::vector<llvm::Value*>(size_t(nc), e.fconst(0)));
  llvm::Value* null = llvm::ConstantPointerNull::get(B.getPtrTy());
  llvm::Value* dds = derivs ? e.spill(std::vector<llvm::Value*>(size_t(nc), e.fconst(0))) : null;
  llvm::Value* ddt = derivs ? e.spill(std::vector<llvm::Value*>(size_t(nc), e.fconst(0))) : null;
  e.call("lobe_texture", {e.sg(), e.env_ptr(), e.load(op.args[1])[0].v, s.v, t.v, dsdx, dtdx, dsdy,
                          dtdy, e.iconst(nc), out, dds, ddt, args});
  std::vector<llvm::Value*> ov = e.reload(out, nc), gs, gt;
  if (derivs) {
    gs = e.reload(dds, nc);
    gt = e.reload(ddt, nc);
  }
  Val r;
  for (int c = 0; c < nc; ++c) {
    Dual rc{ov[size_t(c)]};
    if (derivs) { // d/dx = d/ds * ds/dx + d/dt * dt/dx
      rc.dx = B.CreateFAdd(B.CreateFMul(gs[size_t(c)], dsdx), B.CreateFMul(gt[size_t(c)], dtdx));
      rc.dy = B.CreateFAdd(B.CreateFMul(gs[size_t(c)], dsdy), B.CreateFMul(gt[size_t(c)], dtdy));
    }
    r.push_back(rc);
  }
  if (alpha >= 0) {
    store_alpha(e, op, alpha, r.back());
    r.pop_back();
  }
  e.store(op.args[0], e.convert(r, n == 1 ? BaseType::Float : BaseType::Color, d.type.base));
}

// texture3d a "file" P [dPdx dPdy dPdz] "kw" v...; environment a "file" R [dRdx dRdy]
// "kw" v... (no result derivatives). Without explicit derivatives, those of P or R filter.
void op_texture3d(LayerEmitter& e, const ir::Op& op) {
  const ir::Symbol& d = e.arg(op, 0);
  int n = d.type.components();
  Val p = e.load_as(op, 2, BaseType::Vector);
  std::vector<llvm::Value*> v, dx, dy, dz(3, e.fconst(0));
  for (const Dual& c : p) {
    v.push_back(c.v);
    dx.push_back(c.dx ? c.dx : e.fconst(0));
    dy.push_back(c.dy ? c.dy : e.fconst(0));
  }
  size_t nderivs = op.opcode == ir::Opcode::Texture3d ? 3 : 2;
  const size_t first = ir::first_texture_option(e.shader(), op);
  const bool explicit_d = first > 3;
  if (explicit_d) {
    auto comps = [&](int i) {
      std::vector<llvm::Value*> c;
      for (const Dual& x : e.load_as(op, i, BaseType::Vector, false)) c.push_back(x.v);
      return c;
    };
    dx = comps(3);
    dy = comps(4);
    if (nderivs == 3) dz = comps(5);
  }
  llvm::Value* args = texture_args(e, op, first);
  int alpha = alpha_operand(e, op, first);
  int nc = n + (alpha >= 0 ? 1 : 0);
  llvm::Value* out = e.spill(std::vector<llvm::Value*>(size_t(nc), e.fconst(0)));
  e.call(op.opcode == ir::Opcode::Texture3d ? "lobe_texture3d" : "lobe_environment",
         {e.sg(), e.env_ptr(), e.load(op.args[1])[0].v, e.spill(v), e.spill(dx), e.spill(dy),
          e.spill(dz), e.iconst(nc), out, args});
  Val r;
  for (llvm::Value* x : e.reload(out, nc)) r.push_back(Dual{x});
  if (alpha >= 0) {
    store_alpha(e, op, alpha, r.back());
    r.pop_back();
  }
  e.store(op.args[0], e.convert(r, n == 1 ? BaseType::Float : BaseType::Color, d.type.base));
}

const OpEntry kLibraryOps[] = {
// clang-format off
#define LOBE_LIBRARY_ENTRY_ROW(x, e, name, R, P, fn, doc) {ir::Opcode::e, op_library_call},
    LOBE_LIBRARY_CALLS(LOBE_LIBRARY_ENTRY_ROW, _)
#undef LOBE_LIBRARY_ENTRY_ROW
    // clang-format on
    {ir::Opcode::Printf, op_printf},
    {ir::Opcode::Format, op_printf},
    {ir::Opcode::Error, op_printf},
    {ir::Opcode::Warning, op_printf},
    {ir::Opcode::Fprintf, op_printf},
    {ir::Opcode::Concat, op_string},
    {ir::Opcode::Substr, op_string},
    {ir::Opcode::RegexSearch, op_string},
    {ir::Opcode::RegexMatch, op_string},
    {ir::Opcode::Hash, op_hash},
    {ir::Opcode::Closure, op_closure},
    {ir::Opcode::DeclaredClosure, op_declared_closure},
    {ir::Opcode::Noise, op_noise},
    {ir::Opcode::SNoise, op_noise},
    {ir::Opcode::PNoise, op_noise},
    {ir::Opcode::PSNoise, op_noise},
    {ir::Opcode::CellNoise, op_noise},
    {ir::Opcode::HashNoise, op_noise},
    {ir::Opcode::RayType, op_query},
    {ir::Opcode::Backfacing, op_query},
    {ir::Opcode::SurfaceArea, op_query},
    {ir::Opcode::IsConnected, op_query},
    {ir::Opcode::IsConstant, op_query},
    {ir::Opcode::GetAttribute, op_getattribute},
    {ir::Opcode::GetMessage, op_getmessage},
    {ir::Opcode::Trace, op_trace},
    {ir::Opcode::GetTextureInfo, op_gettextureinfo},
    {ir::Opcode::SetMessage, op_setmessage},
    {ir::Opcode::Spline, op_spline},
    {ir::Opcode::SplineInverse, op_spline},
    {ir::Opcode::Texture, op_texture},
    {ir::Opcode::Texture3d, op_texture3d},
    {ir::Opcode::Environment, op_texture3d},
};

} // namespace

std::span<const OpEntry> library_ops() { return kLibraryOps; }

} // namespace lobe::codegen
