// MixtureLobe: builds a closure tree (components joined by ClosureAdd nodes) by hand, as the
// JIT would, and lets Bsdf flatten it.
#include "closure_lobe.h"

#include <cstring>

namespace lobe::verify {

MixtureLobe::MixtureLobe(std::vector<Term> terms) : terms_(std::move(terms)) {
  std::vector<const ClosureNode*> nodes;
  for (const Term& t : terms_) {
    size_t bytes = sizeof(ClosureComponent) + closures::Params::kMaxBytes;
    auto block = std::make_unique<unsigned char[]>(bytes + 8);
    void* raw = block.get();
    size_t space = bytes + 8;
    void* aligned = std::align(8, bytes, raw, space);
    auto* c = new (aligned) ClosureComponent{};
    c->id = t.params.id();
    c->weight = t.weight;
    std::memcpy(c->params(), t.params.data(), t.params.size());
    nodes.push_back(c);
    storage_.push_back(std::move(block));
  }
  adds_.reserve(nodes.size());
  root_ = nodes.empty() ? nullptr : nodes[0];
  for (size_t i = 1; i < nodes.size(); ++i) {
    ClosureAdd add{};
    add.id = kClosureAdd;
    add.a = root_;
    add.b = nodes[i];
    adds_.push_back(add);
    root_ = &adds_.back();
  }
}

const Bsdf& MixtureLobe::built_for(const Vec3& wo) const {
  if (!built_ || !(built_wo_ == wo)) {
    bsdf_ = Bsdf{};
    bsdf_.build(root_, wo, Vec3{0, 0, 1});
    built_wo_ = wo;
    built_ = true;
  }
  return bsdf_;
}

BsdfEval MixtureLobe::eval(const Vec3& wo, const Vec3& wi, Transport mode) const {
  return built_for(wo).eval(wo, wi, mode);
}
float MixtureLobe::pdf(const Vec3& wo, const Vec3& wi) const { return built_for(wo).pdf(wo, wi); }
std::optional<BsdfSample> MixtureLobe::sample(const Vec3& wo, const Vec3& u, Transport mode) const {
  return built_for(wo).sample(wo, u, mode);
}
Color3 MixtureLobe::albedo(const Vec3& wo) const { return built_for(wo).albedo(wo); }

uint32_t MixtureLobe::flags() const {
  uint32_t f = 0;
  for (const Term& t : terms_) f |= closures::lobe_flags(t.params.id(), t.params.data());
  return f;
}

} // namespace lobe::verify
