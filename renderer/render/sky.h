// The built-in procedural sky: a blue gradient sky with horizon haze, a soft glow around
// the sun, a sun disk, and a dim ground below the horizon. Not a physical sky model (no
// Preetham/Hosek tables); chosen to look plausible and to light a material preview well.
// Units: the sun disk delivers a (luminance) irradiance of `kSunIrradiance` at normal incidence,
// the sky about 1 in radiance at the zenith before the sun glow.
#pragma once

#include "lobe/vec.h"

namespace lobe::render {

inline constexpr float kSunIrradiance = 3.0f;

// Radiance arriving from direction `d` (unit, pointing away from the scene towards the sky).
Color3 procedural_sky(const Vec3& d, const Vec3& sun_dir, float sun_diameter_deg);

} // namespace lobe::render
