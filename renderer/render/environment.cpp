// Lat-long environment table and its importance sampling (see environment.h).
#include "environment.h"

#include "sampling.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

namespace lobe::render {

EnvironmentLight::EnvironmentLight(std::vector<float> rgb, int w, int h, float rotation_deg)
    : w_(w), h_(h) {
  float r = rotation_deg * kPi / 180.0f;
  cos_r_ = std::cos(r), sin_r_ = std::sin(r);
  // Sampling weight: luminance times sin(theta) (the solid angle of a texel's row).
  std::vector<float> f(size_t(w) * h);
  double lum_sum = 0, weight_sum = 0;
  constant_ = true;
  for (int y = 0; y < h; ++y) {
    float s = std::sin(kPi * (y + 0.5f) / float(h));
    for (int x = 0; x < w; ++x) {
      const float* p = &rgb[(size_t(y) * w + x) * 3];
      float l = std::max(0.0f, luminance({p[0], p[1], p[2]}));
      // Keep a small floor so every direction with radiance can be sampled.
      f[size_t(y) * w + x] =
          (l > 0 || p[0] > 0 || p[1] > 0 || p[2] > 0) ? std::max(l, 1e-6f) * s : 0;
      lum_sum += double(l) * s;
      weight_sum += s;
      constant_ &= p[0] == rgb[0] && p[1] == rgb[1] && p[2] == rgb[2];
    }
  }
  avg_lum_ = weight_sum > 0 ? float(lum_sum / weight_sum) : 0;
  if (constant_ && !rgb.empty()) color_ = {rgb[0], rgb[1], rgb[2]};
  dist_ = Distribution2D(f, w, h);
  tex_.resize(size_t(w) * h * 4);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      size_t i = size_t(y) * w + x;
      for (int c = 0; c < 3; ++c) tex_[i * 4 + c] = rgb[i * 3 + c];
      tex_[i * 4 + 3] = dist_.pdf_cell(x, y);
    }
}

EnvironmentLight EnvironmentLight::from_function(const std::function<Color3(const Vec3&)>& radiance,
                                                 int w, int h, float rotation_deg, int per_axis) {
  std::vector<float> rgb(size_t(w) * h * 3);
  EnvironmentLight probe({0, 0, 0}, 1, 1, rotation_deg); // only for uv_to_dir
  const int n = std::max(1, per_axis);
  const float step = 1.0f / float(n), inv = 1.0f / float(n * n);
  tbb::parallel_for(0, h, [&](int y) {
    for (int x = 0; x < w; ++x) {
      Color3 sum;
      for (int sy = 0; sy < n; ++sy)
        for (int sx = 0; sx < n; ++sx) {
          float u = (x + (sx + 0.5f) * step) / float(w), v = (y + (sy + 0.5f) * step) / float(h);
          sum += radiance(probe.uv_to_dir(u, v));
        }
      float* p = &rgb[(size_t(y) * w + x) * 3];
      p[0] = sum.x * inv, p[1] = sum.y * inv, p[2] = sum.z * inv;
    }
  });
  return EnvironmentLight(std::move(rgb), w, h, rotation_deg);
}

Vec3 EnvironmentLight::uv_to_dir(float u, float v) const {
  float theta = v * kPi, phi = (u - 0.5f) * 2 * kPi;
  float st = std::sin(theta);
  Vec3 d{st * std::sin(phi), std::cos(theta), -st * std::cos(phi)};
  // Rotate by +rotation about +Y into the world.
  return {cos_r_ * d.x + sin_r_ * d.z, d.y, -sin_r_ * d.x + cos_r_ * d.z};
}

void EnvironmentLight::dir_to_uv(const Vec3& dw, float& u, float& v) const {
  Vec3 d{cos_r_ * dw.x - sin_r_ * dw.z, dw.y, sin_r_ * dw.x + cos_r_ * dw.z};
  v = std::acos(std::clamp(d.y, -1.0f, 1.0f)) / kPi;
  u = 0.5f + std::atan2(d.x, -d.z) / (2 * kPi);
  u = u - std::floor(u);
}

Color3 EnvironmentLight::eval_table(const Vec3& dir) const {
  float u, v;
  dir_to_uv(dir, u, v);
  const float* p = texel(u, v);
  return {p[0], p[1], p[2]};
}

// sin(theta) of a direction: theta is measured from +Y, which the rotation keeps.
static float sin_theta(const Vec3& d) { return std::sqrt(std::max(0.0f, 1 - d.y * d.y)); }

float EnvironmentLight::pdf(const Vec3& dir) const {
  if (!valid()) return 0;
  if (constant_) return 1 / (4 * kPi);
  float u, v;
  dir_to_uv(dir, u, v);
  return table_pdf(texel(u, v), sin_theta(dir));
}

Color3 EnvironmentLight::eval_pdf(const Vec3& dir, const Vec3& n, float& pdf) const {
  if (constant_) {
    pdf = std::max(0.0f, dot(dir, n)) * kInvPi;
    return color_;
  }
  if (!valid()) {
    pdf = 0;
    return {};
  }
  float u, v;
  dir_to_uv(dir, u, v);
  const float* p = texel(u, v);
  pdf = table_pdf(p, sin_theta(dir));
  return {p[0], p[1], p[2]};
}

Vec3 EnvironmentLight::sample(float u1, float u2, float& pdf) const {
  if (constant_) {
    pdf = 1 / (4 * kPi);
    return square_to_uniform_sphere(u1, u2);
  }
  float u, v, p;
  dist_.sample(u1, u2, u, v, p);
  float st = std::sin(v * kPi);
  pdf = st > 0 ? p / (2 * kPi * kPi * st) : 0;
  return uv_to_dir(u, v);
}

Vec3 EnvironmentLight::sample(const Vec3& n, float u1, float u2, float& pdf, Color3& L) const {
  if (constant_) {
    Vec3 l = sample_cosine_hemisphere(u1, u2);
    pdf = l.z * kInvPi;
    L = color_;
    return Frame(n).to_world(l);
  }
  float u, v;
  int x, y;
  dist_.sample_cell(u1, u2, u, v, x, y);
  // The sampled cell's density, from its texel, which also holds the radiance: one cache miss.
  // (The radiance is read at (u, v), the same texel but where u * w rounds up to the next.)
  float p = tex_[(size_t(y) * w_ + x) * 4 + 3];
  const float* t = texel(u, v);
  L = {t[0], t[1], t[2]};
  float st = std::sin(v * kPi);
  pdf = st > 0 ? p / (2 * kPi * kPi * st) : 0;
  return uv_to_dir(u, v);
}

float EnvironmentLight::pdf(const Vec3& dir, const Vec3& n) const {
  if (!constant_) return pdf(dir);
  return std::max(0.0f, dot(dir, n)) * kInvPi;
}

} // namespace lobe::render
