// testshade's renderer services (see shade_services.h).
#include "shade_services.h"

#include "matrix44.h"

#include <cmath>
#include <cstring>

namespace lobe::cli {
namespace {

using Base = DataType::Base;

// A value to hand out: its type and its scalars.
struct Value {
  DataType type;
  std::vector<float> f;
  std::vector<int32_t> i;
  std::vector<const char*> s;
};

// Writes `v` (index < 0: the whole value, of exactly the asked type; else one element, of the
// element type) into `dst`.
bool write(const Value& v, int index, DataType want, void* dst) {
  DataType elem = v.type;
  elem.arraylen = 0;
  if (index >= 0 ? !(want == elem && index < v.type.elements()) : !(want == v.type)) return false;
  size_t n = size_t(want.elements() * want.components());
  size_t at = index >= 0 ? size_t(index) * n : 0;
  for (size_t k = 0; k < n; ++k) {
    if (want.base == Base::Int)
      static_cast<int32_t*>(dst)[k] = v.i[at + k];
    else if (want.base == Base::String)
      static_cast<const char**>(dst)[k] = v.s[at + k];
    else
      static_cast<float*>(dst)[k] = v.f[at + k];
  }
  return true;
}

Value floats(std::vector<float> f) {
  Value v;
  v.type = {Base::Float, f.size() > 1 ? int(f.size()) : 0};
  v.f = std::move(f);
  return v;
}

// Gauss-Jordan in double; a singular matrix gives false.
bool invert(const float* src, float* dst) {
  double a[4][8];
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 8; ++c) a[r][c] = c < 4 ? src[r * 4 + c] : (c - 4 == r ? 1.0 : 0.0);
  for (int c = 0; c < 4; ++c) {
    int p = c;
    for (int r = c + 1; r < 4; ++r)
      if (std::fabs(a[r][c]) > std::fabs(a[p][c])) p = r;
    if (a[p][c] == 0.0) return false;
    for (int k = 0; k < 8; ++k) std::swap(a[c][k], a[p][k]);
    double inv = 1.0 / a[c][c];
    for (int k = 0; k < 8; ++k) a[c][k] *= inv;
    for (int r = 0; r < 4; ++r) {
      if (r == c) continue;
      double f = a[r][c];
      for (int k = 0; k < 8; ++k) a[r][k] -= f * a[c][k];
    }
  }
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) dst[r * 4 + c] = float(a[r][c + 4]);
  return true;
}

void multiply(const float* a, const float* b, float* out) {
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) {
      double s = 0;
      for (int k = 0; k < 4; ++k) s += double(a[r * 4 + k]) * b[k * 4 + c];
      out[r * 4 + c] = float(s);
    }
}

} // namespace

ShadeServices::ShadeServices(std::vector<ShadeUserDatum> data, int xres, int yres)
    : data_(std::move(data)), xres_(xres), yres_(yres) {
  // common -> space as testshade 1.13.12 prints them (getmatrix("common", space, m)); each
  // space's space -> common is the inverse. cos(90 degrees) in float is -4.37114e-08.
  const float c90 = -4.37113883e-08f, s45 = 0.707106769f;
  const float common_to[][16] = {
      {c90, -1, 0, 0, 1, c90, 0, 0, 0, 0, 1, 0, -1, -c90, 0, 1},              // object
      {s45, -s45, 0, 0, s45, s45, 0, 0, 0, 0, 1, 0, -s45, s45, 0, 1},         // shader
      {1, 0, 0, 0, 0, 0.5f, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1},                    // myspace
      {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1.00010001f, 1, 0, 0, -0.100010001f, 0}, // screen
  };
  const char* names[] = {"object", "shader", "myspace"};
  for (int k = 0; k < 3; ++k) {
    Space s{names[k], {}, {}};
    invert(common_to[k], s.m);
    if (math::mat_is_identity(s.m))
      std::memcpy(s.inv, s.m, sizeof s.m);
    else
      math::mat_invert(s.inv, s.m);
    spaces_.push_back(s);
  }
  // The camera spaces, kept as common -> space.
  // NDC = screen * (x, y in [-1, 1] -> [0, 1]); raster = NDC * scale(xres, yres, 1).
  Space camera{"camera", {}, {}}, screen{"screen", {}, {}}, ndc{"NDC", {}, {}},
      raster{"raster", {}, {}};
  for (int k = 0; k < 16; ++k) camera.m[k] = k % 5 == 0 ? 1.0f : 0.0f;
  std::memcpy(screen.m, common_to[3], sizeof screen.m);
  const float to_ndc[16] = {0.5f, 0, 0, 0, 0, 0.5f, 0, 0, 0, 0, 1, 0, 0.5f, 0.5f, 0, 1};
  multiply(common_to[3], to_ndc, ndc.m);
  const float to_raster[16] = {float(xres), 0, 0, 0, 0, float(yres), 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
  multiply(ndc.m, to_raster, raster.m);
  camera_spaces_ = {camera, screen, ndc, raster};
}

bool ShadeServices::has_userdata(std::string_view name) const {
  for (const ShadeUserDatum& d : data_)
    if (d.name == name) return true;
  return name == "s" || name == "t";
}

bool ShadeServices::get_userdata(const ShaderGlobals& sg, std::string_view name, DataType type,
                                 bool derivatives, void* val) const {
  if ((name == "s" || name == "t") && type == DataType{}) { // before the user's, as testshade
    auto* f = static_cast<float*>(val);
    bool s = name == "s";
    f[0] = s ? sg.u : sg.v;
    if (derivatives) {
      f[1] = s ? sg.dudx : sg.dvdx;
      f[2] = s ? sg.dudy : sg.dvdy;
    }
    return true;
  }
  for (const ShadeUserDatum& d : data_) {
    if (d.name != name) continue;
    if (!(d.value.type == type)) return false; // testshade: exactly the asked type
    Value v{d.value.type, d.value.floats, d.value.ints, {}};
    for (const std::string& w : d.value.words) v.s.push_back(w.c_str());
    return write(v, -1, type, val);
  }
  return false;
}

bool ShadeServices::get_attribute(const ShaderGlobals& sg, std::string_view object,
                                  std::string_view name, int index, DataType type, bool derivatives,
                                  void* val) const {
  if (object == "options" && name == "blahblah") return write(floats({3.14159f}), index, type, val);
  // The camera's attributes for any object (or none), whole only: testshade ignores an index
  // (OSL 1.13.12 answers getattribute("camera:fov", 0, f) with 90, and
  // getattribute("camera:resolution", 1, i) of an int with nothing).
  if (name.starts_with("camera:")) index = -1;
  if (!object.empty() && !name.starts_with("camera:")) return false;
  float aspect = float(xres_) / float(yres_);
  Value v;
  if (name == "camera:resolution") {
    v.type = {Base::Int, 2};
    v.i = {xres_, yres_};
  } else if (name == "camera:projection") {
    v.type = {Base::String, 0};
    v.s = {"perspective"};
  } else if (name == "camera:pixelaspect") {
    v = floats({1});
  } else if (name == "camera:screen_window") {
    v = floats({-aspect, -1, aspect, 1});
  } else if (name == "camera:fov") {
    v = floats({90});
  } else if (name == "camera:clip") {
    v = floats({0.1f, 1000});
  } else if (name == "camera:clip_near") {
    v = floats({0.1f});
  } else if (name == "camera:clip_far") {
    v = floats({1000});
  } else if (name == "camera:shutter") {
    v = floats({0, 1});
  } else if (name == "camera:shutter_open") {
    v = floats({0});
  } else if (name == "camera:shutter_close") {
    v = floats({1});
  } else {
    return index < 0 && get_userdata(sg, name, type, derivatives, val);
  }
  return write(v, index, type, val);
}

bool ShadeServices::get_inverse_matrix(const ShaderGlobals&, std::string_view space,
                                       float* m) const {
  for (const Space& s : camera_spaces_)
    if (space == s.name) {
      std::memcpy(m, s.m, sizeof s.m);
      return true;
    }
  for (const Space& s : spaces_)
    if (space == s.name) {
      std::memcpy(m, s.inv, sizeof s.inv);
      return true;
    }
  return false;
}

bool ShadeServices::get_matrix(const ShaderGlobals&, std::string_view space, float* m) const {
  for (const Space& s : spaces_)
    if (space == s.name) {
      std::memcpy(m, s.m, sizeof s.m);
      return true;
    }
  return false;
}

// testshade's stand-in for ray tracing: repeatable answers from u and the ray (measured
// against OSL 1.13.12's testshade; tests/shade/layers/trace_testshade.osl).
bool ShadeServices::trace(const ShaderGlobals& sg, const TraceOptions&, const Vec3& P, const Vec3&,
                          const Vec3&, const Vec3& R, const Vec3&, const Vec3&, TraceHit&) const {
  return sg.u / dot(P, R) > 0.5f; // 0 / 0 (u = 0 along a perpendicular ray) is no hit
}

// The derivatives of what is written are left as they were, as testshade leaves them.
std::optional<bool> ShadeServices::trace_message(const ShaderGlobals& sg, std::string_view name,
                                                 DataType type, bool, void* val) const {
  bool hit = sg.u > 0.5f;
  if (name == "hit" && type == DataType{Base::Int}) static_cast<int32_t*>(val)[0] = hit ? 1 : 0;
  if (!hit) return false;
  if (name == "hitdist" && type == DataType{Base::Float}) static_cast<float*>(val)[0] = 0.5f;
  if (name == "geom:name" && type == DataType{Base::String})
    static_cast<const char**>(val)[0] = "teapot";
  if (name == "N" && type == DataType{Base::Normal}) {
    float* n = static_cast<float*>(val);
    n[0] = 1.0f - sg.v, n[1] = 0.25f, n[2] = 1.0f - sg.u;
  }
  return true;
}

} // namespace lobe::cli
