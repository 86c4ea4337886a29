// Lat-long environment table and its importance sampling (see environment.h).
#include "environment.h"

#include "sampling.h"

#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <cmath>

namespace lobe::render {

EnvironmentLight::EnvironmentLight(std::span<const float> rgb, int w, int h, float rotation_deg)
    : w_(w), h_(h) {
  float r = rotation_deg * kPi / 180.0f;
  cos_r_ = std::cos(r), sin_r_ = std::sin(r);
  // Sampling weight: luminance times sin(theta) (the solid angle of a texel's row).
  LargeVector<float> f(size_t(w) * h);
  // Rows in parallel, their sums added in order after.
  std::vector<double> row_lum(static_cast<size_t>(h)), row_weight(static_cast<size_t>(h));
  std::vector<char> row_constant(static_cast<size_t>(h));
  tbb::parallel_for(0, h, [&](int y) {
    float s = std::sin(kPi * (y + 0.5f) / float(h));
    double lum = 0;
    bool same = true;
    for (int x = 0; x < w; ++x) {
      const float* p = &rgb[(size_t(y) * w + x) * 3];
      float l = std::max(0.0f, luminance({p[0], p[1], p[2]}));
      // Keep a small floor so every direction with radiance can be sampled.
      f[size_t(y) * w + x] =
          (l > 0 || p[0] > 0 || p[1] > 0 || p[2] > 0) ? std::max(l, 1e-6f) * s : 0;
      lum += double(l) * s;
      same &= p[0] == rgb[0] && p[1] == rgb[1] && p[2] == rgb[2];
    }
    row_lum[size_t(y)] = lum, row_weight[size_t(y)] = double(s) * w;
    row_constant[size_t(y)] = same;
  });
  double lum_sum = 0, weight_sum = 0;
  constant_ = true;
  for (int y = 0; y < h; ++y) {
    lum_sum += row_lum[size_t(y)], weight_sum += row_weight[size_t(y)];
    constant_ &= row_constant[size_t(y)] != 0;
  }
  avg_lum_ = weight_sum > 0 ? float(lum_sum / weight_sum) : 0;
  if (constant_ && !rgb.empty()) color_ = {rgb[0], rgb[1], rgb[2]};
  dist_ = Distribution2D(f, w, h);
  tex_.resize(size_t(w) * h * 4);
  tbb::parallel_for(0, h, [&](int y) {
    for (int x = 0; x < w; ++x) {
      size_t i = size_t(y) * w + x;
      for (int c = 0; c < 3; ++c) tex_[i * 4 + c] = rgb[i * 3 + c];
      tex_[i * 4 + 3] = dist_.pdf_cell(x, y);
    }
  });
  if (!constant_) build_oriented();
}

namespace {

// The oriented tables' directions: the 26 s in {-1, 0, 1}^3 but 0 (index (s.x + 1) * 9 +
// (s.y + 1) * 3 + s.z + 1; 13, the zero vector, unused), each with a cone: a unit normal
// within the cone of the direction it takes (oriented_index) sees, above its horizon, only
// directions within 90 degrees plus the cone of it. The nearest of the 26 is at most 27.6
// degrees from any normal (the cone: 28); one within 2 degrees of an axis (floors, walls)
// takes that axis' tight table instead (index 27 + 2 axis + (negative)).
constexpr int kWideTables = 27, kTightTables = 6;
constexpr int kZeroDirection = 13; // s = (0, 0, 0): no table
constexpr float kWideCone = 28.0f * kPi / 180, kTightCone = 2.0f * kPi / 180;

// Tight tables use grid 0, wide ones grid 1.
int grid_of(int k) { return k >= kWideTables ? 0 : 1; }

Vec3 table_direction(int k) {
  if (k >= kWideTables) {
    Vec3 d{};
    d[(k - kWideTables) / 2] = (k - kWideTables) % 2 ? -1.0f : 1.0f;
    return d;
  }
  return normalize(Vec3{float(k / 9 - 1), float(k / 3 % 3 - 1), float(k % 3 - 1)});
}

// The sampling weight of a cell for a table: 1 where the cell comes within the cone of its
// direction, else the cosine of its angle from the cone's edge, 0 from 90 degrees past it.
// `c`: the cosine of the cell's least angle to the direction; `ca`, `sa`: the cone's cosine and
// sine.
float cone_weight(float c, float ca, float sa) {
  if (c >= ca) return 1.0f;
  float st = std::sqrt(std::max(0.0f, 1 - c * c));
  return std::max(0.0f, c * ca + st * sa); // cos(theta - cone)
}

} // namespace

// The texels [x0, x1) x [y0, y1) of cell (cx, cy) of a grid: texel x is in cell x * g.w / w_.
void EnvironmentLight::block(const Grid& g, int cx, int cy, int& x0, int& x1, int& y0,
                             int& y1) const {
  x0 = int((int64_t(cx) * w_ + g.w - 1) / g.w), x1 = int((int64_t(cx + 1) * w_ + g.w - 1) / g.w);
  y0 = int((int64_t(cy) * h_ + g.h - 1) / g.h), y1 = int((int64_t(cy + 1) * h_ + g.h - 1) / g.h);
}

// The oriented tables, over two grids of blocks of texels (tight tables: blocks of about 2 x 2
// texels, at most 1024 x 512 of them; wide ones about 4 x 4, at most 512 x 256). A block's
// weight is the sum of its texels' densities (Grid::sum) times its cone weight for the table
// (cone_weight of the largest cosine to the table's direction over the block's corners and
// centre). Sampling picks a block from the table, then a texel in it by the texels' own
// densities: radiance at the table's full resolution, the cosine at the block's. Built in
// parallel, one table a task.
void EnvironmentLight::build_oriented() {
  struct Geometry {
    std::vector<Vec3> corner, centre;
  };
  Geometry geo[2];
  auto make = [&](Grid& g, Geometry& ge, int gw, int gh) {
    g.w = gw, g.h = gh;
    g.sum.assign(size_t(gw) * gh, 0.0f);
    for (int y = 0; y < h_; ++y)
      for (int x = 0; x < w_; ++x)
        g.sum[size_t(int64_t(y) * gh / h_) * gw + size_t(int64_t(x) * gw / w_)] +=
            tex_[(size_t(y) * w_ + x) * 4 + 3];
    std::vector<float> cu(size_t(gw) + 1), cv(size_t(gh) + 1);
    for (int c = 0; c <= gw; ++c) cu[size_t(c)] = float((int64_t(c) * w_ + gw - 1) / gw) / w_;
    for (int c = 0; c <= gh; ++c) cv[size_t(c)] = float((int64_t(c) * h_ + gh - 1) / gh) / h_;
    ge.corner.resize(size_t(gw + 1) * (gh + 1));
    ge.centre.resize(size_t(gw) * gh);
    for (int y = 0; y <= gh; ++y)
      for (int x = 0; x <= gw; ++x)
        ge.corner[size_t(y) * (gw + 1) + x] = uv_to_dir(cu[size_t(x)], cv[size_t(y)]);
    for (int y = 0; y < gh; ++y)
      for (int x = 0; x < gw; ++x)
        ge.centre[size_t(y) * gw + x] = uv_to_dir(0.5f * (cu[size_t(x)] + cu[size_t(x) + 1]),
                                                  0.5f * (cv[size_t(y)] + cv[size_t(y) + 1]));
  };
  make(grids_[0], geo[0], std::min((w_ + 1) / 2, 1024), std::min((h_ + 1) / 2, 512));
  make(grids_[1], geo[1], std::min((w_ + 3) / 4, 512), std::min((h_ + 3) / 4, 256));
  oriented_.assign(kWideTables + kTightTables, Distribution2D());
  tbb::enumerable_thread_specific<LargeVector<float>> weights; // one per thread, reused
  tbb::parallel_for(0, kWideTables + kTightTables, [&](int k) {
    if (k == kZeroDirection) return;
    const Grid& g = grids_[grid_of(k)];
    const Geometry& ge = geo[grid_of(k)];
    const float cone = k >= kWideTables ? kTightCone : kWideCone;
    const float ca = std::cos(cone), sa = std::sin(cone);
    const Vec3 d = table_direction(k);
    LargeVector<float>& f = weights.local();
    f.resize(size_t(g.w) * g.h);
    for (int y = 0; y < g.h; ++y)
      for (int x = 0; x < g.w; ++x) {
        float c = dot(ge.centre[size_t(y) * g.w + x], d);
        for (int dy = 0; dy <= 1; ++dy)
          for (int dx = 0; dx <= 1; ++dx)
            c = std::max(c, dot(ge.corner[size_t(y + dy) * (g.w + 1) + x + dx], d));
        f[size_t(y) * g.w + x] = g.sum[size_t(y) * g.w + x] * cone_weight(c, ca, sa);
      }
    // Isolated: while this thread waits for Distribution2D's own parallel rows it must not
    // start another table, which would take the same `f`.
    tbb::this_task_arena::isolate([&] { oriented_[size_t(k)] = Distribution2D(f, g.w, g.h); });
  });
}

// Density over the unit square of texel (x, y) under oriented table k: the table's probability
// of the texel's block, times the texel's share of the block's density, over the texel's area.
float EnvironmentLight::oriented_density(int k, int x, int y) const {
  const Grid& g = grids_[grid_of(k)];
  int cx = int(int64_t(x) * g.w / w_), cy = int(int64_t(y) * g.h / h_);
  float total = g.sum[size_t(cy) * g.w + cx];
  if (!(total > 0)) return 0;
  float cell = oriented_[size_t(k)].pdf_cell(cx, cy) / (float(g.w) * float(g.h));
  return cell * tex_[(size_t(y) * w_ + x) * 4 + 3] / total * (float(w_) * float(h_));
}

// The nearest of the 26 directions to unit n: the one, two or three largest components of n
// with their signs, whichever gives the largest cosine (their sum over the square root of
// their count); the tight table of an axis within its cone.
int EnvironmentLight::oriented_index(const Vec3& n) const {
  if (oriented_.empty() || is_zero(n)) return -1;
  constexpr float kCosTight = 0.99939083f; // cos(kTightCone)
  float a[3] = {std::abs(n.x), std::abs(n.y), std::abs(n.z)};
  // The components by size, largest first (ties: the lower index first).
  int i0 = 0, i1 = 1, i2 = 2;
  if (a[i1] > a[i0]) std::swap(i0, i1);
  if (a[i2] > a[i1]) std::swap(i1, i2);
  if (a[i1] > a[i0] || (a[i1] == a[i0] && i1 < i0)) std::swap(i0, i1);
  if (a[i2] == a[i1] && i2 < i1) std::swap(i1, i2);
  float c1 = a[i0], c2 = (a[i0] + a[i1]) * 0.70710678f, c3 = (a[0] + a[1] + a[2]) * 0.57735027f;
  if (c1 >= c2 && c1 >= c3) {
    if (c1 >= kCosTight) return kWideTables + 2 * i0 + (n[i0] < 0 ? 1 : 0);
    return kZeroDirection + (n[i0] < 0 ? -1 : 1) * (i0 == 0 ? 9 : i0 == 1 ? 3 : 1);
  }
  int s[3] = {0, 0, 0};
  s[i0] = n[i0] < 0 ? -1 : 1;
  s[i1] = n[i1] < 0 ? -1 : 1;
  if (c3 > c2) s[i2] = n[i2] < 0 ? -1 : 1;
  return (s[0] + 1) * 9 + (s[1] + 1) * 3 + s[2] + 1;
}

EnvironmentLight EnvironmentLight::from_function(const std::function<Color3(const Vec3&)>& radiance,
                                                 int w, int h, float rotation_deg, int per_axis) {
  LargeVector<float> rgb(size_t(w) * h * 3);
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
  return EnvironmentLight(rgb, w, h, rotation_deg);
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
  if (k < 0) {
    pdf = table_pdf(p, sin_theta(dir));
  } else {
    int x, y;
    texel_at(u, v, x, y);
    pdf = solid_angle_pdf(oriented_density(k, x, y), sin_theta(dir));
  }
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
    // The block from the table, then a texel in it by the texels' densities (the position in
    // the block along u chooses, its rest and the position along v place the point).
    const Grid& g = grids_[grid_of(k)];
    int cx, cy;
    oriented_[size_t(k)].sample_cell(u1, u2, u, v, cx, cy);
    float total = g.sum[size_t(cy) * g.w + cx];
    pdf = 0;
    L = {};
    if (!(total > 0)) return {0, 1, 0};
    constexpr float kBelowOne = 0x1.fffffep-1f;
    float fu = std::clamp(u * g.w - cx, 0.0f, kBelowOne),
          fv = std::clamp(v * g.h - cy, 0.0f, kBelowOne);
    int x0, x1, y0, y1;
    block(g, cx, cy, x0, x1, y0, y1);
    // The texel where the running sum of densities passes fu * total (else the last with any).
    float target = fu * total, before = 0, p = 0;
    int sx = -1, sy = -1;
    [&] {
      float acc = 0;
      for (int ty = y0; ty < y1; ++ty)
        for (int tx = x0; tx < x1; ++tx) {
          float q = tex_[(size_t(ty) * w_ + tx) * 4 + 3];
          if (!(q > 0)) continue;
          before = acc, p = q, sx = tx, sy = ty;
          if ((acc += q) > target) return;
        }
    }();
    if (sx < 0) return {0, 1, 0};
    float r = std::clamp((target - before) / p, 0.0f, kBelowOne);
    u = (float(sx) + r) / float(w_), v = (float(sy) + fv) / float(h_);
    const float* t = &tex_[(size_t(sy) * w_ + sx) * 4];
    L = {t[0], t[1], t[2]};
    pdf = solid_angle_pdf(oriented_density(k, sx, sy), std::sin(v * kPi));
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
