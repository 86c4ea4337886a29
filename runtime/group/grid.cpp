// Grid shading globals (see grid.h).
#include "grid.h"

#include <algorithm>
#include <cstring>

namespace lobe::group {

namespace {
// The coordinate of cell i of n, unscaled, and its derivative.
void coord(bool center, int i, int n, float& t, float& dt) {
  if (center) {
    t = (float(i) + 0.5f) / float(n);
    dt = 1.0f / float(n);
  } else if (n == 1) {
    t = 0.5f;
    dt = 1.0f;
  } else {
    t = float(i) / float(n - 1);
    dt = 1.0f / float(n - 1);
  }
}
} // namespace

ShaderGlobals grid_globals(const GridSpec& g, int x, int y, ShadingContext* ctx) {
  return GridGlobals(g, ctx).at(x, y);
}

GridGlobals::GridGlobals(const GridSpec& g, ShadingContext* ctx) : g_(g) {
  ShaderGlobals& sg = shared_;
  sg.dPdx = {g.scale_u / float(std::max(1, g.width - 1)), 0, 0};
  sg.dPdy = {0, g.scale_v / float(std::max(1, g.height - 1)), 0};
  sg.N = sg.Ng = {0, 0, 1};
  sg.dPdu = {1, 0, 0};
  sg.dPdv = {0, 1, 0};
  sg.surfacearea = 1;
  sg.raytype = g.raytype;
  sg.context = ctx;
}

namespace {
// `dst = src`, in 16-byte moves: GCC copies the 272-byte struct with `rep movsq`, whose
// start-up cost was 40% of this function's time (perf, `lobe shade` of a trivial shader).
void copy_globals(ShaderGlobals& dst, const ShaderGlobals& src) {
  static_assert(sizeof(ShaderGlobals) % 16 == 0);
  auto* d = reinterpret_cast<unsigned char*>(&dst);
  const auto* s = reinterpret_cast<const unsigned char*>(&src);
#pragma GCC unroll 32
  for (size_t i = 0; i < sizeof(ShaderGlobals); i += 16) {
    unsigned char chunk[16];
    std::memcpy(chunk, s + i, 16);
    std::memcpy(d + i, chunk, 16);
  }
}
} // namespace

void GridGlobals::at(int x, int y, ShaderGlobals& sg) const {
  const GridSpec& g = g_;
  copy_globals(sg, shared_);
  coord(g.center, x, g.width, sg.u, sg.dudx);
  coord(g.center, y, g.height, sg.v, sg.dvdy);
  sg.u = g.scale_u * sg.u + g.offset_u;
  sg.v = g.scale_v * sg.v + g.offset_v;
  sg.dudx *= g.scale_u;
  sg.dvdy *= g.scale_v;
  sg.P = {sg.u, sg.v, 1};
  if (g.vary_pdxdy) {
    sg.dPdx = {1 - sg.u, 1 - sg.v, sg.u * 0.5f};
    sg.dPdy = {1 - sg.v, 1 - sg.u, sg.v * 0.5f};
  }
  if (g.vary_udxdy) {
    sg.dudx = 1 - sg.u;
    sg.dudy = sg.u;
  }
  if (g.vary_vdxdy) {
    sg.dvdx = 1 - sg.v;
    sg.dvdy = sg.v;
  }
}

int32_t raytype_from_name(const std::string& name) {
  const char* names[] = {"camera",  "shadow", "reflection", "refraction",
                         "diffuse", "glossy", "subsurface", "displacement"};
  for (int i = 0; i < 8; ++i)
    if (name == names[i]) return int32_t(1) << i;
  return 0;
}

} // namespace lobe::group
