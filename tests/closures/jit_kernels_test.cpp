// Closure kernels (runtime/jit/closure_kernels.h): the closure library compiled by clang-19 to
// bitcode, linked into a JIT module and inlined, against the same C++ compiled natively. For
// every BSDF entry of the registry, its quick configurations and its parameter extremes, over
// random direction pairs on the whole sphere and random numbers: eval (value, pdf), sample
// (ok, direction, weight, pdf, flags, eta) and albedo agree to 1e-6 relative (1e-6 absolute
// below magnitude 1). The two builds differ only in code generation (inlining, FMA
// contraction), so agreement is expected to float rounding.
#include "closure_kernels.h"
#include "closure_registry.h"
#include "closures.h"
#include "common.h"
#include "configs.h"
#include "param_stress.h"
#include "rng.h"

#include "lobe/shadingsys.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <memory>
#include <thread>

using namespace lobe;
using namespace lobe::verify;

namespace {

// Bit-for-bit equality of results (the set-up-once path against the set-up-per-call one).
bool same_bits(const Vec3& a, const Vec3& b) { return std::memcmp(&a, &b, sizeof a) == 0; }
bool same_bits(const BsdfEval& a, const BsdfEval& b) {
  return same_bits(a.value, b.value) && std::memcmp(&a.pdf, &b.pdf, sizeof a.pdf) == 0;
}
bool same_bits(const BsdfSample& a, const BsdfSample& b) {
  return same_bits(a.wi, b.wi) && same_bits(a.weight, b.weight) &&
         std::memcmp(&a.pdf, &b.pdf, sizeof a.pdf) == 0 && a.flags == b.flags &&
         std::memcmp(&a.eta, &b.eta, sizeof a.eta) == 0;
}

bool close(float a, float b, double* worst) {
  if (!std::isfinite(a) || !std::isfinite(b)) return false;
  double d =
      std::fabs(double(a) - double(b)) / std::fmax(1.0, std::fmax(std::fabs(a), std::fabs(b)));
  *worst = std::fmax(*worst, d);
  return d <= 1e-6;
}
bool close(const Vec3& a, const Vec3& b, double* worst) {
  return close(a.x, b.x, worst) && close(a.y, b.y, worst) && close(a.z, b.z, worst);
}

// The BSDF entries the bitcode provides: the property suites' testable entries (every
// implemented reflect/transmit entry but the file-reading measured_bsdf).
std::vector<int> bsdf_ids() {
  std::vector<int> ids;
  for (int id = 0; id < int(registry::closures().size()); ++id)
    if (is_testable(id)) ids.push_back(id);
  return ids;
}

struct Kernels {
  std::unique_ptr<jit::Jit> jit;
  ClosureKernels k;
  jit::CompiledGroup code;
  ~Kernels() {
    if (jit) jit->remove(code);
  }
};

class JitKernels : public ::testing::Test {
protected:
  static void SetUpTestSuite() {
    std::string err;
    kernels_ = new Kernels;
    kernels_->jit = jit::Jit::create(err);
    ASSERT_TRUE(kernels_->jit) << err;
    jit::JitTimes t;
    ASSERT_TRUE(jit::compile_closure_kernels(*kernels_->jit, bsdf_ids(), kernels_->k,
                                             kernels_->code, t, err))
        << err;
  }
  static void TearDownTestSuite() {
    delete kernels_;
    kernels_ = nullptr;
  }
  static Kernels* kernels_;
};
Kernels* JitKernels::kernels_ = nullptr;

TEST_F(JitKernels, CoverEveryBsdfWithBitcode) {
  for (int id : bsdf_ids()) EXPECT_TRUE(kernels_->k.covers(id)) << registry::closures()[id].key;
  EXPECT_FALSE(kernels_->k.covers(registry::id_of("measured_bsdf")));
  EXPECT_FALSE(kernels_->k.covers(registry::id_of("emission")));
}

TEST_F(JitKernels, AgreeWithNativeLibrary) {
  const ClosureKernels& k = kernels_->k;
  double worst = 0;
  for (int id : bsdf_ids()) {
    const char* key = registry::closures()[size_t(id)].key;
    std::vector<closures::Params> blocks;
    std::vector<ClosureConfig> cs = configs_for(id, Level::Quick);
    for (const ClosureConfig& c : cs) blocks.push_back(c.params);
    for (const ParamVariant& v : param_variants(cs.front().params)) blocks.push_back(v.params);
    Pcg32 rng(77 + uint64_t(id));
    int mismatches = 0;
    for (const closures::Params& p : blocks) {
      // Set up once per block, as Bsdf::build does: natively and through the kernels.
      alignas(Bsdf::kLobeStateAlign) unsigned char ns_state[Bsdf::kLobeStateBytes];
      alignas(Bsdf::kLobeStateAlign) unsigned char js_state[Bsdf::kLobeStateBytes];
      uint32_t nf = closures::setup(id, p.data(), ns_state);
      uint32_t jf = k.setup(id, p.data(), js_state);
      EXPECT_EQ(nf, jf) << key;
      EXPECT_EQ(nf, closures::lobe_flags(id, p.data())) << key;
      if (nf == 0 || jf == 0) { // a degenerate block: no lobe either way, nothing evaluates
        EXPECT_FALSE(closures::sample(id, p.data(), Vec3{0, 0, 1}, Vec3{0.5f, 0.5f, 0.5f})) << key;
        continue;
      }
      for (int n = 0; n < 200; ++n) {
        Vec3 wo = uniform_sphere(rng.next_double(), rng.next_double());
        Vec3 wi = uniform_sphere(rng.next_double(), rng.next_double());
        if (n % 4 == 0) wo.z = std::fabs(wo.z); // more pairs above the surface
        Vec3 u = rng.next_vec3();
        for (int mode = 0; mode < 2; ++mode) {
          Transport t = mode ? Transport::Importance : Transport::Radiance;
          BsdfEval ne = closures::eval(id, p.data(), wo, wi, t);
          BsdfEval je;
          k.eval(id, js_state, &wo, &wi, mode, &je);
          bool ok = close(ne.value, je.value, &worst) && close(ne.pdf, je.pdf, &worst);
          auto ns = closures::sample(id, p.data(), wo, u, t);
          BsdfSample js;
          bool jok = k.sample(id, js_state, &wo, &u, mode, &js) != 0;
          // The natively prepared lobe gives the same bits as setting it up at every call.
          BsdfEval pe = closures::eval_prepared(id, ns_state, wo, wi, t);
          auto ps = closures::sample_prepared(id, ns_state, wo, u, t);
          ok = ok && same_bits(pe, ne) && bool(ps) == bool(ns) && (!ps || same_bits(*ps, *ns));
          ok = ok && jok == bool(ns);
          if (ok && ns)
            ok = close(ns->wi, js.wi, &worst) && close(ns->weight, js.weight, &worst) &&
                 close(ns->pdf, js.pdf, &worst) && ns->flags == js.flags &&
                 close(ns->eta, js.eta, &worst);
          if (mode == 0) {
            Vec3 ja;
            k.albedo(id, js_state, &wo, &ja);
            Color3 na = closures::albedo(id, p.data(), wo);
            ok = ok && close(na, ja, &worst) &&
                 same_bits(closures::albedo_prepared(id, ns_state, wo), na);
          }
          if (!ok && ++mismatches <= 3)
            ADD_FAILURE() << key << ": native and JIT differ at wo (" << wo.x << ", " << wo.y
                          << ", " << wo.z << "), wi (" << wi.x << ", " << wi.y << ", " << wi.z
                          << "), mode " << mode << ": eval " << ne.value.x << "/" << je.value.x
                          << " pdf " << ne.pdf << "/" << je.pdf << " sample " << bool(ns) << "/"
                          << jok << " u (" << u.x << ", " << u.y << ", " << u.z << ")"
                          << (ns ? " native wi (" + std::to_string(ns->wi.x) + ", " +
                                       std::to_string(ns->wi.y) + ", " + std::to_string(ns->wi.z) +
                                       ") w " + std::to_string(ns->weight.x) + " pdf " +
                                       std::to_string(ns->pdf)
                                 : std::string())
                          << (jok ? " jit wi (" + std::to_string(js.wi.x) + ", " +
                                        std::to_string(js.wi.y) + ", " + std::to_string(js.wi.z) +
                                        ") w " + std::to_string(js.weight.x) + " pdf " +
                                        std::to_string(js.pdf)
                                  : std::string());
        }
      }
    }
  }
  std::printf("largest relative difference, native vs JIT: %.3g\n", worst);
}

// A material's kernels hold only its own closures; its Bsdf gives the native results.
TEST(MaterialKernels, OnlyTheMaterialsClosuresAndSameMixture) {
  ShadingSystem ss;
  DiagnosticList d;
  ASSERT_TRUE(ss.add_shader_ir("two", R"(lobe-ir 1
surface two
symbols
  global normal N
  global closure Ci
  local closure a
  local closure b
  const string $c0 = "diffuse"
  const string $c1 = "phong"
  const float $c2 = 20
main
  closure a $c0 N
  closure b $c1 N $c2
  add Ci a b
end
)",
                               d));
  DiagnosticList diags;
  auto g = ss.parse_group("shader two layer ;", "t", diags);
  ASSERT_TRUE(g);
  auto mat = ss.compile(*g, diags);
  ASSERT_TRUE(mat) << (diags.empty() ? "" : diags.front().text);
  const ClosureKernels* k = mat->closure_kernels();
  ASSERT_NE(k, nullptr) << mat->closure_kernels_error();
  EXPECT_TRUE(k->covers(registry::id_of("diffuse")));
  EXPECT_TRUE(k->covers(registry::id_of("phong")));
  EXPECT_FALSE(k->covers(registry::id_of("ward")));
  EXPECT_FALSE(k->covers(registry::id_of("dielectric_bsdf")));

  ShadingContext ctx;
  ShaderGlobals sg{};
  sg.context = &ctx;
  sg.N = sg.Ng = {0, 0, 1};
  mat->shade(sg);
  Vec3 wo = normalize(Vec3{0.3f, 0.1f, 0.9f});
  Bsdf native, jitted;
  native.build(sg.Ci, wo, sg.Ng);
  jitted.build(sg.Ci, wo, sg.Ng, k);
  ASSERT_EQ(jitted.lobe_count(), 2);
  double worst = 0;
  Pcg32 rng(5);
  for (int n = 0; n < 500; ++n) {
    Vec3 wi = uniform_sphere(rng.next_double(), rng.next_double());
    BsdfEval a = native.eval(wo, wi), b = jitted.eval(wo, wi);
    EXPECT_TRUE(close(a.value, b.value, &worst) && close(a.pdf, b.pdf, &worst));
    Vec3 u = rng.next_vec3();
    auto sa = native.sample(wo, u), sb = jitted.sample(wo, u);
    ASSERT_EQ(bool(sa), bool(sb));
    if (sa) {
      EXPECT_TRUE(close(sa->wi, sb->wi, &worst) && close(sa->weight, sb->weight, &worst));
    }
  }
  // Lambert (1/pi) plus Phong at wo: eval at the mirror direction is positive and finite.
  EXPECT_GT(native.eval(wo, Vec3{-wo.x, -wo.y, wo.z}).value.x, 1.0f / float(M_PI) * wo.z);
}

// Materials compiled, and their kernels compiled, from several threads at once (as the
// renderer does at scene load): every thread's kernels give the native value.
TEST(MaterialKernels, CompileConcurrently) {
  ShadingSystem ss;
  std::vector<std::shared_ptr<const Material>> mats(4);
  std::vector<std::thread> threads;
  const char* shaders[4] = {"matte", "plastic", "metal", "glass"};
  ss.options().include_dirs.push_back(LOBE_TEST_STDLIB_DIR);
  for (int t = 0; t < 4; ++t)
    threads.emplace_back([&, t] {
      DiagnosticList d;
      ShaderGroup g;
      g.layers.push_back({shaders[t], "m", {}});
      mats[size_t(t)] = ss.compile(g, d);
      if (mats[size_t(t)]) mats[size_t(t)]->closure_kernels();
    });
  for (auto& th : threads) th.join();
  for (int t = 0; t < 4; ++t) {
    ASSERT_TRUE(mats[size_t(t)]) << shaders[t];
    const ClosureKernels* k = mats[size_t(t)]->closure_kernels();
    ASSERT_NE(k, nullptr) << shaders[t] << ": " << mats[size_t(t)]->closure_kernels_error();
    ShadingContext ctx;
    ShaderGlobals sg{};
    sg.context = &ctx;
    sg.N = sg.Ng = {0, 0, 1};
    sg.dPdu = {1, 0, 0};
    sg.dPdv = {0, 1, 0};
    sg.I = {0, 0, -1};
    mats[size_t(t)]->shade(sg);
    Vec3 wo = normalize(Vec3{0.2f, 0.1f, 0.95f}), wi = normalize(Vec3{-0.3f, 0.2f, 0.9f});
    Bsdf a, b;
    a.build(sg.Ci, wo, sg.Ng);
    b.build(sg.Ci, wo, sg.Ng, k);
    BsdfEval ea = a.eval(wo, wi), eb = b.eval(wo, wi);
    EXPECT_EQ(ea.value, eb.value) << shaders[t];
    EXPECT_EQ(ea.pdf, eb.pdf) << shaders[t];
  }
}

} // namespace

// The disk cache of closure kernels (runtime/jit/disk_cache.h): a second compile of the same
// ids is read from the cache and computes bit for bit what the compiled one does; a corrupt
// entry is detected, rebuilt and replaced; LOBE_CACHE_DIR=off turns the cache off.
namespace {
struct Compiled {
  Kernels k;
  bool cached = false;
};
std::unique_ptr<Compiled> compile_ids(const std::vector<int>& ids) {
  auto c = std::make_unique<Compiled>();
  std::string err;
  c->k.jit = jit::Jit::create(err);
  EXPECT_TRUE(c->k.jit) << err;
  jit::JitTimes t;
  EXPECT_TRUE(jit::compile_closure_kernels(*c->k.jit, ids, c->k.k, c->k.code, t, err)) << err;
  c->cached = t.from_cache;
  return c;
}
// eval and sample of every id at a few direction pairs, as raw floats.
std::vector<float> outputs(const ClosureKernels& k, const std::vector<int>& ids) {
  std::vector<float> out;
  Pcg32 rng(5);
  for (int id : ids) {
    closures::Params p = configs_for(id, Level::Quick).front().params;
    for (int n = 0; n < 16; ++n) {
      Vec3 wo = uniform_sphere(rng.next_double(), rng.next_double());
      wo.z = std::fabs(wo.z);
      Vec3 wi = uniform_sphere(rng.next_double(), rng.next_double()), u = rng.next_vec3();
      alignas(Bsdf::kLobeStateAlign) unsigned char state[Bsdf::kLobeStateBytes];
      uint32_t flags = k.setup(id, p.data(), state);
      BsdfEval e;
      BsdfSample s{};
      int ok = 0;
      if (flags) {
        k.eval(id, state, &wo, &wi, 0, &e);
        ok = k.sample(id, state, &wo, &u, 0, &s);
      }
      out.insert(out.end(), {e.value.x, e.value.y, e.value.z, e.pdf, float(ok), s.wi.x, s.pdf});
    }
  }
  return out;
}
} // namespace

TEST(KernelCache, HitAfterMissCorruptEntriesRebuiltOffSwitch) {
  char dir[] = "/tmp/lobe_kernel_cache_XXXXXX";
  ASSERT_NE(mkdtemp(dir), nullptr);
  setenv("LOBE_CACHE_DIR", dir, 1);
  const std::vector<int> ids = {registry::id_of("diffuse"), registry::id_of("microfacet")};
  auto first = compile_ids(ids);
  EXPECT_FALSE(first->cached);
  auto second = compile_ids({ids[1], ids[0], ids[1]}); // the same set, in another order
  EXPECT_TRUE(second->cached);
  EXPECT_TRUE(second->k.k.covers(ids[0]) && second->k.k.covers(ids[1]));
  const std::vector<float> expected = outputs(first->k.k, ids);
  EXPECT_EQ(outputs(second->k.k, ids), expected);

  int entries = 0;
  for (const auto& f : std::filesystem::directory_iterator(dir)) {
    ++entries;
    std::fstream io(f.path(), std::ios::in | std::ios::out | std::ios::binary);
    const auto middle = std::streamoff(std::filesystem::file_size(f.path()) / 2);
    char c = 0;
    io.seekg(middle);
    io.get(c);
    io.seekp(middle);
    io.put(char(c ^ 0x5a)); // a changed byte in the object
  }
  EXPECT_EQ(entries, 1);
  auto rebuilt = compile_ids(ids);
  EXPECT_FALSE(rebuilt->cached);
  EXPECT_EQ(outputs(rebuilt->k.k, ids), expected);
  EXPECT_TRUE(compile_ids(ids)->cached); // replaced by the rebuild

  setenv("LOBE_CACHE_DIR", "off", 1);
  EXPECT_FALSE(compile_ids(ids)->cached);
  unsetenv("LOBE_CACHE_DIR");
  std::filesystem::remove_all(dir);
}
