// The table of light kinds (light_kinds.h) and their emission profiles.
#include "light_kinds.h"

#include <algorithm>
#include <cctype>
#include <cmath>

namespace lobe::scene {
namespace {

using T = ShapeParam::Type;
constexpr float kPi = 3.14159265358979323846f;

// A point light: the same intensity every way.
std::string build_point(ShapeArgs&, const Vec3&, std::string&) { return ""; }
float profile_point(const std::vector<Vec3>&, const Vec3&) { return 1.0f; }
float solid_point(const std::vector<Vec3>&) { return 4 * kPi; }

// A spot light: values direction (unit, from the light), look_at, cone_angle, falloff_angle.
// Its intensity holds inside the cone less the falloff, then falls by a smoothstep to 0 at
// the cone's edge.
enum Spot { kDirection, kLookAt, kCone, kFalloff };
std::string build_spot(ShapeArgs& a, const Vec3& position, std::string& key) {
  Vec3 d = a.values[kDirection];
  if (a.given[kLookAt] && !a.given[kDirection]) d = a.values[kLookAt] - position;
  d = normalize(d);
  if (is_zero(d)) return "spot direction is zero";
  a.values[kDirection] = d;
  float cone = a.number(kCone), falloff = a.number(kFalloff);
  if (!(cone > 0 && cone <= 90)) {
    key = "cone_angle";
    return "expected degrees in (0, 90]";
  }
  if (!(falloff >= 0 && falloff <= cone)) {
    key = "falloff_angle";
    return "expected degrees in [0, cone_angle]";
  }
  return "";
}
float profile_spot(const std::vector<Vec3>& v, const Vec3& dir) {
  float c = dot(dir, v[kDirection]);
  float cone = v[kCone].x, falloff = v[kFalloff].x;
  float c_out = std::cos(cone * kPi / 180.0f);
  float c_in = std::cos((cone - falloff) * kPi / 180.0f);
  float t = c_in > c_out ? std::clamp((c - c_out) / (c_in - c_out), 0.0f, 1.0f)
                         : (c >= c_out ? 1.0f : 0.0f);
  return t * t * (3 - 2 * t); // smoothstep edge
}
float solid_spot(const std::vector<Vec3>& v) {
  return 2 * kPi * (1 - std::cos(v[kCone].x * kPi / 180.0f));
}

const LightKind kKinds[] = {
    {"point", "the same intensity in every direction", {}, build_point, profile_point, solid_point},
    {"spot",
     "a cone of light with a smooth edge",
     {{T::Vector, "direction", "0 -1 0", "the axis (this, else towards look_at)"},
      {T::Point, "look_at", "", "a point on the axis (optional)"},
      {T::Number, "cone_angle", "30", "half-angle where the light ends, degrees in (0, 90]"},
      {T::Number, "falloff_angle", "5", "width of the smooth edge inside the cone, degrees"}},
     build_spot,
     profile_spot,
     solid_spot},
};

} // namespace

std::span<const LightKind> light_kinds() { return kKinds; }

const LightKind* find_light_kind(std::string_view name) {
  for (const LightKind& k : kKinds)
    if (name == k.name) return &k;
  return nullptr;
}

std::string light_element(const LightKind& k) {
  std::string e = k.name;
  if (!e.empty()) e[0] = char(std::toupper((unsigned char)e[0]));
  return e + "Light";
}

std::string light_reference_markdown() {
  std::string out = "| type | XML | parameters (type, default) | what |\n"
                    "|---|---|---|---|\n";
  for (const LightKind& k : kKinds) {
    out.append("| `").append(k.name).append("` | `<").append(light_element(k)).append(">` | ");
    out.append(params_markdown(k.params)).append(" | ").append(k.doc).append(" |\n");
  }
  return out;
}

} // namespace lobe::scene
