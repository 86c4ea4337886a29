// The shadeop table (see shadeops.h): every symbol JIT code may call, with its signature.
// libm and libc entries are here too: LLVM lowers intrinsics (llvm.sin, memcpy, ...) to calls
// of these names, and the JIT resolves nothing that is not in this table.
#include "shadeops.h"

#include <cmath>
#include <cstring>
#include <math.h>
#include <vector>

extern "C" {
// Declarations of the shadeops defined in this folder (C linkage, one definition each).
void lobe_printf();
void lobe_format();
void lobe_warning();
void lobe_error();
void lobe_range_error();
void lobe_loop_check();
void lobe_naninf_check();
void lobe_uninit_check();
void lobe_fprintf();
void lobe_concat();
void lobe_strlen();
void lobe_substr();
void lobe_startswith();
void lobe_endswith();
void lobe_stoi();
void lobe_stof();
void lobe_getchar();
void lobe_strhash();
void lobe_hash();
void lobe_regex();
void lobe_regex_results();
void lobe_split();
void lobe_dict_find();
void lobe_dict_find_node();
void lobe_dict_next();
void lobe_dict_value();
void lobe_pointcloud();
void lobe_closure_component();
void lobe_closure_add();
void lobe_closure_declared();
void lobe_closure_mul();
void lobe_mat_mul();
void lobe_mat_inverse();
void lobe_mat_div();
void lobe_mat_transpose();
void lobe_mat_det();
void lobe_get_matrix();
void lobe_space_matrix();
void lobe_transform();
void lobe_transformc();
void lobe_transformc_d();
void lobe_color_from();
void lobe_transformu_scale();
void lobe_wavelength_color();
void lobe_blackbody();
void lobe_noise();
void lobe_noise_named();
void lobe_noise_d();
void lobe_noise_named_d();
void lobe_gabor();
void lobe_spline();
void lobe_texture();
void lobe_getattribute();
void lobe_get_userdata();
void lobe_setmessage();
void lobe_getmessage();
void lobe_gettextureinfo();
void lobe_trace();
void lobe_texture3d();
void lobe_environment();
void lobe_splineinverse();
}

namespace lobe::shadeops {
namespace {

template <class F> void* addr(F* f) { return reinterpret_cast<void*>(f); }
using F1 = float (*)(float);
using F2 = float (*)(float, float);

const ShadeOpSymbol kTable[] = {
    // name, address, signature (return type, then parameters)
    {"lobe_printf", addr(lobe_printf), "vppppp"},
    {"lobe_format", addr(lobe_format), "ppppp"},
    {"lobe_warning", addr(lobe_warning), "vpppppp"},
    {"lobe_error", addr(lobe_error), "vpppppp"},
    {"lobe_fprintf", addr(lobe_fprintf), "vpppppp"},
    {"lobe_range_error", addr(lobe_range_error), "vpiippip"},
    {"lobe_loop_check", addr(lobe_loop_check), "lppllpppi"},
    {"lobe_naninf_check", addr(lobe_naninf_check), "vppiiiippip"},
    {"lobe_uninit_check", addr(lobe_uninit_check), "vpppiiipppipipi"},
    {"lobe_split", addr(lobe_split), "ipppipi"},
    {"lobe_dict_find", addr(lobe_dict_find), "ippp"},
    {"lobe_dict_find_node", addr(lobe_dict_find_node), "ipip"},
    {"lobe_dict_next", addr(lobe_dict_next), "ipi"},
    {"lobe_dict_value", addr(lobe_dict_value), "ippipiip"},
    {"lobe_pointcloud", addr(lobe_pointcloud), "ippp"},
    {"lobe_concat", addr(lobe_concat), "pppp"},
    {"lobe_strlen", addr(lobe_strlen), "ip"},
    {"lobe_substr", addr(lobe_substr), "pppii"},
    {"lobe_startswith", addr(lobe_startswith), "ipp"},
    {"lobe_endswith", addr(lobe_endswith), "ipp"},
    {"lobe_stoi", addr(lobe_stoi), "ip"},
    {"lobe_stof", addr(lobe_stof), "fp"},
    {"lobe_getchar", addr(lobe_getchar), "ipi"},
    {"lobe_strhash", addr(lobe_strhash), "ip"},
    {"lobe_hash", addr(lobe_hash), "ipi"},
    {"lobe_regex", addr(lobe_regex), "ippi"},
    {"lobe_regex_results", addr(lobe_regex_results), "ippipi"},
    {"lobe_closure_component", addr(lobe_closure_component), "ppipi"},
    {"lobe_closure_add", addr(lobe_closure_add), "pppp"},
    {"lobe_closure_declared", addr(lobe_closure_declared), "pppp"},
    {"lobe_closure_mul", addr(lobe_closure_mul), "pppp"},
    {"lobe_mat_mul", addr(lobe_mat_mul), "vppp"},
    {"lobe_mat_inverse", addr(lobe_mat_inverse), "vpp"},
    {"lobe_mat_div", addr(lobe_mat_div), "vppp"},
    {"lobe_mat_transpose", addr(lobe_mat_transpose), "vpp"},
    {"lobe_mat_det", addr(lobe_mat_det), "fp"},
    {"lobe_get_matrix", addr(lobe_get_matrix), "ipppp"},
    {"lobe_space_matrix", addr(lobe_space_matrix), "vppp"},
    {"lobe_transform", addr(lobe_transform), "vpppi"},
    {"lobe_transformc", addr(lobe_transformc), "vpppppp"},
    {"lobe_transformc_d", addr(lobe_transformc_d), "vpppppp"},
    {"lobe_color_from", addr(lobe_color_from), "vppppp"},
    {"lobe_transformu_scale", addr(lobe_transformu_scale), "fppppi"},
    {"lobe_wavelength_color", addr(lobe_wavelength_color), "vppf"},
    {"lobe_blackbody", addr(lobe_blackbody), "vppf"},
    {"lobe_noise", addr(lobe_noise), "vipippip"},
    {"lobe_noise_named", addr(lobe_noise_named), "vpppippippi"},
    {"lobe_noise_d", addr(lobe_noise_d), "vipppippppi"},
    {"lobe_noise_named_d", addr(lobe_noise_named_d), "vpppppipppppipi"},
    {"lobe_gabor", addr(lobe_gabor), "vpppipppppi"},
    {"lobe_spline", addr(lobe_spline), "vpfpiipp"},
    {"lobe_texture", addr(lobe_texture), "vpppffffffipppp"},
    {"lobe_getattribute", addr(lobe_getattribute), "ippppiiipppp"},
    {"lobe_get_userdata", addr(lobe_get_userdata), "ipppiip"},
    {"lobe_setmessage", addr(lobe_setmessage), "vppippii"},
    {"lobe_getmessage", addr(lobe_getmessage), "ipppiippii"},
    {"lobe_gettextureinfo", addr(lobe_gettextureinfo), "ipppiffpip"},
    {"lobe_trace", addr(lobe_trace), "ipppppppp"},
    {"lobe_texture3d", addr(lobe_texture3d), "vpppppppipp"},
    {"lobe_environment", addr(lobe_environment), "vpppppppipp"},
    {"lobe_splineinverse", addr(lobe_splineinverse), "fpfpi"},
    // libm / libc
    {"sinf", addr(F1(::sinf)), "ff"},
    {"cosf", addr(F1(::cosf)), "ff"},
    {"tanf", addr(F1(::tanf)), "ff"},
    {"asinf", addr(F1(::asinf)), "ff"},
    {"acosf", addr(F1(::acosf)), "ff"},
    {"atanf", addr(F1(::atanf)), "ff"},
    {"atan2f", addr(F2(::atan2f)), "fff"},
    {"sinhf", addr(F1(::sinhf)), "ff"},
    {"coshf", addr(F1(::coshf)), "ff"},
    {"tanhf", addr(F1(::tanhf)), "ff"},
    {"expf", addr(F1(::expf)), "ff"},
    {"exp2f", addr(F1(::exp2f)), "ff"},
    {"exp10f", addr(F1(::exp10f)), "ff"},
    {"expm1f", addr(F1(::expm1f)), "ff"},
    {"logf", addr(F1(::logf)), "ff"},
    {"log2f", addr(F1(::log2f)), "ff"},
    {"log10f", addr(F1(::log10f)), "ff"},
    {"logbf", addr(F1(::logbf)), "ff"},
    {"powf", addr(F2(::powf)), "fff"},
    {"sqrtf", addr(F1(::sqrtf)), "ff"},
    {"cbrtf", addr(F1(::cbrtf)), "ff"},
    {"erff", addr(F1(::erff)), "ff"},
    {"erfcf", addr(F1(::erfcf)), "ff"},
    {"fmodf", addr(F2(::fmodf)), "fff"},
    {"floorf", addr(F1(::floorf)), "ff"},
    {"ceilf", addr(F1(::ceilf)), "ff"},
    {"roundf", addr(F1(::roundf)), "ff"},
    {"truncf", addr(F1(::truncf)), "ff"},
    {"fabsf", addr(F1(::fabsf)), "ff"},
    {"hypotf", addr(F2(::hypotf)), "fff"},
    {"fminf", addr(F2(::fminf)), "fff"},
    {"fmaxf", addr(F2(::fmaxf)), "fff"},
    {"sincosf", addr(::sincosf), "vfpp"},
    {"ldexpf", addr(static_cast<float (*)(float, int)>(::ldexpf)), "ffi"},
    {"memcpy", addr(::memcpy), "pppl"},
    {"memmove", addr(::memmove), "pppl"},
    {"memset", addr(::memset), "ppil"},
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
