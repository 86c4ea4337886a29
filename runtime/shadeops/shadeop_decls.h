// The shadeops' C prototypes, one per function, as defined in this folder: table.cpp takes
// each address and derives its signature string from the type (shadeop_sig), and every
// defining file includes this header, so a definition that drifts from its prototype does not
// compile (two extern "C" declarations of one name with different types are an error).
#pragma once

#include "library_calls.h"

#include <cstdint>

namespace lobe {
struct ShaderGlobals;
struct ClosureNode;
struct DeclaredClosureInfo;
struct TraceOptions;
namespace shadeops {
struct RuntimeEnv;
struct TextureArgs;
struct GaborOptions;
} // namespace shadeops
} // namespace lobe

extern "C" {
void lobe_printf(lobe::ShaderGlobals* sg, lobe::shadeops::RuntimeEnv* env, const char* fmt,
                 const char* codes, const void* const* args);
const char* lobe_format(lobe::shadeops::RuntimeEnv* env, const char* fmt, const char* codes,
                        const void* const* args);
void lobe_warning(lobe::ShaderGlobals* sg, lobe::shadeops::RuntimeEnv* env, const char* shader,
                  const char* fmt, const char* codes, const void* const* args);
void lobe_error(lobe::ShaderGlobals* sg, lobe::shadeops::RuntimeEnv* env, const char* shader,
                const char* fmt, const char* codes, const void* const* args);
void lobe_range_error(lobe::ShaderGlobals* sg, int index, int length, const char* what,
                      const char* file, int line, const char* where);
int64_t lobe_loop_check(lobe::ShaderGlobals* sg, int64_t* count, int64_t chunk, int64_t limit,
                        const char* shader, const char* where, const char* file, int line);
void lobe_naninf_check(lobe::ShaderGlobals* sg, const float* vals, int ncomps, int derivs,
                       int first, int count, const char* symbol, const char* file, int line,
                       const char* opname);
void lobe_uninit_check(lobe::ShaderGlobals* sg, lobe::shadeops::RuntimeEnv* env, void* vals,
                       int kind, int first, int count, const char* type, const char* symbol,
                       const char* file, int line, const char* where, int opnum, const char* opname,
                       int argnum);
void lobe_fprintf(lobe::ShaderGlobals* sg, lobe::shadeops::RuntimeEnv* env, const char* file,
                  const char* fmt, const char* codes, const void* const* args);
const char* lobe_concat(lobe::shadeops::RuntimeEnv* env, const char* a, const char* b);
const char* lobe_substr(lobe::shadeops::RuntimeEnv* env, const char* s, int start, int len);
int lobe_strhash(const char* s);
// raytype(name)'s bit in ShaderGlobals::raytype (kRayCamera...; 0 for a name that is none).
int lobe_raytype_bit(const char* name);
int32_t lobe_hash(const uint32_t* words, int32_t n);
int lobe_regex(const char* s, const char* pattern, int full_match);
int lobe_regex_results(const char* s, const char* pattern, int full_match, int* results, int n);
int lobe_split(lobe::shadeops::RuntimeEnv* env, const char* s, const char* sep, int maxsplit,
               const char** results, int n);
int lobe_dict_find(lobe::ShaderGlobals* sg, const char* dict, const char* query);
int lobe_dict_find_node(lobe::ShaderGlobals* sg, int node, const char* query);
int lobe_dict_next(lobe::ShaderGlobals* sg, int node);
int lobe_dict_value(lobe::ShaderGlobals* sg, lobe::shadeops::RuntimeEnv* env, int node,
                    const char* attribute, int code, int derivs, void* dest);
int lobe_pointcloud(lobe::ShaderGlobals* sg, lobe::shadeops::RuntimeEnv* env, const char* function);
const lobe::ClosureNode* lobe_closure_component(lobe::ShaderGlobals* sg, int id, const void* block,
                                                int block_size);
const lobe::ClosureNode* lobe_closure_add(lobe::ShaderGlobals* sg, const lobe::ClosureNode* a,
                                          const lobe::ClosureNode* b);
const lobe::ClosureNode* lobe_closure_declared(lobe::ShaderGlobals* sg,
                                               const lobe::DeclaredClosureInfo* info,
                                               const void* block);
const lobe::ClosureNode* lobe_closure_mul(lobe::ShaderGlobals* sg, const lobe::ClosureNode* c,
                                          const float* w);
// A component just made and read by nothing else, weighted in place: as lobe_closure_mul, without
// the node (codegen uses it for a `closure` result whose only reader is the weighting op).
const lobe::ClosureNode* lobe_closure_weight(lobe::ShaderGlobals* sg, const lobe::ClosureNode* c,
                                             const float* w);
void lobe_mat_mul(float* dst, const float* a, const float* b);
void lobe_mat_inverse(float* dst, const float* src);
void lobe_mat_div(float* dst, const float* a, const float* b);
void lobe_mat_transpose(float* dst, const float* m);
float lobe_mat_det(const float* m);
int lobe_get_matrix(lobe::ShaderGlobals* sg, const char* from, const char* to, float* dst);
void lobe_get_transform(lobe::ShaderGlobals* sg, const char* from, const char* to, float* dst);
void lobe_space_matrix(lobe::ShaderGlobals* sg, const char* space, float* dst);
void lobe_transform(float* dst, const float* m, const float* p, int kind);
void lobe_transformc(lobe::ShaderGlobals* sg, const void* cs, const char* from, const char* to,
                     float* dst, const float* src);
void lobe_transformc_d(lobe::ShaderGlobals* sg, const void* cs, const char* from, const char* to,
                       float* dst, const float* src);
void lobe_color_from(lobe::ShaderGlobals* sg, const void* cs, const char* space, float* dst,
                     const float* src);
float lobe_transformu_scale(lobe::ShaderGlobals* sg, const char* from, const char* to,
                            const char* file, int line);
void lobe_wavelength_color(const void* cs, float* dst, float lambda_nm);
void lobe_blackbody(const void* cs, float* dst, float kelvin);
void lobe_noise(int kind, const float* x, int nin, const float* period, float* out, int nout,
                float* grad);
void lobe_noise_named(lobe::ShaderGlobals* sg, const char* name, const float* x, int nin,
                      const float* period, float* out, int nout, float* grad, const char* file,
                      int line);
void lobe_noise_d(int kind, const float* x, const float* dx, const float* dy, int nin,
                  const float* period, float* out, float* odx, float* ody, int nout);
// Value-only noise for batching (runtime/jit/noise_batch.h): 2-D to 4-D signed gradient noise
// of one channel or three (c: lanes 0-2 of the result; out[j * W + l] in the W-point form), and
// simplex noise; one point, and W = 4 or 8 points at once (x[a * W + l] is coordinate a of
// point l, seed[l] its channel, unused by gradient noise; each lane the one-point function's
// bits). Only the bitcode's copies are called from shaders; the one-point vector forms are not
// in the shadeop table (no signature letter for a vector).
typedef float lobe_float4 __attribute__((vector_size(16)));
// The W-point forms of a one-point function `name`: name_x4 and name_x8.
#define LOBE_WIDE_DECLS(name)                                                                      \
  void name##_x4(const float* x, const uint32_t* seed, float* out);                                \
  void name##_x8(const float* x, const uint32_t* seed, float* out);
float lobe_perlin_v2(float x, float y);
lobe_float4 lobe_perlin_v2c(float x, float y);
float lobe_perlin_v3(float x, float y, float z);
lobe_float4 lobe_perlin_v3c(float x, float y, float z);
float lobe_perlin_v4(float x, float y, float z, float w);
lobe_float4 lobe_perlin_v4c(float x, float y, float z, float w);
float lobe_simplex_v1(float x, uint32_t seed);
float lobe_simplex_v2(float x, float y, uint32_t seed);
float lobe_simplex_v3(float x, float y, float z, uint32_t seed);
float lobe_simplex_v4(float x, float y, float z, float w, uint32_t seed);
LOBE_WIDE_DECLS(lobe_perlin_v2)
LOBE_WIDE_DECLS(lobe_perlin_v2c)
LOBE_WIDE_DECLS(lobe_perlin_v3)
LOBE_WIDE_DECLS(lobe_perlin_v3c)
LOBE_WIDE_DECLS(lobe_perlin_v4)
LOBE_WIDE_DECLS(lobe_perlin_v4c)
LOBE_WIDE_DECLS(lobe_simplex_v1)
LOBE_WIDE_DECLS(lobe_simplex_v2)
LOBE_WIDE_DECLS(lobe_simplex_v3)
LOBE_WIDE_DECLS(lobe_simplex_v4)
#undef LOBE_WIDE_DECLS
void lobe_noise_named_d(lobe::ShaderGlobals* sg, const char* name, const float* x, const float* dx,
                        const float* dy, int nin, const float* period, const void* gabor_opts,
                        float* out, float* odx, float* ody, int nout, const char* file, int line);
void lobe_gabor(const float* x, const float* dx, const float* dy, int nin, const float* period,
                const lobe::shadeops::GaborOptions* opt, float* out, float* odx, float* ody,
                int nout);
void lobe_spline(const char* basis, float x, float xdx, float xdy, int x_derivs, const float* knots,
                 const float* kdx, const float* kdy, int nknots, int comps, float* out, float* odx,
                 float* ody);
void lobe_texture(lobe::ShaderGlobals* sg, lobe::shadeops::RuntimeEnv* env, const char* file,
                  float s, float t, float dsdx, float dtdx, float dsdy, float dtdy, int n,
                  float* out, float* dds, float* ddt, const lobe::shadeops::TextureArgs* a);
int lobe_getattribute(lobe::ShaderGlobals* sg, lobe::shadeops::RuntimeEnv* env, const char* object,
                      const char* name, int index, int code, int derivs, void* dest,
                      const char* shadername, const char* layername, const char* groupname);
int lobe_get_userdata(lobe::ShaderGlobals* sg, lobe::shadeops::RuntimeEnv* env, const char* name,
                      int code, int derivs, void* dest);
void lobe_setmessage(lobe::ShaderGlobals* sg, const char* name, int code, const void* src,
                     const char* file, int line, int layer);
int lobe_getmessage(lobe::ShaderGlobals* sg, lobe::shadeops::RuntimeEnv* env, const char* source,
                    const char* name, int code, int derivs, void* dest, const char* file, int line,
                    int layer);
int lobe_gettextureinfo(lobe::ShaderGlobals* sg, lobe::shadeops::RuntimeEnv* env,
                        const char* shader, const char* file, int udim, float s, float t,
                        const char* query, int code, void* dest);
int lobe_trace(lobe::ShaderGlobals* sg, const float* p, const float* dpdx, const float* dpdy,
               const float* r, const float* drdx, const float* drdy, const lobe::TraceOptions* opt);
void lobe_texture3d(lobe::ShaderGlobals* sg, lobe::shadeops::RuntimeEnv* env, const char* file,
                    const float* p, const float* dpdx, const float* dpdy, const float* dpdz, int n,
                    float* out, const lobe::shadeops::TextureArgs* a);
void lobe_environment(lobe::ShaderGlobals* sg, lobe::shadeops::RuntimeEnv* env, const char* file,
                      const float* r, const float* drdx, const float* drdy, const float* unused,
                      int n, float* out, const lobe::shadeops::TextureArgs* a);
float lobe_splineinverse(const char* basis, float y, const float* knots, int nknots);
void lobe_splineinverse_d(const char* basis, float y, float ydx, float ydy, const float* knots,
                          int nknots, float* out);
}

// The library calls' prototypes, from their rows in compiler/ir/library_calls.h: each tag type
// names the C type the function takes (a definition of another type does not compile).
namespace lobe::shadeops::library_c {
using Int = int;
using Float = float;
using String = const char*;
using Color = const float*;
using Point = const float*;
using Vector = const float*;
using Normal = const float*;
using Env = RuntimeEnv*;
extern "C" {
#define LOBE_LIBRARY_DECL_ROW(x, e, name, R, P, fn, doc) R fn P;
LOBE_LIBRARY_CALLS(LOBE_LIBRARY_DECL_ROW, _)
#undef LOBE_LIBRARY_DECL_ROW
}
} // namespace lobe::shadeops::library_c
