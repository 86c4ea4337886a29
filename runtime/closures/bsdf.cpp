// Bsdf (bsdf.h): a closure tree flattened into weighted lobes, sampled as a mixture.
//
// Layering model, layer(top, base): the top's lobes keep their weight; the base's weight is
// multiplied, per channel, by 1 - A_top(wo), where A_top is the top's directional albedo at
// the viewing direction (clamped to [0, 1]). The total albedo is then A_top + (1 - A_top)
// A_base <= 1, so layering never creates energy. The attenuation uses wo only: the model is
// not reciprocal (documented in docs/closures.md). Base emission is attenuated the same way.
//
// Geometric-normal side test: when Ng is given, a direction pair on the same side of Ng
// counts as reflection and only reflecting lobes see it; opposite sides only transmitting
// lobes. This is what stops light leaks through shading normals.
#include "lobe/bsdf.h"
#include "closure_registry.h"
#include "closures.h"
#include "common.h"
#include "components.h"
#include "lobe/detail/closure_kernels.h"

#include <cstring>

namespace lobe {
namespace {

using closures::luminance;

// Room for a parameter block copied to turn its N (kSidedIor closures; theirs are ~100 bytes).
constexpr size_t kMaxParamBlock = 256;

bool usable_weight(const Color3& w) {
  return is_finite(w) && (w.x > 0.0f || w.y > 0.0f || w.z > 0.0f);
}

int mode_of(Transport t) { return t == Transport::Importance ? 1 : 0; }

// One lobe's set-up/eval/sample/albedo through the material's JIT kernels when they cover its
// id, else through the native library. `state` is the lobe's block in the Bsdf, written by
// lobe_setup once per build() and read by the others.
bool use_kernels(const ClosureKernels* k, int id) { return k && k->covers(id); }

uint32_t lobe_setup(const ClosureKernels* k, int id, const unsigned char* p, void* state) {
  if (!use_kernels(k, id)) return closures::setup(id, p, state);
  return k->setup(id, p, state);
}
BsdfEval lobe_eval(const ClosureKernels* k, int id, const void* state, const Vec3& wo,
                   const Vec3& wi, Transport mode) {
  if (!use_kernels(k, id)) return closures::eval_prepared(id, state, wo, wi, mode);
  BsdfEval e;
  k->eval(id, state, &wo, &wi, mode_of(mode), &e);
  return e;
}
std::optional<BsdfSample> lobe_sample(const ClosureKernels* k, int id, const void* state,
                                      const Vec3& wo, const Vec3& u, Transport mode) {
  if (!use_kernels(k, id)) return closures::sample_prepared(id, state, wo, u, mode);
  BsdfSample s;
  if (!k->sample(id, state, &wo, &u, mode_of(mode), &s)) return std::nullopt;
  return s;
}
Color3 lobe_albedo_of(const ClosureKernels* k, int id, const void* state, const Vec3& wo) {
  if (!use_kernels(k, id)) return closures::albedo_prepared(id, state, wo);
  Vec3 a;
  k->albedo(id, state, &wo, &a);
  return a;
}

} // namespace

// Collects a tree into a Bsdf, setting each lobe up as it is added; one per build() call.
struct BsdfBuilder {
  Bsdf& bsdf;
  const Vec3& wo;
  // The closure registry, looked up once per build.
  const std::span<const registry::ClosureEntry> table = registry::closures();
  // Each lobe's albedo at wo, estimated once when first wanted (known[i]): layer() weighs its
  // top lobes with it and build() the selection weights of two or more lobes. Not
  // initialised: only known[i] says which hold a value.
  union Albedos {
    Albedos() {}
    Color3 at[Bsdf::kMaxLobes];
  } albedo;
  bool known[Bsdf::kMaxLobes] = {};

  const Color3& albedo_of(int i) {
    if (!known[i]) albedo.at[i] = bsdf.lobe_albedo(i, wo), known[i] = true;
    return albedo.at[i];
  }

  void visit(const ClosureNode* node, const Color3& w, int depth) {
    if (!node || depth > 64 || !is_finite(w)) return;
    if (node->id == kClosureAdd) {
      const auto* a = static_cast<const ClosureAdd*>(node);
      visit(a->a, w, depth + 1);
      visit(a->b, w, depth + 1);
    } else if (node->id == kClosureMul) {
      const auto* m = static_cast<const ClosureMul*>(node);
      visit(m->closure, w * m->weight, depth + 1);
    } else if (node->id >= 0 && node->id < static_cast<int>(table.size())) {
      const auto* c = static_cast<const ClosureComponent*>(node);
      component(c->id, c->params(), w * c->weight, depth);
    }
  }

  void component(int id, const unsigned char* p, const Color3& w, int depth) {
    uint32_t fl = table[size_t(id)].flags;
    if (fl & registry::kLayer) return layer(p, w, depth);
    if (!usable_weight(w)) return;
    if (fl & registry::kEmission) {
      Color3 e =
          id == closures::closure_id::uniform_edf
              ? closures::sanitize(closures::as_params<closures::EmittanceParams>(p).emittance)
              : Color3{1, 1, 1};
      bsdf.emission += w * e;
    }
    if (fl & registry::kTransparent) bsdf.transparency += w;
    if (fl & registry::kHoldout) bsdf.holdout += w;
    if (fl & registry::kBackground) bsdf.background += w;
    if (fl & registry::kDebug) {
      bsdf.debug_tag = closures::as_params<closures::DebugParams>(p).tag;
      bsdf.debug_weight += w;
    }
    if (!(fl & (registry::kReflect | registry::kTransmit))) return;
    int& n = bsdf.n_lobes_;
    if (n >= Bsdf::kMaxLobes) return;
    const unsigned char* setup_params = p;
    alignas(16) unsigned char turned[kMaxParamBlock];
    if (bsdf.backfacing_ && (fl & registry::kSidedIor)) {
      // N (a vector, the first parameter) turned back to the outside of the object when it
      // faces the viewer, i.e. points into the object (a shader that already passes the
      // outside normal keeps it).
      const auto& params = table[size_t(id)].params;
      size_t size = registry::param_block_size(params);
      if (size > sizeof(turned) || params.empty() || params[0].type != registry::ArgType::Vector)
        return;
      Vec3 normal;
      std::memcpy(&normal, p, sizeof(normal));
      if (is_zero(bsdf.ng_) || dot(normal, bsdf.ng_) < 0.0f) {
        std::memcpy(turned, p, size);
        normal = -normal;
        std::memcpy(turned, &normal, sizeof(normal));
        setup_params = turned;
      }
    }
    uint32_t lobe_flags = lobe_setup(bsdf.kernels_, id, setup_params, bsdf.states_[n]);
    if (lobe_flags == 0) return;
    bsdf.lobes_[n] = Lobe{id, w, p, 0.0f, lobe_flags};
    ++n;
  }

  void layer(const unsigned char* p, const Color3& w, int depth) {
    const auto& q = closures::as_params<closures::LayerParams>(p);
    int first = bsdf.n_lobes_;
    visit(q.top, w, depth + 1);
    Color3 a; // top albedo per unit weight
    for (int i = first; i < bsdf.n_lobes_; ++i) a += bsdf.lobes_[i].weight * albedo_of(i);
    auto frac = [](float x, float wc) {
      return wc > 0.0f ? closures::clampf(x / wc, 0.0f, 1.0f) : 1.0f;
    };
    Color3 t = {1.0f - frac(a.x, w.x), 1.0f - frac(a.y, w.y), 1.0f - frac(a.z, w.z)};
    visit(q.base, w * t, depth + 1);
  }
};

namespace {

// Lobe i sees the pair (wo, wi) given the geometric side test.
bool side_ok(uint32_t flags, const Vec3& wo, const Vec3& wi, const Vec3& ng) {
  if (is_zero(ng)) return true;
  bool reflect = dot(wo, ng) * dot(wi, ng) > 0.0f;
  return reflect ? (flags & kLobeReflect) != 0 : (flags & kLobeTransmit) != 0;
}

} // namespace

void Bsdf::build(const ClosureNode* closure, const Vec3& wo, const Vec3& Ng,
                 const ClosureKernels* kernels, bool backfacing) {
  backfacing_ = backfacing;
  // Only what build() fills is reset: the lobe slots past n_lobes_ and their states are unused.
  emission = transparency = holdout = background = debug_weight = Color3{};
  debug_tag = nullptr;
  n_lobes_ = 0;
  ng_ = normalize(Ng);
  kernels_ = kernels;
  BsdfBuilder b{*this, wo};
  b.visit(closure, Color3{1, 1, 1}, 0);
  // A lone lobe is always the one sampled: its selection weight is 1 (sample() then uses u.x
  // as it is), and its albedo is not estimated.
  if (n_lobes_ == 1) {
    lobes_[0].select_weight = total_select_ = 1.0f;
    return;
  }
  total_select_ = 0.0f;
  for (int i = 0; i < n_lobes_; ++i) {
    Lobe& l = lobes_[i];
    float s = luminance(l.weight * b.albedo_of(i));
    // A lobe with no albedo estimate at wo still gets a small share, so that it is sampled.
    l.select_weight = closures::maxf(s, 1e-3f * luminance(l.weight));
    total_select_ += l.select_weight;
  }
}

Color3 Bsdf::lobe_albedo(int i, const Vec3& wo) const {
  return lobe_albedo_of(kernels_, lobes_[i].id, state(i), wo);
}

bool Bsdf::has_non_delta() const {
  for (int i = 0; i < n_lobes_; ++i)
    if (!(lobes_[i].flags & kLobeSpecular)) return true;
  return false;
}

bool Bsdf::has_delta() const {
  for (int i = 0; i < n_lobes_; ++i)
    if (lobes_[i].flags & kLobeSpecular) return true;
  return false;
}

BsdfEval Bsdf::eval(const Vec3& wo, const Vec3& wi, Transport mode) const {
  BsdfEval r;
  if (!(total_select_ > 0.0f)) return r;
  for (int i = 0; i < n_lobes_; ++i) {
    const Lobe& l = lobes_[i];
    if ((l.flags & kLobeSpecular) || !side_ok(l.flags, wo, wi, ng_)) continue;
    BsdfEval e = lobe_eval(kernels_, l.id, state(i), wo, wi, mode);
    r.value += l.weight * e.value;
    r.pdf += (l.select_weight / total_select_) * e.pdf;
  }
  r.value = closures::sanitize(r.value);
  if (!(r.pdf > 0.0f && r.pdf < INFINITY)) r.pdf = 0.0f;
  return r;
}

float Bsdf::pdf(const Vec3& wo, const Vec3& wi) const { return eval(wo, wi).pdf; }

std::optional<BsdfSample> Bsdf::sample(const Vec3& wo, const Vec3& u, Transport mode) const {
  if (!(total_select_ > 0.0f)) return std::nullopt;
  // Pick lobe i with probability select_weight / total; re-use u.x within the chosen slice.
  float x = closures::clampf(u.x, 0.0f, closures::kOneMinusEpsilon) * total_select_;
  int i = 0;
  while (i < n_lobes_ - 1 && x >= lobes_[i].select_weight) x -= lobes_[i++].select_weight;
  const Lobe& l = lobes_[i];
  float p_pick = l.select_weight / total_select_;
  float ux = closures::clampf(x / l.select_weight, 0.0f, closures::kOneMinusEpsilon);
  auto s = lobe_sample(kernels_, l.id, state(i), wo, {ux, u.y, u.z}, mode);
  if (!s || !side_ok(s->flags, wo, s->wi, ng_)) return std::nullopt;
  if (s->flags & kLobeSpecular) {
    s->weight = closures::sanitize(l.weight * s->weight / p_pick);
    s->pdf = p_pick;
    return s;
  }
  if (n_lobes_ == 1) {
    // A lone lobe is its own mixture: its sample's weight is its eval / pdf (every closure's
    // Consistency test checks that), so evaluating it again at wi would add nothing.
    if (!(s->pdf > 0.0f && s->pdf < INFINITY)) return std::nullopt;
    s->weight = closures::sanitize(l.weight * s->weight);
    return s;
  }
  BsdfEval e = eval(wo, s->wi, mode);
  if (!(e.pdf > 0.0f)) return std::nullopt;
  s->weight = closures::sanitize(e.value / e.pdf);
  s->pdf = e.pdf;
  return s;
}

Color3 Bsdf::albedo(const Vec3& wo) const {
  Color3 a;
  for (int i = 0; i < n_lobes_; ++i) a += lobes_[i].weight * lobe_albedo(i, wo);
  return a;
}

} // namespace lobe
