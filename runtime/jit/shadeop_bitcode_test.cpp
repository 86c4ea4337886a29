// The shadeop bitcode (shadeop_bitcode.h) against the native library it is compiled from: a
// module calls each noise variant with constant selectors, as codegen does; at -O2 the calls are
// linked from lobe_shadeops.bc and inlined (no call is left), and the results are those of the
// native functions to the bit (NaN to NaN), over ordinary, boundary and non-finite inputs. (Parity
// only: the native functions' own values are checked against OSL and closed forms in
// shadeops_test.)
#include "jit.h"
#include "noise_batch.h"
#include "shadeop_bitcode.h"
#include "shadeops.h"

#include <gtest/gtest.h>
#include <llvm/IR/IRBuilder.h>
#include <llvm/IR/LLVMContext.h>
#include <llvm/IR/Module.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <random>
#include <string>
#include <vector>

extern "C" {
void lobe_noise_d(int kind, const float* x, const float* dx, const float* dy, int nin,
                  const float* period, float* out, float* odx, float* ody, int nout);
}

namespace {

using namespace lobe;

// One noise configuration: kind, dimension, channels, periodic, with derivatives.
struct NoiseCase {
  int kind, nin, nout;
  bool periodic, derivs;
  std::string name() const {
    return "noise_" + std::to_string(kind) + "_" + std::to_string(nin) + "_" +
           std::to_string(nout) + (periodic ? "p" : "") + (derivs ? "d" : "");
  }
};

std::vector<NoiseCase> noise_cases() {
  std::vector<NoiseCase> cases;
  for (int kind = 0; kind < 6; ++kind)
    for (int nin = 1; nin <= 4; ++nin)
      for (int nout : {1, 3})
        for (bool periodic : {false, true})
          for (bool derivs : {false, true}) {
            bool simplex = kind == shadeops::kSimplex || kind == shadeops::kUSimplex;
            if (periodic && simplex) continue; // no periodic simplex noise
            cases.push_back({kind, nin, nout, periodic, derivs});
          }
  return cases;
}

// void name(float* x, float* dx, float* dy, float* period, float* out, float* odx, float* ody):
// lobe_noise_d with the case's constants (null pointers where codegen passes null).
void emit_noise(llvm::Module& m, const NoiseCase& c) {
  llvm::LLVMContext& ctx = m.getContext();
  llvm::IRBuilder<> b(ctx);
  auto* ptr = b.getPtrTy();
  auto* i32 = b.getInt32Ty();
  auto* callee_t = llvm::FunctionType::get(
      b.getVoidTy(), {i32, ptr, ptr, ptr, i32, ptr, ptr, ptr, ptr, i32}, false);
  auto callee = m.getOrInsertFunction("lobe_noise_d", callee_t);
  auto* t = llvm::FunctionType::get(b.getVoidTy(), {ptr, ptr, ptr, ptr, ptr, ptr, ptr}, false);
  auto* f = llvm::Function::Create(t, llvm::Function::ExternalLinkage, c.name(), m);
  b.SetInsertPoint(llvm::BasicBlock::Create(ctx, "entry", f));
  llvm::Value* null = llvm::ConstantPointerNull::get(ptr);
  auto arg = [&](unsigned i, bool used) { return used ? f->getArg(i) : null; };
  b.CreateCall(callee,
               {b.getInt32(uint32_t(c.kind)), f->getArg(0), arg(1, c.derivs), arg(2, c.derivs),
                b.getInt32(uint32_t(c.nin)), arg(3, c.periodic), f->getArg(4), arg(5, c.derivs),
                arg(6, c.derivs), b.getInt32(uint32_t(c.nout))});
  b.CreateRetVoid();
}

bool calls(const llvm::Module& m, const char* name) {
  for (const llvm::Function& f : m)
    if (!f.isDeclaration())
      for (const llvm::BasicBlock& bb : f)
        for (const llvm::Instruction& i : bb)
          if (auto* call = llvm::dyn_cast<llvm::CallBase>(&i))
            if (call->getCalledFunction() && call->getCalledFunction()->getName() == name)
              return true;
  return false;
}

// The same bits, or both NaN: a NaN's sign and payload follow operand order, which LLVM may
// commute in any shader arithmetic (as between -O levels), so only NaN-ness is compared.
bool same_bits(float a, float b) {
  return (std::isnan(a) && std::isnan(b)) || std::memcmp(&a, &b, 4) == 0;
}

// Inputs: ordinary values of both signs, lattice points and their neighbours, large values
// near the int range, infinities and NaN.
std::vector<float> sample_inputs() {
  std::vector<float> v = {0.0f,
                          -0.0f,
                          0.5f,
                          -0.5f,
                          1.0f,
                          -1.0f,
                          2.25f,
                          -7.75f,
                          1e-7f,
                          -1e-7f,
                          std::nextafter(1.0f, 0.0f),
                          std::nextafter(1.0f, 2.0f),
                          123.456f,
                          -98765.4f,
                          2147483520.0f,
                          -2147483648.0f,
                          3e9f,
                          std::numeric_limits<float>::infinity(),
                          -std::numeric_limits<float>::infinity(),
                          std::numeric_limits<float>::quiet_NaN()};
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(-40.0f, 40.0f);
  for (int i = 0; i < 300; ++i) v.push_back(u(rng));
  return v;
}

TEST(ShadeopBitcode, NoiseInlinesAndMatchesTheNativeLibrary) {
  std::string err;
  auto jit = jit::Jit::create(err);
  ASSERT_TRUE(jit) << err;
  auto ctx = std::make_unique<llvm::LLVMContext>();
  auto mod = std::make_unique<llvm::Module>("noise", *ctx);
  jit->configure(*mod);
  std::vector<NoiseCase> cases = noise_cases();
  std::vector<std::string> names;
  for (const NoiseCase& c : cases) {
    emit_noise(*mod, c);
    names.push_back(c.name());
  }
  jit->optimize(*mod, 2);
  EXPECT_FALSE(calls(*mod, "lobe_noise_d")) << "every call is linked and inlined";
  jit::CompiledGroup code;
  jit::JitTimes times;
  std::vector<void*> addr;
  ASSERT_TRUE(jit->add(std::move(ctx), std::move(mod), 0, names, addr, code, times, err)) << err;

  using Fn = void (*)(float*, float*, float*, float*, float*, float*, float*);
  std::vector<float> in = sample_inputs();
  std::mt19937 rng(11);
  std::uniform_int_distribution<size_t> pick(0, in.size() - 1);
  int mismatches = 0;
  for (size_t ci = 0; ci < cases.size(); ++ci) {
    const NoiseCase& c = cases[ci];
    auto fn = reinterpret_cast<Fn>(addr[ci]);
    for (int trial = 0; trial < 400; ++trial) {
      float x[4], dx[4], dy[4], per[4];
      for (int k = 0; k < 4; ++k) {
        x[k] = in[pick(rng)];
        dx[k] = in[pick(rng)] * 0.01f;
        dy[k] = in[pick(rng)] * 0.01f;
        per[k] = float(1 + pick(rng) % 9) + (trial % 3 == 0 ? 0.5f : 0.0f);
      }
      float a[3] = {0, 0, 0}, adx[3] = {0, 0, 0}, ady[3] = {0, 0, 0};
      float e[3] = {0, 0, 0}, edx[3] = {0, 0, 0}, edy[3] = {0, 0, 0};
      fn(x, dx, dy, per, a, adx, ady);
      lobe_noise_d(c.kind, x, c.derivs ? dx : nullptr, c.derivs ? dy : nullptr, c.nin,
                   c.periodic ? per : nullptr, e, c.derivs ? edx : nullptr,
                   c.derivs ? edy : nullptr, c.nout);
      for (int j = 0; j < c.nout; ++j) {
        bool ok = same_bits(a[j], e[j]) &&
                  (!c.derivs || (same_bits(adx[j], edx[j]) && same_bits(ady[j], edy[j])));
        if (!ok && ++mismatches <= 10)
          ADD_FAILURE() << c.name() << " at (" << x[0] << ", " << x[1] << ", " << x[2] << ", "
                        << x[3] << ") channel " << j << ": " << a[j] << " vs " << e[j] << ", d/dx "
                        << adx[j] << " vs " << edx[j] << ", d/dy " << ady[j] << " vs " << edy[j];
      }
    }
  }
  EXPECT_EQ(mismatches, 0);
  jit->remove(code);
}

// Noise batching (noise_batch.h): `calls` value-only noise calls of one kind, each of `nin`
// coordinates, as codegen emits them (inputs stored to a stack array, lobe_noise_d with
// constants, the result read back) in one block after all inputs are loaded:
// void name(const float* in /* [calls][4] */, float* out /* [calls] */). With `chained`, each
// call's first coordinate adds the previous call's result, so no two calls are independent.
struct BatchCase {
  int kind, nin, calls;
  bool chained;
  int gathered;     // calls batching should gather
  int channels = 1; // 1 or 3
  std::string name() const {
    return "batch_" + std::to_string(kind) + "_" + std::to_string(nin) + "_" +
           std::to_string(calls) + "_" + std::to_string(channels) + (chained ? "c" : "");
  }
};

void emit_batch(llvm::Module& m, const BatchCase& c) {
  llvm::LLVMContext& ctx = m.getContext();
  llvm::IRBuilder<> b(ctx);
  auto* ptr = b.getPtrTy();
  auto* i32 = b.getInt32Ty();
  auto* f32 = b.getFloatTy();
  auto callee = m.getOrInsertFunction(
      "lobe_noise_d",
      llvm::FunctionType::get(b.getVoidTy(), {i32, ptr, ptr, ptr, i32, ptr, ptr, ptr, ptr, i32},
                              false));
  auto* t = llvm::FunctionType::get(b.getVoidTy(), {ptr, ptr}, false);
  auto* f = llvm::Function::Create(t, llvm::Function::ExternalLinkage, c.name(), m);
  b.SetInsertPoint(llvm::BasicBlock::Create(ctx, "entry", f));
  std::vector<llvm::Value*> in;
  for (int k = 0; k < 4 * c.calls; ++k)
    in.push_back(b.CreateLoad(f32, b.CreateConstInBoundsGEP1_32(f32, f->getArg(0), unsigned(k))));
  llvm::Value* null = llvm::ConstantPointerNull::get(ptr);
  llvm::Value* previous = nullptr;
  for (int i = 0; i < c.calls; ++i) {
    llvm::Value* x = b.CreateAlloca(llvm::ArrayType::get(f32, 4));
    llvm::Value* r = b.CreateAlloca(llvm::ArrayType::get(f32, unsigned(c.channels)));
    for (int a = 0; a < c.nin; ++a) {
      llvm::Value* v = in[size_t(4 * i + a)];
      if (a == 0 && c.chained && previous) v = b.CreateFAdd(v, previous);
      b.CreateStore(v, b.CreateConstInBoundsGEP1_32(f32, x, unsigned(a)));
    }
    b.CreateCall(callee, {b.getInt32(uint32_t(c.kind)), x, null, null, b.getInt32(uint32_t(c.nin)),
                          null, r, null, null, b.getInt32(c.channels)});
    for (int j = 0; j < c.channels; ++j) {
      llvm::Value* v = b.CreateLoad(f32, b.CreateConstInBoundsGEP1_32(f32, r, unsigned(j)));
      if (j == 0) previous = v;
      b.CreateStore(v,
                    b.CreateConstInBoundsGEP1_32(f32, f->getArg(1), unsigned(i * c.channels + j)));
    }
  }
  b.CreateRetVoid();
}

// Independent calls are gathered (8 at most a group; simplex and 2-D gradient noise from 2
// calls, in 4 lanes up to 4; 3-D and 4-D gradient noise from 5, in 8 lanes) and give the native
// library's bits; dependent ones are left alone. Every call is inlined either way.
TEST(ShadeopBitcode, IndependentNoiseCallsAreBatchedToTheBit) {
  if (!jit::noise_batching()) GTEST_SKIP() << "LOBE_NOISE_BATCH=0";
  std::string err;
  auto jit = jit::Jit::create(err);
  ASSERT_TRUE(jit) << err;
  const BatchCase cases[] = {{shadeops::kSimplex, 3, 12, false, 12},
                             {shadeops::kUSimplex, 2, 5, false, 5},
                             {shadeops::kSimplex, 1, 2, false, 2},
                             {shadeops::kSimplex, 4, 8, false, 8},
                             {shadeops::kUSimplex, 4, 3, false, 3},
                             {shadeops::kSimplex, 3, 4, true, 0},
                             {shadeops::kPerlin, 3, 6, false, 6},
                             {shadeops::kUPerlin, 3, 9, false, 8}, // 8, and one alone
                             {shadeops::kPerlin, 3, 3, true, 0},
                             {shadeops::kPerlin, 4, 5, false, 5},
                             {shadeops::kPerlin, 3, 4, false, 0}, // gradient noise: 5 at least
                             {shadeops::kPerlin, 3, 6, false, 6, 3},
                             {shadeops::kUPerlin, 4, 5, false, 5, 3},
                             {shadeops::kPerlin, 4, 3, true, 0, 3},
                             {shadeops::kPerlin, 2, 4, false, 4},
                             {shadeops::kUPerlin, 2, 3, false, 3, 3},
                             {shadeops::kPerlin, 1, 4, false, 0}, // no 1-D form
                             {shadeops::kCell, 3, 4, false, 0}};
  std::vector<float> samples = sample_inputs();
  std::mt19937 rng(13);
  std::uniform_int_distribution<size_t> pick(0, samples.size() - 1);
  int mismatches = 0;
  for (const BatchCase& c : cases) {
    auto ctx = std::make_unique<llvm::LLVMContext>();
    auto mod = std::make_unique<llvm::Module>("batch", *ctx);
    jit->configure(*mod);
    emit_batch(*mod, c);
    EXPECT_EQ(jit->optimize(*mod, 2), c.gathered) << c.name();
    EXPECT_FALSE(calls(*mod, "lobe_noise_d")) << c.name();
    for (const char* f :
         {"lobe_simplex_v1", "lobe_simplex_v2", "lobe_simplex_v3", "lobe_simplex_v4",
          "lobe_simplex_v3_x8", "lobe_simplex_v3_x4", "lobe_perlin_v3", "lobe_perlin_v3_x8",
          "lobe_perlin_v3_x4", "lobe_perlin_v3c", "lobe_perlin_v4", "lobe_perlin_v4c",
          "lobe_perlin_v4c_x4"})
      EXPECT_FALSE(calls(*mod, f)) << c.name() << " still calls " << f;
    jit::CompiledGroup code;
    jit::JitTimes times;
    std::vector<void*> addr;
    ASSERT_TRUE(jit->add(std::move(ctx), std::move(mod), 0, {c.name()}, addr, code, times, err))
        << err;
    auto fn = reinterpret_cast<void (*)(const float*, float*)>(addr[0]);
    for (int trial = 0; trial < 200; ++trial) {
      std::vector<float> in(size_t(4 * c.calls)), out(size_t(c.calls * c.channels));
      // One trial in four on lattice points, signed zeros among them (the value is then a
      // signed zero, whose sign the lanes must keep).
      const float lattice[] = {0.0f, -0.0f, 1.0f, -1.0f, 2.0f};
      for (float& v : in) v = trial % 4 ? samples[pick(rng)] : lattice[pick(rng) % 5];
      fn(in.data(), out.data());
      float previous = 0;
      for (int i = 0; i < c.calls; ++i) {
        float x[4], e[3];
        for (int a = 0; a < 4; ++a) x[a] = in[size_t(4 * i + a)];
        if (c.chained && i > 0) x[0] = x[0] + previous;
        lobe_noise_d(c.kind, x, nullptr, nullptr, c.nin, nullptr, e, nullptr, nullptr, c.channels);
        previous = e[0];
        for (int j = 0; j < c.channels; ++j) {
          float got = out[size_t(i * c.channels + j)];
          if (!same_bits(got, e[j]) && ++mismatches <= 10)
            ADD_FAILURE() << c.name() << " call " << i << " channel " << j << " at (" << x[0]
                          << ", " << x[1] << ", " << x[2] << ", " << x[3] << "): " << got << " vs "
                          << e[j];
        }
      }
    }
    jit->remove(code);
  }
  EXPECT_EQ(mismatches, 0);
}

TEST(ShadeopBitcode, OnlyTheLinkableShadeopsAreLinked) {
  // A call the allowlist leaves out (it reads the context) stays a declaration.
  llvm::LLVMContext ctx;
  llvm::Module mod("none", ctx);
  llvm::IRBuilder<> b(ctx);
  auto* t =
      llvm::FunctionType::get(b.getVoidTy(), {b.getPtrTy(), b.getPtrTy(), b.getPtrTy()}, false);
  mod.getOrInsertFunction("lobe_space_matrix", t);
  EXPECT_EQ(jit::link_shadeop_bitcode(mod), 0);
  EXPECT_TRUE(mod.getFunction("lobe_space_matrix")->isDeclaration());
  // The same name with another type than the bitcode's is left alone; with its own type, it
  // links.
  mod.getOrInsertFunction("lobe_math_sin", llvm::FunctionType::get(b.getVoidTy(), {}, false));
  EXPECT_EQ(jit::link_shadeop_bitcode(mod), 0);
  EXPECT_TRUE(mod.getFunction("lobe_math_sin")->isDeclaration());
  llvm::Module mod2("sin", ctx);
  mod2.getOrInsertFunction(
      "lobe_math_sin",
      llvm::FunctionType::get(b.getFloatTy(), {b.getFloatTy(), b.getInt32Ty()}, false));
  EXPECT_EQ(jit::link_shadeop_bitcode(mod2), 1); // (and dropped again: nothing calls it)
  // The closure builders link too: the context's arena is bumped inline (lobe/context.h), so
  // they need nothing outside the bitcode (their results: group_test's ClosureBuilders).
  llvm::Module mod3("closures", ctx);
  auto* p = b.getPtrTy();
  mod3.getOrInsertFunction("lobe_closure_mul", llvm::FunctionType::get(p, {p, p, p}, false));
  mod3.getOrInsertFunction("lobe_closure_add", llvm::FunctionType::get(p, {p, p, p}, false));
  mod3.getOrInsertFunction(
      "lobe_closure_component",
      llvm::FunctionType::get(p, {p, b.getInt32Ty(), p, b.getInt32Ty()}, false));
  EXPECT_EQ(jit::link_shadeop_bitcode(mod3), 3);
}

} // namespace
