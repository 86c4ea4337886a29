// Analytic lobes for testing the harness itself (not the closure library): each is written
// here from its textbook formula, and the broken variants carry one deliberate defect that
// the corresponding check must detect. Local frame: normal +z.
#pragma once

#include "lobe_view.h"

#include <cmath>

namespace lobe::verify::testing {

// A usable direction: finite and not zero-length.
inline bool valid_dir(const Vec3& w) { return is_finite(w) && !is_zero(w); }

inline Vec3 onb_apply(const Vec3& n, const Vec3& local) {
  // Duff et al. 2017 orthonormal basis around n.
  float sign = std::copysign(1.0f, n.z);
  float a = -1.0f / (sign + n.z), b = n.x * n.y * a;
  Vec3 t{1.0f + sign * n.x * n.x * a, sign * b, -sign * n.x};
  Vec3 s{b, sign + n.y * n.y * a, -n.y};
  return t * local.x + s * local.y + n * local.z;
}

// Lambert: f = rho / pi above the surface, cosine-weighted sampling.
class Lambert : public LobeView {
public:
  explicit Lambert(Color3 rho, bool uniform_sampling_bug = false, float weight_bug = 1.0f)
      : rho_(rho), uniform_bug_(uniform_sampling_bug), weight_bug_(weight_bug) {}
  BsdfEval eval(const Vec3& wo, const Vec3& wi, Transport) const override {
    if (!valid_dir(wo) || !valid_dir(wi) || !(wo.z > 0) || !(wi.z > 0)) return {};
    return {rho_ * (wi.z / float(M_PI)), wi.z / float(M_PI)};
  }
  float pdf(const Vec3& wo, const Vec3& wi) const override {
    return (valid_dir(wo) && valid_dir(wi) && wo.z > 0 && wi.z > 0) ? wi.z / float(M_PI) : 0.0f;
  }
  std::optional<BsdfSample> sample(const Vec3& wo, const Vec3& u, Transport) const override {
    if (!valid_dir(wo) || !(wo.z > 0)) return std::nullopt;
    float z = uniform_bug_ ? u.x : std::sqrt(1.0f - u.x); // the bug: uniform, not cosine
    float r = std::sqrt(std::fmax(0.0f, 1.0f - z * z)), phi = 2.0f * float(M_PI) * u.y;
    if (!(z > 0)) return std::nullopt;
    Vec3 wi{r * std::cos(phi), r * std::sin(phi), z};
    return BsdfSample{wi, rho_ * weight_bug_, z / float(M_PI), kLobeReflect | kLobeDiffuse, 1};
  }
  Color3 albedo(const Vec3& wo) const override { return wo.z > 0 ? rho_ : Color3{}; }
  uint32_t flags() const override { return kLobeReflect | kLobeDiffuse; }

private:
  Color3 rho_;
  bool uniform_bug_;
  float weight_bug_;
};

// Normalised Phong lobe around the mirror direction r of wo (Lafortune & Willems 1994):
// f = ks (n+2)/(2 pi) cos^n(alpha), sampled with pdf (n+1)/(2 pi) cos^n(alpha).
class Phong : public LobeView {
public:
  Phong(float n, float ks) : n_(n), ks_(ks) {}
  BsdfEval eval(const Vec3& wo, const Vec3& wi, Transport) const override {
    if (!valid_dir(wo) || !valid_dir(wi) || !(wo.z > 0) || !(wi.z > 0)) return {};
    float c = cos_alpha(wo, wi);
    float f = ks_ * (n_ + 2) / (2 * float(M_PI)) * std::pow(c, n_);
    return {Color3{f, f, f} * wi.z, pdf(wo, wi)};
  }
  float pdf(const Vec3& wo, const Vec3& wi) const override {
    if (!valid_dir(wo) || !valid_dir(wi) || !(wo.z > 0) || !(wi.z > 0)) return 0.0f;
    return (n_ + 1) / (2 * float(M_PI)) * std::pow(cos_alpha(wo, wi), n_);
  }
  std::optional<BsdfSample> sample(const Vec3& wo, const Vec3& u, Transport m) const override {
    if (!valid_dir(wo) || !(wo.z > 0)) return std::nullopt;
    float c = std::pow(1.0f - u.x, 1.0f / (n_ + 1)), s = std::sqrt(std::fmax(0.f, 1 - c * c));
    float phi = 2.0f * float(M_PI) * u.y;
    Vec3 wi = onb_apply({-wo.x, -wo.y, wo.z}, {s * std::cos(phi), s * std::sin(phi), c});
    if (!(wi.z > 0)) return std::nullopt;
    BsdfEval e = eval(wo, wi, m);
    float p = pdf(wo, wi);
    if (!(p > 0)) return std::nullopt;
    return BsdfSample{wi, e.value / p, p, kLobeReflect | kLobeGlossy, 1};
  }
  Color3 albedo(const Vec3&) const override { return {ks_, ks_, ks_}; }
  uint32_t flags() const override { return kLobeReflect | kLobeGlossy; }

private:
  float cos_alpha(const Vec3& wo, const Vec3& wi) const {
    return std::fmax(0.0f, -wo.x * wi.x - wo.y * wi.y + wo.z * wi.z);
  }
  float n_, ks_;
};

// Diffuse transmission through an interface of relative IOR eta (below / above), uniform
// sampling of the opposite hemisphere. f(wo <- wi) = c * eta(wo)^2 in radiance mode and
// c * eta(wi)^2 in importance mode, which is generalised-reciprocal; `drop_eta` forgets the
// eta^2 factor, which breaks the generalised form.
class EtaTransmission : public LobeView {
public:
  EtaTransmission(float eta, bool drop_eta = false) : eta_(eta), drop_(drop_eta) {}
  BsdfEval eval(const Vec3& wo, const Vec3& wi, Transport m) const override {
    if (!valid_dir(wo) || !valid_dir(wi) || !(wo.z * wi.z < 0)) return {};
    const Vec3& side = (m == Transport::Radiance) ? wo : wi;
    float f = kC * ((side.z < 0 && !drop_) ? eta_ * eta_ : 1.0f);
    return {Color3{f, f, f} * std::fabs(wi.z), pdf(wo, wi)};
  }
  float pdf(const Vec3& wo, const Vec3& wi) const override {
    return (valid_dir(wo) && valid_dir(wi) && wo.z * wi.z < 0) ? 1.0f / (2 * float(M_PI)) : 0.0f;
  }
  std::optional<BsdfSample> sample(const Vec3& wo, const Vec3& u, Transport m) const override {
    if (!valid_dir(wo) || !(wo.z != 0)) return std::nullopt;
    float z = -std::copysign(u.x, wo.z), r = std::sqrt(std::fmax(0.f, 1 - z * z));
    if (z == 0) return std::nullopt;
    float phi = 2.0f * float(M_PI) * u.y;
    Vec3 wi{r * std::cos(phi), r * std::sin(phi), z};
    float p = pdf(wo, wi);
    return BsdfSample{wi, eval(wo, wi, m).value / p, p, kLobeTransmit | kLobeDiffuse, eta_};
  }
  Color3 albedo(const Vec3&) const override { return {}; }
  uint32_t flags() const override { return kLobeTransmit | kLobeDiffuse; }

private:
  static constexpr float kC = 0.1f;
  float eta_;
  bool drop_;
};

} // namespace lobe::verify::testing
