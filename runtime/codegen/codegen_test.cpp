// Codegen + JIT on hand-written IR (no front end): each test compiles one shader at -O0 and
// -O2, runs it on ShaderGlobals and checks printed output or written globals against values
// worked out by hand.
#include "codegen.h"
#include "env.h"
#include "ir/parser.h"
#include "jit.h"
#include "lobe/context.h"
#include "lobe/shading.h"
#include "op_tables.h"
#include "passes/derivs.h"

#include <gtest/gtest.h>
#include <llvm/IR/LLVMContext.h>
#include <llvm/IR/Module.h>

#include <cstring>

using namespace lobe;

namespace {

struct Compiled {
  std::unique_ptr<jit::Jit> jit;
  jit::CompiledGroup code;
  std::vector<unsigned char> groupdata;
  ~Compiled() {
    if (jit) jit->remove(code);
  }
};

// Compiles one-layer IR text; params get group-data slots holding their constant defaults.
std::unique_ptr<Compiled> compile(const std::string& text, int opt, shadeops::RuntimeEnv& env,
                                  ir::Shader& shader, std::string& error) {
  auto parsed = ir::parse(text);
  if (!parsed.shader) {
    error = parsed.error.to_string();
    return nullptr;
  }
  shader = *parsed.shader;
  passes::analyze_derivatives(shader);
  codegen::GroupPlan plan;
  plan.env = &env;
  codegen::LayerPlan lp;
  lp.shader = &shader;
  lp.function_name = "layer0";
  lp.ran_offset = 0;
  size_t off = 8;
  auto out = std::make_unique<Compiled>();
  for (const ir::Symbol& s : shader.symbols) {
    bool param = s.kind == ir::SymKind::Param || s.kind == ir::SymKind::OutputParam;
    lp.symbol_offset.push_back(param ? int(off) : -1);
    lp.run_default.push_back(param && s.init_begin >= 0);
    if (param) off += (codegen::storage_bytes(s) + 7) / 8 * 8;
  }
  out->groupdata.assign(off, 0);
  for (size_t i = 0; i < shader.symbols.size(); ++i) {
    const ir::Symbol& s = shader.symbols[i];
    if (lp.symbol_offset[i] < 0) continue;
    for (size_t k = 0; k < s.init.size(); ++k) {
      unsigned char* p = out->groupdata.data() + lp.symbol_offset[i] + 4 * k;
      if (s.type.base == ir::BaseType::Int)
        std::memcpy(p, &s.init[k].i, 4);
      else
        std::memcpy(p, &s.init[k].f, 4);
    }
  }
  plan.layers.push_back(lp);
  auto ctx = std::make_unique<llvm::LLVMContext>();
  auto mod = std::make_unique<llvm::Module>("test", *ctx);
  out->jit = jit::Jit::create(error);
  if (!out->jit) return nullptr;
  out->jit->configure(*mod);
  codegen::HostSymbols host;
  error = codegen::emit_group(plan, *mod, host);
  if (!error.empty()) return nullptr;
  jit::JitTimes times;
  if (!out->jit->add(std::move(ctx), std::move(mod), opt, "group_entry", out->code, times, error,
                     host))
    return nullptr;
  return out;
}

ShaderGlobals grid_globals(ShadingContext& ctx, float u, float v, float dudx, float dvdy) {
  ShaderGlobals sg{};
  sg.P = {u, v, 1};
  sg.dPdx = {dudx, 0, 0};
  sg.dPdy = {0, dvdy, 0};
  sg.u = u;
  sg.v = v;
  sg.dudx = dudx;
  sg.dvdy = dvdy;
  sg.N = sg.Ng = {0, 0, 1};
  sg.dPdu = {1, 0, 0};
  sg.dPdv = {0, 1, 0};
  sg.surfacearea = 1;
  sg.raytype = kRayCamera;
  sg.context = &ctx;
  return sg;
}

// Runs `text` at -O0 and -O2 on one point; both must print the same, which is returned.
// `setup` may adjust the globals (e.g. object2common) before the shader runs.
std::string run(const std::string& text, float u = 0.5f, float v = 0.5f,
                void (*setup)(ShaderGlobals&) = nullptr) {
  std::string results[2];
  for (int pass = 0; pass < 2; ++pass) {
    shadeops::RuntimeEnv env;
    ir::Shader shader;
    std::string error;
    auto c = compile(text, pass == 0 ? 0 : 2, env, shader, error);
    EXPECT_TRUE(c) << error;
    if (!c) return "<compile error: " + error + ">";
    ShadingContext ctx;
    ShaderGlobals sg = grid_globals(ctx, u, v, 0.25f, 0.5f);
    if (setup) setup(sg);
    std::vector<unsigned char> gd = c->groupdata;
    reinterpret_cast<void (*)(ShaderGlobals*, void*)>(c->code.entry)(&sg, gd.data());
    results[pass] = ctx.output;
  }
  EXPECT_EQ(results[0], results[1]) << "-O0 and -O2 differ";
  return results[1];
}

TEST(Codegen, FloatArithmeticAndSafeDivision) {
  EXPECT_EQ(run(R"(lobe-ir 1
surface t
symbols
  local float a
  local float b
  local color c
  const float $c0 = 3
  const float $c1 = 0.5
  const float $c2 = 0
  const string $f = "%g %g %g\n"
main
  mul a $c0 $c1
  div b a $c2
  add c a $c0
  printf $f a b c
end
)"),
            "1.5 0 4.5 4.5 4.5\n");
}

TEST(Codegen, IntegerDivisionModuloAndShifts) {
  EXPECT_EQ(run(R"(lobe-ir 1
surface t
symbols
  local int a
  local int b
  local int c
  local int d
  local int e
  const int $c7 = 7
  const int $c0 = 0
  const int $cm2 = -2
  const int $min = -2147483648
  const int $m1 = -1
  const int $c33 = 33
  const string $f = "%d %d %d %d %d\n"
main
  div a $c7 $cm2
  mod b $c7 $cm2
  div c $c7 $c0
  div d $min $m1
  shl e $c7 $c33
  printf $f a b c d e
  mod a $c7 $c0
  mod b $min $m1
  printf $f a b c d e
end
)"),
            "-3 1 0 -2147483648 14\n0 0 0 -2147483648 14\n");
}

TEST(Codegen, LoopWithBranches) {
  // sum = 0; for (i = 1; i <= 10; ++i) sum += i;
  EXPECT_EQ(run(R"(lobe-ir 1
surface t
symbols
  local int i
  local int sum
  local int c
  const int $c1 = 1
  const int $c10 = 10
  const string $f = "sum %d\n"
main
  assign i $c1
Lcond:
  le c i $c10
  cbr c -> Lbody Ldone
Lbody:
  add sum sum i
  add i i $c1
  br -> Lcond
Ldone:
  printf $f sum
end
)"),
            "sum 55\n");
}

TEST(Codegen, DerivativesOfUSquared) {
  // Dx(u*u) = 2 u dudx = 2 * 0.5 * 0.25; Dy(u*u) = 0; Dy(v) = dvdy; filterwidth(u) = 0.25.
  EXPECT_EQ(run(R"(lobe-ir 1
surface t
symbols
  global float u
  global float v
  global point P
  local float q
  local float dx
  local float dy
  local float dv
  local float fw
  local vector dp
  local float s
  local float ds
  const string $f = "%g %g %g %g %g %g\n"
main
  mul q u u
  Dx dx q
  Dy dy q
  Dy dv v
  filterwidth fw u
  Dx dp P
  sin s u
  Dx ds s
  printf $f dx dy dv fw dp ds
end
)"),
            "0.25 0 0.5 0.25 0.25 0 0 0.219396\n");
}

TEST(Codegen, OutOfRangeIndexClampsAndReports) {
  std::string out = run(R"(lobe-ir 1
surface t
symbols
  local float[3] a
  local int i
  local float x
  const int $c5 = 5
  const int $c2 = 2
  const float $c9 = 9
  const string $f = "x = %g\n"
main
  aassign a $c2 $c9
  assign i $c5
  aref x a i @t.osl:4:7
  printf $f x
end
)");
  // OSL's wording (testshade 1.13.12 on the same code): the symbol, the range, the location and
  // the layer.
  EXPECT_EQ(out, "ERROR: Index [5] out of range a[0..2]: t.osl:4 (group unnamed_group, layer 0 , "
                 "shader t)\nx = 9\n");
}

TEST(Codegen, TriplesAndGeometry) {
  EXPECT_EQ(run(R"(lobe-ir 1
surface t
symbols
  local vector a
  local vector b
  local vector c
  local float d
  local vector n
  local float x
  const float $c1 = 1
  const float $c0 = 0
  const float $c3 = 3
  const float $c4 = 4
  const string $f = "%g | %g | %g | %g\n"
main
  construct a $c1 $c0 $c0
  construct b $c0 $c1 $c0
  cross c a b
  construct n $c3 $c4 $c0
  length d n
  normalize n n
  compref x n $c1
  printf $f c d n x
end
)"),
            "0 0 1 | 5 | 0.6 0.8 0 | 0.8\n");
}

TEST(Codegen, ExitStopsAndOutputsGlobals) {
  EXPECT_EQ(run(R"(lobe-ir 1
surface t
symbols
  const string $a = "before\n"
  const string $b = "after\n"
main
  printf $a
  exit
  printf $b
end
)"),
            "before\n");
}

TEST(Codegen, ClosureComponentParamsAndWeights) {
  // Ci = 0.5 * diffuse(N): a mul node over a component whose block holds N.
  std::string text = R"(lobe-ir 1
surface t
symbols
  global normal N
  global closure Ci
  local closure c
  const string $k = "diffuse"
  const float $h = 0.5
main
  closure c $k N
  mul Ci c $h
end
)";
  shadeops::RuntimeEnv env;
  ir::Shader shader;
  std::string error;
  auto c = compile(text, 2, env, shader, error);
  ASSERT_TRUE(c) << error;
  ShadingContext ctx;
  ShaderGlobals sg = grid_globals(ctx, 0.5f, 0.5f, 1, 1);
  sg.N = {0, 0.6f, 0.8f};
  std::vector<unsigned char> gd = c->groupdata;
  reinterpret_cast<void (*)(ShaderGlobals*, void*)>(c->code.entry)(&sg, gd.data());
  ASSERT_NE(sg.Ci, nullptr);
  ASSERT_EQ(sg.Ci->id, kClosureMul);
  auto* mul = static_cast<const ClosureMul*>(sg.Ci);
  EXPECT_EQ(mul->weight, (Vec3{0.5f, 0.5f, 0.5f}));
  auto* comp = static_cast<const ClosureComponent*>(mul->closure);
  float n[3];
  std::memcpy(n, comp->params(), 12);
  EXPECT_EQ(n[1], 0.6f);
  EXPECT_EQ(n[2], 0.8f);
}

TEST(Codegen, ZeroWeightClosureIsDropped) {
  std::string text = R"(lobe-ir 1
surface t
symbols
  global normal N
  global closure Ci
  global float u
  local closure c
  local float w
  const string $k = "diffuse"
main
  closure c $k N
  sub w u u
  mul Ci c w
end
)";
  shadeops::RuntimeEnv env;
  ir::Shader shader;
  std::string error;
  auto c = compile(text, 0, env, shader, error);
  ASSERT_TRUE(c) << error;
  ShadingContext ctx;
  ShaderGlobals sg = grid_globals(ctx, 0.5f, 0.5f, 1, 1);
  std::vector<unsigned char> gd = c->groupdata;
  reinterpret_cast<void (*)(ShaderGlobals*, void*)>(c->code.entry)(&sg, gd.data());
  EXPECT_EQ(sg.Ci, nullptr);
}

TEST(Codegen, UnsupportedOpIsAnErrorNotACrash) {
  shadeops::RuntimeEnv env;
  ir::Shader shader;
  std::string error;
  auto c = compile(R"(lobe-ir 1
surface t
symbols
  local closure c
  const string $k = "no_such_closure"
main
  closure c $k
end
)",
                   0, env, shader, error);
  EXPECT_FALSE(c);
  EXPECT_NE(error.find("unknown closure"), std::string::npos) << error;
}

} // namespace

// matrix("from", "to") is the transform from space `from` to space `to`:
// M = from2common * inverse(to2common). With object2common a translation by (1,2,3) and a
// scale by 2 (row vectors, p' = p M), "object" -> "world" is that matrix itself and
// "world" -> "object" its inverse (scale 0.5, translation -(1,2,3)/2). This used to load the
// "to" string pointer as a matrix (garbage, and a crash at -O2).
TEST(Codegen, MatrixFromSpaceToSpace) {
  const char* ir = R"(lobe-ir 1
shader t
symbols
  local matrix g
  local matrix h
  local point p
  const string $obj = "object"
  const string $world = "world"
  const float $one = 1
  const string $f = "%g\n%g\n%g\n"
main
  construct g $obj $world
  construct h $world $obj
  construct p $one $one $one
  transform p g p
  printf $f g h p
end
)";
  auto setup = [](ShaderGlobals& sg) {
    static const float o2c[16] = {2, 0, 0, 0, 0, 2, 0, 0, 0, 0, 2, 0, 1, 2, 3, 1};
    sg.object2common = o2c;
  };
  // p = (1,1,1) * g = (2+1, 2+2, 2+3).
  EXPECT_EQ(run(ir, 0.5f, 0.5f, setup), "2 0 0 0 0 2 0 0 0 0 2 0 1 2 3 1\n"
                                        "0.5 0 0 0 0 0.5 0 0 0 0 0.5 0 -0.5 -1 -1.5 1\n"
                                        "3 4 5\n");
  // Without an object transform (lobe shade's grid), every named space is the identity.
  EXPECT_EQ(run(ir), "1 0 0 0 0 1 0 0 0 0 1 0 0 0 0 1\n"
                     "1 0 0 0 0 1 0 0 0 0 1 0 0 0 0 1\n"
                     "1 1 1\n");
}

// The emitter is found by index: every opcode of the table is in exactly one family table,
// and every opcode but the control flow emit_op does itself has an emitter.
TEST(Codegen, EveryOpcodeHasExactlyOneEmitter) {
  std::array<int, ir::kOpcodeCount> rows = codegen::op_emitter_rows();
  for (size_t i = 0; i < ir::kOpcodeCount; ++i) {
    ir::Opcode op = ir::Opcode(i);
    EXPECT_EQ(rows[i], 1) << ir::to_string(op);
    bool flow = op == ir::Opcode::Nop || op == ir::Opcode::Br || op == ir::Opcode::Cbr ||
                op == ir::Opcode::Exit || op == ir::Opcode::UseParam;
    EXPECT_EQ(codegen::op_emitter(op) == nullptr, flow) << ir::to_string(op);
  }
}

// A library call is one row of runtime/registry/library_calls.h: its opcode (name, operand
// counts), its emitter and its JIT symbol (name, signature string) all come from the row. The
// expected values are the rows' declared types, written out by hand.
TEST(Codegen, LibraryCallRowsAreWired) {
  struct Expect {
    ir::Opcode op;
    const char* name;
    int operands;
    const char* shadeop;
    const char* sig;
  };
  const Expect rows[] = {
      {ir::Opcode::Strlen, "strlen", 2, "lobe_strlen", "ip"},
      {ir::Opcode::StartsWith, "startswith", 3, "lobe_startswith", "ipp"},
      {ir::Opcode::EndsWith, "endswith", 3, "lobe_endswith", "ipp"},
      {ir::Opcode::Stoi, "stoi", 2, "lobe_stoi", "ip"},
      {ir::Opcode::Stof, "stof", 2, "lobe_stof", "fp"},
      {ir::Opcode::GetChar, "getchar", 3, "lobe_getchar", "ipi"},
  };
  EXPECT_EQ(ir::library::kCount, std::size(rows));
  for (const Expect& x : rows) {
    const ir::OpcodeInfo& info = ir::info(x.op);
    EXPECT_STREQ(info.name, x.name);
    EXPECT_EQ(info.min_args, x.operands) << x.name;
    EXPECT_EQ(info.max_args, x.operands) << x.name;
    EXPECT_EQ(info.written, 1u) << x.name;
    EXPECT_NE(codegen::op_emitter(x.op), nullptr) << x.name;
    int found = 0;
    for (const shadeops::ShadeOpSymbol& s : shadeops::shadeop_symbols())
      if (std::strcmp(s.name, x.shadeop) == 0) {
        ++found;
        EXPECT_STREQ(s.sig, x.sig) << x.shadeop;
      }
    EXPECT_EQ(found, 1) << x.shadeop;
  }
}

// A math function is one row of runtime/registry/math_functions.h: its opcode, emitter and
// shadeops (value, and the derivative's: _slope for one argument, _dual for two) come from it.
// The expected names and counts are written out by hand for three rows.
TEST(Codegen, MathFunctionRowsAreWired) {
  struct Expect {
    ir::Opcode op;
    const char* name;
    int min, max;
    const char* value_sig;
    const char* deriv;
    const char* deriv_sig;
  };
  const Expect rows[] = {
      {ir::Opcode::Sin, "sin", 2, 2, "ffi", "lobe_math_sin_slope", "ffi"},
      {ir::Opcode::Log, "log", 2, 3, "ffi", "lobe_math_log_slope", "ffi"},
      {ir::Opcode::Pow, "pow", 3, 3, "fffi", "lobe_math_pow_dual", "vpppi"},
  };
  auto sig_of = [](const std::string& name) -> std::string {
    for (const shadeops::ShadeOpSymbol& s : shadeops::shadeop_symbols())
      if (name == s.name) return s.sig;
    return "(missing)";
  };
  for (const Expect& x : rows) {
    const ir::OpcodeInfo& info = ir::info(x.op);
    EXPECT_STREQ(info.name, x.name);
    EXPECT_EQ(info.min_args, x.min) << x.name;
    EXPECT_EQ(info.max_args, x.max) << x.name;
    EXPECT_EQ(info.flags, ir::kArith) << x.name;
    EXPECT_NE(codegen::op_emitter(x.op), nullptr) << x.name;
    EXPECT_EQ(sig_of(std::string("lobe_math_") + x.name), x.value_sig) << x.name;
    EXPECT_EQ(sig_of(x.deriv), x.deriv_sig) << x.name;
  }
}
