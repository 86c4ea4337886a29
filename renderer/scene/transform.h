// 4x4 affine transforms for scene placement (row-major, column vectors: p' = M p).
#pragma once

#include "lobe/vec.h"

#include <cmath>

namespace lobe::scene {

struct Mat4 {
  float m[4][4] = {{1, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, 1, 0}, {0, 0, 0, 1}};

  static Mat4 translate(const Vec3& t) {
    Mat4 r;
    r.m[0][3] = t.x, r.m[1][3] = t.y, r.m[2][3] = t.z;
    return r;
  }
  static Mat4 scale(const Vec3& s) {
    Mat4 r;
    r.m[0][0] = s.x, r.m[1][1] = s.y, r.m[2][2] = s.z;
    return r;
  }
  // Rotation by `degrees` about `axis` (Rodrigues' formula).
  static Mat4 rotate(float degrees, const Vec3& axis) {
    Vec3 a = normalize(axis);
    float t = degrees * 3.14159265358979f / 180.0f, c = std::cos(t), s = std::sin(t);
    Mat4 r;
    r.m[0][0] = c + a.x * a.x * (1 - c);
    r.m[0][1] = a.x * a.y * (1 - c) - a.z * s;
    r.m[0][2] = a.x * a.z * (1 - c) + a.y * s;
    r.m[1][0] = a.y * a.x * (1 - c) + a.z * s;
    r.m[1][1] = c + a.y * a.y * (1 - c);
    r.m[1][2] = a.y * a.z * (1 - c) - a.x * s;
    r.m[2][0] = a.z * a.x * (1 - c) - a.y * s;
    r.m[2][1] = a.z * a.y * (1 - c) + a.x * s;
    r.m[2][2] = c + a.z * a.z * (1 - c);
    return r;
  }
  friend Mat4 operator*(const Mat4& a, const Mat4& b) {
    Mat4 r;
    for (int i = 0; i < 4; ++i)
      for (int j = 0; j < 4; ++j) {
        r.m[i][j] = 0;
        for (int k = 0; k < 4; ++k) r.m[i][j] += a.m[i][k] * b.m[k][j];
      }
    return r;
  }
  Vec3 point(const Vec3& p) const {
    return {m[0][0] * p.x + m[0][1] * p.y + m[0][2] * p.z + m[0][3],
            m[1][0] * p.x + m[1][1] * p.y + m[1][2] * p.z + m[1][3],
            m[2][0] * p.x + m[2][1] * p.y + m[2][2] * p.z + m[2][3]};
  }
  Vec3 vector(const Vec3& v) const {
    return {m[0][0] * v.x + m[0][1] * v.y + m[0][2] * v.z,
            m[1][0] * v.x + m[1][1] * v.y + m[1][2] * v.z,
            m[2][0] * v.x + m[2][1] * v.y + m[2][2] * v.z};
  }
  // Normals transform by the inverse transpose: the cofactor matrix of the 3x3 part does it
  // up to a positive scale (the determinant), which normalisation removes.
  Vec3 normal(const Vec3& n) const {
    // c0..c2: rows of the cofactor matrix of the 3x3 part.
    Vec3 c0{m[1][1] * m[2][2] - m[1][2] * m[2][1], m[1][2] * m[2][0] - m[1][0] * m[2][2],
            m[1][0] * m[2][1] - m[1][1] * m[2][0]};
    Vec3 c1{m[0][2] * m[2][1] - m[0][1] * m[2][2], m[0][0] * m[2][2] - m[0][2] * m[2][0],
            m[0][1] * m[2][0] - m[0][0] * m[2][1]};
    Vec3 c2{m[0][1] * m[1][2] - m[0][2] * m[1][1], m[0][2] * m[1][0] - m[0][0] * m[1][2],
            m[0][0] * m[1][1] - m[0][1] * m[1][0]};
    float det = m[0][0] * c0.x + m[0][1] * c0.y + m[0][2] * c0.z;
    Vec3 r{dot(c0, n), dot(c1, n), dot(c2, n)}; // rows of cof(A) = det * A^-T
    return normalize(det < 0 ? -r : r);
  }
};

} // namespace lobe::scene
