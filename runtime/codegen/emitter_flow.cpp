// LayerEmitter: the layer function's frame (entry, parameter set-up, exit), control flow
// (basic blocks at jump targets, `br`/`cbr`/`exit`), lazy upstream layers (`useparam`), and
// emit_group, which creates one function per layer plus the group entry.
#include "emitter.h"

#include "env.h"
#include "ir/edit.h"
#include "lobe/shading.h"

#include <llvm/IR/Constants.h>
#include <llvm/IR/MDBuilder.h>
#include <llvm/IR/Verifier.h>
#include <llvm/Support/raw_ostream.h>

#include <algorithm>
#include <limits>

namespace lobe::codegen {

using ir::BaseType;
using ir::SymKind;

namespace {
const GlobalField* find_global(const std::string& name) {
  for (const GlobalField& g : kGlobalFields)
    if (name == g.name) return &g;
  return nullptr;
}
} // namespace

bool LayerEmitter::is_leader(int i) const {
  return i >= 0 && size_t(i) < leader_.size() && leader_[size_t(i)];
}

llvm::BasicBlock* LayerEmitter::block_at(int i) {
  if (i == region_end_) return region_after_;
  auto it = blocks_.find(i);
  if (it != blocks_.end()) return it->second;
  auto* bb = llvm::BasicBlock::Create(ctx(), "op" + std::to_string(i), fn_);
  blocks_[i] = bb;
  return bb;
}

void LayerEmitter::emit_exit() { b_.CreateBr(exit_block_); }

// Locals and temps start zeroed (strings ""), globals are read from ShaderGlobals. With
// debug_uninit the values of locals and temps start as OSL's markers instead: NaN, INT_MIN and
// the marker string (their derivatives zero).
void LayerEmitter::init_symbols() {
  const auto& syms = shader().symbols;
  for (size_t i = 0; i < syms.size(); ++i) {
    const ir::Symbol& s = syms[i];
    int si = int(i);
    if (s.kind == SymKind::Local || s.kind == SymKind::Temp) {
      b_.CreateMemSet(storage_[i], b_.getInt8(0), storage_bytes(s), llvm::MaybeAlign(8));
      bool mark = group_.debug_uninit && s.type.base != BaseType::Closure;
      if (s.type.base == BaseType::String || mark) {
        // The value plane only: [elements][components] scalars at the start of the storage.
        int n = int(storage_bytes(s) / (s.type.base == BaseType::String ? 8 : 4));
        if (s.derivs) n /= 3;
        llvm::Type* st = scalar_type(s);
        llvm::Value* v = s.type.base == BaseType::String
                             ? string_const(mark ? shadeops::kUninitializedString : "")
                         : s.type.base == BaseType::Int ? iconst(std::numeric_limits<int>::min())
                                                        : llvm::ConstantFP::getNaN(f32());
        for (int k = 0; k < n; ++k)
          b_.CreateStore(v, b_.CreateConstInBoundsGEP2_32(llvm::ArrayType::get(st, unsigned(n)),
                                                          storage_[i], 0, unsigned(k)));
      }
    } else if (s.kind == SymKind::Global) {
      const GlobalField* g = find_global(s.name);
      if (!g) {
        error_ = shader().name + ": unknown global '" + s.name + "'";
        return;
      }
      Val v(static_cast<size_t>(s.type.components()));
      read_global(s, *g, v);
      store(si, v);
    }
  }
}

// Params: the value in group data (instance value or constant default), then the renderer's
// user data for `lockgeom = 0` params, then computed defaults (unless user data came);
// connections are fetched eagerly when the layer has no `useparam` ops.
void LayerEmitter::init_params() {
  const auto& syms = shader().symbols;
  for (size_t i = 0; i < syms.size(); ++i) {
    const ir::Symbol& s = syms[i];
    if (s.kind != SymKind::Param && s.kind != SymKind::OutputParam) continue;
    if (plan().symbol_offset[i] >= 0) {
      b_.CreateMemCpy(storage_[i], llvm::MaybeAlign(8), groupdata_address(layer_, int(i), 0, 0, 0),
                      llvm::MaybeAlign(4), storage_bytes(s));
    } else {
      b_.CreateMemSet(storage_[i], b_.getInt8(0), storage_bytes(s), llvm::MaybeAlign(8));
    }
  }
  for (const ConnectionPlan& c : plan().connections)
    b_.CreateStore(b_.getFalse(), fetched_flag_[size_t(c.dst_symbol)]);
  // In declaration order, so that a computed default sees the user data of earlier params.
  for (size_t i = 0; i < syms.size(); ++i) {
    const ir::Symbol& s = syms[i];
    llvm::Value* found = nullptr; // i1: the renderer had user data for it
    if (i < plan().userdata.size() && plan().userdata[i]) {
      llvm::Value* r = call("lobe_get_userdata",
                            {sg_, env_ptr(), string_const(s.name), iconst(type_code(s.type)),
                             iconst(s.derivs ? 1 : 0), storage_address(int(i))});
      found = b_.CreateICmpNE(r, iconst(0));
    }
    if (i < plan().run_default.size() && plan().run_default[i] && s.init_begin >= 0) {
      auto* after = llvm::BasicBlock::Create(ctx(), "default_done", fn_);
      if (found) {
        auto* compute = llvm::BasicBlock::Create(ctx(), "default", fn_);
        b_.CreateCondBr(found, after, compute);
        b_.SetInsertPoint(compute);
      }
      emit_region(s.init_begin, s.init_end, after);
      b_.SetInsertPoint(after);
    }
  }
  // OSL begins a layer's main code with a `useparam` of its connected output parameters
  // (LayerPlan::osl_output_useparam): one connected into runs its upstream layer now, before
  // the layer's own code.
  for (const ConnectionPlan& c : plan().connections)
    if (syms[size_t(c.dst_symbol)].kind == SymKind::OutputParam) run_useparam(c.dst_symbol);
  // Without useparam ops (IR written by hand) the connections are fetched here, but only
  // those of params something reads (an op, or a downstream layer through a connection from
  // the param): as OSL, an upstream layer whose value nothing reads does not run.
  const auto& ops = shader().ops;
  if (shader().useparams) return; // the useparam ops fetch them where they are first read
  std::vector<bool> read(syms.size(), false);
  for (const ir::Op& op : ops)
    for (size_t a = 0; a < op.args.size(); ++a)
      if (ir::op_reads(op, int(a))) read[size_t(op.args[a])] = true;
  for (const LayerPlan& lp : group_.layers)
    for (const ConnectionPlan& c : lp.connections)
      if (c.src_layer == layer_) read[size_t(c.src_symbol)] = true;
  for (const ConnectionPlan& c : plan().connections)
    if (read[size_t(c.dst_symbol)]) run_useparam(c.dst_symbol);
}

// Runs the upstream layer if it has not run yet and copies the connected value, once.
void LayerEmitter::run_useparam(int symbol) {
  llvm::Value* flag = fetched_flag_[size_t(symbol)];
  if (!flag) return;
  auto* fetch = llvm::BasicBlock::Create(ctx(), "fetch", fn_);
  auto* done = llvm::BasicBlock::Create(ctx(), "fetched", fn_);
  b_.CreateCondBr(b_.CreateLoad(b_.getInt1Ty(), flag), done, fetch);
  b_.SetInsertPoint(fetch);
  for (const ConnectionPlan& c : plan().connections)
    if (c.dst_symbol == symbol) fetch_connection(c);
  b_.CreateStore(b_.getTrue(), flag);
  b_.CreateBr(done);
  b_.SetInsertPoint(done);
}

void LayerEmitter::fetch_connection(const ConnectionPlan& c) {
  const LayerPlan& up = group_.layers[size_t(c.src_layer)];
  llvm::Value* ran = b_.CreateLoad(
      i32(), b_.CreateConstInBoundsGEP1_64(b_.getInt8Ty(), gd_, size_t(up.ran_offset)));
  auto* run = llvm::BasicBlock::Create(ctx(), "run_upstream", fn_);
  auto* have = llvm::BasicBlock::Create(ctx(), "upstream_done", fn_);
  b_.CreateCondBr(b_.CreateICmpEQ(ran, iconst(0)), run, have);
  b_.SetInsertPoint(run);
  store_globals();
  b_.CreateCall(layer_fns_[size_t(c.src_layer)], {sg_, gd_});
  reload_globals();
  b_.CreateBr(have);
  b_.SetInsertPoint(have);

  const ir::Symbol& src = up.shader->symbols[size_t(c.src_symbol)];
  const ir::Symbol& dst = sym(c.dst_symbol);
  int src_comps = src.type.components();
  llvm::Type* st = src.type.base == BaseType::Int ? i32()
                   : (src.type.base == BaseType::String || src.type.base == BaseType::Closure)
                       ? ptr()
                       : f32();
  int selem = c.src_element < 0 ? 0 : c.src_element;
  int c0 = c.src_component < 0 ? 0 : c.src_component;
  int nc = c.src_component < 0 ? src_comps : 1;
  BaseType from = c.src_component < 0 ? src.type.base : BaseType::Float;
  // Whole arrays are copied element by element; otherwise one element (or component).
  int nelem = (c.src_element < 0 && src.type.is_array() && c.dst_element < 0)
                  ? std::min(std::max(1, src.type.arraylen), std::max(1, dst.type.arraylen))
                  : 1;
  for (int e = 0; e < nelem; ++e) {
    Val v(static_cast<size_t>(nc));
    for (int k = 0; k < nc; ++k) {
      v[size_t(k)].v =
          b_.CreateLoad(st, groupdata_address(c.src_layer, c.src_symbol, 0, selem + e, c0 + k));
      if (src.derivs) {
        v[size_t(k)].dx =
            b_.CreateLoad(st, groupdata_address(c.src_layer, c.src_symbol, 1, selem + e, c0 + k));
        v[size_t(k)].dy =
            b_.CreateLoad(st, groupdata_address(c.src_layer, c.src_symbol, 2, selem + e, c0 + k));
      }
    }
    llvm::Value* delem = iconst(c.dst_element < 0 ? e : c.dst_element);
    if (c.dst_component >= 0) {
      Val whole = load(c.dst_symbol, delem);
      whole[size_t(c.dst_component)] = convert(v, from, BaseType::Float)[0];
      store(c.dst_symbol, whole, delem);
    } else {
      store(c.dst_symbol, convert(v, from, dst.type.base), delem);
    }
  }
}

// Emits ops [begin, end) starting in a new block; falls through (or jumps to `end`) to `after`.
void LayerEmitter::emit_region(int begin, int end, llvm::BasicBlock* after) {
  int saved_end = region_end_;
  llvm::BasicBlock* saved_after = region_after_;
  region_end_ = end;
  region_after_ = after;
  llvm::BasicBlock* first = block_at(begin);
  if (begin == end) first = after;
  b_.CreateBr(first);
  for (int i = begin; i < end && !failed(); ++i) {
    if (i == begin || is_leader(i)) {
      llvm::BasicBlock* bb = block_at(i);
      if (!b_.GetInsertBlock()->getTerminator()) b_.CreateBr(bb);
      b_.SetInsertPoint(bb);
    }
    emit_op(i);
  }
  if (!b_.GetInsertBlock()->getTerminator()) b_.CreateBr(after);
  region_end_ = saved_end;
  region_after_ = saved_after;
}

void LayerEmitter::emit_op(int index) {
  const ir::Op& op = shader().ops[size_t(index)];
  if (op.opcode == ir::Opcode::Nop) return;
  if (loop_budget_ && ir::is_jump(op.opcode))
    for (int t : op.jumps)
      if (t >= 0 && t <= index) {
        emit_loop_check(op);
        break;
      }
  if (op.opcode == ir::Opcode::Br) {
    b_.CreateBr(block_at(op.jumps.at(0)));
  } else if (op.opcode == ir::Opcode::Cbr) {
    if (group_.debug_uninit) check_uninit_reads(index);
    llvm::Value* c = truthy(load(op.args[0], nullptr, false), arg(op, 0).type.base);
    b_.CreateCondBr(c, block_at(op.jumps.at(0)), block_at(op.jumps.at(1)));
  } else if (op.opcode == ir::Opcode::Exit) {
    emit_exit();
  } else if (op.opcode == ir::Opcode::UseParam) {
    for (int a : op.args) run_useparam(a);
  } else if (OpEmitFn fn = op_emitter(op.opcode)) {
    if (group_.debug_uninit) check_uninit_reads(index);
    fn(*this, op);
    if (group_.debug_nan && !b_.GetInsertBlock()->getTerminator()) check_nan_writes(index);
  } else {
    fail(op, "not supported by codegen");
  }
  // Code after a terminator (an op following `exit` in the same block) goes to a dead block.
  if (b_.GetInsertBlock()->getTerminator() && !is_leader(index + 1))
    b_.SetInsertPoint(llvm::BasicBlock::Create(ctx(), "dead", fn_));
}

// One more iteration of a loop: the budget counts down; at zero lobe_loop_check says whether
// the shade may go on (a new chunk) or must stop (0: the layer returns now).
void LayerEmitter::emit_loop_check(const ir::Op& op) {
  llvm::Type* i64 = b_.getInt64Ty();
  llvm::Value* left = b_.CreateSub(b_.CreateLoad(i64, loop_budget_), b_.getInt64(1));
  b_.CreateStore(left, loop_budget_);
  auto* check = llvm::BasicBlock::Create(ctx(), "loop_check", fn_);
  auto* stop = llvm::BasicBlock::Create(ctx(), "loop_stop", fn_);
  auto* go = llvm::BasicBlock::Create(ctx(), "loop_go", fn_);
  llvm::MDBuilder md(ctx());
  b_.CreateCondBr(b_.CreateICmpSLE(left, b_.getInt64(0)), check, go,
                  md.createBranchWeights(1, 1 << 20));
  b_.SetInsertPoint(check);
  std::string where = "layer " + std::to_string(plan().group_index) + " " + plan().layer_name;
  if (!group_.group_name.empty()) where = "group " + group_.group_name + ", " + where;
  llvm::Value* more = call(
      "lobe_loop_check",
      {sg_, b_.CreateConstInBoundsGEP1_64(b_.getInt8Ty(), gd_, size_t(group_.loop_count_offset)),
       b_.getInt64(uint64_t(std::min(
           kLoopChunk, group_.max_loop_iterations > 0 ? group_.max_loop_iterations : kLoopChunk))),
       b_.getInt64(uint64_t(group_.max_loop_iterations)), string_const(shader().name),
       string_const(where), string_const(op.loc.file.empty() ? shader().name : op.loc.file),
       iconst(op.loc.line)});
  b_.CreateStore(more, loop_budget_);
  b_.CreateCondBr(b_.CreateICmpSGT(more, b_.getInt64(0)), go, stop);
  b_.SetInsertPoint(stop);
  b_.CreateBr(exit_block_);
  b_.SetInsertPoint(go);
}

llvm::Type* LayerEmitter::global_type(const GlobalField& g) {
  return g.kind == GlobalKind::Closure ? ptr() : (g.kind == GlobalKind::Int ? i32() : f32());
}

void LayerEmitter::store_globals() {
  const auto& syms = shader().symbols;
  for (size_t i = 0; i < syms.size(); ++i) {
    if (syms[i].kind != SymKind::Global || !written_[i]) continue;
    const GlobalField* g = find_global(syms[i].name);
    // With its derivatives when it carries them (group_build: another layer reads them).
    bool derivs = syms[i].derivs && g->dx;
    Val v = load(int(i), nullptr, derivs);
    auto put = [&](llvm::Value* x, size_t offset, size_t c) {
      b_.CreateStore(x ? x : fconst(0), global_slot(offset, c));
    };
    for (size_t c = 0; c < v.size(); ++c) {
      put(v[c].v, g->offset, c);
      if (derivs) {
        put(v[c].dx, find_global(g->dx)->offset, c);
        put(v[c].dy, find_global(g->dy)->offset, c);
      }
    }
  }
}

// The address of component `c` of the ShaderGlobals field at `offset`.
llvm::Value* LayerEmitter::global_slot(size_t offset, size_t c) {
  return b_.CreateConstInBoundsGEP1_64(b_.getInt8Ty(), sg_, offset + 4 * c);
}

// The value of global `s` from ShaderGlobals into `v`, and its derivatives when it carries them
// and ShaderGlobals has them (other derivatives in `v` stay as they are).
void LayerEmitter::read_global(const ir::Symbol& s, const GlobalField& g, Val& v) {
  llvm::Type* t = global_type(g);
  auto get = [&](size_t offset, size_t c) { return b_.CreateLoad(t, global_slot(offset, c)); };
  bool derivs = s.derivs && g.dx;
  for (size_t c = 0; c < v.size(); ++c) {
    v[c].v = get(g.offset, c);
    if (derivs) {
      v[c].dx = get(find_global(g.dx)->offset, c);
      v[c].dy = get(find_global(g.dy)->offset, c);
    }
  }
}

void LayerEmitter::reload_globals() {
  const auto& syms = shader().symbols;
  for (size_t i = 0; i < syms.size(); ++i) {
    if (syms[i].kind != SymKind::Global) continue;
    Val v = load(int(i)); // with its derivatives: those ShaderGlobals lacks stay as they are
    read_global(syms[i], *find_global(syms[i].name), v);
    store(int(i), v);
  }
}

// Stores output params (and every param or global another layer reads) to group data and the
// written globals back to ShaderGlobals.
void LayerEmitter::finish_exit_block() {
  b_.SetInsertPoint(exit_block_);
  const auto& syms = shader().symbols;
  std::vector<bool> is_source(syms.size(), false);
  for (const LayerPlan& lp : group_.layers)
    for (const ConnectionPlan& c : lp.connections)
      if (c.src_layer == layer_) is_source[size_t(c.src_symbol)] = true;
  // A connected input that leads on to another layer holds its upstream value when it leaves,
  // read or not, as OSL resolves it (the upstream layer runs now if nothing here read it).
  for (const ConnectionPlan& c : plan().connections)
    if (is_source[size_t(c.dst_symbol)]) run_useparam(c.dst_symbol);
  for (size_t i = 0; i < syms.size(); ++i) {
    const ir::Symbol& s = syms[i];
    bool param = s.kind == SymKind::Param || s.kind == SymKind::OutputParam;
    bool global_source = s.kind == SymKind::Global && is_source[i];
    if ((param || global_source) && plan().symbol_offset[i] >= 0 &&
        (s.kind == SymKind::OutputParam || is_source[i]))
      b_.CreateMemCpy(groupdata_address(layer_, int(i), 0, 0, 0), llvm::MaybeAlign(4), storage_[i],
                      llvm::MaybeAlign(8), storage_bytes(s));
  }
  store_globals();
  b_.CreateRetVoid();
}

bool LayerEmitter::emit() {
  fn_ = layer_fns_[size_t(layer_)];
  sg_ = fn_->getArg(0);
  gd_ = fn_->getArg(1);
  alloca_block_ = llvm::BasicBlock::Create(ctx(), "entry", fn_);
  auto* start = llvm::BasicBlock::Create(ctx(), "start", fn_);
  exit_block_ = llvm::BasicBlock::Create(ctx(), "exit", fn_);
  const auto& ops = shader().ops;
  leader_.assign(ops.size() + 1, 0);
  for (size_t i = 0; i < ops.size(); ++i) {
    if (ir::is_jump(ops[i].opcode)) {
      leader_[i + 1] = 1;
      for (int t : ops[i].jumps)
        if (t >= 0 && size_t(t) <= ops.size()) leader_[size_t(t)] = 1;
    }
  }
  written_.assign(shader().symbols.size(), false);
  for (const ir::Op& op : ops)
    for (size_t a = 0; a < op.args.size(); ++a)
      if (op.writes(int(a))) written_[size_t(op.args[a])] = true;
  if (group_.debug_uninit) number_ops_as_osl();
  b_.SetInsertPoint(start);
  create_storage();
  if (group_.loop_count_offset >= 0 && group_.max_loop_iterations >= 0) {
    bool loops = false;
    for (size_t i = 0; i < ops.size(); ++i)
      if (ir::is_jump(ops[i].opcode))
        for (int t : ops[i].jumps) loops |= t >= 0 && size_t(t) <= i;
    if (loops) {
      loop_budget_ = entry_alloca(b_.getInt64Ty(), 1, "loop_budget");
      int64_t chunk = group_.max_loop_iterations > 0
                          ? std::min(kLoopChunk, group_.max_loop_iterations)
                          : kLoopChunk;
      b_.CreateStore(b_.getInt64(uint64_t(chunk)), loop_budget_);
    }
  }
  b_.CreateStore(iconst(1),
                 b_.CreateConstInBoundsGEP1_64(b_.getInt8Ty(), gd_, size_t(plan().ran_offset)));
  init_symbols();
  if (!failed()) init_params();
  if (!failed()) emit_region(shader().main_begin, int(ops.size()), exit_block_);
  finish_exit_block();
  llvm::IRBuilder<> eb(alloca_block_);
  eb.CreateBr(start);
  return !failed();
}

std::string emit_group(const GroupPlan& plan, llvm::Module& module, HostSymbols& host) {
  host.clear();
  llvm::LLVMContext& ctx = module.getContext();
  auto* ptr = llvm::PointerType::get(ctx, 0);
  auto* fty = llvm::FunctionType::get(llvm::Type::getVoidTy(ctx), {ptr, ptr}, false);
  std::vector<llvm::Function*> fns;
  for (const LayerPlan& lp : plan.layers) {
    auto* f =
        llvm::Function::Create(fty, llvm::Function::InternalLinkage, lp.function_name, module);
    f->addFnAttr(llvm::Attribute::NoUnwind);
    fns.push_back(f);
  }
  for (size_t i = 0; i < plan.layers.size(); ++i) {
    LayerEmitter e(plan, int(i), module, fns, host);
    if (!e.emit()) return e.error();
  }
  auto* entry =
      llvm::Function::Create(fty, llvm::Function::ExternalLinkage, plan.entry_name, module);
  llvm::IRBuilder<> b(llvm::BasicBlock::Create(ctx, "entry", entry));
  llvm::Value* sg = entry->getArg(0);
  llvm::Value* gd = entry->getArg(1);
  // The entry layers in order, each unless it already ran (lazily, for an earlier one); with
  // none marked, the last layer. Without lazy layers (and with no entry layers named, where
  // testshade stays lazy), every layer the group kept, in order.
  bool any_entry = false, eager = !plan.lazy_layers && !plan.explicit_entries;
  for (const LayerPlan& lp : plan.layers) any_entry |= lp.entry;
  std::vector<size_t> order(plan.entry_order.begin(), plan.entry_order.end()); // none if eager
  for (size_t i = 0; i < plan.layers.size(); ++i)
    if (std::find(order.begin(), order.end(), i) == order.end()) order.push_back(i);
  for (size_t i : order) {
    bool runs = eager || (any_entry ? plan.layers[i].entry : i + 1 == plan.layers.size());
    if (!runs) continue;
    llvm::Value* ran = b.CreateLoad(
        b.getInt32Ty(), b.CreateConstInBoundsGEP1_64(b.getInt8Ty(), gd, plan.layers[i].ran_offset));
    auto* run = llvm::BasicBlock::Create(ctx, "run_entry", entry);
    auto* next = llvm::BasicBlock::Create(ctx, "next", entry);
    b.CreateCondBr(b.CreateICmpEQ(ran, b.getInt32(0)), run, next);
    b.SetInsertPoint(run);
    b.CreateCall(fns[i], {sg, gd});
    b.CreateBr(next);
    b.SetInsertPoint(next);
  }
  b.CreateRetVoid();
  std::string err;
  llvm::raw_string_ostream os(err);
  if (llvm::verifyModule(module, &os)) return "internal: invalid LLVM IR: " + os.str();
  return "";
}

} // namespace lobe::codegen
