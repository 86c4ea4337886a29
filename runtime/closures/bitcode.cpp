// Closure entry points compiled with clang-19 to LLVM bitcode (lobe_closures.bc) for the JIT
// to link and inline into materials. Each registry BSDF key K gets, with C linkage:
//   void  lobe_closure_K_eval(const unsigned char* params, const Vec3* wo, const Vec3* wi,
//                             int mode, LobeEval* out)        mode: 0 radiance, 1 importance
//   int   lobe_closure_K_sample(const unsigned char* params, const Vec3* wo, const Vec3* u,
//                               int mode, LobeSample* out)    returns out->ok
//   float lobe_closure_K_pdf(const unsigned char* params, const Vec3* wo, const Vec3* wi)
//   void  lobe_closure_K_albedo(const unsigned char* params, const Vec3* wo, Vec3* out)
// and the same four with an explicit registry id as first argument, lobe_closure_eval(id, ...)
// etc., whose switch folds away when the id is a constant. Structs are those of common.h;
// directions are world space as in closures.h. measured_bsdf is native-only (it reads files).
#include "dispatch.h"

using namespace lobe;
using namespace lobe::closures;

namespace {

Transport to_mode(int m) { return m == 1 ? Transport::Importance : Transport::Radiance; }

inline void eval_id(int id, const unsigned char* p, const Vec3* wo, const Vec3* wi, int mode,
                    LobeEval* out) {
  *out = LobeEval{};
  with_lobe(id, p, [&](const auto& l, const Frame& f) {
    *out = eval_lobe(l, f, *wo, *wi, to_mode(mode));
  });
}
inline int sample_id(int id, const unsigned char* p, const Vec3* wo, const Vec3* u, int mode,
                     LobeSample* out) {
  *out = LobeSample{};
  with_lobe(id, p, [&](const auto& l, const Frame& f) {
    *out = sample_lobe(l, f, *wo, *u, to_mode(mode));
  });
  return out->ok ? 1 : 0;
}
inline void albedo_id(int id, const unsigned char* p, const Vec3* wo, Vec3* out) {
  *out = Vec3{};
  with_lobe(id, p, [&](const auto& l, const Frame& f) { *out = albedo_lobe(l, f, *wo); });
}

} // namespace

extern "C" {

void lobe_closure_eval(int id, const unsigned char* p, const Vec3* wo, const Vec3* wi, int mode,
                       LobeEval* out) {
  eval_id(id, p, wo, wi, mode, out);
}
int lobe_closure_sample(int id, const unsigned char* p, const Vec3* wo, const Vec3* u, int mode,
                        LobeSample* out) {
  return sample_id(id, p, wo, u, mode, out);
}
float lobe_closure_pdf(int id, const unsigned char* p, const Vec3* wo, const Vec3* wi) {
  LobeEval e;
  eval_id(id, p, wo, wi, 0, &e);
  return e.pdf;
}
void lobe_closure_albedo(int id, const unsigned char* p, const Vec3* wo, Vec3* out) {
  albedo_id(id, p, wo, out);
}

// One set of four entries per BSDF key (the names are the registry keys).
#define LOBE_ENTRIES(key, ID)                                                                      \
  void lobe_closure_##key##_eval(const unsigned char* p, const Vec3* wo, const Vec3* wi, int mode, \
                                 LobeEval* out) {                                                  \
    eval_id(ID, p, wo, wi, mode, out);                                                             \
  }                                                                                                \
  int lobe_closure_##key##_sample(const unsigned char* p, const Vec3* wo, const Vec3* u, int mode, \
                                  LobeSample* out) {                                               \
    return sample_id(ID, p, wo, u, mode, out);                                                     \
  }                                                                                                \
  float lobe_closure_##key##_pdf(const unsigned char* p, const Vec3* wo, const Vec3* wi) {         \
    LobeEval e;                                                                                    \
    eval_id(ID, p, wo, wi, 0, &e);                                                                 \
    return e.pdf;                                                                                  \
  }                                                                                                \
  void lobe_closure_##key##_albedo(const unsigned char* p, const Vec3* wo, Vec3* out) {            \
    albedo_id(ID, p, wo, out);                                                                     \
  }

LOBE_ENTRIES(diffuse, kDiffuseId)
LOBE_ENTRIES(oren_nayar, kOrenNayarId)
LOBE_ENTRIES(oren_nayar_diffuse_bsdf, kOrenNayarDiffuseId)
LOBE_ENTRIES(burley_diffuse_bsdf, kBurleyId)
LOBE_ENTRIES(translucent, kTranslucentId)
LOBE_ENTRIES(translucent_bsdf, kTranslucentBsdfId)
LOBE_ENTRIES(phong, kPhongId)
LOBE_ENTRIES(blinn_phong, kBlinnPhongId)
LOBE_ENTRIES(ward, kWardId)
LOBE_ENTRIES(microfacet, kMicrofacetId)
LOBE_ENTRIES(reflection, kReflectionId)
LOBE_ENTRIES(refraction, kRefractionId)
LOBE_ENTRIES(conductor_bsdf, kConductorId)
LOBE_ENTRIES(dielectric_bsdf, kDielectricId)
LOBE_ENTRIES(generalized_schlick_bsdf, kGeneralizedSchlickId)
LOBE_ENTRIES(sheen_bsdf, kSheenId)
LOBE_ENTRIES(toon, kToonId)
LOBE_ENTRIES(subsurface_bssrdf, kSubsurfaceBssrdfId)
#undef LOBE_ENTRIES

} // extern "C"
