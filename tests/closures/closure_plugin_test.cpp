// A renderer's own closure, end to end through the public API only: registered with
// lobe::register_closure (lobe/closure_plugin.h), type-checked in a shader that declares it
// `[[ int builtin = 1 ]]`, built into the closure tree by generated code, printed, and
// evaluated, sampled and weighted by a Bsdf (with and without the material's JIT kernels,
// which do not cover it). The closure is a Lambertian lobe with albedo `albedo * scale`, so
// every expected value is a closed form: f cos = a cos_i / pi, pdf = cos_i / pi, a sample's
// weight = a, its cos_i = sqrt(1 - u.x) (the warp below), directional albedo = a.
#include "lobe/bsdf.h"
#include "lobe/closure_plugin.h"
#include "lobe/detail/closure_kernels.h" // covers(): the test checks which lobes the kernels take
#include "lobe/shadingsys.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

namespace lobe {
namespace {

constexpr float kPi = 3.14159265358979f;

// Where the parameters are in the block (closure_param_offset, filled at registration).
struct Layout {
  long N = -1, albedo = -1, scale = -1;
};
Layout g_layout;

Vec3 read_vec(const unsigned char* p, long off) {
  Vec3 v;
  std::memcpy(&v, p + off, sizeof v);
  return v;
}
float read_float(const unsigned char* p, long off) {
  float f;
  std::memcpy(&f, p + off, sizeof f);
  return f;
}
Color3 albedo_of(const unsigned char* p, const Layout& l) {
  return read_vec(p, l.albedo) * read_float(p, l.scale);
}

BsdfEval eval_fn(const unsigned char* p, const Vec3& wo, const Vec3& wi, Transport, void* user) {
  const Layout& l = *static_cast<const Layout*>(user);
  Vec3 n = normalize(read_vec(p, l.N));
  float co = dot(n, wo), ci = dot(n, wi);
  if (!(co > 0.0f) || !(ci > 0.0f)) return {};
  return {albedo_of(p, l) * (ci / kPi), ci / kPi};
}
float pdf_fn(const unsigned char* p, const Vec3& wo, const Vec3& wi, void* user) {
  return eval_fn(p, wo, wi, Transport::Radiance, user).pdf;
}
// Cosine-weighted around N: cos theta = sqrt(1 - u.x), phi = 2 pi u.y.
BsdfSample sample_fn(const unsigned char* p, const Vec3& wo, const Vec3& u, Transport, void* user) {
  const Layout& l = *static_cast<const Layout*>(user);
  Vec3 n = normalize(read_vec(p, l.N));
  if (!(dot(n, wo) > 0.0f)) return {};
  Vec3 t = normalize(std::fabs(n.x) > 0.5f ? cross(n, Vec3{0, 1, 0}) : cross(n, Vec3{1, 0, 0}));
  Vec3 b = cross(n, t);
  float r = std::sqrt(u.x), phi = 2.0f * kPi * u.y, z = std::sqrt(1.0f - u.x);
  Vec3 wi = t * (r * std::cos(phi)) + b * (r * std::sin(phi)) + n * z;
  BsdfSample s;
  s.wi = wi;
  s.pdf = z / kPi;
  s.weight = albedo_of(p, l);
  s.flags = kLobeReflect | kLobeDiffuse;
  return s;
}
Color3 albedo_fn(const unsigned char* p, const Vec3&, void* user) {
  return albedo_of(p, *static_cast<const Layout*>(user));
}

CustomClosure test_lambert() {
  CustomClosure c;
  c.name = "test_lambert";
  c.params = {{"N", ClosureParamType::Vector, false, "", "shading normal"},
              {"albedo", ClosureParamType::Color, false, "", "reflectance"},
              {"scale", ClosureParamType::Float, true, "1", "multiplies albedo"}};
  c.lobe_flags = kLobeReflect | kLobeDiffuse;
  c.doc = "a Lambertian lobe for the plugin test";
  c.eval = eval_fn;
  c.pdf = pdf_fn;
  c.sample = sample_fn;
  c.albedo = albedo_fn;
  c.user = &g_layout;
  return c;
}

// Registered once for the whole binary (registrations last for the process).
int registered_id() {
  static int id = [] {
    std::string err;
    int i = register_closure(test_lambert(), &err);
    EXPECT_GE(i, 0) << err;
    g_layout = {closure_param_offset("test_lambert", "N"),
                closure_param_offset("test_lambert", "albedo"),
                closure_param_offset("test_lambert", "scale")};
    return i;
  }();
  return id;
}

const char* kPrototype =
    "closure color test_lambert(normal N, color albedo) [[ int builtin = 1 ]];\n";

std::shared_ptr<const Material> compile(ShadingSystem& ss, const std::string& body,
                                        DiagnosticList& d) {
  std::string src = std::string(kPrototype) + "surface s() {\n  " + body + "\n}\n";
  if (!ss.add_shader_source("s", src, "plugin_test.osl", d)) return nullptr;
  ShaderGroup g;
  g.layers.push_back({"s", "l", {}});
  return ss.compile(g, d);
}

std::string text(const DiagnosticList& d) {
  std::string s;
  for (const Diagnostic& x : d) s += x.text + "\n";
  return s;
}

void expect_near(const Vec3& a, const Vec3& b, float tol) {
  EXPECT_NEAR(a.x, b.x, tol);
  EXPECT_NEAR(a.y, b.y, tol);
  EXPECT_NEAR(a.z, b.z, tol);
}

TEST(ClosurePlugin, RegistersWithItsLayout) {
  ASSERT_GE(registered_id(), 0);
  // Natural alignment, declaration order: N at 0, albedo at 12, scale at 24.
  EXPECT_EQ(g_layout.N, 0);
  EXPECT_EQ(g_layout.albedo, 12);
  EXPECT_EQ(g_layout.scale, 24);
  EXPECT_EQ(closure_param_offset("test_lambert", "nosuch"), -1);
  EXPECT_EQ(closure_param_offset("nosuch", "N"), -1);
}

TEST(ClosurePlugin, RejectsBadRegistrations) {
  ASSERT_GE(registered_id(), 0);
  std::string err;
  EXPECT_EQ(register_closure(test_lambert(), &err), -1); // registered already
  EXPECT_NE(err.find("exists"), std::string::npos) << err;
  CustomClosure c = test_lambert();
  c.name = "diffuse"; // a built-in closure
  EXPECT_EQ(register_closure(c, &err), -1);
  c.name = "no_sample";
  c.sample = nullptr;
  EXPECT_EQ(register_closure(c, &err), -1);
  EXPECT_NE(err.find("required"), std::string::npos) << err;
  c = test_lambert();
  c.name = "2bad";
  EXPECT_EQ(register_closure(c, &err), -1);
  c.name = "delta_plugin";
  c.lobe_flags = kLobeReflect | kLobeSpecular;
  EXPECT_EQ(register_closure(c, &err), -1);
  c.lobe_flags = kLobeDiffuse; // neither reflection nor transmission
  EXPECT_EQ(register_closure(c, &err), -1);
  c = test_lambert();
  c.name = "keyword_first";
  std::swap(c.params[0], c.params[2]); // a positional parameter after a keyword
  EXPECT_EQ(register_closure(c, &err), -1);
}

// The type checker knows the registered signature: wrong argument types and counts are
// errors, as for built-in closures.
TEST(ClosurePlugin, TypeCheckerSeesTheSignature) {
  ASSERT_GE(registered_id(), 0);
  ShadingSystem ss;
  DiagnosticList d;
  EXPECT_FALSE(compile(ss, "Ci = test_lambert(N, \"red\");", d));
  EXPECT_NE(text(d).find("test_lambert"), std::string::npos) << text(d);
  d.clear();
  EXPECT_FALSE(compile(ss, "Ci = test_lambert(N);", d));
  EXPECT_NE(text(d).find("test_lambert"), std::string::npos) << text(d);
}

TEST(ClosurePlugin, ShaderBuildsItAndBsdfEvaluatesIt) {
  const int id = registered_id();
  ASSERT_GE(id, 0);
  ShadingSystem ss;
  DiagnosticList d;
  auto mat = compile(ss, "Ci = 0.5 * test_lambert(N, color(0.2, 0.4, 0.6), \"scale\", 0.5);", d);
  ASSERT_TRUE(mat) << text(d);
  ShadingContext ctx;
  ShaderGlobals sg{};
  sg.context = &ctx;
  sg.N = sg.Ng = {0, 0, 1};
  sg.I = {0, 0, -1};
  mat->shade(sg);
  ASSERT_NE(sg.Ci, nullptr);
  EXPECT_EQ(closure_to_string(sg.Ci),
            "(0.5, 0.5, 0.5) * test_lambert ((0, 0, 1), (0.2, 0.4, 0.6), \"scale\", 0.5)");

  const Color3 a = Color3{0.2f, 0.4f, 0.6f} * 0.25f; // weight 0.5 times scale 0.5
  const Vec3 wo = normalize(Vec3{0.3f, -0.2f, 0.9f});
  const ClosureKernels* kernels = mat->closure_kernels(); // none cover the plugin closure
  for (const ClosureKernels* k : {static_cast<const ClosureKernels*>(nullptr), kernels}) {
    Bsdf b;
    b.build(sg.Ci, wo, sg.Ng, k);
    ASSERT_EQ(b.lobe_count(), 1);
    EXPECT_EQ(b.lobe(0).id, id);
    EXPECT_EQ(b.lobe(0).flags, uint32_t(kLobeReflect | kLobeDiffuse));
    const Vec3 wi{0.8f, 0.0f, 0.6f};
    BsdfEval e = b.eval(wo, wi);
    expect_near(e.value, a * (0.6f / kPi), 1e-6f);
    EXPECT_NEAR(e.pdf, 0.6f / kPi, 1e-6f);
    EXPECT_NEAR(b.pdf(wo, wi), 0.6f / kPi, 1e-6f);
    EXPECT_EQ(b.eval(wo, Vec3{0.8f, 0.0f, -0.6f}).pdf, 0.0f); // below the surface
    expect_near(b.albedo(wo), a, 1e-6f);
    for (float ux : {0.1f, 0.5f, 0.9f}) {
      auto s = b.sample(wo, {ux, 0.3f, 0.7f});
      ASSERT_TRUE(s);
      EXPECT_NEAR(s->wi.z, std::sqrt(1.0f - ux), 1e-5f);
      EXPECT_NEAR(s->pdf, std::sqrt(1.0f - ux) / kPi, 1e-5f);
      expect_near(s->weight, a, 1e-5f);
      EXPECT_EQ(s->flags, uint32_t(kLobeReflect | kLobeDiffuse));
    }
  }
}

// Mixed with a built-in lobe that the material's kernels do cover: the plugin lobe goes to its
// own functions, diffuse to the kernel, and the mixture is the sum of two Lambert lobes
// (value (a + 1) cos_i / pi, pdf cos_i / pi whatever the selection weights, weight a + 1).
TEST(ClosurePlugin, MixesWithKernelLobes) {
  ASSERT_GE(registered_id(), 0);
  ShadingSystem ss;
  DiagnosticList d;
  auto mat = compile(ss, "Ci = test_lambert(N, color(0.2, 0.4, 0.6)) + diffuse(N);", d);
  ASSERT_TRUE(mat) << text(d);
  const ClosureKernels* k = mat->closure_kernels();
  ASSERT_NE(k, nullptr) << mat->closure_kernels_error();
  EXPECT_TRUE(k->covers(0)); // diffuse is registry id 0
  EXPECT_FALSE(k->covers(registered_id()));
  ShadingContext ctx;
  ShaderGlobals sg{};
  sg.context = &ctx;
  sg.N = sg.Ng = {0, 0, 1};
  mat->shade(sg);
  const Color3 a{1.2f, 1.4f, 1.6f};
  const Vec3 wo = normalize(Vec3{-0.4f, 0.1f, 0.8f}), wi{0.0f, 0.6f, 0.8f};
  for (const ClosureKernels* kk : {static_cast<const ClosureKernels*>(nullptr), k}) {
    Bsdf b;
    b.build(sg.Ci, wo, sg.Ng, kk);
    ASSERT_EQ(b.lobe_count(), 2);
    BsdfEval e = b.eval(wo, wi);
    expect_near(e.value, a * (0.8f / kPi), 1e-6f);
    EXPECT_NEAR(e.pdf, 0.8f / kPi, 1e-6f);
    expect_near(b.albedo(wo), a, 1e-6f);
    for (float ux : {0.05f, 0.3f, 0.6f, 0.95f}) {
      auto s = b.sample(wo, {ux, 0.25f, 0.5f});
      ASSERT_TRUE(s);
      expect_near(s->weight, a, 1e-5f);
      EXPECT_NEAR(s->pdf, s->wi.z / kPi, 1e-5f);
    }
  }
}

} // namespace
} // namespace lobe
