#include "small_loops.h"

#include "noise_batch.h"

#include <llvm/Analysis/LoopInfo.h>
#include <llvm/Analysis/ScalarEvolution.h>
#include <llvm/IR/Instructions.h>
#include <llvm/Transforms/Utils/LoopUtils.h>

#include <cstdlib>

namespace lobe::jit {

unsigned small_loop_budget() {
  static const unsigned budget = [] {
    const char* e = std::getenv("LOBE_UNROLL_BUDGET");
    return e && *e ? unsigned(std::strtoul(e, nullptr, 10)) : kSmallLoopMaxUnrolledSize;
  }();
  return budget;
}

llvm::PreservedAnalyses MarkSmallLoopsPass::run(llvm::Loop& loop, llvm::LoopAnalysisManager&,
                                                llvm::LoopStandardAnalysisResults& ar,
                                                llvm::LPMUpdater&) {
  if (!loop.isInnermost()) return llvm::PreservedAnalyses::all();
  llvm::BasicBlock* latch = loop.getLoopLatch();
  if (!latch || !loop.isLoopExiting(latch)) return llvm::PreservedAnalyses::all();
  unsigned trips = ar.SE.getSmallConstantTripCount(&loop, latch);
  if (trips < 2 || trips > kSmallLoopMaxTrips) return llvm::PreservedAnalyses::all();
  unsigned size = 0;
  for (llvm::BasicBlock* bb : loop.blocks())
    for (const llvm::Instruction& i : *bb) {
      if (i.isDebugOrPseudoInst()) continue;
      // A one-point noise call is one instruction here and hundreds once inlined after -O2:
      // such loops are MarkNoiseLoopsPass's to unroll, when their calls would form a group.
      if (auto* call = llvm::dyn_cast<llvm::CallInst>(&i))
        if (llvm::Function* callee = call->getCalledFunction())
          if (batchable_function(callee->getName())) return llvm::PreservedAnalyses::all();
      ++size;
    }
  if (size * trips > small_loop_budget()) return llvm::PreservedAnalyses::all();
  llvm::addStringMetadataToLoop(&loop, "llvm.loop.unroll.full");
  return llvm::PreservedAnalyses::all(); // metadata only
}

} // namespace lobe::jit
