// JsonReader: typed, located access to scene JSON (see json_reader.h).
#include "json_reader.h"

#include <cmath>
#include <limits>

namespace lobe::scene {

static const char* kind_name(const JsonReader::json& j) { return j.type_name(); }

void JsonReader::check_keys(const json& j, const std::string& ptr,
                            std::span<const char* const> allowed) const {
  for (auto it = j.begin(); it != j.end(); ++it) {
    bool ok = false;
    for (const char* a : allowed) ok |= it.key() == a;
    if (ok) continue;
    std::string list;
    for (const char* a : allowed) list += (list.empty() ? "" : ", ") + std::string(a);
    fail(ptr + "/" + it.key(), "unknown key (expected one of: " + list + ")");
  }
}

const JsonReader::json& JsonReader::object(const json& j, const std::string& ptr) const {
  if (!j.is_object()) fail(ptr, std::string("expected an object, found ") + kind_name(j));
  return j;
}

float JsonReader::number(const json& j, const std::string& ptr) const {
  if (!j.is_number()) fail(ptr, std::string("expected a number, found ") + kind_name(j));
  double v = j.get<double>();
  if (!std::isfinite(v)) fail(ptr, "expected a finite number");
  if (std::fabs(v) > std::numeric_limits<float>::max())
    fail(ptr, "number " + j.dump() + " is out of the range of a 32-bit float");
  return static_cast<float>(v);
}

int JsonReader::integer(const json& j, const std::string& ptr, int lo, int hi) const {
  if (!j.is_number_integer()) fail(ptr, std::string("expected an integer, found ") + kind_name(j));
  long long v = j.get<long long>();
  if (v < lo || v > hi)
    fail(ptr, "expected an integer in [" + std::to_string(lo) + ", " + std::to_string(hi) +
                  "], found " + std::to_string(v));
  return static_cast<int>(v);
}

std::string JsonReader::string(const json& j, const std::string& ptr) const {
  if (!j.is_string()) fail(ptr, std::string("expected a string, found ") + kind_name(j));
  return j.get<std::string>();
}

Vec3 JsonReader::vec3(const json& j, const std::string& ptr) const {
  if (!j.is_array() || j.size() != 3) fail(ptr, "expected an array of 3 numbers");
  return {number(j[0], ptr + "/0"), number(j[1], ptr + "/1"), number(j[2], ptr + "/2")};
}

Vec3 JsonReader::color(const json& j, const std::string& ptr) const {
  if (j.is_number()) {
    float v = number(j, ptr);
    return {v, v, v};
  }
  if (!j.is_array() || j.size() != 3) fail(ptr, "expected a colour: [r, g, b] or a number");
  return vec3(j, ptr);
}

Vec3 JsonReader::emission(const json& j, const std::string& ptr) const {
  Vec3 c = color(j, ptr);
  if (!(c.x >= 0 && c.y >= 0 && c.z >= 0))
    fail(ptr, "expected components >= 0 (emitted light cannot be negative)");
  return c;
}

float JsonReader::emission_scale(const json& j, const std::string& ptr) const {
  float v = number(j, ptr);
  if (!(v >= 0)) fail(ptr, "expected a number >= 0 (emitted light cannot be negative)");
  return v;
}

Mat4 JsonReader::transform(const json& j, const std::string& ptr) const {
  if (j.is_array()) {
    Mat4 m;
    for (size_t i = 0; i < j.size(); ++i) m = transform(j[i], ptr + "/" + std::to_string(i)) * m;
    return m;
  }
  object(j, ptr);
  check_keys(j, ptr, {"translate", "rotate", "scale", "matrix"});
  Mat4 s, r, t, m;
  if (j.contains("scale")) {
    const json& sj = j.at("scale");
    Vec3 v = sj.is_number() ? Vec3{1, 1, 1} * number(sj, ptr + "/scale") : vec3(sj, ptr + "/scale");
    s = Mat4::scale(v);
  }
  if (j.contains("rotate")) {
    const json& rj = j.at("rotate");
    if (!rj.is_array() || rj.size() != 4)
      fail(ptr + "/rotate", "expected [degrees, axis_x, axis_y, axis_z]");
    Vec3 axis{number(rj[1], ptr + "/rotate/1"), number(rj[2], ptr + "/rotate/2"),
              number(rj[3], ptr + "/rotate/3")};
    if (is_zero(axis)) fail(ptr + "/rotate", "rotation axis is zero");
    r = Mat4::rotate(number(rj[0], ptr + "/rotate/0"), axis);
  }
  if (j.contains("translate")) t = Mat4::translate(vec3(j.at("translate"), ptr + "/translate"));
  if (j.contains("matrix")) {
    const json& mj = j.at("matrix");
    if (!mj.is_array() || mj.size() != 16) fail(ptr + "/matrix", "expected 16 numbers, row-major");
    for (int i = 0; i < 16; ++i)
      m.m[i / 4][i % 4] = number(mj[i], ptr + "/matrix/" + std::to_string(i));
  }
  return m * t * r * s;
}

} // namespace lobe::scene
