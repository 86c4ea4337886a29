// Grid shading globals (see grid.h).
#include "grid.h"

namespace lobe::group {

namespace {
void coord(const GridSpec& g, int i, int n, float& t, float& dt) {
  if (g.center) {
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
  ShaderGlobals sg{};
  coord(g, x, g.width, sg.u, sg.dudx);
  coord(g, y, g.height, sg.v, sg.dvdy);
  sg.P = {sg.u, sg.v, 1};
  sg.dPdx = {sg.dudx, 0, 0};
  sg.dPdy = {0, sg.dvdy, 0};
  sg.N = sg.Ng = {0, 0, 1};
  sg.dPdu = {1, 0, 0};
  sg.dPdv = {0, 1, 0};
  sg.surfacearea = 1;
  sg.raytype = g.raytype;
  sg.context = ctx;
  return sg;
}

int32_t raytype_from_name(const std::string& name) {
  const char* names[] = {"camera",  "shadow", "reflection", "refraction",
                         "diffuse", "glossy", "subsurface", "displacement"};
  for (int i = 0; i < 8; ++i)
    if (name == names[i]) return int32_t(1) << i;
  return kRayCamera;
}

} // namespace lobe::group
