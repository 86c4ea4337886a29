// LayerEmitter: turns one layer's ops into the body of its LLVM function. Internal to codegen.
//
// Values are handled per component as dual numbers (value, d/dx, d/dy; a null derivative
// means zero), so that every op writes its chain rule once, per scalar. Symbols live in
// allocas (params and outputs also in group data); LLVM's SROA/mem2reg turns them into SSA.
#pragma once

#include "codegen.h"
#include "ir/opcodes.h"

#include <llvm/IR/IRBuilder.h>
#include <llvm/IR/Module.h>

#include <algorithm>
#include <functional>
#include <map>
#include <string>
#include <vector>

namespace lobe {
struct GlobalField;
}

namespace lobe::codegen {

struct Dual {
  llvm::Value* v = nullptr;
  llvm::Value* dx = nullptr; // null: zero
  llvm::Value* dy = nullptr;
};
using Val = std::vector<Dual>; // one element of a symbol: its components

class LayerEmitter;
using OpEmitFn = void (*)(LayerEmitter&, const ir::Op&);

class LayerEmitter {
public:
  LayerEmitter(const GroupPlan& group, int layer, llvm::Module& module,
               std::vector<llvm::Function*>& layer_fns, HostSymbols& host);
  // Emits the layer function's body; false with error() set on failure.
  bool emit();
  const std::string& error() const { return error_; }

  // ---- used by the op emitters (ops_*.cpp) ----
  llvm::IRBuilder<>& b() { return b_; }
  llvm::LLVMContext& ctx() { return module_.getContext(); }
  const ir::Shader& shader() const { return *plan().shader; }
  const GroupPlan& group() const { return group_; }
  int layer() const { return layer_; }
  const ir::Symbol& sym(int i) const { return shader().symbols[size_t(i)]; }
  const ir::Symbol& arg(const ir::Op& op, int i) const { return sym(op.args[size_t(i)]); }
  void fail(const ir::Op& op, const std::string& msg);
  bool failed() const { return !error_.empty(); }

  llvm::Type* f32() { return b_.getFloatTy(); }
  llvm::Type* i32() { return b_.getInt32Ty(); }
  llvm::Type* ptr() { return b_.getPtrTy(); }
  llvm::Value* fconst(float f) { return llvm::ConstantFP::get(f32(), f); }
  llvm::Value* iconst(int i) { return b_.getInt32(uint32_t(i)); }
  llvm::Value* sg() { return sg_; }
  llvm::Value* env_ptr();
  llvm::Value* colors_ptr();                       // the GroupPlan's colour system (null: Rec709)
  llvm::Value* string_const(const std::string& s); // interned, as a pointer constant
  // A host object's address as its external global (HostSymbols); null stays a null constant.
  llvm::Constant* host_address(const void* p);
  llvm::FunctionCallee shadeop(const char* name); // declared from the shadeop table
  llvm::Value* call(const char* name, std::vector<llvm::Value*> args);

  // Whole-element access. `elem` null means element 0 (scalars). Loading a symbol without
  // derivatives gives null derivatives; derivatives are loaded only if `derivs`.
  Val load(int symbol, llvm::Value* elem = nullptr, bool derivs = true);
  void store(int symbol, const Val& v, llvm::Value* elem = nullptr);
  llvm::Value* address(int symbol, int plane, llvm::Value* elem, int comp);
  // Converts an element value of base type `from` to base type `to` (docs/ir.md conversions).
  Val convert(const Val& v, ir::BaseType from, ir::BaseType to);
  // Loads operand i of op converted to base type `to` (element 0).
  Val load_as(const ir::Op& op, int i, ir::BaseType to, bool derivs = true);
  bool wants_derivs(int symbol) const { return sym(symbol).derivs; }
  // Spills float components into a temporary array; returns its address.
  llvm::Value* spill(const std::vector<llvm::Value*>& comps, llvm::Type* ty = nullptr);
  std::vector<llvm::Value*> reload(llvm::Value* p, int n, llvm::Type* ty = nullptr);
  // Address of a symbol's whole storage (all planes), for shadeops that read or write a value
  // of any type in place; a scalar constant, which has no storage, is spilled first.
  llvm::Value* storage_address(int symbol);
  // A type as one int for shadeops: base | arraylen << 8 (runtime/shadeops/ops_query.cpp).
  static int type_code(const ir::Type& t) { return int(t.base) | (std::max(0, t.arraylen) << 8); }
  llvm::AllocaInst* entry_alloca(llvm::Type* ty, unsigned count, const char* name = "");
  // An in-range index: constant indices are checked at compile time, others clamped at run
  // time with a range error reported through the ShadingContext.
  llvm::Value* checked_index(const ir::Op& op, int index_arg, int length);
  // An index operand as an int clamped to [0, length) (no report: checked_index reports).
  llvm::Value* clamped_index(const ir::Op& op, int index_arg, int length);
  // "group g, layer 0 l, shader s", as OSL's run-time errors name the layer.
  std::string layer_description() const;
  llvm::Value* truthy(const Val& v, ir::BaseType t); // i1: v != 0
  void emit_exit();                                  // branch to the layer's exit block
  void run_useparam(int symbol);                     // fetch a connected param once

  static ir::BaseType base_of(const ir::Symbol& s) { return s.type.base; }
  static bool is_float_based(ir::BaseType t) {
    return t != ir::BaseType::Int && t != ir::BaseType::String && t != ir::BaseType::Closure;
  }
  static int comps_of(ir::BaseType t) { return ir::Type{t, 0}.components(); }

private:
  const LayerPlan& plan() const { return group_.layers[size_t(layer_)]; }
  llvm::Type* scalar_type(const ir::Symbol& s);
  llvm::Type* storage_type(const ir::Symbol& s);
  void create_storage();
  void init_symbols();
  void init_params();
  void fetch_connection(const ConnectionPlan& c);
  // The group's layers share one ShaderGlobals, as OSL's do: around a call of an upstream layer
  // (and at the exit) this one's written globals go out to it (store_globals) and after the
  // call every global comes back (reload_globals: values, and the derivatives of P and I when
  // they carry them, as ShaderGlobals has them; other derivatives stay as they are).
  void store_globals();
  void reload_globals();
  void read_global(const ir::Symbol& s, const GlobalField& g, Val& v);
  llvm::Value* global_slot(size_t offset, size_t c);
  llvm::Type* global_type(const GlobalField& g); // a ShaderGlobals field's scalar type
  void emit_region(int begin, int end, llvm::BasicBlock* after);
  void emit_op(int index);
  void emit_loop_check(const ir::Op& op); // counts a back edge (GroupPlan::loop_count_offset)
  void check_uninit_reads(int index);     // GroupPlan::debug_uninit, before the op
  void check_nan_writes(int index);       // GroupPlan::debug_nan, after the op
  void number_ops_as_osl();
  void finish_exit_block();
  llvm::BasicBlock* block_at(int op_index);
  bool is_leader(int op_index) const;
  llvm::Value* groupdata_address(int layer, int symbol, int plane, int elem, int comp);

  const GroupPlan& group_;
  int layer_;
  llvm::Module& module_;
  std::vector<llvm::Function*>& layer_fns_;
  HostSymbols& host_;
  llvm::IRBuilder<> b_;
  llvm::Function* fn_ = nullptr;
  llvm::Value* sg_ = nullptr;
  llvm::Value* gd_ = nullptr;
  llvm::BasicBlock* alloca_block_ = nullptr;
  llvm::BasicBlock* exit_block_ = nullptr;
  llvm::Value* loop_budget_ = nullptr;      // i64 alloca: back edges left before lobe_loop_check
  std::vector<llvm::Value*> storage_;       // per symbol: alloca (null for scalar consts)
  std::vector<llvm::Value*> fetched_flag_;  // per symbol: i1 alloca "connection fetched"
  std::vector<char> leader_;                // per op: starts a basic block
  std::vector<bool> written_;               // per symbol: some op writes it
  std::vector<int> osl_opnum_;              // per op: its number as OSL counts (debug_uninit)
  std::map<int, llvm::BasicBlock*> blocks_; // op index -> block
  int region_end_ = 0;
  llvm::BasicBlock* region_after_ = nullptr;
  std::string error_;
};

// The emitter of an opcode (ops_*.cpp), by direct index; null for the control flow
// (nop, br, cbr, exit, useparam) that LayerEmitter::emit_op does itself.
OpEmitFn op_emitter(ir::Opcode op);

} // namespace lobe::codegen
