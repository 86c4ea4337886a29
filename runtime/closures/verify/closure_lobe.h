// Adapters from the closure library to the harness's LobeView: one registry component with
// its parameter block (ClosureLobe), and a Bsdf mixture of several (MixtureLobe).
#pragma once

#include "closures.h"
#include "lobe_view.h"

#include "lobe/bsdf.h"
#include "lobe/shading.h"

#include <memory>
#include <vector>

namespace lobe::verify {

// One closure component, weight 1, in the local frame the Params block describes.
class ClosureLobe : public LobeView {
public:
  explicit ClosureLobe(const closures::Params& p) : p_(p) {}
  // A block whose string parameters point into `strings` (a parsed closure call): the lobe keeps
  // that storage alive, so the parameters never outlive the text they point into.
  ClosureLobe(const closures::Params& p, std::shared_ptr<const void> strings)
      : p_(p), strings_(std::move(strings)) {}
  BsdfEval eval(const Vec3& wo, const Vec3& wi, Transport mode) const override {
    return closures::eval(p_.id(), p_.data(), wo, wi, mode);
  }
  float pdf(const Vec3& wo, const Vec3& wi) const override {
    return closures::pdf(p_.id(), p_.data(), wo, wi);
  }
  std::optional<BsdfSample> sample(const Vec3& wo, const Vec3& u, Transport mode) const override {
    return closures::sample(p_.id(), p_.data(), wo, u, mode);
  }
  Color3 albedo(const Vec3& wo) const override { return closures::albedo(p_.id(), p_.data(), wo); }
  uint32_t flags() const override { return closures::lobe_flags(p_.id(), p_.data()); }
  const closures::Params& params() const { return p_; }

private:
  closures::Params p_;
  std::shared_ptr<const void> strings_;
};

// A weighted sum of components flattened by Bsdf::build, viewed from a fixed wo (Bsdf's lobe
// selection depends on wo, so the mixture is rebuilt when wo changes).
class MixtureLobe : public LobeView {
public:
  struct Term {
    Color3 weight;
    closures::Params params;
  };
  explicit MixtureLobe(std::vector<Term> terms);
  MixtureLobe(const MixtureLobe&) = delete; // the tree points into this object
  MixtureLobe& operator=(const MixtureLobe&) = delete;
  BsdfEval eval(const Vec3& wo, const Vec3& wi, Transport mode) const override;
  float pdf(const Vec3& wo, const Vec3& wi) const override;
  std::optional<BsdfSample> sample(const Vec3& wo, const Vec3& u, Transport mode) const override;
  Color3 albedo(const Vec3& wo) const override;
  uint32_t flags() const override;

private:
  const Bsdf& built_for(const Vec3& wo) const;
  std::vector<Term> terms_;
  std::vector<std::unique_ptr<unsigned char[]>> storage_; // ClosureComponent + params blocks
  std::vector<ClosureAdd> adds_;
  const ClosureNode* root_ = nullptr;
  mutable Bsdf bsdf_;
  mutable Vec3 built_wo_{0, 0, 0};
  mutable bool built_ = false;
};

} // namespace lobe::verify
