// The closures a renderer registered (lobe/closure_plugin.h), as the closure library sees
// them: closures.cpp calls their functions for ids past the built-in table and sanitises what
// they return.
#pragma once

#include "lobe/closure_plugin.h"

namespace lobe::closures {

// The registered closure of registry id `id`, or null (a built-in id, or unknown).
const CustomClosure* plugin(int id);

// The plugin's eval / pdf / sample / albedo with the library's guarantees: finite values >= 0,
// pdf 0 for none; a sample with a unit, non-zero wi, pdf > 0, flags set (the lobe's when the
// plugin gave none); albedo 1 when the plugin has no albedo function.
BsdfEval plugin_eval(const CustomClosure& c, const unsigned char* p, const Vec3& wo, const Vec3& wi,
                     Transport mode);
float plugin_pdf(const CustomClosure& c, const unsigned char* p, const Vec3& wo, const Vec3& wi);
BsdfSample plugin_sample(const CustomClosure& c, const unsigned char* p, const Vec3& wo,
                         const Vec3& u, Transport mode);
Color3 plugin_albedo(const CustomClosure& c, const unsigned char* p, const Vec3& wo);

} // namespace lobe::closures
