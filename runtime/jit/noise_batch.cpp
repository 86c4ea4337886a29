// Noise call batching (noise_batch.h).
#include "noise_batch.h"

#include <llvm/ADT/SetVector.h>
#include <llvm/ADT/SmallVector.h>
#include <llvm/ADT/Twine.h>
#include <llvm/Analysis/LoopInfo.h>
#include <llvm/Analysis/ScalarEvolution.h>
#include <llvm/Analysis/ValueTracking.h>
#include <llvm/IR/BasicBlock.h>
#include <llvm/IR/Function.h>
#include <llvm/IR/IRBuilder.h>
#include <llvm/IR/Instructions.h>
#include <llvm/IR/Module.h>
#include <llvm/Transforms/Utils/LoopUtils.h>

#include <algorithm>
#include <cstdlib>
#include <map>
#include <string>
#include <vector>

namespace lobe::jit {
namespace {

// A one-point function of the family: how many coordinates it takes, then whether a 32-bit
// seed (the channel); it returns a float, or with three channels a <4 x float> (channels in
// lanes 0-2, lane 3 zero). Its W-point forms are name_x4 and name_x8. `fewest`: the smallest
// group worth gathering. One point of 3-D or 4-D gradient noise already fills eight lanes
// with its corners (runtime/shadeops/noise.cpp), so four points in four lanes hash with twice
// the instructions; eight points in eight lanes pay for themselves from five calls (measured:
// fbm of 6 octaves 1.57x, 5 octaves 1.4x faster; 4 calls of 4-D triple noise 9% slower in four
// lanes). 2-D gradient noise (four corners) and simplex noise of one point keep few lanes busy:
// two calls already pay (4 octaves of 2-D noise and a 2-D colour noise: 1.53x).
struct Family {
  const char* name;
  unsigned coords;
  bool seeded;
  unsigned channels;
  unsigned fewest;
};
constexpr Family kFamily[] = {
    {"lobe_perlin_v2", 2, false, 1, 2}, {"lobe_perlin_v2c", 2, false, 3, 2},
    {"lobe_perlin_v3", 3, false, 1, 5}, {"lobe_perlin_v3c", 3, false, 3, 5},
    {"lobe_perlin_v4", 4, false, 1, 5}, {"lobe_perlin_v4c", 4, false, 3, 5},
    {"lobe_simplex_v1", 1, true, 1, 2}, {"lobe_simplex_v2", 2, true, 1, 2},
    {"lobe_simplex_v3", 3, true, 1, 2}, {"lobe_simplex_v4", 4, true, 1, 2}};

const Family* family_of(llvm::StringRef name) {
  for (const Family& f : kFamily)
    if (name == f.name) return &f;
  return nullptr;
}

// The one-point function's expected type: (float x coords[, i32]) -> float or <4 x float>.
bool has_expected_type(const llvm::Function& fn, const Family& f) {
  llvm::FunctionType* t = fn.getFunctionType();
  llvm::Type* r = t->getReturnType();
  bool result = f.channels == 1 ? r->isFloatTy()
                                : r->isVectorTy() && r->getScalarType()->isFloatTy() &&
                                      llvm::cast<llvm::FixedVectorType>(r)->getNumElements() == 4;
  if (t->isVarArg() || !result || t->getNumParams() != f.coords + (f.seeded ? 1 : 0)) return false;
  for (unsigned a = 0; a < f.coords; ++a)
    if (!t->getParamType(a)->isFloatTy()) return false;
  return !f.seeded || t->getParamType(f.coords)->isIntegerTy(32);
}

// Instructions that may move ahead within their block: no memory access, no side effect, safe
// to compute whether or not the block would have reached them, not a phi.
bool movable(const llvm::Instruction& i) {
  return !llvm::isa<llvm::PHINode>(i) && !i.mayReadOrWriteMemory() && !i.mayHaveSideEffects() &&
         !i.isTerminator() && llvm::isSafeToSpeculativelyExecute(&i);
}

// Whether `call` can join the group that starts at `first` (members in `group`): collects into
// `need` the instructions of the block after `first` that its arguments depend on; false if one
// of them is a member or cannot move ahead of `first`.
bool can_join(llvm::CallInst* call, llvm::CallInst* first,
              const llvm::SmallPtrSetImpl<llvm::Instruction*>& group,
              llvm::SmallSetVector<llvm::Instruction*, 16>& need) {
  llvm::SmallVector<llvm::Value*, 16> work(call->arg_begin(), call->arg_end());
  while (!work.empty()) {
    auto* i = llvm::dyn_cast<llvm::Instruction>(work.pop_back_val());
    if (!i || i->getParent() != first->getParent() || i->comesBefore(first)) continue;
    if (group.contains(i) || !movable(*i)) return false;
    if (!need.insert(i)) continue;
    for (llvm::Value* op : i->operands()) work.push_back(op);
  }
  return true;
}

// The W-point function for `f` (declared; linked from the bitcode afterwards).
llvm::FunctionCallee wide_function(llvm::Module& m, const Family& f, unsigned width) {
  llvm::LLVMContext& ctx = m.getContext();
  llvm::Type* ptr = llvm::PointerType::getUnqual(ctx);
  auto* type = llvm::FunctionType::get(llvm::Type::getVoidTy(ctx), {ptr, ptr, ptr}, false);
  return m.getOrInsertFunction((llvm::Twine(f.name) + "_x" + llvm::Twine(width)).str(), type);
}

// Replaces the calls of `group` (in block order, all calling the function of `f`) by one W-point
// call where the first one was, after moving `need` (in block order) ahead of it.
void rewrite(const Family& f, const std::vector<llvm::CallInst*>& group,
             const std::vector<llvm::Instruction*>& need) {
  llvm::CallInst* first = group.front();
  for (llvm::Instruction* i : need) i->moveBefore(first);
  llvm::Function& fn = *first->getFunction();
  llvm::Module& m = *fn.getParent();
  llvm::LLVMContext& ctx = m.getContext();
  const unsigned width = group.size() <= 4 ? 4 : 8; // (gradient noise: always 8, fewest 5)
  // The lanes' buffers are vectors, stored and loaded whole, as the W-point function reads and
  // writes them: SROA then keeps them in registers (buffers of scalars stayed in memory, each
  // vector read a store-forwarding stall).
  auto* fv = llvm::FixedVectorType::get(llvm::Type::getFloatTy(ctx), width);
  auto* iv = llvm::FixedVectorType::get(llvm::Type::getInt32Ty(ctx), width);
  llvm::IRBuilder<> entry(&fn.getEntryBlock(), fn.getEntryBlock().getFirstInsertionPt());
  llvm::AllocaInst* xs = entry.CreateAlloca(llvm::ArrayType::get(fv, f.coords));
  llvm::AllocaInst* seeds = entry.CreateAlloca(iv);
  llvm::AllocaInst* outs = entry.CreateAlloca(llvm::ArrayType::get(fv, f.channels));
  llvm::IRBuilder<> b(first);
  // Lanes past the group's compute its first point again (their results are not read).
  auto lane = [&](unsigned l) { return group[l < group.size() ? l : 0]; };
  for (unsigned a = 0; a < f.coords; ++a) {
    llvm::Value* v = llvm::PoisonValue::get(fv);
    for (unsigned l = 0; l < width; ++l)
      v = b.CreateInsertElement(v, lane(l)->getArgOperand(a), uint64_t(l));
    b.CreateStore(v, b.CreateConstInBoundsGEP2_32(xs->getAllocatedType(), xs, 0, a));
  }
  llvm::Value* sv = llvm::PoisonValue::get(iv);
  for (unsigned l = 0; l < width; ++l)
    sv = b.CreateInsertElement(sv, f.seeded ? lane(l)->getArgOperand(f.coords) : b.getInt32(0),
                               uint64_t(l));
  b.CreateStore(sv, seeds);
  b.CreateCall(wide_function(m, f, width), {xs, seeds, outs});
  std::vector<llvm::Value*> results;
  for (unsigned j = 0; j < f.channels; ++j)
    results.push_back(
        b.CreateLoad(fv, b.CreateConstInBoundsGEP2_32(outs->getAllocatedType(), outs, 0, j)));
  for (unsigned l = 0; l < group.size(); ++l) {
    llvm::Value* v = b.CreateExtractElement(results[0], uint64_t(l));
    if (f.channels > 1) { // <c0, c1, c2, 0>, as the one-point function returns
      llvm::Type* v4 = group[l]->getType();
      llvm::Value* r = llvm::Constant::getNullValue(v4);
      for (unsigned j = 0; j < f.channels; ++j)
        r = b.CreateInsertElement(r, b.CreateExtractElement(results[j], uint64_t(l)), uint64_t(j));
      v = r;
    }
    group[l]->replaceAllUsesWith(v);
  }
  for (llvm::CallInst* c : group) c->eraseFromParent();
}

int batch_block(llvm::BasicBlock& bb) {
  std::map<const Family*, std::vector<llvm::CallInst*>> calls;
  for (llvm::Instruction& i : bb)
    if (auto* call = llvm::dyn_cast<llvm::CallInst>(&i))
      if (llvm::Function* callee = call->getCalledFunction())
        if (const Family* f = family_of(callee->getName()); f && has_expected_type(*callee, *f))
          calls[f].push_back(call);
  int gathered = 0;
  for (auto& [f, list] : calls) {
    while (list.size() >= 2) {
      llvm::CallInst* first = list.front();
      llvm::SmallPtrSet<llvm::Instruction*, 8> members{first};
      std::vector<llvm::CallInst*> group{first}, rest;
      llvm::SmallSetVector<llvm::Instruction*, 16> need;
      for (size_t k = 1; k < list.size(); ++k) {
        llvm::SmallSetVector<llvm::Instruction*, 16> more = need;
        if (group.size() < 8 && can_join(list[k], first, members, more)) {
          group.push_back(list[k]);
          members.insert(list[k]);
          need = std::move(more);
        } else {
          rest.push_back(list[k]);
        }
      }
      if (group.size() >= std::max(2u, f->fewest)) {
        std::vector<llvm::Instruction*> ordered;
        for (llvm::Instruction& i : bb)
          if (need.contains(&i)) ordered.push_back(&i);
        rewrite(*f, group, ordered);
        gathered += int(group.size());
      }
      list = std::move(rest);
    }
  }
  return gathered;
}

} // namespace

bool noise_batching() {
  static const bool on = [] {
    const char* e = std::getenv("LOBE_NOISE_BATCH");
    return !(e && std::string(e) == "0");
  }();
  return on;
}

bool batchable_function(llvm::StringRef name) { return family_of(name) != nullptr; }

bool wide_noise_function(llvm::StringRef name) {
  return (name.consume_back("_x4") || name.consume_back("_x8")) && batchable_function(name);
}

bool defines_noise_family(const llvm::Module& module) {
  for (const llvm::Function& fn : module)
    if (!fn.isDeclaration() && batchable_function(fn.getName())) return true;
  return false;
}

llvm::PreservedAnalyses MarkNoiseLoopsPass::run(llvm::Function& f,
                                                llvm::FunctionAnalysisManager& fam) {
  auto& loops = fam.getResult<llvm::LoopAnalysis>(f);
  auto& se = fam.getResult<llvm::ScalarEvolutionAnalysis>(f);
  for (llvm::Loop* l : loops.getLoopsInPreorder()) {
    if (!l->isInnermost()) continue;
    std::map<const Family*, unsigned> per_family;
    unsigned calls = 0;
    for (llvm::BasicBlock* bb : l->blocks())
      for (llvm::Instruction& i : *bb)
        if (auto* call = llvm::dyn_cast<llvm::CallInst>(&i))
          if (llvm::Function* callee = call->getCalledFunction())
            if (const Family* fam_of = family_of(callee->getName())) {
              ++per_family[fam_of];
              ++calls;
            }
    llvm::BasicBlock* latch = l->getLoopLatch();
    if (calls == 0 || !latch || !l->isLoopExiting(latch)) continue;
    unsigned trips = se.getSmallConstantTripCount(l, latch);
    if (trips < 2 || trips > 16 || trips * calls > 64) continue;
    // Unrolled only if a group could form: a loop whose calls would stay alone is code grown
    // for nothing (4 iterations of 4-D triple noise: twice the machine-code time).
    bool worth = false;
    for (const auto& [fm, n] : per_family) worth |= n * trips >= std::max(2u, fm->fewest);
    if (worth) llvm::addStringMetadataToLoop(l, "llvm.loop.unroll.full");
  }
  return llvm::PreservedAnalyses::all(); // metadata only
}

int batch_noise_calls(llvm::Module& module) {
  int gathered = 0;
  for (llvm::Function& fn : module) {
    if (fn.isDeclaration() || batchable_function(fn.getName())) continue;
    for (llvm::BasicBlock& bb : fn) gathered += batch_block(bb);
  }
  return gathered;
}

void inline_noise_family(llvm::Module& module) {
  // (The W-point functions are gone already: link_shadeop_bitcode inlines them as it links them.)
  for (llvm::Function& fn : module) {
    if (fn.isDeclaration() || !batchable_function(fn.getName())) continue;
    fn.removeFnAttr(llvm::Attribute::NoInline);
    fn.addFnAttr(llvm::Attribute::AlwaysInline);
    fn.setLinkage(llvm::GlobalValue::InternalLinkage);
  }
}

} // namespace lobe::jit
