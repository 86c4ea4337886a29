// Full unrolling of small counted loops at -O2, beyond LLVM's own cost model.
//
// Shader loops are often a few iterations over a neighbourhood or a handful of layers
// (`for (int k = -1; k <= 1; ++k)` of a Voronoi search, four rotations of a transform chain).
// LLVM's O2 unrolls a loop in full only when the copies fit its size threshold (about 300
// instructions): a 3-trip loop of 150 instructions stays rolled, and with it each iteration's
// data-dependent branch (`if (d < f1)`) waits for the loop's whole chain of work, and its
// iteration budget check (lobe_loop_check) stays on the path. Unrolled, the iterations' work
// overlaps, the branches become selects where they can, and the budget checks fold away.
//
// MarkSmallLoopsPass runs inside -O2's loop pipeline (PassBuilder's late loop optimisations
// extension point, just before its LoopFullUnrollPass) and marks llvm.loop.unroll.full the
// innermost loops whose latch exits after a small constant number of iterations and whose
// copies stay within a size budget (loops that call one-point noise functions are left to
// MarkNoiseLoopsPass, noise_batch.h: their calls are inlined only later); that LoopFullUnrollPass
// then unrolls them and the rest of the O2 pipeline (GVN, SLP vectorisation, ...) cleans up the
// copies. A nest unrolls from the inside out while the budget holds: an unrolled inner loop makes
// its parent innermost. Unrolling changes no result: the same operations run in the same order.
#pragma once

#include <llvm/Analysis/LoopAnalysisManager.h>
#include <llvm/IR/PassManager.h>
#include <llvm/Transforms/Scalar/LoopPassManager.h>

namespace lobe::jit {

// The most iterations a loop may have to be unrolled, and the most instructions (IR, the
// loop's blocks times its trip count) its unrolled copies may take.
inline constexpr unsigned kSmallLoopMaxTrips = 8;
inline constexpr unsigned kSmallLoopMaxUnrolledSize = 1600;

// The size budget in force: kSmallLoopMaxUnrolledSize, or LOBE_UNROLL_BUDGET (a measurement
// switch; 0 turns this unrolling off). Part of the code cache's key (Jit::target_identity).
unsigned small_loop_budget();

class MarkSmallLoopsPass : public llvm::PassInfoMixin<MarkSmallLoopsPass> {
public:
  llvm::PreservedAnalyses run(llvm::Loop& loop, llvm::LoopAnalysisManager& lam,
                              llvm::LoopStandardAnalysisResults& ar, llvm::LPMUpdater& updater);
};

} // namespace lobe::jit
