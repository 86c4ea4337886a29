// Bsdf: flattening (sums, weights, layer), dropped lobes, collected emission/transparency,
// mixture pdf and sample consistency, the geometric side test, and closure_to_string.
#include "closures.h"
#include "lobe/bsdf.h"
#include "test_util.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <deque>
#include <vector>

namespace lobe {
namespace {

using closures::Params;
using closures::test::dir_cos;
constexpr double kPiD = 3.14159265358979323846;

// Builds closure trees in owned storage (a stand-in for the ShadingContext arena).
struct Tree {
  std::deque<std::vector<unsigned char>> blocks;
  template <class T> T* alloc(size_t extra = 0) {
    blocks.emplace_back(sizeof(T) + extra + 8);
    return reinterpret_cast<T*>(blocks.back().data());
  }
  const ClosureNode* comp(const Params& p, Color3 w = {1, 1, 1}) {
    auto* c = alloc<ClosureComponent>(p.size());
    c->id = p.id();
    c->weight = w;
    std::memcpy(c->params(), p.data(), p.size());
    return c;
  }
  const ClosureNode* mul(Color3 w, const ClosureNode* x) {
    auto* m = alloc<ClosureMul>();
    m->id = kClosureMul;
    m->weight = w;
    m->closure = x;
    return m;
  }
  const ClosureNode* add(const ClosureNode* a, const ClosureNode* b) {
    auto* s = alloc<ClosureAdd>();
    s->id = kClosureAdd;
    s->a = a;
    s->b = b;
    return s;
  }
};

const Vec3 kUp{0, 0, 1};

TEST(Bsdf, NullClosureIsBlack) {
  Bsdf b;
  b.build(nullptr, dir_cos(0.5), kUp);
  EXPECT_EQ(b.lobe_count(), 0);
  EXPECT_EQ(b.eval(dir_cos(0.5), dir_cos(0.5)).value.x, 0.0f);
  EXPECT_FALSE(b.sample(dir_cos(0.5), {0.5f, 0.5f, 0.5f}).has_value());
}

TEST(Bsdf, MixturePdfAndValue) {
  Tree t;
  Params d("diffuse"), tr("translucent");
  const ClosureNode* c =
      t.add(t.mul({0.5f, 0.5f, 0.5f}, t.comp(d)), t.mul({0.25f, 0.25f, 0.25f}, t.comp(tr)));
  Bsdf b;
  Vec3 wo = dir_cos(0.6);
  b.build(c, wo, kUp);
  ASSERT_EQ(b.lobe_count(), 2);
  // Selection 0.5 : 0.25 (both albedos 1): reflection pdf = 2/3 cos/pi, value 0.5 cos/pi.
  BsdfEval e = b.eval(wo, dir_cos(0.8, 1.0));
  EXPECT_NEAR(e.value.x, 0.5 * 0.8 / kPiD, 1e-6);
  EXPECT_NEAR(e.pdf, (2.0 / 3.0) * 0.8 / kPiD, 1e-6);
  BsdfEval et = b.eval(wo, dir_cos(-0.4, 1.0));
  EXPECT_NEAR(et.value.y, 0.25 * 0.4 / kPiD, 1e-6);
  EXPECT_NEAR(et.pdf, (1.0 / 3.0) * 0.4 / kPiD, 1e-6);
  EXPECT_NEAR(b.albedo(wo).z, 0.75f, 1e-6f);
}

TEST(Bsdf, SampleWeightIsValueOverPdf) {
  Tree t;
  Params d("diffuse"), on("oren_nayar");
  on.set("sigma", 0.5f);
  Bsdf b;
  Vec3 wo = dir_cos(0.7, 0.3);
  b.build(t.add(t.mul({0.3f, 0.3f, 0.3f}, t.comp(d)), t.comp(on, {0.6f, 0.2f, 0.1f})), wo, kUp);
  for (float u0 : {0.05f, 0.4f, 0.6f, 0.95f}) {
    auto s = b.sample(wo, {u0, 0.37f, 0.81f});
    ASSERT_TRUE(s.has_value());
    BsdfEval e = b.eval(wo, s->wi);
    EXPECT_NEAR(s->pdf, e.pdf, 1e-5f * e.pdf);
    EXPECT_NEAR(s->weight.x, e.value.x / e.pdf, 1e-4f);
    EXPECT_NEAR(s->weight.y, e.value.y / e.pdf, 1e-4f);
  }
}

// A lone lobe takes its weight from its own sample (no second evaluation): still the mixture's
// eval / pdf, scaled by the closure weight, for a diffuse-like and a glossy lobe.
TEST(Bsdf, LoneLobeSampleWeightIsValueOverPdf) {
  Tree t;
  Params on("oren_nayar"), mf("microfacet");
  on.set("sigma", 0.5f);
  mf.set("distribution", "ggx").set("xalpha", 0.3f).set("yalpha", 0.3f).set("eta", 1.5f);
  for (const Params* p : {&on, &mf}) {
    Bsdf b;
    Vec3 wo = dir_cos(0.7, 0.3);
    b.build(t.comp(*p, {0.6f, 0.2f, 0.1f}), wo, kUp);
    ASSERT_EQ(b.lobe_count(), 1);
    int n = 0;
    for (float u1 : {0.1f, 0.37f, 0.62f, 0.9f})
      for (float u2 : {0.05f, 0.5f, 0.81f}) {
        auto s = b.sample(wo, {0.5f, u1, u2});
        if (!s) continue;
        ++n;
        BsdfEval e = b.eval(wo, s->wi);
        ASSERT_GT(e.pdf, 0.0f);
        EXPECT_NEAR(s->pdf, e.pdf, 1e-5f * e.pdf);
        for (int c = 0; c < 3; ++c)
          EXPECT_NEAR(s->weight[c], e.value[c] / e.pdf, 1e-4f * (1 + e.value[c] / e.pdf));
      }
    EXPECT_GE(n, 6);
  }
}

TEST(Bsdf, DropsZeroNanAndDegenerate) {
  Tree t;
  Params d("diffuse"), bad("diffuse");
  bad.set("N", Vec3{0, 0, 0});
  const ClosureNode* c =
      t.add(t.mul({0, 0, 0}, t.comp(d)), t.add(t.mul({NAN, 1, 1}, t.comp(d)), t.comp(bad)));
  Bsdf b;
  b.build(c, dir_cos(0.5), kUp);
  EXPECT_EQ(b.lobe_count(), 0);
  EXPECT_FALSE(b.sample(dir_cos(0.5), {0.1f, 0.2f, 0.3f}).has_value());
}

TEST(Bsdf, CollectsNonBsdfComponents) {
  Tree t;
  Params em("emission"), ue("uniform_edf"), tp("transparent"), ho("holdout"), dbg("debug");
  ue.set("emittance", Vec3{2, 3, 4});
  dbg.set("tag", "aov1");
  const ClosureNode* c =
      t.add(t.add(t.mul({0.5f, 0.5f, 0.5f}, t.comp(em)), t.comp(ue)),
            t.add(t.comp(tp, {0.2f, 0.2f, 0.2f}), t.add(t.comp(ho), t.comp(dbg))));
  Bsdf b;
  b.build(c, dir_cos(0.5), kUp);
  EXPECT_EQ(b.lobe_count(), 0);
  EXPECT_EQ(b.emission, (Color3{2.5f, 3.5f, 4.5f}));
  EXPECT_EQ(b.transparency, (Color3{0.2f, 0.2f, 0.2f}));
  EXPECT_EQ(b.holdout, (Color3{1, 1, 1}));
  EXPECT_STREQ(b.debug_tag, "aov1");
}

TEST(Bsdf, LayerAttenuatesBaseByTopAlbedo) {
  Tree t;
  Params d("diffuse"), tb("translucent_bsdf"), layer("layer");
  tb.set("albedo", Vec3{0.2f, 0.2f, 0.2f});
  layer.set_closure("top", t.mul({0.3f, 0.5f, 0.0f}, t.comp(d)));
  layer.set_closure("base", t.comp(tb));
  Bsdf b;
  Vec3 wo = dir_cos(0.5);
  b.build(t.comp(layer), wo, Vec3{});
  ASSERT_EQ(b.lobe_count(), 2);
  EXPECT_NEAR(b.lobe(1).weight.x, 0.7f, 1e-6f);
  EXPECT_NEAR(b.lobe(1).weight.y, 0.5f, 1e-6f);
  EXPECT_NEAR(b.lobe(1).weight.z, 1.0f, 1e-6f);
  // albedo: 0.3 + 0.7 * 0.2
  EXPECT_NEAR(b.albedo(wo).x, 0.3f + 0.7f * 0.2f, 1e-6f);
}

TEST(Bsdf, GeometricSideTestBlocksLeaks) {
  Tree t;
  Params d("diffuse");
  d.set("N", normalize(Vec3{0.3f, 0, 1}));
  Bsdf b;
  b.build(t.comp(d), dir_cos(0.5), kUp);
  // wi below the geometric surface but above the tilted shading normal: no reflection.
  Vec3 wi = normalize(Vec3{1, 0, -0.05f});
  EXPECT_EQ(b.eval(dir_cos(0.5), wi).value.x, 0.0f);
  b.build(t.comp(d), dir_cos(0.5), Vec3{});
  EXPECT_GT(b.eval(dir_cos(0.5), wi).value.x, 0.0f); // no Ng: no side test
}

// Seen from inside (wo below the outward Ng = +Z, cos 0.9), with N turned towards the viewer
// and `backfacing`: dielectric_bsdf (kSidedIor) keeps its IOR as the object's inside over
// outside and leaves the glass (relative index 1/1.5: |cos t| = sqrt(1 - 1.5^2 (1 - 0.81)) =
// 0.7566), exactly as with N outward and no flag; refraction() takes eta across the side N
// faces, i.e. enters a denser medium (|cos t| = sqrt(1 - 0.19 / 1.5^2) = 0.9569).
TEST(Bsdf, BackfacingTurnsNBackOnlyForSidedIorClosures) {
  const Vec3 wo = dir_cos(-0.9, 0.4), down{0, 0, -1};
  const Vec3 u{0.5f, 0.3f, 0.999f}; // picks transmission
  Tree t;
  Params glass_in("dielectric_bsdf"), glass_out("dielectric_bsdf"), refr("refraction");
  glass_in.set("N", down);
  glass_in.set("ior", 1.5f);
  glass_out.set("N", kUp);
  glass_out.set("ior", 1.5f);
  refr.set("N", down);
  refr.set("eta", 1.5f);
  Bsdf turned, outward, classic;
  turned.build(t.comp(glass_in), wo, kUp, nullptr, /*backfacing=*/true);
  outward.build(t.comp(glass_out), wo, kUp);
  classic.build(t.comp(refr), wo, kUp, nullptr, /*backfacing=*/true);
  // A shader that passes the outside normal itself (N = backfacing() ? -N : N) keeps it.
  Bsdf kept;
  kept.build(t.comp(glass_out), wo, kUp, nullptr, /*backfacing=*/true);
  auto a = turned.sample(wo, u), b = outward.sample(wo, u), c = classic.sample(wo, u);
  auto k = kept.sample(wo, u);
  ASSERT_TRUE(k);
  EXPECT_EQ(k->wi.z, b->wi.z);
  EXPECT_EQ(k->eta, b->eta);
  ASSERT_TRUE(a && b && c);
  EXPECT_NEAR(a->eta, 1.0f / 1.5f, 1e-6f);
  EXPECT_NEAR(std::fabs(a->wi.z), 0.7566f, 1e-4f);
  EXPECT_GT(a->wi.z, 0.0f); // out of the object
  EXPECT_EQ(a->wi.x, b->wi.x);
  EXPECT_EQ(a->wi.z, b->wi.z);
  EXPECT_EQ(a->weight.x, b->weight.x);
  EXPECT_NEAR(c->eta, 1.5f, 1e-6f);
  EXPECT_NEAR(std::fabs(c->wi.z), 0.9569f, 1e-4f);
  EXPECT_GT(c->wi.z, 0.0f);
}

TEST(ClosureString, OslPrintFormat) {
  Tree t;
  Params d("diffuse"), em("emission"), on("oren_nayar_diffuse_bsdf");
  on.set("albedo", Vec3{0.5f, 0.25f, 1}).set("roughness", 0.5f).set("energy_compensation", 1);
  const ClosureNode* c = t.add(t.mul({0.5f, 0.5f, 0.5f}, t.comp(d)), t.add(t.comp(em), t.comp(on)));
  // diffuse prints its "label" even unset, as OSL's testshade does (OSL 1.13.12:
  // printf("%s\n", diffuse(N)) prints `(1, 1, 1) * diffuse ((0, 0, 1), "label", "")`); other
  // keywords print only when they differ from their default.
  EXPECT_EQ(closure_to_string(c), "(0.5, 0.5, 0.5) * diffuse ((0, 0, 1), \"label\", \"\")\n"
                                  "\t+ (1, 1, 1) * emission ()\n"
                                  "\t+ (1, 1, 1) * oren_nayar_diffuse_bsdf ((0, 0, 1), "
                                  "(0.5, 0.25, 1), 0.5, \"energy_compensation\", 1)");
  EXPECT_EQ(closure_to_string(nullptr), "");
}

} // namespace
} // namespace lobe
