// Shadeop bitcode (shadeop_bitcode.h): the pure shadeops a shader module calls, linked in from
// lobe_shadeops.bc so that they inline.
#include "shadeop_bitcode.h"

#include "disk_cache.h"
#include "install_paths.h"
#include "noise_batch.h"
#include "shadeops.h"

#include <llvm/Bitcode/BitcodeReader.h>
#include <llvm/IR/LLVMContext.h>
#include <llvm/IR/Module.h>
#include <llvm/IR/PassManager.h>
#include <llvm/Linker/Linker.h>
#include <llvm/Passes/PassBuilder.h>
#include <llvm/Support/Error.h>
#include <llvm/Support/MemoryBuffer.h>
#include <llvm/Transforms/IPO/AlwaysInliner.h>
#include <llvm/Transforms/IPO/GlobalDCE.h>

#include <cstdlib>
#include <fstream>
#include <mutex>
#include <sstream>
#include <utility>
#include <vector>

namespace lobe::jit {
namespace {

// The bitcode file's bytes, read once per process (empty: none, every call stays out of line).
const std::string& bitcode_bytes() {
  static std::once_flag once;
  static std::string bytes;
  std::call_once(once, [] {
    std::string path = shadeop_bitcode_path();
    if (path.empty() || path == "off") return;
    std::ifstream in(path, std::ios::binary);
    if (!in) return;
    std::stringstream ss;
    ss << in.rdbuf();
    bytes = ss.str();
  });
  return bytes;
}

// The shadeops worth linking: pure functions of their arguments on the hot path whose calls
// carry constants to specialise on (noise) or that are small (math, hash, the closure
// builders, which bump the context's arena, and the matrix product, transpose and transform;
// inverse, division and determinant cost more compile time than they save: docs/runtime.md,
// "Shadeop bitcode").
bool linkable(llvm::StringRef name) {
  return name.starts_with("lobe_math_") || name == "lobe_mat_mul" || name == "lobe_transform" ||
         name == "lobe_mat_transpose" || name == "lobe_noise_d" || name == "lobe_noise" ||
         name == "lobe_hash" || name == "lobe_closure_component" || name == "lobe_closure_add" ||
         name == "lobe_closure_mul" || name == "lobe_closure_weight" ||
         wide_noise_function(name); // noise_batch.h
}

// What linked code may still call: intrinsics and the JIT's runtime symbols (shadeops.h).
bool resolvable(const llvm::Function& f) {
  return f.isIntrinsic() || shadeops::find_shadeop(f.getName().str()) != nullptr;
}

// The noise variants lose the bitcode build's noinline too (the inliner decides), unless
// LOBE_SHADEOPS_INLINE=dispatch (a measurement switch: only the dispatchers inline).
bool inline_all_variants() {
  static const bool all = [] {
    const char* e = std::getenv("LOBE_SHADEOPS_INLINE");
    return !(e && std::string(e) == "dispatch");
  }();
  return all;
}

// The library's CPU attributes go (the JIT's target applies), and so does the bitcode build's
// noinline on the noise variants (noise.cpp, LOBE_VARIANT) when inline_all_variants() (the
// default): then the inliner decides.
void strip_attributes(llvm::Function& f) {
  f.removeFnAttr("target-cpu");
  f.removeFnAttr("target-features");
  f.removeFnAttr("tune-cpu");
  // The functions noise batching gathers stay calls through -O2 (noise_batch.h).
  if (inline_all_variants() && !(noise_batching() && batchable_function(f.getName())))
    f.removeFnAttr(llvm::Attribute::NoInline);
}

// Dispatchers over their constant arguments: always inlined, so the call's constants pick one
// variant (kind, dimension, channels, derivatives or not) and the rest folds away.
// The W-point noise functions (noise_batch.h) inline where batching put them.
bool dispatcher(llvm::StringRef name) {
  return name == "lobe_noise_d" || name == "lobe_noise" || wide_noise_function(name);
}

} // namespace

std::string shadeop_bitcode_path() { return install::shadeops_bitcode(); }

std::string shadeop_bitcode_identity() {
  static const std::string id = [] {
    const std::string& bytes = bitcode_bytes();
    if (bytes.empty()) return std::string("shadeops none");
    return "shadeops " + bytes_identity(bytes) +
           (inline_all_variants() ? " inline all" : " dispatch") +
           (noise_batching() ? " batch" : "");
  }();
  return id;
}

int link_shadeop_bitcode(llvm::Module& module) {
  std::vector<std::pair<std::string, llvm::FunctionType*>> wanted;
  for (llvm::Function& f : module)
    if (f.isDeclaration() && !f.isIntrinsic() && linkable(f.getName()))
      wanted.emplace_back(f.getName().str(), f.getFunctionType());
  if (wanted.empty()) return 0;
  const std::string& bytes = bitcode_bytes();
  if (bytes.empty()) return 0;

  llvm::LLVMContext& ctx = module.getContext();
  auto lib = llvm::getLazyBitcodeModule(llvm::MemoryBufferRef(bytes, "lobe_shadeops.bc"), ctx);
  if (!lib) {
    llvm::consumeError(lib.takeError());
    return 0;
  }
  std::unique_ptr<llvm::Module> library = std::move(*lib);
  library->setTargetTriple(module.getTargetTriple());
  library->setDataLayout(module.getDataLayout());
  // The wanted functions are linked into a module of their own first, so that what they pull
  // in can be checked before anything reaches the shader's module.
  auto ops = std::make_unique<llvm::Module>("lobe_shadeops", ctx);
  ops->setTargetTriple(module.getTargetTriple());
  ops->setDataLayout(module.getDataLayout());
  std::vector<std::string> linked;
  for (const auto& [name, type] : wanted) {
    llvm::Function* lf = library->getFunction(name);
    if (!lf || lf->getFunctionType() != type) continue; // not in the bitcode, or another type
    ops->getOrInsertFunction(name, type);
    linked.push_back(name);
  }
  if (linked.empty()) return 0;
  if (llvm::Linker::linkModules(*ops, std::move(library), llvm::Linker::Flags::LinkOnlyNeeded))
    return 0;
  for (llvm::Function& f : *ops) {
    if (f.isDeclaration() && !resolvable(f)) return 0; // would not resolve in the JIT
    strip_attributes(f);
    if (f.isDeclaration()) continue;
    if (dispatcher(f.getName())) f.addFnAttr(llvm::Attribute::AlwaysInline);
    f.setComdat(nullptr);
    bool entry = false;
    for (const std::string& n : linked) entry |= f.getName() == n;
    if (!entry) f.setLinkage(llvm::GlobalValue::InternalLinkage);
  }
  for (llvm::GlobalVariable& g : ops->globals()) {
    if (g.isDeclaration()) return 0; // data the JIT does not define
    g.setComdat(nullptr);
    g.setLinkage(llvm::GlobalValue::InternalLinkage);
  }
  if (llvm::Linker::linkModules(module, std::move(ops))) return 0;
  for (const std::string& n : linked)
    if (llvm::Function* f = module.getFunction(n); f && !f->isDeclaration())
      f->setLinkage(llvm::GlobalValue::InternalLinkage); // dropped once inlined everywhere
  // The dispatchers inline now, pruned by their constant arguments as they are cloned, and the
  // variants no call selects are dropped before the optimiser spends any time on them (a noise
  // call pulls in every kind and dimension; it uses one).
  llvm::LoopAnalysisManager lam;
  llvm::FunctionAnalysisManager fam;
  llvm::CGSCCAnalysisManager cgam;
  llvm::ModuleAnalysisManager mam;
  llvm::PassBuilder pb;
  pb.registerModuleAnalyses(mam);
  pb.registerCGSCCAnalyses(cgam);
  pb.registerFunctionAnalyses(fam);
  pb.registerLoopAnalyses(lam);
  pb.crossRegisterProxies(lam, fam, cgam, mam);
  llvm::ModulePassManager mpm;
  mpm.addPass(llvm::AlwaysInlinerPass(false));
  mpm.addPass(llvm::GlobalDCEPass());
  mpm.run(module, mam);
  // The one-point functions batching gathers, where still called, go through -O2 with external
  // linkage: internal, their signatures could change (a constant argument propagated into the
  // body and dropped), and batching would no longer recognise them. Made internal again after.
  if (noise_batching())
    for (llvm::Function& f : module)
      if (!f.isDeclaration() && batchable_function(f.getName()))
        f.setLinkage(llvm::GlobalValue::ExternalLinkage);
  return int(linked.size());
}

} // namespace lobe::jit
