// Params blocks against the registry: defaults land at the registry's offsets, setters write
// where the registry says, and every registry entry has an implementation.
#include "closure_registry.h"
#include "closures.h"
#include "dispatch.h"

#include <gtest/gtest.h>

#include <stdexcept>
#include <string>

#include <cstring>

namespace lobe::closures {
namespace {

TEST(Params, DefaultsAndSettersFollowRegistryOffsets) {
  Params p("microfacet");
  const auto& e = *registry::find_by_key("microfacet");
  ASSERT_EQ(p.size(), registry::param_block_size(e.params));
  p.set("xalpha", 0.25f).set("refract", 2).set("U", Vec3{0, 1, 0});
  const auto& q = *reinterpret_cast<const MicrofacetParams*>(p.data());
  EXPECT_STREQ(q.distribution, "ggx");
  EXPECT_EQ(q.N, (Vec3{0, 0, 1}));
  EXPECT_EQ(q.U, (Vec3{0, 1, 0}));
  EXPECT_EQ(q.xalpha, 0.25f);
  EXPECT_EQ(q.refract, 2);
  EXPECT_EQ(q.energy_compensation, 1); // registry default
  float raw;
  std::memcpy(&raw, p.data() + 32, 4); // xalpha at byte 32 (worked out by hand)
  EXPECT_EQ(raw, 0.25f);
}

TEST(Params, KeywordDefaultsParsed) {
  Params t("toon");
  const auto& q = *reinterpret_cast<const ToonParams*>(t.data());
  EXPECT_EQ(q.bands, 3);
  EXPECT_FLOAT_EQ(q.softness, 0.05f);
  EXPECT_STREQ(q.label, "");
  Params m("measured_bsdf");
  EXPECT_EQ(reinterpret_cast<const MeasuredParams*>(m.data())->tint, (Vec3{1, 1, 1}));
  Params c("conductor_bsdf");
  EXPECT_FLOAT_EQ(reinterpret_cast<const ConductorParams*>(c.data())->thinfilm_ior, 1.5f);
  EXPECT_EQ(param_warning(c.id(), c.data()), nullptr);
  c.set("thinfilm_thickness", 400.0f); // implemented: no warning
  EXPECT_EQ(param_warning(c.id(), c.data()), nullptr);
  c.set("thinfilm_thickness", -1.0f);
  EXPECT_NE(param_warning(c.id(), c.data()), nullptr);
}

TEST(Params, FloatPromotesToColour) {
  Params p("translucent_bsdf");
  p.set("albedo", 0.5f);
  EXPECT_EQ(reinterpret_cast<const AlbedoParams*>(p.data())->albedo, (Vec3{0.5f, 0.5f, 0.5f}));
}

// Asking for what the registry lacks is the caller's bug: an exception naming it (the library
// neither prints nor aborts).
TEST(Params, UnknownKeyThrows) {
  try {
    Params p("no_such_closure");
    ADD_FAILURE() << "no exception";
  } catch (const std::logic_error& e) {
    EXPECT_NE(std::string(e.what()).find("unknown closure key 'no_such_closure'"),
              std::string::npos)
        << e.what();
  }
  try {
    Params("diffuse").set("sigma", 1.0f);
    ADD_FAILURE() << "no exception";
  } catch (const std::logic_error& e) {
    EXPECT_NE(std::string(e.what()).find("diffuse has no parameter 'sigma'"), std::string::npos)
        << e.what();
  }
}

} // namespace
} // namespace lobe::closures
