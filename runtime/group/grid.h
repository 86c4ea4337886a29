// Shading globals for a point of a W x H grid, with OSL testshade's conventions (1.13.12,
// measured): u = x/(W-1) (0.5 when W = 1; (x+0.5)/W with `center`), then scaled and offset
// (u = su * u + ou), likewise v; P = (u, v, 1); dudx = su/(W-1) (su/W with `center`), dvdy
// likewise; dPdx = (su/max(1, W-1), 0, 0) and dPdy = (0, sv/max(1, H-1), 0) even with
// `center`; N = Ng = (0,0,1), dPdu = (1,0,0), dPdv = (0,1,0), I = 0, surfacearea = 1. The
// `vary_*` switches make derivatives vary over the grid as testshade's do: dPdx = (1-u, 1-v,
// u/2), dPdy = (1-v, 1-u, v/2); dudx = 1-u, dudy = u; dvdx = 1-v, dvdy = v. Used by
// `lobe shade` and the execution corpus (tests/shade).
#pragma once

#include "lobe/shading.h"

#include <string>

namespace lobe::group {

struct GridSpec {
  int width = 1, height = 1;
  bool center = false;
  int32_t raytype = kRayCamera;
  float offset_u = 0, offset_v = 0, scale_u = 1, scale_v = 1;
  bool vary_pdxdy = false, vary_udxdy = false, vary_vdxdy = false;
};

ShaderGlobals grid_globals(const GridSpec& g, int x, int y, ShadingContext* ctx);

// The same, for shading a whole grid: the fields every point shares are set up once, and
// at(x, y) fills in the rest (grid_globals's values, bit for bit).
class GridGlobals {
public:
  GridGlobals(const GridSpec& g, ShadingContext* ctx);
  ShaderGlobals at(int x, int y) const {
    ShaderGlobals sg;
    at(x, y, sg);
    return sg;
  }
  // The same into `sg`, every field overwritten (the grid's per-point loop reuses one).
  void at(int x, int y, ShaderGlobals& sg) const;

private:
  GridSpec g_;
  ShaderGlobals shared_{};
};

// RayType bit for a name ("camera", "shadow", ...); 0 (no type) for an unknown name, as
// testshade: every raytype() is then 0.
int32_t raytype_from_name(const std::string& name);

} // namespace lobe::group
