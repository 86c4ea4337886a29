// The shadeop table (see shadeops.h): every symbol JIT code may call, with its signature.
// libm and libc entries are here too: LLVM lowers intrinsics (llvm.sin, memcpy, ...) to calls
// of these names, and the JIT resolves nothing that is not in this table.
#include "shadeops.h"

#include "shadeop_decls.h"
#include "shadeop_sig.h"

#include <cmath>
#include <cstring>
#include <math.h>
#include <vector>

namespace lobe::shadeops {
namespace {

template <class F> void* addr(F* f) { return reinterpret_cast<void*>(f); }
// A row: the symbol's name, its address and the signature its C type gives (shadeop_sig.h).
// clang-format off
#define LOBE_SHADEOP(f) {#f, addr(f), shadeop_sig<decltype(f)>}
#define LOBE_LIBC(name, fp) {name, addr(fp), shadeop_sig<decltype(fp)>}
#define LOBE_WIDE_SHADEOPS(f) LOBE_SHADEOP(f##_x4), LOBE_SHADEOP(f##_x8) // noise_batch.h's W-point forms
// clang-format on
using F1 = float (*)(float);
using F2 = float (*)(float, float);
using Copy = void* (*)(void*, const void*, size_t); // without glibc's nonnull attributes
using Fill = void* (*)(void*, int, size_t);

const ShadeOpSymbol kTable[] = {
    // the shadeops of this folder (prototypes in shadeop_decls.h)
    LOBE_SHADEOP(lobe_printf),
    LOBE_SHADEOP(lobe_format),
    LOBE_SHADEOP(lobe_warning),
    LOBE_SHADEOP(lobe_error),
    LOBE_SHADEOP(lobe_fprintf),
    LOBE_SHADEOP(lobe_range_error),
    LOBE_SHADEOP(lobe_loop_check),
    LOBE_SHADEOP(lobe_naninf_check),
    LOBE_SHADEOP(lobe_uninit_check),
    LOBE_SHADEOP(lobe_split),
    LOBE_SHADEOP(lobe_dict_find),
    LOBE_SHADEOP(lobe_dict_find_node),
    LOBE_SHADEOP(lobe_dict_next),
    LOBE_SHADEOP(lobe_dict_value),
    LOBE_SHADEOP(lobe_pointcloud),
    LOBE_SHADEOP(lobe_concat),
    LOBE_SHADEOP(lobe_substr),
    LOBE_SHADEOP(lobe_strhash),
    LOBE_SHADEOP(lobe_raytype_bit),
// clang-format off
    // the library calls, from their rows (runtime/registry/library_calls.h)
#define LOBE_LIBRARY_TABLE_ROW(x, e, name, R, P, fn, doc) \
    {#fn, addr(library_c::fn), shadeop_sig<decltype(library_c::fn)>},
    LOBE_LIBRARY_CALLS(LOBE_LIBRARY_TABLE_ROW, _)
#undef LOBE_LIBRARY_TABLE_ROW
    // clang-format on
    LOBE_SHADEOP(lobe_hash),
    LOBE_SHADEOP(lobe_regex),
    LOBE_SHADEOP(lobe_regex_results),
    LOBE_SHADEOP(lobe_closure_component),
    LOBE_SHADEOP(lobe_closure_add),
    LOBE_SHADEOP(lobe_closure_declared),
    LOBE_SHADEOP(lobe_closure_mul),
    LOBE_SHADEOP(lobe_closure_weight),
    LOBE_SHADEOP(lobe_mat_mul),
    LOBE_SHADEOP(lobe_mat_inverse),
    LOBE_SHADEOP(lobe_mat_div),
    LOBE_SHADEOP(lobe_mat_transpose),
    LOBE_SHADEOP(lobe_mat_det),
    LOBE_SHADEOP(lobe_get_matrix),
    LOBE_SHADEOP(lobe_get_transform),
    LOBE_SHADEOP(lobe_space_matrix),
    LOBE_SHADEOP(lobe_transform),
    LOBE_SHADEOP(lobe_transformc),
    LOBE_SHADEOP(lobe_transformc_d),
    LOBE_SHADEOP(lobe_color_from),
    LOBE_SHADEOP(lobe_transformu_scale),
    LOBE_SHADEOP(lobe_wavelength_color),
    LOBE_SHADEOP(lobe_blackbody),
    LOBE_SHADEOP(lobe_noise),
    LOBE_SHADEOP(lobe_noise_named),
    LOBE_SHADEOP(lobe_noise_d),
    LOBE_SHADEOP(lobe_perlin_v2),
    LOBE_SHADEOP(lobe_perlin_v3),
    LOBE_SHADEOP(lobe_perlin_v4),
    LOBE_SHADEOP(lobe_simplex_v1),
    LOBE_SHADEOP(lobe_simplex_v2),
    LOBE_SHADEOP(lobe_simplex_v3),
    LOBE_SHADEOP(lobe_simplex_v4),
    LOBE_WIDE_SHADEOPS(lobe_perlin_v2),
    LOBE_WIDE_SHADEOPS(lobe_perlin_v2c),
    LOBE_WIDE_SHADEOPS(lobe_perlin_v3),
    LOBE_WIDE_SHADEOPS(lobe_perlin_v3c),
    LOBE_WIDE_SHADEOPS(lobe_perlin_v4),
    LOBE_WIDE_SHADEOPS(lobe_perlin_v4c),
    LOBE_WIDE_SHADEOPS(lobe_simplex_v1),
    LOBE_WIDE_SHADEOPS(lobe_simplex_v2),
    LOBE_WIDE_SHADEOPS(lobe_simplex_v3),
    LOBE_WIDE_SHADEOPS(lobe_simplex_v4),
    LOBE_SHADEOP(lobe_noise_named_d),
    LOBE_SHADEOP(lobe_gabor),
    LOBE_SHADEOP(lobe_spline),
    LOBE_SHADEOP(lobe_texture),
    LOBE_SHADEOP(lobe_getattribute),
    LOBE_SHADEOP(lobe_get_userdata),
    LOBE_SHADEOP(lobe_setmessage),
    LOBE_SHADEOP(lobe_getmessage),
    LOBE_SHADEOP(lobe_gettextureinfo),
    LOBE_SHADEOP(lobe_trace),
    LOBE_SHADEOP(lobe_texture3d),
    LOBE_SHADEOP(lobe_environment),
    LOBE_SHADEOP(lobe_splineinverse),
    LOBE_SHADEOP(lobe_splineinverse_d),
    // libm / libc
    LOBE_LIBC("sinf", F1(::sinf)),
    LOBE_LIBC("cosf", F1(::cosf)),
    LOBE_LIBC("tanf", F1(::tanf)),
    LOBE_LIBC("asinf", F1(::asinf)),
    LOBE_LIBC("acosf", F1(::acosf)),
    LOBE_LIBC("atanf", F1(::atanf)),
    LOBE_LIBC("atan2f", F2(::atan2f)),
    LOBE_LIBC("sinhf", F1(::sinhf)),
    LOBE_LIBC("coshf", F1(::coshf)),
    LOBE_LIBC("tanhf", F1(::tanhf)),
    LOBE_LIBC("expf", F1(::expf)),
    LOBE_LIBC("exp2f", F1(::exp2f)),
    LOBE_LIBC("exp10f", F1(::exp10f)),
    LOBE_LIBC("expm1f", F1(::expm1f)),
    LOBE_LIBC("logf", F1(::logf)),
    LOBE_LIBC("log2f", F1(::log2f)),
    LOBE_LIBC("log10f", F1(::log10f)),
    LOBE_LIBC("logbf", F1(::logbf)),
    LOBE_LIBC("powf", F2(::powf)),
    LOBE_LIBC("sqrtf", F1(::sqrtf)),
    LOBE_LIBC("cbrtf", F1(::cbrtf)),
    LOBE_LIBC("erff", F1(::erff)),
    LOBE_LIBC("erfcf", F1(::erfcf)),
    LOBE_LIBC("fmodf", F2(::fmodf)),
    LOBE_LIBC("floorf", F1(::floorf)),
    LOBE_LIBC("ceilf", F1(::ceilf)),
    LOBE_LIBC("roundf", F1(::roundf)),
    LOBE_LIBC("truncf", F1(::truncf)),
    LOBE_LIBC("fabsf", F1(::fabsf)),
    LOBE_LIBC("hypotf", F2(::hypotf)),
    LOBE_LIBC("fminf", F2(::fminf)),
    LOBE_LIBC("fmaxf", F2(::fmaxf)),
    LOBE_LIBC("sincosf", ::sincosf),
    LOBE_LIBC("ldexpf", static_cast<float (*)(float, int)>(::ldexpf)),
    LOBE_LIBC("memcpy", Copy(::memcpy)),
    LOBE_LIBC("memmove", Copy(::memmove)),
    LOBE_LIBC("memset", Fill(::memset)),
};

} // namespace

std::span<const ShadeOpSymbol> shadeop_symbols() {
  static const std::vector<ShadeOpSymbol> all = [] {
    std::vector<ShadeOpSymbol> v(std::begin(kTable), std::end(kTable));
    for (const ShadeOpSymbol& s : math_shadeop_symbols()) v.push_back(s);
    return v;
  }();
  return all;
}

const ShadeOpSymbol* find_shadeop(std::string_view name) {
  for (const auto& s : shadeop_symbols())
    if (name == s.name) return &s;
  return nullptr;
}

} // namespace lobe::shadeops
