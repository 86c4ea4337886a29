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
  if (!constant_) build_oriented(f);
  tex_.resize(size_t(w) * h * 4);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      size_t i = size_t(y) * w + x;
      for (int c = 0; c < 3; ++c) tex_[i * 4 + c] = rgb[i * 3 + c];
      tex_[i * 4 + 3] = dist_.pdf_cell(x, y);
    }
}

// The six oriented tables at half resolution: each cell's weight is the sum of its texels'
// sampling weights (luminance times sin(theta)) times the largest cosine to the axis over the
// cell's corners and centre, clamped at 0 (a cell across the axis' horizon keeps the part
// above it). Built in parallel, one table a task.
void EnvironmentLight::build_oriented(const std::vector<float>& weight) {
  const int ow = (w_ + 1) / 2, oh = (h_ + 1) / 2;
  std::vector<float> block(size_t(ow) * oh, 0.0f);
  for (int y = 0; y < h_; ++y)
    for (int x = 0; x < w_; ++x) block[size_t(y / 2) * ow + x / 2] += weight[size_t(y) * w_ + x];
  // Directions of the cells' corners ((ow + 1) x (oh + 1)) and centres.
  std::vector<Vec3> corner(size_t(ow + 1) * (oh + 1)), centre(size_t(ow) * oh);
  for (int y = 0; y <= oh; ++y)
    for (int x = 0; x <= ow; ++x)
      corner[size_t(y) * (ow + 1) + x] = uv_to_dir(float(x) / float(ow), float(y) / float(oh));
  for (int y = 0; y < oh; ++y)
    for (int x = 0; x < ow; ++x)
      centre[size_t(y) * ow + x] = uv_to_dir((x + 0.5f) / float(ow), (y + 0.5f) / float(oh));
  oriented_.assign(6, Distribution2D());
  tbb::parallel_for(0, 6, [&](int k) {
    const int axis = k / 2;
    const float sign = k % 2 ? -1.0f : 1.0f;
    std::vector<float> f(size_t(ow) * oh);
    for (int y = 0; y < oh; ++y)
      for (int x = 0; x < ow; ++x) {
        float c = sign * centre[size_t(y) * ow + x][axis];
        for (int dy = 0; dy <= 1; ++dy)
          for (int dx = 0; dx <= 1; ++dx)
            c = std::max(c, sign * corner[size_t(y + dy) * (ow + 1) + x + dx][axis]);
        f[size_t(y) * ow + x] = block[size_t(y) * ow + x] * std::max(c, 0.0f);
      }
    oriented_[size_t(k)] = Distribution2D(f, ow, oh);
  });
}

int EnvironmentLight::oriented_index(const Vec3& n) const {
  if (oriented_.empty() || is_zero(n)) return -1;
  Vec3 a{std::abs(n.x), std::abs(n.y), std::abs(n.z)};
  int axis = a.x >= a.y ? (a.x >= a.z ? 0 : 2) : (a.y >= a.z ? 1 : 2);
  return 2 * axis + (n[axis] < 0 ? 1 : 0);
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
    pdf = is_zero(n) ? 1 / (4 * kPi) : std::max(0.0f, dot(dir, n)) * kInvPi;
    return color_;
  }
  if (!valid()) {
    pdf = 0;
    return {};
  }
  float u, v;
  dir_to_uv(dir, u, v);
  const float* p = texel(u, v);
  int k = oriented_index(n);
  pdf = k < 0 ? table_pdf(p, sin_theta(dir))
              : solid_angle_pdf(oriented_[size_t(k)].pdf(u, v), sin_theta(dir));
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
  if (constant_ && is_zero(n)) {
    L = color_;
    return sample(u1, u2, pdf);
  }
  if (constant_) {
    Vec3 l = sample_cosine_hemisphere(u1, u2);
    pdf = l.z * kInvPi;
    L = color_;
    return Frame(n).to_world(l);
  }
  float u, v;
  int x, y;
  if (int k = oriented_index(n); k >= 0) {
    const Distribution2D& d = oriented_[size_t(k)];
    d.sample_cell(u1, u2, u, v, x, y);
    const float* t = texel(u, v);
    L = {t[0], t[1], t[2]};
    pdf = solid_angle_pdf(d.pdf_cell(x, y), std::sin(v * kPi));
    return uv_to_dir(u, v);
  }
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
  float p;
  eval_pdf(dir, n, p);
  return p;
}

} // namespace lobe::render
