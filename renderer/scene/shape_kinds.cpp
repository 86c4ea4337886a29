// The table of shape kinds made of triangles (shape_kinds.h) and their mesh builders.
#include "shape_kinds.h"

#include "light_kinds.h"

#include "generated_docs.h"

#include <cctype>
#include <cmath>
#include <sstream>

namespace lobe::scene {
namespace {

using T = ShapeParam::Type;

std::string finite(Vec3 v, const char* what) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z)
             ? std::string()
             : std::string(what) + " must be finite";
}

// A disk: a fan of `segments` triangles around the centre, facing `normal`; uv maps the
// disk's square [-r, r]^2 in its plane to [0, 1]^2.
std::string build_disk(const ShapeArgs& a, Mesh& m) {
  Vec3 c = a.vec(0), n = a.vec(1);
  float r = a.number(2);
  int segments = a.count(3);
  if (std::string e = finite(c, "center"); !e.empty()) return e;
  if (!(r > 0 && std::isfinite(r))) return "radius expects a number > 0";
  if (segments < 3) return "segments expects a whole number >= 3";
  if (!finite(n, "normal").empty() || is_zero(n)) return "normal expects a non-zero vector";
  n = normalize(n);
  Vec3 t = normalize(cross(std::abs(n.x) < 0.9f ? Vec3{1, 0, 0} : Vec3{0, 1, 0}, n));
  Vec3 b = cross(n, t); // t x b = n: the fan's winding faces along n
  m.positions = {c};
  m.uvs = {0.5f, 0.5f};
  for (int i = 0; i < segments; ++i) {
    float phi = 2 * 3.14159265358979f * float(i) / float(segments);
    float x = std::cos(phi), y = std::sin(phi);
    m.positions.push_back(c + (t * x + b * y) * r);
    m.uvs.push_back(0.5f + 0.5f * x);
    m.uvs.push_back(0.5f + 0.5f * y);
  }
  for (int i = 0; i < segments; ++i)
    m.indices.insert(m.indices.end(), {0u, uint32_t(1 + i), uint32_t(1 + (i + 1) % segments)});
  return "";
}

// An axis-aligned box from `min` to `max`: six faces of two triangles, facing out, each with
// uv [0, 1]^2 across it.
std::string build_box(const ShapeArgs& a, Mesh& m) {
  Vec3 lo = a.vec(0), hi = a.vec(1);
  if (std::string e = finite(lo, "min"); !e.empty()) return e;
  if (std::string e = finite(hi, "max"); !e.empty()) return e;
  if (!(hi.x > lo.x && hi.y > lo.y && hi.z > lo.z))
    return "max must exceed min in every coordinate";
  const float* l = &lo.x;
  const float* h = &hi.x;
  for (int axis = 0; axis < 3; ++axis)
    for (int side = 0; side < 2; ++side) {
      int u = (axis + 1) % 3, v = (axis + 2) % 3; // e_u x e_v = e_axis
      // Corners in (u, v), counter-clockwise seen from outside.
      static const int kPlus[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
      static const int kMinus[4][2] = {{0, 0}, {0, 1}, {1, 1}, {1, 0}};
      const int(*corners)[2] = side ? kPlus : kMinus;
      uint32_t base = uint32_t(m.positions.size());
      for (int k = 0; k < 4; ++k) {
        float p[3];
        p[axis] = side ? h[axis] : l[axis];
        p[u] = corners[k][0] ? h[u] : l[u];
        p[v] = corners[k][1] ? h[v] : l[v];
        m.positions.push_back({p[0], p[1], p[2]});
        m.uvs.push_back(float(corners[k][0]));
        m.uvs.push_back(float(corners[k][1]));
      }
      m.indices.insert(m.indices.end(), {base, base + 1, base + 2, base, base + 2, base + 3});
    }
  return "";
}

const ShapeKind kKinds[] = {
    {"disk",
     "a flat disk (a fan of triangles)",
     {{T::Point, "center", "0 0 0", "its centre"},
      {T::Vector, "normal", "0 1 0", "the side it faces"},
      {T::Number, "radius", "1", "> 0"},
      {T::Count, "segments", "64", "triangles around it, >= 3"}},
     build_disk},
    {"box",
     "an axis-aligned box (before its transform), facing out",
     {{T::Point, "min", "-1 -1 -1", "one corner"},
      {T::Point, "max", "1 1 1", "the opposite corner, greater in every coordinate"}},
     build_box},
};

const char* type_word(T t) {
  switch (t) {
  case T::Point:
    return "point";
  case T::Vector:
    return "vector";
  case T::Number:
    return "number";
  case T::Count:
    return "whole number";
  }
  return "";
}

} // namespace

std::span<const ShapeKind> shape_kinds() { return kKinds; }

const ShapeKind* find_shape_kind(std::string_view name) {
  for (const ShapeKind& k : kKinds)
    if (name == k.name) return &k;
  return nullptr;
}

std::string shape_element(const ShapeKind& k) {
  std::string e = k.name;
  if (!e.empty()) e[0] = char(std::toupper((unsigned char)e[0]));
  return e;
}

std::string parse_shape_value(const ShapeParam& p, std::string_view text, Vec3& out) {
  std::string s(text);
  for (char& c : s) c = c == ',' ? ' ' : c;
  std::istringstream in(s);
  int n = p.type == T::Point || p.type == T::Vector ? 3 : 1;
  float v[3] = {0, 0, 0};
  std::string expected = n == 3 ? "expects 3 numbers" : "expects a number";
  if (p.type == T::Count) expected = "expects a whole number in [1, 1048576]";
  for (int i = 0; i < n; ++i)
    if (!(in >> v[i]) || !std::isfinite(v[i])) return expected;
  std::string extra;
  if (in >> extra) return expected;
  if (p.type == T::Count && !(v[0] >= 1 && v[0] <= float(1 << 20) && v[0] == std::floor(v[0])))
    return expected;
  out = {v[0], v[1], v[2]};
  return "";
}

std::string params_markdown(const std::vector<ShapeParam>& params) {
  std::string out;
  for (const ShapeParam& p : params) {
    if (!out.empty()) out += "; ";
    // appended piece by piece: `"literal" + std::string` trips GCC 12's -Wrestrict
    out.append("`").append(p.name).append("` (").append(type_word(p.type)).append(", ");
    out.append(!p.default_value ? "required" : *p.default_value ? p.default_value : "none");
    out.append("): ").append(p.doc);
  }
  return out.empty() ? "-" : out;
}

std::string shape_reference_markdown() {
  std::string out = "| type | parameters (type, default) | what |\n"
                    "|---|---|---|\n";
  for (const ShapeKind& k : kKinds) {
    out.append("| `").append(k.name).append("` | ").append(params_markdown(k.params));
    out.append(" | ").append(k.doc).append(" |\n");
  }
  return out;
}

bool replace_scene_sections(std::string& doc) {
  int s =
      registry::replace_between(doc, kShapeDocsBegin, kShapeDocsEnd, shape_reference_markdown());
  int l =
      registry::replace_between(doc, kLightDocsBegin, kLightDocsEnd, light_reference_markdown());
  return s >= 0 && l >= 0 && (s > 0 || l > 0);
}

} // namespace lobe::scene
