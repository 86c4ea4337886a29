// Tests of the closure call parser: values land at the registry's offsets, overloads resolve,
// and errors point at the offending argument.
#include "closure_expr.h"

#include "closure_registry.h"

#include <gtest/gtest.h>

#include <cstring>

using namespace lobe;
using namespace lobe::verify;

namespace {
template <class T> T read(const ParsedClosure& pc, const char* name) {
  const auto* e = registry::find_by_key(pc.key);
  for (size_t i = 0; i < e->params.size(); ++i)
    if (std::string_view(e->params[i].name) == name) {
      T v;
      std::memcpy(&v, pc.params.data() + registry::param_offset(e->params, i), sizeof(T));
      return v;
    }
  ADD_FAILURE() << name;
  return T{};
}
} // namespace

TEST(ClosureExpr, ConductorCall) {
  ExprResult r = parse_closure_expr(
      "conductor_bsdf(N, U, 0.2, 0.3, color(0.2,0.9,1.1), color(3.9, 2.4, 2.2), \"beckmann\", "
      "\"energy_compensation\", 0)");
  ASSERT_TRUE(r.closure) << r.error.message;
  EXPECT_EQ(r.closure->key, "conductor_bsdf");
  EXPECT_FLOAT_EQ(read<float>(*r.closure, "roughness_y"), 0.3f);
  EXPECT_EQ(read<Vec3>(*r.closure, "extinction"), (Vec3{3.9f, 2.4f, 2.2f}));
  EXPECT_EQ(read<Vec3>(*r.closure, "N"), (Vec3{0, 0, 1}));
  EXPECT_STREQ(read<const char*>(*r.closure, "distribution"), "beckmann");
  EXPECT_EQ(read<int>(*r.closure, "energy_compensation"), 0);
  EXPECT_EQ(r.closure->eta_below, 1.0);
}

TEST(ClosureExpr, OverloadsAndPromotion) {
  ExprResult r5 = parse_closure_expr("microfacet(\"ggx\", N, 0.3, 1.5, 2)");
  ASSERT_TRUE(r5.closure) << r5.error.message;
  EXPECT_EQ(r5.closure->key, "microfacet"); // stdosl.h's forward to the 7-argument form
  EXPECT_FLOAT_EQ(read<float>(*r5.closure, "yalpha"), 0.3f);
  EXPECT_DOUBLE_EQ(r5.closure->eta_below, 1.5);
  ExprResult r7 = parse_closure_expr("microfacet(\"ggx\", N, U, 0.3, 0.1, 1.33, 1)");
  ASSERT_TRUE(r7.closure) << r7.error.message;
  EXPECT_EQ(r7.closure->key, "microfacet");
  // The 5-argument form is stdosl.h's: U = vector(0) and both alphas from the one given.
  EXPECT_EQ(read<Vec3>(*r5.closure, "U"), (Vec3{0, 0, 0}));
  EXPECT_FLOAT_EQ(read<float>(*r5.closure, "xalpha"), 0.3f);
  EXPECT_EQ(read<int>(*r5.closure, "refract"), 2);
  // reflection(N) is stdosl.h's reflection(N, 0.0).
  ExprResult refl = parse_closure_expr("reflection(vector(0, 1, 0))");
  ASSERT_TRUE(refl.closure) << refl.error.message;
  EXPECT_EQ(refl.closure->key, "reflection");
  EXPECT_EQ(read<Vec3>(*refl.closure, "N"), (Vec3{0, 1, 0}));
  EXPECT_FLOAT_EQ(read<float>(*refl.closure, "eta"), 0.0f);
  ExprResult d = parse_closure_expr("oren_nayar_diffuse_bsdf(N, 0.5, 0.25)");
  ASSERT_TRUE(d.closure) << d.error.message;
  EXPECT_EQ(read<Vec3>(*d.closure, "albedo"), (Vec3{0.5f, 0.5f, 0.5f}));
}

TEST(ClosureExpr, ErrorsPointAtTheProblem) {
  ExprResult u = parse_closure_expr("  shiny(N)");
  ASSERT_FALSE(u.closure);
  EXPECT_EQ(u.error.pos, 2u);
  EXPECT_NE(u.error.message.find("unknown closure"), std::string::npos);
  std::string text = "conductor_bsdf(N, U, 0.2, 0.2, \"x\", color(1), \"ggx\")";
  ExprResult t = parse_closure_expr(text);
  ASSERT_FALSE(t.closure);
  EXPECT_EQ(t.error.pos, text.find("\"x\""));
  EXPECT_NE(t.error.message.find("'ior' expects a color"), std::string::npos);
  ExprResult k = parse_closure_expr("diffuse(N, \"nope\", 1)");
  ASSERT_FALSE(k.closure);
  EXPECT_EQ(k.error.pos, 11u);
  ExprResult few = parse_closure_expr("phong(N)");
  ASSERT_FALSE(few.closure);
  EXPECT_EQ(few.error.pos, 7u);
  ExprResult junk = parse_closure_expr("diffuse(N) x");
  ASSERT_FALSE(junk.closure);
  EXPECT_EQ(junk.error.pos, 11u);
}
