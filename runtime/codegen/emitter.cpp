// LayerEmitter: storage, loads/stores with conversions, parameter set-up, control flow and the
// op loop of one layer function. The ops themselves are in ops_*.cpp.
#include "emitter.h"

#include "env.h"
#include "lobe/shading.h"
#include "shadeops.h"

#include <llvm/IR/Constants.h>
#include <llvm/IR/Intrinsics.h>

#include <cstring>

namespace lobe::codegen {

using ir::BaseType;
using ir::SymKind;

namespace {
int elements_of(const ir::Symbol& s) {
  if (s.type.arraylen > 0) return s.type.arraylen;
  if (s.type.arraylen < 0) {
    int c = s.type.components();
    return std::max<int>(1, int(s.init.size()) / c);
  }
  return 1;
}
int planes_of(const ir::Symbol& s) { return s.derivs ? 3 : 1; }
size_t scalar_bytes(const ir::Symbol& s) {
  return (s.type.base == BaseType::String || s.type.base == BaseType::Closure) ? 8 : 4;
}
// A symbol's name as the source spells it: a local that shadows another of its name is `x~2`
// in the IR, `x` in OSL's run-time messages.
std::string source_name(const std::string& name) {
  return std::string(name.begin(), std::find(name.begin(), name.end(), '~'));
}
} // namespace

size_t storage_bytes(const ir::Symbol& s) {
  // In size_t throughout: a huge array must not wrap (build_group checks the arrays against
  // kMaxLocalBytes before anything is laid out).
  return size_t(planes_of(s)) * size_t(elements_of(s)) * size_t(s.type.components()) *
         scalar_bytes(s);
}
size_t storage_offset(const ir::Symbol& s, int plane, int elem, int comp) {
  size_t idx = size_t((plane * elements_of(s) + elem) * s.type.components() + comp);
  return idx * scalar_bytes(s);
}

LayerEmitter::LayerEmitter(const GroupPlan& group, int layer, llvm::Module& module,
                           std::vector<llvm::Function*>& layer_fns, HostSymbols& host)
    : group_(group), layer_(layer), module_(module), layer_fns_(layer_fns), host_(host),
      b_(module.getContext()) {}

void LayerEmitter::fail(const ir::Op& op, const std::string& msg) {
  if (!error_.empty()) return;
  // `file:line:col: error: ...`, as the front end's diagnostics (the column when the op has one).
  std::string where = op.loc.file.empty() ? shader().name : op.loc.file;
  // Appended piecewise: ":" + to_string(...) trips GCC 12's false -Wrestrict.
  if (op.loc.line > 0) where.append(":").append(std::to_string(op.loc.line));
  if (op.loc.line > 0 && op.loc.column > 0) where.append(":").append(std::to_string(op.loc.column));
  error_ = where + ": error: " + ir::to_string(op.opcode) + ": " + msg;
}

llvm::Constant* LayerEmitter::host_address(const void* p) {
  if (!p) return llvm::ConstantPointerNull::get(b_.getPtrTy());
  for (const auto& [name, address] : host_)
    if (address == p) return module_.getNamedGlobal(name);
  // Opaque: nothing is assumed of the object's size or contents.
  llvm::StructType* opaque = llvm::StructType::getTypeByName(ctx(), "lobe.host");
  if (!opaque) opaque = llvm::StructType::create(ctx(), "lobe.host");
  std::string name = "lobe.host." + std::to_string(host_.size());
  host_.emplace_back(name, p);
  return new llvm::GlobalVariable(module_, opaque, /*isConstant=*/false,
                                  llvm::GlobalValue::ExternalLinkage, nullptr, name);
}

llvm::Value* LayerEmitter::env_ptr() { return host_address(group_.env); }

llvm::Value* LayerEmitter::colors_ptr() { return host_address(group_.colors); }

llvm::Value* LayerEmitter::string_const(const std::string& s) {
  return host_address(group_.env->strings.intern(s));
}

llvm::FunctionCallee LayerEmitter::shadeop(const char* name) {
  const shadeops::ShadeOpSymbol* s = shadeops::find_shadeop(name);
  if (!s) {
    error_ = std::string("internal: no shadeop ") + name;
    s = shadeops::find_shadeop("lobe_strlen");
  }
  auto type_of = [&](char c) -> llvm::Type* {
    switch (c) {
    case 'v':
      return b_.getVoidTy();
    case 'i':
      return i32();
    case 'l':
      return b_.getInt64Ty();
    case 'f':
      return f32();
    default:
      return ptr();
    }
  };
  std::vector<llvm::Type*> params;
  for (const char* c = s->sig + 1; *c; ++c) params.push_back(type_of(*c));
  auto* ft = llvm::FunctionType::get(type_of(s->sig[0]), params, false);
  return module_.getOrInsertFunction(s->name, ft);
}

llvm::Value* LayerEmitter::call(const char* name, std::vector<llvm::Value*> args) {
  return b_.CreateCall(shadeop(name), args);
}

llvm::AllocaInst* LayerEmitter::entry_alloca(llvm::Type* ty, unsigned count, const char* name) {
  llvm::IRBuilder<> eb(alloca_block_, alloca_block_->begin());
  auto* a = eb.CreateAlloca(ty, count > 1 ? eb.getInt32(count) : nullptr, name);
  a->setAlignment(llvm::Align(8));
  return a;
}

llvm::Type* LayerEmitter::scalar_type(const ir::Symbol& s) {
  switch (s.type.base) {
  case BaseType::Int:
    return i32();
  case BaseType::String:
  case BaseType::Closure:
    return ptr();
  default:
    return f32();
  }
}

llvm::Type* LayerEmitter::storage_type(const ir::Symbol& s) {
  unsigned n = unsigned(planes_of(s) * elements_of(s) * s.type.components());
  return llvm::ArrayType::get(scalar_type(s), n);
}

// Scalar constants have no storage (loads give LLVM constants); constant arrays are private
// globals; everything else is an alloca.
void LayerEmitter::create_storage() {
  const auto& syms = shader().symbols;
  storage_.assign(syms.size(), nullptr);
  fetched_flag_.assign(syms.size(), nullptr);
  for (size_t i = 0; i < syms.size(); ++i) {
    const ir::Symbol& s = syms[i];
    if (s.kind == SymKind::Const) {
      if (!s.type.is_array()) continue;
      std::vector<llvm::Constant*> elems;
      for (const ir::ConstValue& c : s.init) {
        if (s.type.base == BaseType::Int)
          elems.push_back(b_.getInt32(uint32_t(c.i)));
        else if (s.type.base == BaseType::String)
          elems.push_back(llvm::cast<llvm::Constant>(string_const(c.s)));
        else
          elems.push_back(llvm::ConstantFP::get(f32(), c.f));
      }
      auto* at = llvm::cast<llvm::ArrayType>(storage_type(s));
      while (elems.size() < at->getNumElements())
        elems.push_back(llvm::Constant::getNullValue(scalar_type(s)));
      elems.resize(at->getNumElements());
      storage_[i] = new llvm::GlobalVariable(module_, at, true, llvm::GlobalValue::PrivateLinkage,
                                             llvm::ConstantArray::get(at, elems), s.name);
      continue;
    }
    storage_[i] = entry_alloca(storage_type(s), 1, s.name.c_str());
  }
  for (const ConnectionPlan& c : plan().connections)
    if (!fetched_flag_[size_t(c.dst_symbol)])
      fetched_flag_[size_t(c.dst_symbol)] = entry_alloca(b_.getInt1Ty(), 1, "fetched");
}

llvm::Value* LayerEmitter::address(int symbol, int plane, llvm::Value* elem, int comp) {
  const ir::Symbol& s = sym(symbol);
  int comps = s.type.components();
  llvm::Value* idx;
  if (!elem || llvm::isa<llvm::ConstantInt>(elem)) {
    int e = elem ? int(llvm::cast<llvm::ConstantInt>(elem)->getSExtValue()) : 0;
    idx = iconst((plane * elements_of(s) + e) * comps + comp);
  } else {
    idx = b_.CreateAdd(b_.CreateMul(elem, iconst(comps)),
                       iconst(plane * elements_of(s) * comps + comp));
  }
  return b_.CreateInBoundsGEP(storage_type(s), storage_[size_t(symbol)], {iconst(0), idx});
}

llvm::Value* LayerEmitter::groupdata_address(int layer, int symbol, int plane, int elem, int comp) {
  const LayerPlan& lp = group_.layers[size_t(layer)];
  const ir::Symbol& s = lp.shader->symbols[size_t(symbol)];
  size_t off = size_t(lp.symbol_offset[size_t(symbol)]) + storage_offset(s, plane, elem, comp);
  return b_.CreateInBoundsGEP(b_.getInt8Ty(), gd_, b_.getInt64(off));
}

Val LayerEmitter::load(int symbol, llvm::Value* elem, bool derivs) {
  const ir::Symbol& s = sym(symbol);
  int comps = s.type.components();
  Val v(static_cast<size_t>(comps));
  if (s.kind == SymKind::Const && !s.type.is_array()) {
    for (int c = 0; c < comps; ++c) {
      const ir::ConstValue cv = size_t(c) < s.init.size() ? s.init[size_t(c)] : ir::ConstValue{};
      if (s.type.base == BaseType::Int)
        v[size_t(c)].v = iconst(cv.i);
      else if (s.type.base == BaseType::String)
        v[size_t(c)].v = string_const(cv.s);
      else if (s.type.base == BaseType::Closure)
        v[size_t(c)].v = llvm::ConstantPointerNull::get(b_.getPtrTy());
      else
        v[size_t(c)].v = fconst(cv.f);
    }
    return v;
  }
  llvm::Type* st = scalar_type(s);
  for (int c = 0; c < comps; ++c) {
    v[size_t(c)].v = b_.CreateLoad(st, address(symbol, 0, elem, c));
    if (s.derivs && derivs) {
      v[size_t(c)].dx = b_.CreateLoad(st, address(symbol, 1, elem, c));
      v[size_t(c)].dy = b_.CreateLoad(st, address(symbol, 2, elem, c));
    }
  }
  return v;
}

void LayerEmitter::store(int symbol, const Val& v, llvm::Value* elem) {
  const ir::Symbol& s = sym(symbol);
  if (s.kind == SymKind::Const) return;
  int comps = s.type.components();
  for (int c = 0; c < comps && size_t(c) < v.size(); ++c) {
    b_.CreateStore(v[size_t(c)].v, address(symbol, 0, elem, c));
    if (s.derivs) {
      llvm::Value* zero = llvm::Constant::getNullValue(scalar_type(s));
      b_.CreateStore(v[size_t(c)].dx ? v[size_t(c)].dx : zero, address(symbol, 1, elem, c));
      b_.CreateStore(v[size_t(c)].dy ? v[size_t(c)].dy : zero, address(symbol, 2, elem, c));
    }
  }
}

Val LayerEmitter::convert(const Val& v, BaseType from, BaseType to) {
  bool ff = is_float_based(from), tf = is_float_based(to);
  if (from == to || (ir::Type{from, 0}.is_triple() && ir::Type{to, 0}.is_triple())) return v;
  if (to == BaseType::Closure) // int 0 -> the null closure
    return Val{Dual{llvm::ConstantPointerNull::get(b_.getPtrTy())}};
  if (from == BaseType::Int && tf) {
    Dual d{b_.CreateSIToFP(v[0].v, f32())};
    return convert(Val{d}, BaseType::Float, to);
  }
  if (ff && to == BaseType::Int) {
    // Truncation; NaN and values outside int32 give INT_MIN, as x86's cvttss2si does in OSL
    // (math::cvtt, which the constant folder uses: the same answer folded or not).
    llvm::Value* f = v[0].v;
    llvm::Value* in_range =
        b_.CreateFCmpOLT(b_.CreateUnaryIntrinsic(llvm::Intrinsic::fabs, f), fconst(2147483648.0f));
    llvm::Value* x = b_.CreateSelect(in_range, b_.CreateFPToSI(f, i32()), iconst(INT32_MIN));
    return Val{Dual{x}};
  }
  if (from == BaseType::Float && ir::Type{to, 0}.is_triple()) return Val{v[0], v[0], v[0]};
  if (from == BaseType::Float && to == BaseType::Matrix) {
    Val m(16, Dual{fconst(0)});
    for (int i = 0; i < 4; ++i) m[size_t(i * 5)] = Dual{v[0].v};
    return m;
  }
  if (ir::Type{from, 0}.is_triple() && to == BaseType::Float) return Val{v[0]};
  return v; // the verifier rejects other combinations; keep what we have
}

Val LayerEmitter::load_as(const ir::Op& op, int i, BaseType to, bool derivs) {
  int s = op.args[size_t(i)];
  return convert(load(s, nullptr, derivs), sym(s).type.base, to);
}

llvm::Value* LayerEmitter::storage_address(int symbol) {
  if (storage_[size_t(symbol)]) return address(symbol, 0, nullptr, 0);
  std::vector<llvm::Value*> comps;
  for (const Dual& d : load(symbol, nullptr, false)) comps.push_back(d.v);
  return spill(comps, scalar_type(sym(symbol)));
}

llvm::Value* LayerEmitter::spill(const std::vector<llvm::Value*>& comps, llvm::Type* ty) {
  if (!ty) ty = f32();
  auto* a =
      entry_alloca(llvm::ArrayType::get(ty, unsigned(std::max<size_t>(1, comps.size()))), 1, "tmp");
  for (size_t i = 0; i < comps.size(); ++i)
    b_.CreateStore(comps[i],
                   b_.CreateConstInBoundsGEP2_32(a->getAllocatedType(), a, 0, unsigned(i)));
  return a;
}

std::vector<llvm::Value*> LayerEmitter::reload(llvm::Value* p, int n, llvm::Type* ty) {
  if (!ty) ty = f32();
  std::vector<llvm::Value*> out;
  auto* at = llvm::ArrayType::get(ty, unsigned(n));
  for (int i = 0; i < n; ++i)
    out.push_back(b_.CreateLoad(ty, b_.CreateConstInBoundsGEP2_32(at, p, 0, unsigned(i))));
  return out;
}

llvm::Value* LayerEmitter::truthy(const Val& v, BaseType t) {
  if (t == BaseType::Int) return b_.CreateICmpNE(v[0].v, iconst(0));
  if (t == BaseType::String || t == BaseType::Closure) return b_.CreateIsNotNull(v[0].v);
  llvm::Value* any = nullptr;
  for (const Dual& d : v) {
    llvm::Value* nz = b_.CreateFCmpUNE(d.v, fconst(0));
    any = any ? b_.CreateOr(any, nz) : nz;
  }
  return any;
}

std::string LayerEmitter::layer_description() const {
  return "group " + (group_.group_name.empty() ? "unnamed_group" : group_.group_name) + ", layer " +
         std::to_string(plan().group_index) + " " + plan().layer_name + ", shader " + shader().name;
}

llvm::Value* LayerEmitter::clamped_index(const ir::Op& op, int index_arg, int length) {
  const ir::Symbol& is = arg(op, index_arg);
  if (is.kind == SymKind::Const && !is.type.is_array()) {
    int i =
        is.init.empty() ? 0 : (is.type.base == BaseType::Int ? is.init[0].i : int(is.init[0].f));
    return iconst(std::clamp(i, 0, std::max(0, length - 1)));
  }
  llvm::Value* idx = load_as(op, index_arg, BaseType::Int)[0].v;
  llvm::Value* lo = b_.CreateSelect(b_.CreateICmpSLT(idx, iconst(0)), iconst(0), idx);
  return b_.CreateSelect(b_.CreateICmpSGT(lo, iconst(length - 1)), iconst(length - 1), lo);
}

llvm::Value* LayerEmitter::checked_index(const ir::Op& op, int index_arg, int length) {
  if (!group_.range_checking) return clamped_index(op, index_arg, length);
  const ir::Symbol& is = arg(op, index_arg);
  if (is.kind == SymKind::Const && !is.type.is_array()) {
    int i =
        is.init.empty() ? 0 : (is.type.base == BaseType::Int ? is.init[0].i : int(is.init[0].f));
    if (i >= 0 && i < length) return iconst(i);
  }
  llvm::Value* idx = load_as(op, index_arg, BaseType::Int)[0].v;
  llvm::Value* bad = b_.CreateICmpUGE(idx, iconst(length));
  auto* report = llvm::BasicBlock::Create(ctx(), "range_error", fn_);
  auto* ok = llvm::BasicBlock::Create(ctx(), "range_ok", fn_);
  b_.CreateCondBr(bad, report, ok);
  b_.SetInsertPoint(report);
  // The indexed symbol: the destination of an element store, else the source.
  bool store = op.opcode == ir::Opcode::AAssign || op.opcode == ir::Opcode::CompAssign ||
               op.opcode == ir::Opcode::MxCompAssign;
  const ir::Symbol& what = arg(op, store ? 0 : 1);
  std::string where = "(";
  where.append(layer_description()).append(")");
  call("lobe_range_error", {sg_, idx, iconst(length), string_const(source_name(what.name)),
                            string_const(op.loc.file.empty() ? shader().name : op.loc.file),
                            iconst(op.loc.line), string_const(where)});
  b_.CreateBr(ok);
  b_.SetInsertPoint(ok);
  llvm::Value* lo = b_.CreateSelect(b_.CreateICmpSLT(idx, iconst(0)), iconst(0), idx);
  return b_.CreateSelect(b_.CreateICmpSGT(lo, iconst(length - 1)), iconst(length - 1), lo);
}

} // namespace lobe::codegen

namespace lobe::codegen {

namespace {
// The op's name as OSL's run-time checks print it: Lobe's `construct` is OSL's type-named
// constructor op (`color`, `point`, ...), a conditional branch OSL's `if`.
std::string osl_opname(const ir::Op& op, const ir::Shader& sh) {
  if (op.opcode == ir::Opcode::Construct && !op.args.empty())
    return to_string(sh.symbols[size_t(op.args[0])].type.base);
  if (op.opcode == ir::Opcode::Cbr) return "if";
  if (op.opcode == ir::Opcode::DeclaredClosure) return "closure";
  return ir::to_string(op.opcode);
}
} // namespace

// The op numbers OSL's debug_uninit messages give, for a shader as oslc compiles it: Lobe's
// `br` ops (the jump back of a loop, over an else) are part of OSL's `for`/`if` ops, and OSL
// inserts its own `useparam` ops: before an op, one for each input parameter the op reads
// that no earlier op outside a conditional read, and one at the start of the main code for the
// outputs connected or read downstream (LayerPlan::osl_output_useparam), and a `functioncall`
// op before each inlined user function's body (ir::Op::calls_begin) and a `return` op for a
// return before its end (ir::Op::osl_return); Lobe's useparam ops are not counted.
void LayerEmitter::number_ops_as_osl() {
  const auto& ops = shader().ops;
  osl_opnum_.assign(ops.size(), 0);
  int furthest = -1;
  std::vector<bool> used(shader().symbols.size(), false);
  int n = 0;
  for (size_t i = 0; i < ops.size(); ++i) {
    const ir::Op& op = ops[i];
    if (int(i) == shader().main_begin && plan().osl_output_useparam) ++n;
    bool conditional = furthest > int(i);
    n += op.calls_begin; // OSL's functioncall ops
    if (op.opcode != ir::Opcode::UseParam && (op.opcode != ir::Opcode::Br || op.osl_return)) {
      std::vector<int> fresh;
      for (size_t a = 0; a < op.args.size(); ++a) {
        int si = op.args[a];
        if (op.writes(int(a)) || sym(si).kind != SymKind::Param || used[size_t(si)]) continue;
        if (std::find(fresh.begin(), fresh.end(), si) == fresh.end()) fresh.push_back(si);
      }
      n += int(fresh.size());
      if (!conditional)
        for (int si : fresh) used[size_t(si)] = true;
      osl_opnum_[i] = n++;
    } else {
      osl_opnum_[i] = n;
    }
    if (op.opcode == ir::Opcode::Cbr)
      for (int t : op.jumps) furthest = std::max(furthest, t);
  }
}

// OSL's debug_uninit: each operand the op reads (but no constant or global, closure or struct
// of them) is checked as a whole, except an aref/compref/mxcompref source, of which only the
// element or component read is.
void LayerEmitter::check_uninit_reads(int index) {
  const ir::Op& op = shader().ops[size_t(index)];
  std::string opname = osl_opname(op, shader());
  for (size_t a = 0; a < op.args.size(); ++a) {
    if (op.writes(int(a))) continue;
    int si = op.args[a];
    const ir::Symbol& s = sym(si);
    if (s.kind == SymKind::Const || s.kind == SymKind::Global || !storage_[size_t(si)]) continue;
    if (s.type.base == BaseType::Closure) continue;
    // The value after an attribute name of pointcloud_search/get is where it is written.
    if ((op.opcode == ir::Opcode::PointcloudSearch || op.opcode == ir::Opcode::PointcloudGet) &&
        a > 0 && sym(op.args[a - 1]).type.base == BaseType::String)
      continue;
    int comps = s.type.components();
    llvm::Value* first = iconst(0);
    llvm::Value* count = iconst(elements_of(s) * comps);
    if (a == 1 && op.opcode == ir::Opcode::ARef && op.args.size() > 2 && s.type.is_array()) {
      first = b_.CreateMul(clamped_index(op, 2, elements_of(s)), iconst(comps));
      count = iconst(comps);
    } else if (a == 1 && op.opcode == ir::Opcode::CompRef && op.args.size() > 2 &&
               !s.type.is_array()) {
      first = clamped_index(op, 2, comps);
      count = iconst(1);
    } else if (a == 1 && op.opcode == ir::Opcode::MxCompRef && op.args.size() > 3 &&
               !s.type.is_array()) {
      first =
          b_.CreateAdd(b_.CreateMul(clamped_index(op, 2, 4), iconst(4)), clamped_index(op, 3, 4));
      count = iconst(1);
    }
    int kind = s.type.base == BaseType::Int ? 1 : s.type.base == BaseType::String ? 2 : 0;
    call("lobe_uninit_check",
         {sg_, env_ptr(), address(si, 0, nullptr, 0), iconst(kind), first, count,
          string_const(to_string(s.type)), string_const(source_name(s.name)),
          string_const(op.loc.file.empty() ? shader().name : op.loc.file), iconst(op.loc.line),
          string_const(layer_description()),
          iconst(size_t(index) < osl_opnum_.size() ? osl_opnum_[size_t(index)] : index),
          string_const(opname), iconst(int(a))});
  }
}

// OSL's debug_nan: each float-based operand the op wrote is checked, values and derivatives;
// of an aassign/compassign/mxcompassign destination only the element or component written.
void LayerEmitter::check_nan_writes(int index) {
  const ir::Op& op = shader().ops[size_t(index)];
  std::string opname = osl_opname(op, shader());
  for (size_t a = 0; a < op.args.size(); ++a) {
    if (!op.writes(int(a))) continue;
    int si = op.args[a];
    const ir::Symbol& s = sym(si);
    if (s.kind == SymKind::Const || !storage_[size_t(si)] || !is_float_based(s.type.base)) continue;
    int comps = s.type.components();
    int all = elements_of(s) * comps;
    llvm::Value* first = iconst(0);
    llvm::Value* count = iconst(all);
    if (a == 0 && op.opcode == ir::Opcode::AAssign && op.args.size() > 2 && s.type.is_array()) {
      first = b_.CreateMul(clamped_index(op, 1, elements_of(s)), iconst(comps));
      count = iconst(comps);
    } else if (a == 0 && op.opcode == ir::Opcode::CompAssign && op.args.size() > 2 &&
               !s.type.is_array()) {
      first = clamped_index(op, 1, comps);
      count = iconst(1);
    } else if (a == 0 && op.opcode == ir::Opcode::MxCompAssign && op.args.size() > 3 &&
               !s.type.is_array()) {
      first =
          b_.CreateAdd(b_.CreateMul(clamped_index(op, 1, 4), iconst(4)), clamped_index(op, 2, 4));
      count = iconst(1);
    }
    call("lobe_naninf_check",
         {sg_, address(si, 0, nullptr, 0), iconst(all), iconst(s.derivs ? 1 : 0), first, count,
          string_const(source_name(s.name)),
          string_const(op.loc.file.empty() ? shader().name : op.loc.file), iconst(op.loc.line),
          string_const(opname)});
  }
}

} // namespace lobe::codegen
