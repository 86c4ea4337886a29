// Shading globals for a point of a W x H grid, with OSL testshade's conventions: u = x/(W-1)
// (0.5 when W = 1; (x+0.5)/W with `center`), P = (u, v, 1), dPdx = (dudx, 0, 0),
// dPdy = (0, dvdy, 0), N = Ng = (0,0,1), dPdu = (1,0,0), dPdv = (0,1,0), I = 0,
// surfacearea = 1. Used by `lobe shade` and the execution corpus (tests/shade).
#pragma once

#include "lobe/shading.h"

#include <string>

namespace lobe::group {

struct GridSpec {
  int width = 1, height = 1;
  bool center = false;
  int32_t raytype = kRayCamera;
};

ShaderGlobals grid_globals(const GridSpec& g, int x, int y, ShadingContext* ctx);

// RayType bit for a name ("camera", "shadow", ...); camera for an unknown name.
int32_t raytype_from_name(const std::string& name);

} // namespace lobe::group
