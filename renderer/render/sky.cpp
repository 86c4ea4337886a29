// Procedural sky (see sky.h).
#include "sky.h"

#include "sampling.h"

#include <algorithm>
#include <cmath>

namespace lobe::render {

Color3 procedural_sky(const Vec3& d, const Vec3& sun_dir_in, float sun_diameter_deg) {
  Vec3 sun = normalize(sun_dir_in);
  float cos_sun = dot(d, sun);
  float sun_r = 0.5f * sun_diameter_deg * kPi / 180.0f;
  float cos_r = std::cos(sun_r);
  if (d.y < 0) {
    // Ground: a warm grey, brightest at the horizon (where it meets a lit ground plane).
    float k = 0.3f + 0.5f * std::exp(8.0f * d.y);
    return Color3{0.38f, 0.34f, 0.30f} * k;
  }
  const Color3 zenith{0.22f, 0.42f, 0.90f}, horizon{0.80f, 0.88f, 1.00f};
  float t = std::pow(1.0f - d.y, 4.0f);
  Color3 sky = zenith * (1 - t) + horizon * t;
  // Forward-scattering glow around the sun (a Henyey-Greenstein-like lobe).
  float g = 0.8f, denom = 1 + g * g - 2 * g * cos_sun;
  float glow = 0.08f * (1 - g * g) / (denom * std::sqrt(denom));
  sky += Color3{1.0f, 0.9f, 0.75f} * glow;
  if (cos_sun >= cos_r && sun.y > -0.05f) {
    float solid_angle = 2 * kPi * (1 - cos_r);
    // Sun colour normalised to luminance 1, so the disk's luminance irradiance is exact.
    const Color3 sun_color = Color3{1.0f, 0.95f, 0.88f} / luminance({1.0f, 0.95f, 0.88f});
    sky += sun_color * (kSunIrradiance / solid_angle);
  }
  return sky;
}

} // namespace lobe::render
