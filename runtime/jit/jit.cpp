// Jit: LLJIT set-up, the absolute-symbol runtime library, the pass pipeline (see jit.h).
#include "jit.h"

#include "energy_dielectric.h"
#include "noise_batch.h"
#include "shadeop_bitcode.h"
#include "shadeops.h"
#include "small_loops.h"

#include <llvm/Config/llvm-config.h>
#include <llvm/ExecutionEngine/Orc/CompileUtils.h>
#include <llvm/ExecutionEngine/Orc/Core.h>
#include <llvm/ExecutionEngine/Orc/JITTargetMachineBuilder.h>
#include <llvm/ExecutionEngine/Orc/LLJIT.h>
#include <llvm/ExecutionEngine/Orc/ThreadSafeModule.h>
#include <llvm/IR/LLVMContext.h>
#include <llvm/IR/LegacyPassManager.h>
#include <llvm/IR/Module.h>
#include <llvm/Passes/PassBuilder.h>
#include <llvm/Support/MemoryBuffer.h>
#include <llvm/Support/TargetSelect.h>
#include <llvm/Support/raw_ostream.h>
#include <llvm/Target/TargetMachine.h>
#include <llvm/TargetParser/Host.h>
#include <llvm/Transforms/IPO/AlwaysInliner.h>
#include <llvm/Transforms/IPO/GlobalDCE.h>
#include <llvm/Transforms/InstCombine/InstCombine.h>
#include <llvm/Transforms/Scalar/ADCE.h>
#include <llvm/Transforms/Scalar/DeadStoreElimination.h>
#include <llvm/Transforms/Scalar/EarlyCSE.h>
#include <llvm/Transforms/Scalar/GVN.h>
#include <llvm/Transforms/Scalar/LoopPassManager.h>
#include <llvm/Transforms/Scalar/LoopUnrollPass.h>
#include <llvm/Transforms/Scalar/Reassociate.h>
#include <llvm/Transforms/Scalar/SCCP.h>
#include <llvm/Transforms/Scalar/SROA.h>
#include <llvm/Transforms/Scalar/SimplifyCFG.h>
#include <llvm/Transforms/Vectorize/SLPVectorizer.h>

#include <dlfcn.h>
#include <elf.h>
#include <link.h>

#include <atomic>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <functional>
#include <utility>

namespace lobe::jit {

struct Jit::State {
  std::unique_ptr<llvm::orc::LLJIT> lljit;
  std::unique_ptr<llvm::TargetMachine> tm; // for emit_assembly (shared: under opt_mutex)
  std::unique_ptr<llvm::orc::JITTargetMachineBuilder> jtmb; // a TargetMachine per optimiser run
  llvm::orc::JITDylib* runtime = nullptr;                   // shadeops and libm, absolute symbols
  std::atomic<uint64_t> counter{0};
  mutable std::mutex opt_mutex; // guards `tm`
  std::mutex dylib_mutex;       // JITDylib creation and removal
};

namespace {
// What the runtime library does not define (a libc function LLVM emits a call to), looked up
// in the process with dlsym when first needed; the runtime library is LLJIT's process-symbols
// dylib (Jit::create). LLJIT's own one opens the process handle at start-up, and it came
// ahead of the runtime library in every group's link order, so every symbol a group linked
// went through dlsym, whose loader lock a concurrent dlopen (the image library, loaded in the
// background while a scene loads) holds for about half a second.
class ProcessFallback : public llvm::orc::DefinitionGenerator {
public:
  llvm::Error tryToGenerate(llvm::orc::LookupState&, llvm::orc::LookupKind, llvm::orc::JITDylib& jd,
                            llvm::orc::JITDylibLookupFlags,
                            const llvm::orc::SymbolLookupSet& symbols) override {
    llvm::orc::SymbolMap found;
    for (const auto& [name, flags] : symbols) {
      if (void* address = dlsym(RTLD_DEFAULT, (*name).str().c_str()))
        found[name] = llvm::orc::ExecutorSymbolDef(llvm::orc::ExecutorAddr::fromPtr(address),
                                                   llvm::JITSymbolFlags::Exported);
    }
    if (found.empty()) return llvm::Error::success();
    return jd.define(llvm::orc::absoluteSymbols(std::move(found)));
  }
};

// Where what goes wrong while linking on this thread is written (ORC reports "Symbols not found:
// [...]" to the session's error reporter and returns only "Failed to materialize symbols" to
// the lookup): Jit::load points it at its own string while it links, and puts that in front of
// the lookup's error. Lookups materialise on the calling thread. A plain pointer: a
// thread_local with a destructor registers it through the loader's lock on first use.
thread_local std::string* t_session_error = nullptr;

double ms_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}
} // namespace

// On x86-64 the target is the host's ISA level capped at x86-64-v3 (AVX2, FMA): with the
// full host feature set (measured on znver4, AVX-512) shader code that calls libm ran 1.35x
// slower than the same C++; at x86-64-v3 it matches it (docs/runtime.md, "Measured").
void cap_x86_level(llvm::orc::JITTargetMachineBuilder& jtmb) {
  if (!jtmb.getTargetTriple().isX86() || jtmb.getTargetTriple().isArch32Bit()) return;
  llvm::StringMap<bool> host = llvm::sys::getHostCPUFeatures();
  auto has = [&](const char* f) { return host.lookup(f); };
  const char* cpu = "x86-64";
  if (has("avx2") && has("fma") && has("bmi2") && has("f16c") && has("movbe"))
    cpu = "x86-64-v3";
  else if (has("sse4.2") && has("popcnt") && has("ssse3"))
    cpu = "x86-64-v2";
  jtmb.setCPU(cpu);
  jtmb.getFeatures() = llvm::SubtargetFeatures();
}

Jit::~Jit() = default;

std::unique_ptr<Jit> Jit::create(std::string& error) {
  llvm::InitializeNativeTarget();
  llvm::InitializeNativeTargetAsmPrinter();
  auto jtmb = llvm::orc::JITTargetMachineBuilder::detectHost();
  if (!jtmb) {
    error = llvm::toString(jtmb.takeError());
    return nullptr;
  }
  jtmb->setCodeGenOptLevel(llvm::CodeGenOptLevel::Less);
  cap_x86_level(*jtmb);
  auto tm = jtmb->createTargetMachine();
  if (!tm) {
    error = llvm::toString(tm.takeError());
    return nullptr;
  }
  // ConcurrentIRCompiler makes a TargetMachine per module, so groups compiled on several
  // threads at once (materials at scene load) compile to machine code in parallel.
  auto lljit =
      llvm::orc::LLJITBuilder()
          .setJITTargetMachineBuilder(*jtmb)
          .setProcessSymbolsJITDylibSetup(
              [](llvm::orc::LLJIT& j) -> llvm::Expected<llvm::orc::JITDylibSP> {
                llvm::orc::JITDylib& rt =
                    j.getExecutionSession().createBareJITDylib("lobe_runtime");
                rt.addGenerator(std::make_unique<ProcessFallback>());
                return &rt;
              })
          .setCompileFunctionCreator(
              [](llvm::orc::JITTargetMachineBuilder j)
                  -> llvm::Expected<std::unique_ptr<llvm::orc::IRCompileLayer::IRCompiler>> {
                return std::make_unique<llvm::orc::ConcurrentIRCompiler>(std::move(j));
              })
          .create();
  if (!lljit) {
    error = llvm::toString(lljit.takeError());
    return nullptr;
  }
  std::unique_ptr<Jit> jit(new Jit);
  jit->s_ = std::make_unique<State>();
  jit->s_->lljit = std::move(*lljit);
  jit->s_->tm = std::move(*tm);
  jit->s_->jtmb = std::make_unique<llvm::orc::JITTargetMachineBuilder>(*jtmb);
  llvm::orc::JITDylib& rt = *jit->s_->lljit->getProcessSymbolsJITDylib();
  llvm::orc::SymbolMap symbols;
  for (const auto& s : shadeops::shadeop_symbols())
    symbols[jit->s_->lljit->mangleAndIntern(s.name)] = llvm::orc::ExecutorSymbolDef(
        llvm::orc::ExecutorAddr::fromPtr(s.address),
        llvm::JITSymbolFlags::Exported | llvm::JITSymbolFlags::Callable);
  // Data the closure bitcode declares instead of defining (energy_dielectric.h): the host's
  // copies, by their Itanium-mangled names.
  const std::pair<const char*, const void*> tables[] = {
      {"_ZN4lobe8closures6kDielEE", &closures::kDielE},
      {"_ZN4lobe8closures11kDielEAnisoE", &closures::kDielEAniso}};
  for (const auto& [name, address] : tables)
    symbols[jit->s_->lljit->mangleAndIntern(name)] = llvm::orc::ExecutorSymbolDef(
        llvm::orc::ExecutorAddr::fromPtr(address), llvm::JITSymbolFlags::Exported);
  if (auto err = rt.define(llvm::orc::absoluteSymbols(std::move(symbols)))) {
    error = llvm::toString(std::move(err));
    return nullptr;
  }
  jit->s_->runtime = &rt;
  jit->s_->lljit->getExecutionSession().setErrorReporter([](llvm::Error err) {
    if (!t_session_error) // not while Jit::load links: as LLJIT's default reporter does
      return llvm::logAllUnhandledErrors(std::move(err), llvm::errs(), "JIT session error: ");
    if (!t_session_error->empty()) *t_session_error += "; ";
    *t_session_error += llvm::toString(std::move(err));
  });
  return jit;
}

void Jit::configure(llvm::Module& module) const {
  module.setTargetTriple(s_->tm->getTargetTriple().str());
  module.setDataLayout(s_->tm->createDataLayout());
}

namespace {
// A pass builder for `tm` with its analysis managers registered and cross-linked.
struct Analyses {
  llvm::LoopAnalysisManager lam;
  llvm::FunctionAnalysisManager fam;
  llvm::CGSCCAnalysisManager cgam;
  llvm::ModuleAnalysisManager mam;
  llvm::PassBuilder pb;
  explicit Analyses(llvm::TargetMachine* tm) : pb(tm) {
    pb.registerModuleAnalyses(mam);
    pb.registerCGSCCAnalyses(cgam);
    pb.registerFunctionAnalyses(fam);
    pb.registerLoopAnalyses(lam);
    pb.crossRegisterProxies(lam, fam, cgam, mam);
  }
};

// After -O2 with noise batching (noise_batch.h): the loops that would form groups unrolled,
// independent calls gathered into W-point ones, those linked, the family inlined and the
// functions cleaned up: SSA for the lanes' buffers, the inlined bodies folded on their constant
// arguments (the seeds), vectorised where the host allows, and what is dead removed. Fresh
// analyses each time: the module changed outside any pass. Returns the calls gathered.
int finish_noise_batching(llvm::Module& module, llvm::TargetMachine* tm) {
  if (!defines_noise_family(module)) return 0;
  {
    // The loops that call the family a few times unrolled and folded (their iteration budget
    // checks are constants then), so that their calls share a block.
    Analyses a(tm);
    llvm::FunctionPassManager fpm;
    fpm.addPass(MarkNoiseLoopsPass());
    fpm.addPass(llvm::createFunctionToLoopPassAdaptor(llvm::LoopFullUnrollPass(2)));
    fpm.addPass(llvm::InstCombinePass());
    fpm.addPass(llvm::SimplifyCFGPass());
    fpm.addPass(llvm::EarlyCSEPass(true));
    llvm::ModulePassManager mpm;
    mpm.addPass(llvm::createModuleToFunctionPassAdaptor(std::move(fpm)));
    mpm.run(module, a.mam);
  }
  int gathered = batch_noise_calls(module);
  if (gathered > 0) link_shadeop_bitcode(module); // the W-point functions
  inline_noise_family(module);
  Analyses a(tm);
  llvm::ModulePassManager mpm;
  mpm.addPass(llvm::AlwaysInlinerPass(false));
  mpm.addPass(llvm::GlobalDCEPass());
  llvm::FunctionPassManager fpm;
  fpm.addPass(llvm::SROAPass(llvm::SROAOptions::ModifyCFG));
  fpm.addPass(llvm::EarlyCSEPass(true));
  fpm.addPass(llvm::InstCombinePass());
  fpm.addPass(llvm::SimplifyCFGPass());
  fpm.addPass(llvm::SLPVectorizerPass());
  fpm.addPass(llvm::InstCombinePass());
  fpm.addPass(llvm::ADCEPass());
  mpm.addPass(llvm::createModuleToFunctionPassAdaptor(std::move(fpm)));
  mpm.run(module, a.mam);
  return gathered;
}
} // namespace

// -O0: SROA only (turns the symbol allocas into SSA values; no other transformation).
// -O1: a short function pipeline suited to shader code (straight-line, alloca-heavy, calls
// into shadeops): SROA makes SSA, then CSE, combining, CFG clean-up, GVN and dead code.
// -O2: LLVM's full per-module O2 pipeline (adds inlining, loop passes, vectorisation), after
// linking in the bitcode of the pure shadeops the module calls; then noise batching.
int Jit::optimize(llvm::Module& module, int opt_level) const {
  // A TargetMachine of its own (the cost model is not thread-safe), so runs go in parallel.
  auto own = s_->jtmb->createTargetMachine();
  std::unique_lock<std::mutex> lock(s_->opt_mutex, std::defer_lock);
  llvm::TargetMachine* tm = own ? own->get() : nullptr;
  if (!own) {
    llvm::consumeError(own.takeError());
    lock.lock();
    tm = s_->tm.get();
  }
  Analyses a(tm);
  llvm::FunctionAnalysisManager& fam = a.fam;
  if (opt_level >= 2) {
    // The pure shadeops the module calls, from bitcode, so that the inliner below specialises
    // them on their arguments (shadeop_bitcode.h); the same bits as the out-of-line calls.
    link_shadeop_bitcode(module);
    // Small counted loops unrolled in full by the pipeline's own LoopFullUnrollPass
    // (small_loops.h).
    a.pb.registerLateLoopOptimizationsEPCallback(
        [](llvm::LoopPassManager& lpm, llvm::OptimizationLevel) {
          lpm.addPass(MarkSmallLoopsPass());
        });
    llvm::ModulePassManager mpm = a.pb.buildPerModuleDefaultPipeline(llvm::OptimizationLevel::O2);
    mpm.run(module, a.mam);
    return noise_batching() ? finish_noise_batching(module, tm) : 0;
  }
  llvm::FunctionPassManager fpm;
  fpm.addPass(llvm::SROAPass(llvm::SROAOptions::ModifyCFG));
  if (opt_level <= 0) { // only SSA construction: instruction selection on allocas is slow
    for (llvm::Function& f : module)
      if (!f.isDeclaration()) fpm.run(f, fam);
    return 0;
  }
  fpm.addPass(llvm::EarlyCSEPass(true));
  fpm.addPass(llvm::InstCombinePass());
  fpm.addPass(llvm::SimplifyCFGPass());
  fpm.addPass(llvm::SCCPPass());
  fpm.addPass(llvm::GVNPass());
  fpm.addPass(llvm::DSEPass());
  fpm.addPass(llvm::InstCombinePass());
  fpm.addPass(llvm::SimplifyCFGPass());
  fpm.addPass(llvm::ADCEPass());
  for (llvm::Function& f : module)
    if (!f.isDeclaration()) fpm.run(f, fam);
  return 0;
}

bool Jit::add(std::unique_ptr<llvm::LLVMContext> context, std::unique_ptr<llvm::Module> module,
              int opt_level, const std::string& entry, CompiledGroup& out, JitTimes& times,
              std::string& error, const HostSymbols& host) {
  std::vector<void*> addresses;
  return add(std::move(context), std::move(module), opt_level, {entry}, addresses, out, times,
             error, host);
}

bool Jit::add(std::unique_ptr<llvm::LLVMContext> context, std::unique_ptr<llvm::Module> module,
              int opt_level, const std::vector<std::string>& entries, std::vector<void*>& addresses,
              CompiledGroup& out, JitTimes& times, std::string& error, const HostSymbols& host) {
  auto t0 = std::chrono::steady_clock::now();
  times.noise_batched = optimize(*module, opt_level);
  times.optimize_ms = ms_since(t0);
  auto t1 = std::chrono::steady_clock::now();
  llvm::orc::ThreadSafeModule tsm(std::move(module), std::move(context));
  bool ok =
      load([&](llvm::orc::JITDylib& jd) { return s_->lljit->addIRModule(jd, std::move(tsm)); },
           entries, addresses, out, error, host);
  times.codegen_ms = ms_since(t1);
  return ok;
}

// A fresh JITDylib linked against the runtime, filled by `fill`, its `entries` looked up (which
// compiles or links them); on failure the dylib is removed again.
bool Jit::load(const std::function<llvm::Error(llvm::orc::JITDylib&)>& fill,
               const std::vector<std::string>& entries, std::vector<void*>& addresses,
               CompiledGroup& out, std::string& error, const HostSymbols& host) {
  auto& lljit = *s_->lljit;
  std::string name = "lobe_group_" + std::to_string(s_->counter++);
  std::unique_lock<std::mutex> dylib_lock(s_->dylib_mutex);
  auto jd = lljit.createJITDylib(name);
  dylib_lock.unlock();
  if (!jd) {
    error = llvm::toString(jd.takeError());
    return false;
  }
  std::string session_error;
  t_session_error = &session_error;
  struct Unset {
    ~Unset() { t_session_error = nullptr; }
  } unset;
  auto fail = [&](llvm::Error err) {
    error = llvm::toString(std::move(err));
    if (!session_error.empty()) error = session_error + " (" + error + ")";
    llvm::consumeError(lljit.getExecutionSession().removeJITDylib(*jd));
    return false;
  };
  if (!host.empty()) {
    llvm::orc::SymbolMap symbols;
    for (const auto& [symbol, address] : host)
      symbols[lljit.mangleAndIntern(symbol)] = llvm::orc::ExecutorSymbolDef(
          llvm::orc::ExecutorAddr::fromPtr(address), llvm::JITSymbolFlags::Exported);
    if (auto err = jd->define(llvm::orc::absoluteSymbols(std::move(symbols))))
      return fail(std::move(err));
  }
  if (auto err = fill(*jd)) return fail(std::move(err));
  addresses.clear();
  for (const std::string& entry : entries) {
    auto addr = lljit.lookup(*jd, entry);
    if (!addr) return fail(addr.takeError());
    addresses.push_back(addr->toPtr<void*>());
  }
  out.entry = addresses.empty() ? nullptr : addresses.front();
  out.dylib = &*jd;
  return true;
}

bool Jit::compile_object(llvm::Module& module, int opt_level, std::string& object, JitTimes& times,
                         std::string& error) const {
  auto t0 = std::chrono::steady_clock::now();
  times.noise_batched = optimize(module, opt_level);
  times.optimize_ms = ms_since(t0);
  auto t1 = std::chrono::steady_clock::now();
  auto tm = s_->jtmb->createTargetMachine(); // one of its own: runs go in parallel
  if (!tm) {
    error = llvm::toString(tm.takeError());
    return false;
  }
  llvm::SmallString<0> bytes;
  llvm::raw_svector_ostream os(bytes);
  llvm::legacy::PassManager pm;
  if ((*tm)->addPassesToEmitFile(pm, os, nullptr, llvm::CodeGenFileType::ObjectFile)) {
    error = "the target machine cannot emit objects";
    return false;
  }
  pm.run(module);
  object.assign(bytes.begin(), bytes.end());
  times.codegen_ms = ms_since(t1);
  return true;
}

bool Jit::add_object(const std::string& object, const std::vector<std::string>& entries,
                     std::vector<void*>& addresses, CompiledGroup& out, std::string& error,
                     const HostSymbols& host) {
  return load(
      [&](llvm::orc::JITDylib& jd) {
        return s_->lljit->addObjectFile(jd, llvm::MemoryBuffer::getMemBufferCopy(object, "object"));
      },
      entries, addresses, out, error, host);
}

// The GNU build ID (a hash the linker takes of the whole linked file) of the executable or
// shared object that holds this code, in hex; "" when it has none.
std::string own_build_id() {
  struct Search {
    uintptr_t address;
    std::string id;
  } search{reinterpret_cast<uintptr_t>(&own_build_id), {}};
  auto visit = [](dl_phdr_info* info, size_t, void* data) -> int {
    auto* s = static_cast<Search*>(data);
    bool holds = false;
    for (int i = 0; i < info->dlpi_phnum; ++i) {
      const ElfW(Phdr)& ph = info->dlpi_phdr[i];
      uintptr_t start = info->dlpi_addr + ph.p_vaddr;
      holds |= ph.p_type == PT_LOAD && s->address >= start && s->address < start + ph.p_memsz;
    }
    if (!holds) return 0;
    for (int i = 0; i < info->dlpi_phnum; ++i) {
      const ElfW(Phdr)& ph = info->dlpi_phdr[i];
      if (ph.p_type != PT_NOTE) continue;
      const char* p = reinterpret_cast<const char*>(info->dlpi_addr + ph.p_vaddr);
      const char* end = p + ph.p_memsz;
      while (size_t(end - p) >= sizeof(ElfW(Nhdr))) {
        ElfW(Nhdr) n;
        std::memcpy(&n, p, sizeof n);
        const char* name = p + sizeof n;
        const char* desc = name + ((n.n_namesz + 3) & ~3u);
        const char* next = desc + ((n.n_descsz + 3) & ~3u);
        if (next > end) break;
        if (n.n_type == NT_GNU_BUILD_ID && n.n_namesz == 4 && std::memcmp(name, "GNU", 4) == 0) {
          for (uint32_t k = 0; k < n.n_descsz; ++k) {
            char hex[3];
            std::snprintf(hex, sizeof hex, "%02x", static_cast<unsigned char>(desc[k]));
            s->id += hex;
          }
          return 1;
        }
        p = next;
      }
    }
    return 1;
  };
  dl_iterate_phdr(visit, &search);
  return search.id;
}

std::string Jit::target_identity() const {
  std::string id = "llvm " LLVM_VERSION_STRING "; ";
  id += s_->jtmb->getTargetTriple().str() + "; cpu " + s_->jtmb->getCPU() + "; features " +
        s_->jtmb->getFeatures().getString() + "; codegen O1"; // Jit::create's CodeGenOptLevel::Less
  id += "; unroll " + std::to_string(small_loop_budget());
  // What the code cached depends on: optimize()'s pipelines (this file), the linking of the
  // shadeop bitcode and the closure kernels' dispatchers (other files of this library). The
  // build ID of the file holding them changes with any of it; the stamp of this file stands in
  // where the linker wrote none.
  static const std::string build = own_build_id();
  id += build.empty() ? "; jit.cpp of " __DATE__ " " __TIME__ : "; build " + build;
  return id;
}

bool Jit::emit_assembly(llvm::Module& module, std::string& out, std::string& error) const {
  std::lock_guard<std::mutex> lock(s_->opt_mutex); // the TargetMachine is shared
  llvm::SmallString<0> text;
  llvm::raw_svector_ostream os(text);
  llvm::legacy::PassManager pm;
  if (s_->tm->addPassesToEmitFile(pm, os, nullptr, llvm::CodeGenFileType::AssemblyFile)) {
    error = "the target machine cannot emit assembly";
    return false;
  }
  pm.run(module);
  out.assign(text.begin(), text.end());
  return true;
}

void Jit::remove(CompiledGroup& group) {
  if (!group.dylib) return;
  std::lock_guard<std::mutex> lock(s_->dylib_mutex);
  llvm::consumeError(s_->lljit->getExecutionSession().removeJITDylib(*group.dylib));
  group = {};
}

} // namespace lobe::jit
