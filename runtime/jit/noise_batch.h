// Noise call batching: independent calls of one value-only noise function in a shader, gathered
// into one call that evaluates them side by side in vector lanes.
//
// A procedural shader calls noise many times per point at inputs that do not depend on each
// other: the octaves of an fbm loop once unrolled, the channels of a vector noise, the layers of
// a pattern. One call computes one point with scalar arithmetic (vectorised at best over a
// cell's corners, with shuffles and horizontal sums); W calls side by side keep every lane busy
// on the same operations. The W-point functions (lobe_simplex_v3_x8, lobe_perlin_v3_x4 and
// their kin, runtime/shadeops/noise.cpp) compute each lane's bits exactly as the one-point function
// does, so batching never changes a result.
//
// How it runs, at -O2 only and with the shadeop bitcode linked (shadeop_bitcode.h): the
// one-point functions (batchable_function()) stay calls with external linkage through LLVM's O2
// pipeline, so that constants fold and common calls merge around them but their signatures stay
// as written. Then the loops that call them with a small constant trip count are unrolled
// (MarkNoiseLoopsPass), and batch_noise_calls() works through each basic block: calls
// of one function whose arguments do not depend (through the block's pure instructions) on
// another call of the group become one W-point call at the first one's place, with the pure
// instructions computing their arguments moved ahead of it. Finally the W-point functions are
// linked from the bitcode and everything of the family is inlined (Jit::optimize).
#pragma once

#include <llvm/ADT/StringRef.h>
#include <llvm/IR/PassManager.h>

namespace lobe::jit {

// On unless $LOBE_NOISE_BATCH is "0" (a measurement switch; part of the disk-cache key through
// shadeop_bitcode_identity()).
bool noise_batching();

// The one-point functions batching gathers (kept as calls through O2 while batching is on).
bool batchable_function(llvm::StringRef name);

// Their W-point forms (name_x4, name_x8), which batching calls.
bool wide_noise_function(llvm::StringRef name);

// Marks the innermost loops that call the one-point functions, with a small constant trip count
// (at most 16 iterations and 64 calls once unrolled) and calls enough to form a group once
// unrolled, llvm.loop.unroll.full: an octave loop that -O2's cost model left rolled unrolls
// under the mark, and its calls can only be gathered once it has.
class MarkNoiseLoopsPass : public llvm::PassInfoMixin<MarkNoiseLoopsPass> {
public:
  llvm::PreservedAnalyses run(llvm::Function& f, llvm::FunctionAnalysisManager& fam);
};

// Whether `module` defines a one-point function (batching has anything to do).
bool defines_noise_family(const llvm::Module& module);

// Replaces groups of independent calls in `module` by W-point calls (declared, not yet linked);
// returns how many calls were gathered into groups.
int batch_noise_calls(llvm::Module& module);

// After batch_noise_calls() and the W-point functions' linking: every one-point function left in
// `module` made internal and always-inline (the caller runs the inliner and a clean-up).
void inline_noise_family(llvm::Module& module);

} // namespace lobe::jit
