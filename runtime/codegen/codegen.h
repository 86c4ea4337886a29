// Lobe IR -> LLVM IR for a shader group.
//
// Input: a GroupPlan (layers in execution order, each an ir::Shader plus where its parameters
// live in the group-data block and which of them are connected upstream). Output: one LLVM
// function per layer, `void <layer>(ShaderGlobals*, char* groupdata)`, and the entry
// `void <entry>(ShaderGlobals*, char* groupdata)` that runs the entry layers (those with
// renderer outputs), in order, then the last layer; other upstream layers run lazily, the first
// time a connected parameter is used (`useparam`).
//
// Group-data block (laid out by the group compiler): per layer a 4-byte "ran" flag, then every
// parameter's storage. A symbol's storage is [planes][elements][components] of 4-byte scalars
// (8-byte pointers for strings and closures), planes = 3 (value, d/dx, d/dy) for symbols with
// derivatives, else 1.
//
// No exceptions, no LLVM fatal errors: failures come back as a message.
#pragma once

#include "ir/ir.h"

#include <cstdint>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace llvm {
class LLVMContext;
class Module;
} // namespace llvm

namespace lobe::shadeops {
struct RuntimeEnv;
class ColorSystem;
} // namespace lobe::shadeops

namespace lobe::codegen {

// A connection into one parameter (or an element/component of it) of the layer that owns it.
struct ConnectionPlan {
  int dst_symbol = -1;
  int dst_element = -1, dst_component = -1; // -1: whole
  int src_layer = -1;
  int src_symbol = -1;
  int src_element = -1, src_component = -1; // -1: whole
};

struct LayerPlan {
  const ir::Shader* shader = nullptr;
  std::string function_name;
  int ran_offset = 0;             // byte offset of the layer's "ran" flag in group data
  std::vector<int> symbol_offset; // per symbol: group-data byte offset, or -1 (not stored)
  std::vector<bool> run_default;  // per symbol: the param's default ops must run
  std::vector<bool> userdata;     // per symbol: a lockgeom=0 param asks the renderer first
  std::string layer_name;         // for getattribute("shader:layername")
  int group_index = 0;            // position among the group's layers (compiled or not)
  bool entry = false; // runs at every shade (the last layer, a renderer output, an entry layer)
  // OSL begins such a layer's main code with one `useparam` op of its output parameters that a
  // connection reads or writes, the renderer reads or whose computed default runs: one more op
  // in the op numbers --debuguninit prints (LayerEmitter::number_ops_as_osl).
  bool osl_output_useparam = false;
  std::vector<ConnectionPlan> connections;
};

struct GroupPlan {
  std::vector<LayerPlan> layers;
  std::string entry_name = "group_entry";
  std::string group_name;              // for getattribute("shader:groupname")
  shadeops::RuntimeEnv* env = nullptr; // baked into the code as a constant pointer
  // The material's colour system (CompileOptions::colorspace), baked in likewise; null: Rec709.
  const shadeops::ColorSystem* colors = nullptr;
  bool fast_math = true;             // CompileOptions::fast_math: the math shadeops' math::MathMode
  int opt_level = 2;                 // CompileOptions::opt_level (messages OSL words by its level)
  bool userdata_isconnected = false; // CompileOptions::userdata_isconnected
  bool lazy_layers = true;           // CompileOptions::lazy_layers
  bool explicit_entries = false;     // the group names its entry layers (ShaderGroup::entry_layers)
  // The entry layers (indices into `layers`) in the order the group names them, in which they
  // run (as testshade's --entry order); empty: in layer order.
  std::vector<int> entry_order;
  // Bounded loops (CompileOptions::max_loop_iterations): with loop_count_offset >= 0, every
  // backward jump (a loop's back edge) counts down a per-layer-run counter of
  // kLoopChunk iterations; when it runs out the layer calls lobe_loop_check, which adds the
  // chunk to the shade's total (8 bytes of group data at loop_count_offset, zeroed per
  // shade), and either grants another chunk or, past max_loop_iterations (0: unlimited) or
  // when the ShadingContext is cancelled, reports the loop (ShadingContext::stopped) and the
  // layer returns at once (its outputs as they are). max_loop_iterations < 0: no checks.
  int loop_count_offset = -1;
  int64_t max_loop_iterations = 0;
  // CompileOptions::range_checking: an index out of range is reported (as OSL's "Index [4] out
  // of range a[0..2]"); off, it is only clamped, silently.
  bool range_checking = true;
  // CompileOptions::debug_nan: after each op, its float-based results are checked for NaN and
  // Inf (reported as OSL's "Detected inf value in x at f.osl:3 (op mul)").
  bool debug_nan = false;
  // CompileOptions::debug_uninit: locals and temps start as NaN / INT_MIN / a marker string
  // instead of zero, and before each op the values it reads are checked for them (and for any
  // non-finite float, as OSL does); each found is reported and set to zero.
  bool debug_uninit = false;
};

// Iterations a layer runs between two calls of lobe_loop_check (fewer when the limit is lower).
constexpr int64_t kLoopChunk = 1 << 16;

// Bounded memory. Every symbol but a constant has storage on the shading thread's stack while
// its layer runs (parameters are copied in from group data); scalars, triples and matrices end
// up in registers once LLVM promotes them, arrays stay in memory. Connected layers call each
// other, so the limit is on the arrays of all layers together: a quarter of the 4 MiB stack of
// a TBB worker thread, which is where `lobe shade` and `lobe render` shade. build_group refuses
// a material past it with an error naming the largest array (a shader declaring
// `float a[1000000000]` would otherwise overflow the stack at its first shade, as it does in
// OSL); the same bound keeps array parameters' group data (one copy per thread) in check.
constexpr size_t kMaxLocalBytes = size_t(1) << 20;

// Storage size in bytes of a symbol (all planes), as laid out in group data and allocas.
size_t storage_bytes(const ir::Symbol& s);
// Byte offset of plane `plane`, element `elem`, component `comp` within a symbol's storage.
size_t storage_offset(const ir::Symbol& s, int plane, int elem, int comp);

// The host objects the group's code refers to (the environment, the colour system, interned
// strings, declared closures): each is an external global `lobe.host.N` of opaque type in the
// module, so the machine code holds no address of this process and can be cached on disk; the
// JIT binds each name to its address when it loads the code (Jit::add, Jit::add_object).
// Distinct objects get distinct names, since LLVM takes distinct globals to differ in address.
using HostSymbols = std::vector<std::pair<std::string, const void*>>;

// Emits the group into `module`, and into `host` the addresses its names stand for. Returns ""
// on success, else the reason it failed.
std::string emit_group(const GroupPlan& plan, llvm::Module& module, HostSymbols& host);

} // namespace lobe::codegen
