// IR text form: printing a hand-built shader gives the documented text; parsing gives the
// same data back; print(parse(print(x))) == print(x) over many programs; malformed text gives
// errors at the right line and column.
#include "ir/opcodes.h"
#include "ir/parser.h"
#include "ir/printer.h"
#include "ir/verifier.h"

#include <gtest/gtest.h>

#include <cstring>
#include <set>
#include <string_view>

using namespace lobe::ir;

namespace {

Symbol sym(std::string name, BaseType b, SymKind k, int arraylen = 0) {
  Symbol s;
  s.name = std::move(name);
  s.type = Type{b, arraylen};
  s.kind = k;
  return s;
}

ConstValue f(float v) { return ConstValue::of_float(v); }
ConstValue i(int v) { return ConstValue::of_int(v); }
ConstValue s(std::string v) { return ConstValue::of_string(std::move(v)); }

Op op(std::string_view code, std::vector<int> args, uint32_t mask, std::vector<int> jumps = {}) {
  Op o;
  o.opcode = *opcode_from_name(code);
  o.args = std::move(args);
  o.written_mask = mask;
  o.jumps = std::move(jumps);
  return o;
}

// A shader exercising every printed feature.
Shader sample() {
  Shader sh;
  sh.type = ShaderType::Surface;
  sh.name = "plastic";
  sh.metadata.push_back({Type{BaseType::String}, "help", {s("A \"shiny\" one")}});
  Symbol kd = sym("Kd", BaseType::Float, SymKind::Param);
  kd.init = {f(0.5f)};
  kd.metadata.push_back({Type{BaseType::Float}, "min", {f(0)}});
  kd.metadata.push_back({Type{BaseType::Float, 2}, "range", {f(0), f(1)}});
  kd.loc = {"my shader.osl", 3, 9};
  sh.symbols.push_back(kd);
  Symbol nn = sym("Nn", BaseType::Normal, SymKind::Param);
  nn.init_begin = 0;
  nn.init_end = 1;
  nn.loc = {"plastic.osl", 4, 10};
  sh.symbols.push_back(nn);
  sh.structs.push_back({"S", {{"a", Type{BaseType::Int, 2}, ""}}});
  Symbol sa = sym("s.a", BaseType::Int, SymKind::Param, 2);
  sa.init = {i(1), i(-2)};
  sa.folded = true; // an array field of a struct: oslc computes its default
  sa.struct_name = "S";
  sh.symbols.push_back(sa);
  Symbol n = sym("N", BaseType::Normal, SymKind::Global);
  sh.symbols.push_back(n);
  Symbol p = sym("P", BaseType::Point, SymKind::Global);
  p.derivs = true;
  sh.symbols.push_back(p);
  sh.symbols.push_back(sym("Ci", BaseType::Closure, SymKind::Global));
  sh.symbols.push_back(sym("$t0", BaseType::Int, SymKind::Temp));
  Symbol c0 = sym("$c0", BaseType::String, SymKind::Const);
  c0.init = {s("diffuse")};
  sh.symbols.push_back(c0);
  Symbol c1 = sym("$c1", BaseType::Float, SymKind::Const);
  c1.init = {f(0.1f)};
  sh.symbols.push_back(c1);
  sh.ops.push_back(op("assign", {1, 3}, 1));
  sh.ops.back().loc = {"plastic.osl", 4, 15};
  sh.ops.push_back(op("lt", {6, 0, 8}, 1));
  sh.ops.push_back(op("cbr", {6}, 0, {3, 4}));
  sh.ops.push_back(op("closure", {5, 7, 1}, 1));
  sh.ops.push_back(op("sincos", {0, 0, 8}, 3)); // mask differs from the table's? no: 3 == 3
  sh.main_begin = 1;
  return sh;
}

const char* kSampleText = R"(lobe-ir 1
surface plastic [[ string help = "A \"shiny\" one" ]]
struct S { int[2] a }
symbols
  param float Kd = 0.5 [[ float min = 0, float[2] range = 0 1 ]] @"my shader.osl":3:9
  param normal Nn init=0:1 @plastic.osl:4:10
  param int[2] s.a = 1 -2 folded struct=S
  global normal N
  global point P derivs
  global closure Ci
  temp int $t0
  const string $c0 = "diffuse"
  const float $c1 = 0.1
init
  assign Nn N @plastic.osl:4:15
main
  lt $t0 Kd $c1
  cbr $t0 -> L3 L4
L3:
  closure Ci $c0 Nn
L4:
  sincos Kd Kd $c1
end
)";

TEST(IrText, PrintsDocumentedLayout) { EXPECT_EQ(print(sample()), kSampleText); }

TEST(IrText, ParsesBackTheSameData) {
  ParseResult r = parse(kSampleText);
  ASSERT_TRUE(r.shader) << r.error.to_string();
  const Shader& sh = *r.shader;
  Shader want = sample();
  EXPECT_EQ(sh.name, "plastic");
  EXPECT_EQ(sh.metadata, want.metadata);
  EXPECT_EQ(sh.structs, want.structs);
  ASSERT_EQ(sh.symbols.size(), want.symbols.size());
  for (size_t k = 0; k < sh.symbols.size(); ++k) {
    const Symbol& a = sh.symbols[k];
    const Symbol& b = want.symbols[k];
    EXPECT_EQ(a.name, b.name);
    EXPECT_EQ(a.type, b.type);
    EXPECT_EQ(a.kind, b.kind);
    EXPECT_EQ(a.derivs, b.derivs);
    EXPECT_EQ(a.init, b.init) << a.name;
    EXPECT_EQ(a.folded, b.folded) << a.name;
    EXPECT_EQ(a.init_begin, b.init_begin);
    EXPECT_EQ(a.init_end, b.init_end);
    EXPECT_EQ(a.metadata, b.metadata);
    EXPECT_EQ(a.struct_name, b.struct_name);
    EXPECT_EQ(a.loc, b.loc);
  }
  ASSERT_EQ(sh.ops.size(), want.ops.size());
  for (size_t k = 0; k < sh.ops.size(); ++k) {
    EXPECT_EQ(sh.ops[k].opcode, want.ops[k].opcode);
    EXPECT_EQ(sh.ops[k].args, want.ops[k].args);
    EXPECT_EQ(sh.ops[k].jumps, want.ops[k].jumps);
    EXPECT_EQ(sh.ops[k].written_mask, want.ops[k].written_mask);
    EXPECT_EQ(sh.ops[k].loc, want.ops[k].loc);
  }
  EXPECT_EQ(sh.main_begin, 1);
}

TEST(IrText, FloatsRoundTripExactly) {
  const float values[] = {0.1f,  1.0f / 3.0f,     1e-38f,      3.4028235e38f,
                          -0.0f, 1.17549435e-38f, 16777217.0f, 2.5e-45f};
  for (float v : values) {
    std::string t = format_float(v);
    std::string text = "lobe-ir 1\nshader x\nsymbols\n  const float $c = " + t + "\nmain\nend\n";
    ParseResult r = parse(text);
    ASSERT_TRUE(r.shader) << t << ": " << r.error.to_string();
    float back = r.shader->symbols[0].init[0].f;
    EXPECT_EQ(std::memcmp(&back, &v, sizeof v), 0) << t;
  }
  EXPECT_EQ(format_float(0.1f), "0.1");
  EXPECT_EQ(format_float(2.0f), "2");
}

TEST(IrText, StringEscapesRoundTrip) {
  std::string nasty = "a\"b\\c\nd\te\x01"
                      "f g";
  EXPECT_EQ(quote(nasty), "\"a\\\"b\\\\c\\nd\\te\\x01f g\"");
  std::string text =
      "lobe-ir 1\nshader x\nsymbols\n  const string $c = " + quote(nasty) + "\nmain\nend\n";
  ParseResult r = parse(text);
  ASSERT_TRUE(r.shader) << r.error.to_string();
  EXPECT_EQ(r.shader->symbols[0].init[0].s, nasty);
}

// Found by fuzz_ir: a struct name that needs quotes was printed glued to `struct=` (read back
// as a plain word, quotes and escapes included), and a source file name with a comma or a
// control character was printed bare (the comma split it).
TEST(IrText, QuotedStructNamesAndOddFileNamesRoundTrip) {
  Shader sh;
  sh.name = "s";
  Symbol a;
  a.kind = SymKind::OutputParam;
  a.type.base = BaseType::Float;
  a.name = "pr.b";
  a.struct_name = std::string("P\0\x01 q", 5);
  a.init.push_back(ConstValue::of_float(0));
  a.loc = SourceLoc{"dir,with comma/\x02x.osl", 5, 2};
  sh.symbols.push_back(a);
  std::string once = print(sh);
  EXPECT_NE(once.find("struct= \"P\\x00\\x01 q\""), std::string::npos) << once;
  EXPECT_NE(once.find("@\"dir,with comma/\\x02x.osl\":5:2"), std::string::npos) << once;
  ParseResult r = parse(once);
  ASSERT_TRUE(r.shader) << r.error.to_string() << "\n" << once;
  EXPECT_EQ(r.shader->symbols[0].struct_name, a.struct_name);
  EXPECT_EQ(r.shader->symbols[0].loc.file, a.loc.file);
  EXPECT_EQ(print(*r.shader), once);
}

// Hand-written programs: comments, any label names, labels used before definition.
const char* kPrograms[] = {
    R"(lobe-ir 1
shader loop
symbols
  oparam float out = 0
  local int i
  temp int $t0
  const int $c0 = 0
  const int $c1 = 10
  const int $c2 = 1
main
  # for (i = 0; i < 10; ++i) out += i;
  assign i $c0
Lcond:
  lt $t0 i $c1
  cbr $t0 -> Lbody Ldone
Lbody:
  add out out i
  add i i $c2
  br -> Lcond
Ldone:
end
)",
    R"(lobe-ir 1
displacement bump [[ string help = "bumps", int[3] a = 1 2 3 ]]
symbols
  param float amp = 1 [[ float min = 0, float max = 10, string widget = "slider" ]]
  param matrix M = 1 0 0 0 0 1 0 0 0 0 1 0 0 0 0 1
  param string[] names = "a" "b c"
  param float[] w init=0:0 len=3
  global point P derivs
  global normal N
  temp float $t0 derivs
  temp vector $t1
main
  useparam amp
  noise $t0 P @bump.osl:5:13
  mul $t0 $t0 amp @bump.osl:5:20
  calculatenormal $t1 P
  assign N $t1
  exit
end
)",
    R"(lobe-ir 1
volume "odd name"
symbols
  local color "x y"
  local float z
main
  compref z "x y" z wmask=5
end
)",
};

TEST(IrText, RoundTripIsStable) {
  std::vector<std::string> texts = {kSampleText};
  for (const char* p : kPrograms) texts.push_back(p);
  for (const std::string& t : texts) {
    ParseResult r = parse(t);
    ASSERT_TRUE(r.shader) << r.error.to_string() << "\n" << t;
    std::string once = print(*r.shader);
    ParseResult r2 = parse(once);
    ASSERT_TRUE(r2.shader) << r2.error.to_string() << "\n" << once;
    EXPECT_EQ(print(*r2.shader), once);
  }
}

TEST(IrText, LabelsResolveToOpIndices) {
  ParseResult r = parse(kPrograms[0]);
  ASSERT_TRUE(r.shader);
  const Shader& sh = *r.shader;
  ASSERT_EQ(sh.ops.size(), 6u);
  EXPECT_EQ(sh.ops[2].jumps, (std::vector<int>{3, 6})); // body at op 3, done = end
  EXPECT_EQ(sh.ops[5].jumps, (std::vector<int>{1}));
  // Printed labels are op indices.
  EXPECT_NE(print(sh).find("  cbr $t0 -> L3 L6\nL3:\n"), std::string::npos);
}

TEST(IrText, ExplicitWrittenMaskSurvives) {
  ParseResult r = parse(kPrograms[2]);
  ASSERT_TRUE(r.shader) << r.error.to_string();
  EXPECT_EQ(r.shader->ops[0].written_mask, 5u);
  EXPECT_EQ(r.shader->name, "odd name");
  EXPECT_NE(print(*r.shader).find("compref z \"x y\" z wmask=5"), std::string::npos);
}

// `%infn` (an op of an inlined function's body) reads back, with a location or without; an op
// without it stays unmarked.
TEST(IrText, InlinedFunctionMarkSurvives) {
  const char* text = R"(lobe-ir 1
surface s
symbols
  oparam float o = 0
  const float $c0 = 7
main
  assign o $c0 %infn @s.osl:1:26
  assign o $c0 %infn
  assign o $c0
end
)";
  ParseResult r = parse(text);
  ASSERT_TRUE(r.shader) << r.error.to_string();
  ASSERT_EQ(r.shader->ops.size(), 3u);
  EXPECT_TRUE(r.shader->ops[0].in_function);
  EXPECT_EQ(r.shader->ops[0].loc.line, 1);
  EXPECT_TRUE(r.shader->ops[1].in_function);
  EXPECT_FALSE(r.shader->ops[2].in_function);
  EXPECT_EQ(print(*r.shader), text);
  // The mark makes the op conditional in OSL's sense; the unmarked one at the top level is not.
  EXPECT_TRUE(in_conditional(*r.shader, 0));
  EXPECT_FALSE(in_conditional(*r.shader, 2));
}

// An unsized array param with a computed default carries the default's length as `len=N`.
TEST(IrText, UnsizedParamDefaultLengthSurvives) {
  ParseResult r = parse(kPrograms[1]);
  ASSERT_TRUE(r.shader) << r.error.to_string();
  const Symbol& w = r.shader->symbols[size_t(r.shader->find_symbol("w"))];
  EXPECT_EQ(w.type.arraylen, -1);
  EXPECT_EQ(w.default_len, 3);
  EXPECT_NE(print(*r.shader).find("  param float[] w init=0:0 len=3\n"), std::string::npos);
  EXPECT_TRUE(verify(*r.shader).empty());
  Shader bad = *r.shader;
  bad.symbols[size_t(bad.find_symbol("amp"))].default_len = 2; // not an unsized array
  auto errs = verify(bad);
  ASSERT_EQ(errs.size(), 1u);
  EXPECT_EQ(errs[0], "symbol 'amp': len=2 only on unsized array parameters");
}

// The struct table: struct-typed fields name a struct listed before, with an array length.
TEST(IrText, StructTableRoundTripsAndIsVerified) {
  const char* text = R"(lobe-ir 1
shader st
struct S { float a, closure c }
struct T { S s, S[2] sa, int[] k }
symbols
  param float t.s.a = 1 struct=T
main
end
)";
  ParseResult r = parse(text);
  ASSERT_TRUE(r.shader) << r.error.to_string();
  ASSERT_EQ(r.shader->structs.size(), 2u);
  const StructType& t = r.shader->structs[1];
  ASSERT_EQ(t.fields.size(), 3u);
  EXPECT_EQ(t.fields[0].struct_name, "S");
  EXPECT_EQ(t.fields[1].struct_name, "S");
  EXPECT_EQ(t.fields[1].type.arraylen, 2);
  EXPECT_EQ(t.fields[2].type, (Type{BaseType::Int, -1}));
  EXPECT_EQ(print(*r.shader), text);
  EXPECT_TRUE(verify(*r.shader).empty());
  Shader bad = *r.shader;
  std::swap(bad.structs[0], bad.structs[1]);
  auto errs = verify(bad);
  ASSERT_EQ(errs.size(), 2u);
  EXPECT_EQ(errs[0], "struct 'T': field 's' of struct type 'S' not listed before");
  bad = *r.shader;
  bad.symbols[0].folded = true;
  bad.symbols[0].init.clear();
  errs = verify(bad);
  ASSERT_EQ(errs.size(), 1u);
  EXPECT_EQ(errs[0], "symbol 't.s.a': 'folded' only on parameters with a constant default");
  ParseResult u = parse("lobe-ir 1\nshader st\nstruct T { U u }\nsymbols\nmain\nend\n");
  ASSERT_FALSE(u.shader);
  EXPECT_EQ(u.error.to_string(), "3:12: unknown type 'U'");
}

struct BadCase {
  const char* body; // lines after the symbols header
  int line, col;
  const char* message_part;
};

TEST(IrText, ErrorsCarryLineAndColumn) {
  const std::string head = "lobe-ir 1\nsurface s\nsymbols\n  local float x\n";
  const BadCase cases[] = {
      {"main\n  frob x\nend\n", 6, 3, "unknown opcode 'frob'"},
      {"main\n  assign x y\nend\n", 6, 12, "unknown symbol 'y'"},
      {"  local flt y\nmain\nend\n", 5, 9, "unknown type 'flt'"},
      {"  const float c = 1 2\nmain\nend\n", 5, 21, "unexpected '2'"},
      {"  const color c = 1 2\nmain\nend\n", 5, 22, "expected 3 value(s)"},
      {"  local float x\nmain\nend\n", 5, 15, "duplicate symbol 'x'"},
      {"main\n  br -> Lnowhere\nend\n", 6, 9, "undefined label 'Lnowhere'"},
      {"main\n  assign x x @f.osl:three:4\nend\n", 6, 14, "expected line number"},
      {"  const string c = \"open\nmain\nend\n", 5, 20, "unterminated string"},
      {"main\n", 6, 1, "missing 'end'"},
      {"  param float k = 1 [[ float min 0 ]]\nmain\nend\n", 5, 34, "expected '='"},
  };
  for (const BadCase& c : cases) {
    ParseResult r = parse(head + c.body);
    ASSERT_FALSE(r.shader) << c.body;
    EXPECT_EQ(r.error.line, c.line) << c.body << r.error.to_string();
    EXPECT_EQ(r.error.column, c.col) << c.body << r.error.to_string();
    EXPECT_NE(r.error.message.find(c.message_part), std::string::npos) << r.error.to_string();
  }
  ParseResult r = parse("lobe-ir 2\n");
  ASSERT_FALSE(r.shader);
  EXPECT_EQ(r.error.to_string(), "1:1: expected 'lobe-ir 1'");
}

// The table defines the enum: row i is opcode i, every name is unique and maps back to its
// opcode, and a name that is no opcode's maps to nothing.
TEST(Opcodes, NamesAndEnumAgree) {
  std::set<std::string_view> names;
  for (size_t i = 0; i < kOpcodeCount; ++i) {
    Opcode op = Opcode(i);
    EXPECT_EQ(size_t(info(op).op), i);
    EXPECT_TRUE(names.insert(to_string(op)).second) << to_string(op);
    EXPECT_EQ(opcode_from_name(to_string(op)), op) << to_string(op);
  }
  EXPECT_EQ(to_string(Opcode::Add), std::string_view("add"));
  EXPECT_EQ(to_string(Opcode::MxCompAssign), std::string_view("mxcompassign"));
  EXPECT_EQ(opcode_from_name("calculatenormal"), Opcode::CalculateNormal);
  EXPECT_FALSE(opcode_from_name("frob"));
  EXPECT_FALSE(opcode_from_name("Add"));
  EXPECT_TRUE(is_jump(Opcode::Cbr) && is_jump(Opcode::Exit) && !is_jump(Opcode::UseParam));
}

} // namespace
