// Closure entry points compiled with clang-19 to LLVM bitcode (lobe_closures.bc) for the JIT
// to link and inline into materials. Each registry key K gets (symbol names from
// LOBE_KERNEL_SYMBOL, closure_registry.h; only BSDF keys with bitcode are ever linked):
//   unsigned lobe_closure_K_setup(const unsigned char* params, void* state)
//                       sets the lobe up in `state` (Bsdf::kLobeStateBytes), returns its
//                       LobeFlags, 0: no lobe
//   void  lobe_closure_K_eval(const void* state, const Vec3* wo, const Vec3* wi, int mode,
//                             BsdfEval* out)          mode: 0 radiance, 1 importance
//   int   lobe_closure_K_sample(const void* state, const Vec3* wo, const Vec3* u, int mode,
//                               BsdfSample* out)      returns out->pdf > 0
//   float lobe_closure_K_pdf(const void* state, const Vec3* wo, const Vec3* wi)
//   void  lobe_closure_K_albedo(const void* state, const Vec3* wo, Vec3* out)
// and the same five with an explicit registry id as first argument, lobe_closure_setup(id,
// ...) etc., whose switch folds away when the id is a constant. Structs are BsdfEval /
// BsdfSample (lobe/bsdf.h); directions are world space as in closures.h. measured_bsdf is
// native-only (it reads files).
#include "dispatch.h"

using namespace lobe;
using namespace lobe::closures;

namespace {

Transport to_mode(int m) { return m == 1 ? Transport::Importance : Transport::Radiance; }

inline uint32_t setup_id(int id, const unsigned char* p, void* state) {
  return setup_lobe(id, p, state);
}
inline void eval_id(int id, const void* st, const Vec3* wo, const Vec3* wi, int mode,
                    BsdfEval* out) {
  *out = BsdfEval{};
  with_prepared(id, st, [&](const auto& l, const Frame& f) {
    *out = eval_lobe(l, f, *wo, *wi, to_mode(mode));
  });
}
inline int sample_id(int id, const void* st, const Vec3* wo, const Vec3* u, int mode,
                     BsdfSample* out) {
  *out = BsdfSample{};
  with_prepared(id, st, [&](const auto& l, const Frame& f) {
    *out = sample_lobe(l, f, *wo, *u, to_mode(mode));
  });
  return out->pdf > 0.0f ? 1 : 0;
}
inline void albedo_id(int id, const void* st, const Vec3* wo, Vec3* out) {
  *out = Vec3{};
  with_prepared(id, st, [&](const auto& l, const Frame& f) { *out = albedo_lobe(l, f, *wo); });
}

} // namespace

extern "C" {

unsigned lobe_closure_setup(int id, const unsigned char* p, void* state) {
  return setup_id(id, p, state);
}
void lobe_closure_eval(int id, const void* st, const Vec3* wo, const Vec3* wi, int mode,
                       BsdfEval* out) {
  eval_id(id, st, wo, wi, mode, out);
}
int lobe_closure_sample(int id, const void* st, const Vec3* wo, const Vec3* u, int mode,
                        BsdfSample* out) {
  return sample_id(id, st, wo, u, mode, out);
}
float lobe_closure_pdf(int id, const void* st, const Vec3* wo, const Vec3* wi) {
  BsdfEval e;
  eval_id(id, st, wo, wi, 0, &e);
  return e.pdf;
}
void lobe_closure_albedo(int id, const void* st, const Vec3* wo, Vec3* out) {
  albedo_id(id, st, wo, out);
}

} // extern "C"

// One set of five entries per registry key, generated from the registry's table; the symbol
// names are LOBE_KERNEL_SYMBOL's, the ones the JIT asks for (registry::kernel_symbol). Entries
// with no lobe here (non-BSDF, native-only) do nothing and are never linked.
namespace lobe_closure_kernels {
#define LOBE_ENTRIES(key, ...)                                                                     \
  unsigned key##_setup(const unsigned char* p, void* st) __asm__(LOBE_KERNEL_SYMBOL(key, setup));  \
  unsigned key##_setup(const unsigned char* p, void* st) {                                         \
    return setup_id(closure_id::key, p, st);                                                       \
  }                                                                                                \
  void key##_eval(const void* st, const Vec3* wo, const Vec3* wi, int mode,                        \
                  BsdfEval* out) __asm__(LOBE_KERNEL_SYMBOL(key, eval));                           \
  void key##_eval(const void* st, const Vec3* wo, const Vec3* wi, int mode, BsdfEval* out) {       \
    eval_id(closure_id::key, st, wo, wi, mode, out);                                               \
  }                                                                                                \
  int key##_sample(const void* st, const Vec3* wo, const Vec3* u, int mode,                        \
                   BsdfSample* out) __asm__(LOBE_KERNEL_SYMBOL(key, sample));                      \
  int key##_sample(const void* st, const Vec3* wo, const Vec3* u, int mode, BsdfSample* out) {     \
    return sample_id(closure_id::key, st, wo, u, mode, out);                                       \
  }                                                                                                \
  float key##_pdf(const void* st, const Vec3* wo,                                                  \
                  const Vec3* wi) __asm__(LOBE_KERNEL_SYMBOL(key, pdf));                           \
  float key##_pdf(const void* st, const Vec3* wo, const Vec3* wi) {                                \
    BsdfEval e;                                                                                    \
    eval_id(closure_id::key, st, wo, wi, 0, &e);                                                   \
    return e.pdf;                                                                                  \
  }                                                                                                \
  void key##_albedo(const void* st, const Vec3* wo,                                                \
                    Vec3* out) __asm__(LOBE_KERNEL_SYMBOL(key, albedo));                           \
  void key##_albedo(const void* st, const Vec3* wo, Vec3* out) {                                   \
    albedo_id(closure_id::key, st, wo, out);                                                       \
  }
LOBE_CLOSURE_TABLE(LOBE_ENTRIES)
#undef LOBE_ENTRIES
} // namespace lobe_closure_kernels
