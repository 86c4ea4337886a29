// Closure entry points compiled with clang-19 to LLVM bitcode (lobe_closures.bc) for the JIT
// to link and inline into materials. Each registry key K gets (symbol names from
// LOBE_KERNEL_SYMBOL, closure_registry.h; only BSDF keys with bitcode are ever linked):
//   void  lobe_closure_K_eval(const unsigned char* params, const Vec3* wo, const Vec3* wi,
//                             int mode, BsdfEval* out)        mode: 0 radiance, 1 importance
//   int   lobe_closure_K_sample(const unsigned char* params, const Vec3* wo, const Vec3* u,
//                               int mode, BsdfSample* out)    returns out->pdf > 0
//   float lobe_closure_K_pdf(const unsigned char* params, const Vec3* wo, const Vec3* wi)
//   void  lobe_closure_K_albedo(const unsigned char* params, const Vec3* wo, Vec3* out)
// and the same four with an explicit registry id as first argument, lobe_closure_eval(id, ...)
// etc., whose switch folds away when the id is a constant. Structs are BsdfEval / BsdfSample
// (lobe/bsdf.h); directions are world space as in closures.h. measured_bsdf is native-only (it
// reads files).
#include "dispatch.h"

using namespace lobe;
using namespace lobe::closures;

namespace {

Transport to_mode(int m) { return m == 1 ? Transport::Importance : Transport::Radiance; }

inline void eval_id(int id, const unsigned char* p, const Vec3* wo, const Vec3* wi, int mode,
                    BsdfEval* out) {
  *out = BsdfEval{};
  with_lobe(id, p, [&](const auto& l, const Frame& f) {
    *out = eval_lobe(l, f, *wo, *wi, to_mode(mode));
  });
}
inline int sample_id(int id, const unsigned char* p, const Vec3* wo, const Vec3* u, int mode,
                     BsdfSample* out) {
  *out = BsdfSample{};
  with_lobe(id, p, [&](const auto& l, const Frame& f) {
    *out = sample_lobe(l, f, *wo, *u, to_mode(mode));
  });
  return out->pdf > 0.0f ? 1 : 0;
}
inline void albedo_id(int id, const unsigned char* p, const Vec3* wo, Vec3* out) {
  *out = Vec3{};
  with_lobe(id, p, [&](const auto& l, const Frame& f) { *out = albedo_lobe(l, f, *wo); });
}

} // namespace

extern "C" {

void lobe_closure_eval(int id, const unsigned char* p, const Vec3* wo, const Vec3* wi, int mode,
                       BsdfEval* out) {
  eval_id(id, p, wo, wi, mode, out);
}
int lobe_closure_sample(int id, const unsigned char* p, const Vec3* wo, const Vec3* u, int mode,
                        BsdfSample* out) {
  return sample_id(id, p, wo, u, mode, out);
}
float lobe_closure_pdf(int id, const unsigned char* p, const Vec3* wo, const Vec3* wi) {
  BsdfEval e;
  eval_id(id, p, wo, wi, 0, &e);
  return e.pdf;
}
void lobe_closure_albedo(int id, const unsigned char* p, const Vec3* wo, Vec3* out) {
  albedo_id(id, p, wo, out);
}

} // extern "C"

// One set of four entries per registry key, generated from the registry's table; the symbol
// names are LOBE_KERNEL_SYMBOL's, the ones the JIT asks for (registry::kernel_symbol). Entries
// with no lobe here (non-BSDF, native-only) evaluate to nothing and are never linked.
namespace lobe_closure_kernels {
#define LOBE_ENTRIES(key, ...)                                                                     \
  void key##_eval(const unsigned char* p, const Vec3* wo, const Vec3* wi, int mode,                \
                  BsdfEval* out) __asm__(LOBE_KERNEL_SYMBOL(key, eval));                           \
  void key##_eval(const unsigned char* p, const Vec3* wo, const Vec3* wi, int mode,                \
                  BsdfEval* out) {                                                                 \
    eval_id(closure_id::key, p, wo, wi, mode, out);                                                \
  }                                                                                                \
  int key##_sample(const unsigned char* p, const Vec3* wo, const Vec3* u, int mode,                \
                   BsdfSample* out) __asm__(LOBE_KERNEL_SYMBOL(key, sample));                      \
  int key##_sample(const unsigned char* p, const Vec3* wo, const Vec3* u, int mode,                \
                   BsdfSample* out) {                                                              \
    return sample_id(closure_id::key, p, wo, u, mode, out);                                        \
  }                                                                                                \
  float key##_pdf(const unsigned char* p, const Vec3* wo,                                          \
                  const Vec3* wi) __asm__(LOBE_KERNEL_SYMBOL(key, pdf));                           \
  float key##_pdf(const unsigned char* p, const Vec3* wo, const Vec3* wi) {                        \
    BsdfEval e;                                                                                    \
    eval_id(closure_id::key, p, wo, wi, 0, &e);                                                    \
    return e.pdf;                                                                                  \
  }                                                                                                \
  void key##_albedo(const unsigned char* p, const Vec3* wo,                                        \
                    Vec3* out) __asm__(LOBE_KERNEL_SYMBOL(key, albedo));                           \
  void key##_albedo(const unsigned char* p, const Vec3* wo, Vec3* out) {                           \
    albedo_id(closure_id::key, p, wo, out);                                                        \
  }
LOBE_CLOSURE_TABLE(LOBE_ENTRIES)
#undef LOBE_ENTRIES
} // namespace lobe_closure_kernels
