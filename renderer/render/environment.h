// The environment: radiance arriving from infinitely far away, stored as a lat-long table and
// importance-sampled with a piecewise-constant 2-D distribution.
//
// Every environment kind becomes the same table: a constant, an image (.exr/.hdr), the
// procedural sky (sky.h) or a background() shader tabulated at load, like OSL's testrender.
// Radiance lookups read the same table the distribution was built from, so lookup and pdf
// agree exactly and MIS weights are consistent.
//
// A table whose texels are all equal (a constant environment, or a background shader that
// returns one colour) skips the table: eval is the colour, and sampling is uniform over the
// sphere, or cosine-weighted about a surface normal when one is given (pdf cos/pi on its
// hemisphere, 0 below), with exact pdfs; the expected image is the same.
//
// Light samples for a surface: a table is sampled through an oriented table chosen by the
// surface's normal (environment.cpp): one per direction s in {-1, 0, 1}^3 but 0 (the nearest
// of the 26 to the normal, with a 28-degree cone), or an axis' tight one (2 degrees) for a
// normal that close to an axis. A table weighs blocks of texels by their radiance times the
// cosine past the cone, so the light samples avoid most directions behind the surface and
// leave none in front of it without density (but for the corners-and-centre estimate of a
// block's nearest angle); a sample picks a block, then a texel in it by its own density, so
// radiance keeps the table's resolution. The escaped ray's MIS pdf takes the same normal, so
// the estimate stays unbiased. A zero normal (a surface that transmits diffusely, lit from
// both sides) takes the whole-sphere table, or the uniform sphere when constant.
//
// Mapping (after rotating by -rotation about +Y): v = theta/pi with theta measured from +Y
// (row 0 is straight up), u = 0.5 + atan2(x, -z) / (2 pi) (the image centre looks down -Z).
#pragma once

#include "distribution.h"
#include "sampling.h"

#include "lobe/vec.h"

#include <algorithm>
#include <functional>
#include <initializer_list>
#include <span>
#include <vector>

namespace lobe::render {

class EnvironmentLight {
public:
  EnvironmentLight() = default;
  // `rgb`: w*h*3 linear radiance, rows from +Y down to -Y.
  EnvironmentLight(std::span<const float> rgb, int w, int h, float rotation_deg);
  EnvironmentLight(std::initializer_list<float> rgb, int w, int h, float rotation_deg)
      : EnvironmentLight(std::span<const float>(rgb.begin(), rgb.size()), w, h, rotation_deg) {}
  // Tabulates `radiance(direction)` at w x h, averaging per_axis^2 directions in each texel
  // (per_axis 1: the texel's centre). Rows are tabulated in parallel (oneTBB): `radiance` must
  // be safe to call from several threads at once.
  static EnvironmentLight from_function(const std::function<Color3(const Vec3&)>& radiance, int w,
                                        int h, float rotation_deg, int per_axis = 2);

  bool valid() const { return w_ > 0; }
  Color3 eval(const Vec3& dir) const {
    return constant_ ? color_ : (valid() ? eval_table(dir) : Color3{});
  }
  float pdf(const Vec3& dir) const;                  // solid-angle density of sample()
  Vec3 sample(float u1, float u2, float& pdf) const; // direction towards the environment
  // As seen from a surface with unit normal `n` (on the side the light is wanted), or a zero
  // `n` (both sides wanted): a constant environment is sampled cosine-weighted about n
  // (uniformly over the sphere for a zero n); a table through the oriented table n takes (the
  // whole-sphere table for a zero n). `L` gets the radiance of the sampled texel.
  Vec3 sample(const Vec3& n, float u1, float u2, float& pdf, Color3& L) const;
  float pdf(const Vec3& dir, const Vec3& n) const; // solid-angle density of sample(n, ...)
  // eval(dir) and pdf(dir, n) with one direction-to-texel mapping.
  Color3 eval_pdf(const Vec3& dir, const Vec3& n, float& pdf) const;
  float average_luminance() const { return avg_lum_; }
  bool is_constant() const { return constant_; }

  Vec3 uv_to_dir(float u, float v) const;
  void dir_to_uv(const Vec3& d, float& u, float& v) const;

private:
  Color3 eval_table(const Vec3& dir) const;
  // The oriented table for unit normal n (environment.cpp), -1 for a zero n or when there are
  // none (constant or empty environments).
  int oriented_index(const Vec3& n) const;
  // A grid of blocks of texels for the oriented tables: per block, its texels' densities summed.
  struct Grid {
    int w = 0, h = 0;
    LargeVector<float> sum;
  };
  void build_oriented();
  void block(const Grid& g, int cx, int cy, int& x0, int& x1, int& y0, int& y1) const;
  float oriented_density(int k, int x, int y) const;
  // A texel: radiance r, g, b and the distribution's density over the unit square there (one
  // cache line holds what eval and pdf read).
  const float* texel(float u, float v) const {
    int x, y;
    texel_at(u, v, x, y);
    return &tex_[(size_t(y) * w_ + x) * 4];
  }
  // The texel (x, y) holding (u, v), clamped to the table.
  void texel_at(float u, float v, int& x, int& y) const {
    x = std::min(std::max(int(u * w_), 0), w_ - 1), y = std::min(std::max(int(v * h_), 0), h_ - 1);
  }
  static float table_pdf(const float* t, float sin_theta) {
    return solid_angle_pdf(t[3], sin_theta);
  }
  // Solid-angle density of a density `p` over the unit (u, v) square.
  static float solid_angle_pdf(float p, float sin_theta) {
    return sin_theta > 0 ? p / (2 * kPi * kPi * sin_theta) : 0;
  }

  LargeVector<float> tex_; // w x h texels of 4 floats (see texel())
  int w_ = 0, h_ = 0;
  float cos_r_ = 1, sin_r_ = 0;
  float avg_lum_ = 0;
  bool constant_ = false;
  Color3 color_; // the colour of a constant table
  Distribution2D dist_;
  Grid grids_[2];                        // the tight tables' blocks, the wide ones'
  std::vector<Distribution2D> oriented_; // 33 slots, 32 tables (13 unused), or none
};

} // namespace lobe::render
