// Perspective camera with an optional thin lens (depth of field).
#pragma once

#include "sampling.h"
#include "scene.h"

namespace lobe::render {

struct Ray {
  Vec3 org, dir;
  float tmax = 1e30f;
};

class Camera {
public:
  Camera() = default;
  Camera(const scene::Camera& c, int width, int height) : w_(width), h_(height), lens_(c.aperture) {
    Vec3 fwd = normalize(c.look_at - c.eye);
    right_ = normalize(cross(fwd, c.up));
    up_ = cross(right_, fwd);
    fwd_ = fwd;
    eye_ = c.eye;
    tan_half_ = std::tan(0.5f * c.fov * kPi / 180.0f);
    aspect_ = float(width) / float(height);
    focus_ = c.focus_distance > 0 ? c.focus_distance : length(c.look_at - c.eye);
  }
  // Ray through film position (fx, fy) in pixels (y down), lens sample (u1, u2).
  Ray generate(float fx, float fy, float u1, float u2) const {
    float sx = (2 * fx / float(w_) - 1) * tan_half_ * aspect_;
    float sy = (1 - 2 * fy / float(h_)) * tan_half_;
    Vec3 d = normalize(fwd_ + right_ * sx + up_ * sy);
    if (lens_ <= 0) return {eye_, d};
    // Thin lens: all rays through the lens disk meet at the focus plane.
    float lx, ly;
    concentric_disk(u1, u2, lx, ly);
    Vec3 focus_point = eye_ + d * (focus_ / dot(d, fwd_));
    Vec3 o = eye_ + right_ * (lx * lens_) + up_ * (ly * lens_);
    return {o, normalize(focus_point - o)};
  }
  // A thin lens (an aperture): generate() reads its two lens numbers.
  bool has_lens() const { return lens_ > 0; }
  // World-space width of one pixel at distance 1 along the view axis (ray differentials).
  float pixel_spread() const { return 2 * tan_half_ / float(h_); }
  // The film position (fx, fy), in generate()'s pixels, of the pinhole's ray through world
  // point `p`, and the cosine of that ray with the view axis; false for a point not in front.
  bool project(const Vec3& p, float& fx, float& fy, float& cos_axis) const {
    Vec3 d = p - eye_;
    float z = dot(d, fwd_), len = length(d);
    if (!(z > 1e-7f * len)) return false;
    fx = (dot(d, right_) / (z * tan_half_ * aspect_) + 1) * 0.5f * float(w_);
    fy = (1 - dot(d, up_) / (z * tan_half_)) * 0.5f * float(h_);
    cos_axis = z / len;
    return std::isfinite(fx) && std::isfinite(fy);
  }
  const Vec3& position() const { return eye_; }
  const Vec3& right() const { return right_; }
  const Vec3& up() const { return up_; }

private:
  int w_ = 1, h_ = 1;
  float lens_ = 0, tan_half_ = 1, aspect_ = 1, focus_ = 1;
  Vec3 eye_, fwd_{0, 0, -1}, right_{1, 0, 0}, up_{0, 1, 0};
};

} // namespace lobe::render
