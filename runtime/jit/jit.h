// The JIT: LLVM 19's ORC LLJIT for the host CPU, the new-pass-manager optimisation pipeline,
// and one JITDylib per compiled group (so a Material's code is freed with it). Shadeops and
// the libm functions generated code needs are resolved from one absolute-symbol map built
// from the shadeop table (no dlsym look-ups). Thread-safe: several groups may compile at once.
//
// LLVM errors never abort the process: every failure is returned as text.
#pragma once

#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <utility>
#include <vector>

namespace llvm {
class LLVMContext;
class Module;
class Error;
namespace orc {
class LLJIT;
class JITDylib;
} // namespace orc
} // namespace llvm

namespace lobe::jit {

// Machine code of one group; the Jit frees it in remove().
struct CompiledGroup {
  void* entry = nullptr;
  llvm::orc::JITDylib* dylib = nullptr;
};

// Names the code refers to and the host addresses they stand for (codegen::HostSymbols):
// defined in the group's JITDylib when it is loaded.
using HostSymbols = std::vector<std::pair<std::string, const void*>>;

struct JitTimes {
  double optimize_ms = 0, codegen_ms = 0;
  bool from_cache = false; // the machine code came from the disk cache (kernels, materials)
  int noise_batched = 0;   // noise calls gathered into W-point calls (noise_batch.h)
};

// The GNU build ID (the linker's hash of the whole linked file) of the executable or shared
// object holding Lobe's JIT, in hex; "" when the linker wrote none.
std::string own_build_id();

class Jit {
public:
  ~Jit();
  static std::unique_ptr<Jit> create(std::string& error);

  // Prepares a module for this JIT (host triple and data layout).
  void configure(llvm::Module& module) const;
  // Optimises `module` (opt_level 0: no IR passes; 1/2: the O1/O2 pipelines), compiles it into
  // a fresh JITDylib and returns the address of `entry`.
  bool add(std::unique_ptr<llvm::LLVMContext> context, std::unique_ptr<llvm::Module> module,
           int opt_level, const std::string& entry, CompiledGroup& out, JitTimes& times,
           std::string& error, const HostSymbols& host = {});
  // As add(), for a module with several entry points: `addresses[i]` is that of `entries[i]`;
  // out.entry is the first.
  bool add(std::unique_ptr<llvm::LLVMContext> context, std::unique_ptr<llvm::Module> module,
           int opt_level, const std::vector<std::string>& entries, std::vector<void*>& addresses,
           CompiledGroup& out, JitTimes& times, std::string& error, const HostSymbols& host = {});
  void remove(CompiledGroup& group);

  // Optimises `module` and compiles it to a relocatable object for this JIT's target (the
  // code add() would produce), into `object`. Thread-safe.
  bool compile_object(llvm::Module& module, int opt_level, std::string& object, JitTimes& times,
                      std::string& error) const;
  // As add(), for an object compile_object produced (now or in an earlier run).
  bool add_object(const std::string& object, const std::vector<std::string>& entries,
                  std::vector<void*>& addresses, CompiledGroup& out, std::string& error,
                  const HostSymbols& host = {});
  // What machine code depends on besides the IR: LLVM's version, the target triple, CPU and
  // features, the code generator's optimisation level and the build of Lobe that compiles
  // (own_build_id(): its pipelines, shadeop linking and kernel dispatchers); part of every
  // disk-cache key.
  std::string target_identity() const;

  // Runs the optimisation pipeline only (used by add(), and by tests/benchmarks); returns how
  // many noise calls it gathered into W-point calls (noise_batch.h; -O2 only).
  int optimize(llvm::Module& module, int opt_level) const;
  // The host assembly of `module` (configured for this JIT) from the JIT's TargetMachine, as
  // the JIT would compile it (`lobe compile --emit=asm`). The module is consumed by codegen.
  bool emit_assembly(llvm::Module& module, std::string& out, std::string& error) const;

private:
  Jit() = default;
  bool load(const std::function<llvm::Error(llvm::orc::JITDylib&)>& fill,
            const std::vector<std::string>& entries, std::vector<void*>& addresses,
            CompiledGroup& out, std::string& error, const HostSymbols& host);
  struct State;
  std::unique_ptr<State> s_;
};

} // namespace lobe::jit
