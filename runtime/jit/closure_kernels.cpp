// Closure kernels (closure_kernels.h): dispatchers over a material's closure ids, with the
// closure library's bitcode linked in lazily and inlined.
#include "closure_kernels.h"

#include "closure_registry.h"
#include "disk_cache.h"
#include "install_paths.h"

#include <llvm/Bitcode/BitcodeReader.h>
#include <llvm/IR/IRBuilder.h>
#include <llvm/IR/LLVMContext.h>
#include <llvm/IR/Module.h>
#include <llvm/Linker/Linker.h>
#include <llvm/Support/MemoryBuffer.h>

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <mutex>
#include <sstream>

namespace lobe::jit {
namespace {

constexpr int kNumEntries = 4;
const char* const kEntries[kNumEntries] = {"lobe_kernels_setup", "lobe_kernels_eval",
                                           "lobe_kernels_sample", "lobe_kernels_albedo"};
const registry::Kernel kKernel[kNumEntries] = {registry::Kernel::setup, registry::Kernel::eval,
                                               registry::Kernel::sample, registry::Kernel::albedo};

// The bitcode file's bytes, read once per process.
const std::string* bitcode_bytes(std::string& error) {
  static std::once_flag once;
  static std::string bytes, failure;
  std::call_once(once, [] {
    std::string path = closure_bitcode_path();
    std::ifstream in(path, std::ios::binary);
    std::stringstream ss;
    if (in) ss << in.rdbuf();
    bytes = ss.str();
    if (bytes.empty()) failure = "cannot read the closure bitcode '" + path + "'";
  });
  if (!failure.empty()) {
    error = failure;
    return nullptr;
  }
  return &bytes;
}

// The bitcode's identity for cache keys: its size and FNV-1a hash, computed once.
std::string bitcode_identity(const std::string& bytes) {
  static std::once_flag once;
  static std::string id;
  std::call_once(once, [&] { id = "bitcode " + bytes_identity(bytes); });
  return id;
}

// The per-key functions a dispatcher calls, declared in `mod` with the library's types.
struct Case {
  int id;
  llvm::FunctionCallee fn[kNumEntries];
};

// `void|i32 name(i32 id, args...)`: switch (id) { case k: return lobe_closure_<key>_*(args) }.
void emit_dispatcher(llvm::Module& mod, int which, llvm::FunctionType* callee_type,
                     const std::vector<Case>& cases) {
  llvm::LLVMContext& ctx = mod.getContext();
  std::vector<llvm::Type*> params{llvm::Type::getInt32Ty(ctx)};
  for (llvm::Type* t : callee_type->params()) params.push_back(t);
  llvm::Type* ret = callee_type->getReturnType();
  auto* type = llvm::FunctionType::get(ret, params, false);
  auto* f = llvm::Function::Create(type, llvm::Function::ExternalLinkage, kEntries[which], mod);
  llvm::IRBuilder<> b(llvm::BasicBlock::Create(ctx, "entry", f));
  auto* none = llvm::BasicBlock::Create(ctx, "none", f);
  auto* sw = b.CreateSwitch(f->getArg(0), none, unsigned(cases.size()));
  std::vector<llvm::Value*> args;
  for (unsigned i = 1; i < f->arg_size(); ++i) args.push_back(f->getArg(i));
  for (const Case& c : cases) {
    auto* bb = llvm::BasicBlock::Create(ctx, "id" + std::to_string(c.id), f);
    sw->addCase(b.getInt32(uint32_t(c.id)), bb);
    b.SetInsertPoint(bb);
    llvm::Value* r = b.CreateCall(c.fn[which], args);
    if (ret->isVoidTy())
      b.CreateRetVoid();
    else
      b.CreateRet(r);
  }
  b.SetInsertPoint(none); // not reached: Bsdf calls only for covered ids
  if (ret->isVoidTy())
    b.CreateRetVoid();
  else
    b.CreateRet(llvm::Constant::getNullValue(ret));
}

// Everything but the dispatchers becomes internal (so unused code is dropped and the lobes
// inline), and the library's per-function CPU attributes go (the JIT's target applies).
void internalize(llvm::Module& mod) {
  auto is_entry = [](llvm::StringRef n) {
    for (const char* e : kEntries)
      if (n == e) return true;
    return false;
  };
  for (llvm::Function& f : mod) {
    f.removeFnAttr("target-cpu");
    f.removeFnAttr("target-features");
    f.removeFnAttr("tune-cpu");
    if (f.isDeclaration() || is_entry(f.getName())) continue;
    f.setComdat(nullptr);
    f.setLinkage(llvm::GlobalValue::InternalLinkage);
  }
  for (llvm::GlobalVariable& g : mod.globals()) {
    if (g.isDeclaration()) continue;
    g.setComdat(nullptr);
    g.setLinkage(llvm::GlobalValue::InternalLinkage);
  }
}

} // namespace

std::string closure_bitcode_path() { return install::closures_bitcode(); }

bool compile_closure_kernels(Jit& jit, const std::vector<int>& ids, ClosureKernels& out,
                             CompiledGroup& code, JitTimes& times, std::string& error) {
  // Only BSDF entries have bitcode (registry::has_kernel): a material with none (an emitter, a
  // background) needs no module, and the bitcode is not even read for it.
  bool any_kernel = false;
  for (int id : ids) any_kernel |= registry::kernel_symbol(id, registry::Kernel::eval) != nullptr;
  if (!any_kernel) {
    out = ClosureKernels{};
    return true;
  }
  const std::string* bytes = bitcode_bytes(error);
  if (!bytes) return false;

  // The disk cache: the machine code depends on the ids asked for, the bitcode, the target
  // and LLVM (disk_cache.h). An entry holds the ids it covers, then the object.
  std::vector<int> wanted(ids);
  std::sort(wanted.begin(), wanted.end());
  wanted.erase(std::unique(wanted.begin(), wanted.end()), wanted.end());
  std::string key = "closure kernels 2; opt 2; " + jit.target_identity() + "; " +
                    bitcode_identity(*bytes) + "; ids";
  for (int id : wanted) key += " " + std::to_string(id);
  auto finish = [&](const std::string& covered, const std::string& object) {
    ClosureKernels k;
    std::istringstream in(covered);
    for (int id; in >> id;) k.add(id);
    std::vector<void*> addresses;
    if (!jit.add_object(object, {kEntries[0], kEntries[1], kEntries[2], kEntries[3]}, addresses,
                        code, error))
      return false;
    k.setup = reinterpret_cast<ClosureKernels::SetupFn>(addresses[0]);
    k.eval = reinterpret_cast<ClosureKernels::EvalFn>(addresses[1]);
    k.sample = reinterpret_cast<ClosureKernels::SampleFn>(addresses[2]);
    k.albedo = reinterpret_cast<ClosureKernels::AlbedoFn>(addresses[3]);
    out = k;
    return true;
  };
  if (std::string entry; cache_read("kernels", key, entry)) {
    size_t nl = entry.find('\n');
    if (nl != std::string::npos) {
      if (finish(entry.substr(0, nl), entry.substr(nl + 1))) {
        times.from_cache = true;
        return true;
      }
      error.clear(); // an entry that does not load is rebuilt
    }
  }

  auto ctx = std::make_unique<llvm::LLVMContext>();
  auto lib = llvm::getLazyBitcodeModule(llvm::MemoryBufferRef(*bytes, "lobe_closures.bc"), *ctx);
  if (!lib) {
    error = "closure bitcode: " + llvm::toString(lib.takeError());
    return false;
  }
  std::unique_ptr<llvm::Module> library = std::move(*lib);
  auto mod = std::make_unique<llvm::Module>("closure_kernels", *ctx);
  jit.configure(*mod);
  library->setTargetTriple(mod->getTargetTriple());
  library->setDataLayout(mod->getDataLayout());

  std::vector<Case> cases;
  llvm::FunctionType* types[kNumEntries] = {};
  ClosureKernels k;
  for (int id : ids) {
    if (!registry::kernel_symbol(id, registry::Kernel::eval) || id >= ClosureKernels::kMaxIds ||
        k.covers(id))
      continue;
    Case c{id, {}};
    bool complete = true;
    for (int w = 0; w < kNumEntries; ++w) {
      const char* name = registry::kernel_symbol(id, kKernel[w]);
      llvm::Function* lf = library->getFunction(name);
      if (!lf) {
        complete = false;
        break;
      }
      types[w] = lf->getFunctionType();
      c.fn[w] = mod->getOrInsertFunction(name, lf->getFunctionType());
    }
    if (!complete) continue; // no bitcode for this closure: the native library serves it
    cases.push_back(c);
    k.add(id);
  }
  if (cases.empty()) {
    out = ClosureKernels{};
    return true; // nothing to compile: every lobe goes to the native library
  }
  for (int w = 0; w < kNumEntries; ++w) emit_dispatcher(*mod, w, types[w], cases);
  if (llvm::Linker::linkModules(*mod, std::move(library), llvm::Linker::Flags::LinkOnlyNeeded)) {
    error = "closure bitcode: linking failed";
    return false;
  }
  internalize(*mod);
  std::string object;
  if (!jit.compile_object(*mod, 2, object, times, error)) return false;
  std::string covered;
  for (const Case& c : cases) covered += std::to_string(c.id) + " ";
  cache_write("kernels", key, covered + "\n" + object);
  return finish(covered, object);
}

} // namespace lobe::jit
