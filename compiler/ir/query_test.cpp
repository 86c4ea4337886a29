// `lobe info` text (describe): a shader's IR against what OSL's oslinfo prints for the same
// source compiled by oslc, in both formats and for one parameter.
#include "ir/parser.h"
#include "ir/query.h"

#include <gtest/gtest.h>

namespace {

// Lobe's IR for this source (`lobe compile -O0 --emit=ir q.osl`, locations dropped):
//   struct S { float a; color c; };
//   struct T { S s; int k[2]; S sa[2]; };
//   surface q [[ string help = "Tab\there \"q\"", float fl[3] = {1, 2, 3}, color tint = 0.5,
//                matrix m = 1 ]] (
//     int i = -5 [[ string widget = "checkBox", int range[2] = {0, 1} ]],
//     float f = 1.0 / 3.0 [[ float nz = -0.0 ]],
//     float big = 1e20,
//     float small = 1e-7,
//     float c9 = 123456789,
//     float negz = -0.0,
//     float mixed = 2 * 3.5,
//     float fu = u,
//     color c = color(0.1, 0.2, 0.3),
//     matrix m = 2,
//     string s = "a\tb\n\"c\"\\",
//     string sa[2] = {"x", "y"},
//     float f1[1] = {1},
//     float fu2[] = {4, 5},
//     closure color cc = 0,
//     closure color cca[2] = {0, 0},
//     T t = {{1, color(2)}, {3, 4}, {{5, color(6)}, {7, color(8)}}},
//     output float fout = 0 [[ string help = "out" ]],
//     output S sout = {0, 0}
//   ) {}
const char* kIr = R"(lobe-ir 1
surface q [[ string help = "Tab\there \"q\"", float[3] fl = 1 2 3, color tint = 0.5 0.5 0.5, matrix m = 1 0 0 0 0 1 0 0 0 0 1 0 0 0 0 1 ]]
struct S { float a, color c }
struct T { S s, int[2] k, S[2] sa }
symbols
  param int i = -5 [[ string widget = "checkBox", int[2] range = 0 1 ]]
  param float f = 0.33333334 [[ float nz = -0 ]]
  param float big = 1e+20
  param float small = 1e-07
  param float c9 = 123456792
  param float negz = -0
  param float mixed = 7 folded
  param float fu init=0:1
  global float u
  param color c = 0.1 0.2 0.3
  param matrix m = 2 0 0 0 0 2 0 0 0 0 2 0 0 0 0 2
  param string s = "a\tb\n\"c\"\\"
  param string[2] sa = "x" "y"
  param float[1] f1 = 1
  param float[] fu2 = 4 5
  param closure cc init=1:2
  const int $c0 = 0
  param closure[2] cca init=2:2
  param float t.s.a = 1 struct=T
  param color t.s.c = 2 2 2 struct=T
  param int[2] t.k = 3 4 folded struct=T
  param float[2] t.sa.a = 5 7 folded struct=T
  param color[2] t.sa.c = 6 6 6 8 8 8 folded struct=T
  oparam float fout = 0 [[ string help = "out" ]]
  oparam float sout.a = 0 struct=S
  oparam color sout.c = 0 0 0 struct=S
init
  assign fu u
  assign cc $c0
main
end
)";

lobe::ir::Shader shader() {
  lobe::ir::ParseResult r = lobe::ir::parse(kIr);
  EXPECT_TRUE(r.shader) << r.error.to_string();
  return r.shader ? *r.shader : lobe::ir::Shader{};
}

// oslc q.osl && oslinfo -v q   (OSL 1.13.12)
TEST(Query, VerboseIsOslinfoDashV) {
  EXPECT_EQ(lobe::ir::describe(shader()),
            "surface \"q\"\n"
            "\t\tmetadata: string help = \"Tab\\there \\\"q\\\"\"\n"
            "\t\tmetadata: float[3] fl = 1 2 3\n"
            "\t\tmetadata: color tint = 0.5 0.5 0.5\n"
            "\t\tmetadata: matrix m = 1 0 0 0 0 1 0 0 0 0 1 0 0 0 0 1\n"
            "    \"i\" \"int\"\n"
            "\t\tDefault value: -5\n"
            "\t\tmetadata: string widget = \"checkBox\"\n"
            "\t\tmetadata: int[2] range = 0 1\n"
            "    \"f\" \"float\"\n"
            "\t\tDefault value: 0.333333\n"
            "\t\tmetadata: float nz = -0\n"
            "    \"big\" \"float\"\n"
            "\t\tDefault value: 1e+20\n"
            "    \"small\" \"float\"\n"
            "\t\tDefault value: 1e-07\n"
            "    \"c9\" \"float\"\n"
            "\t\tDefault value: 1.23457e+08\n"
            "    \"negz\" \"float\"\n"
            "\t\tDefault value: 0\n"
            "    \"mixed\" \"float\"\n"
            "\t\tUnknown default value\n"
            "    \"fu\" \"float\"\n"
            "\t\tUnknown default value\n"
            "    \"c\" \"color\"\n"
            "\t\tDefault value: [ 0.1 0.2 0.3 ]\n"
            "    \"m\" \"matrix\"\n"
            "\t\tDefault value: [ 2 0 0 0 0 2 0 0 0 0 2 0 0 0 0 2 ]\n"
            "    \"s\" \"string\"\n"
            "\t\tDefault value: \"a\\tb\\n\\\"c\\\"\\\\\"\n"
            "    \"sa\" \"string[2]\"\n"
            "\t\tDefault value: \"x\"\n"
            "\t\tDefault value: \"y\"\n"
            "    \"f1\" \"float[1]\"\n"
            "\t\tDefault value: [ 1 ]\n"
            "    \"fu2\" \"float[]\"\n"
            "\t\tDefault value: [ 4 5 ]\n"
            "    \"cc\" \"pointer\"\n"
            "\t\tUnknown default value\n"
            "    \"cca\" \"pointer[2]\"\n"
            "\t\tUnknown default value\n"
            "    \"t\" \"struct T\"\n"
            "\t\tfields: {unknown s, int[2] k, unknown[2] sa}\n"
            "    \"t.s\" \"struct S\"\n"
            "\t\tfields: {float a, color c}\n"
            "    \"t.s.a\" \"float\"\n"
            "\t\tDefault value: 1\n"
            "    \"t.s.c\" \"color\"\n"
            "\t\tDefault value: [ 2 2 2 ]\n"
            "    \"t.k\" \"int[2]\"\n"
            "\t\tUnknown default value\n"
            "    \"t.sa\" \"unknown[2]\"\n"
            "\t\tUnknown default value\n"
            "    \"t.sa.a\" \"float[2]\"\n"
            "\t\tUnknown default value\n"
            "    \"t.sa.c\" \"color[2]\"\n"
            "\t\tUnknown default value\n"
            "    \"fout\" \"output float\"\n"
            "\t\tDefault value: 0\n"
            "\t\tmetadata: string help = \"out\"\n"
            "    \"sout\" \"output struct S\"\n"
            "\t\tfields: {float a, color c}\n"
            "    \"sout.a\" \"output float\"\n"
            "\t\tDefault value: 0\n"
            "    \"sout.c\" \"output color\"\n"
            "\t\tDefault value: [ 0 0 0 ]\n");
}

// oslc q.osl && oslinfo q   (OSL 1.13.12)
TEST(Query, PlainIsOslinfo) {
  EXPECT_EQ(lobe::ir::describe(shader(), {.verbose = false, .param = ""}),
            "surface \"q\"\n"
            "int i  -5\n"
            "float f  0.333333\n"
            "float big  1e+20\n"
            "float small  1e-07\n"
            "float c9  1.23457e+08\n"
            "float negz  0\n"
            "float mixed nodefault\n"
            "float fu nodefault\n"
            "color c  [ 0.1 0.2 0.3 ]\n"
            "matrix m  [ 2 0 0 0 0 2 0 0 0 0 2 0 0 0 0 2 ]\n"
            "string s \"a\\tb\\n\\\"c\\\"\\\\\" \n"
            "string[2] sa \"x\" \"y\" \n"
            "float[1] f1  [ 1 ]\n"
            "float[] fu2  [ 4 5 ]\n"
            "pointer cc nodefault\n"
            "pointer[2] cca nodefault\n"
            "struct T t fields: {unknown s, int[2] k, unknown[2] sa}\n"
            "struct S t.s fields: {float a, color c}\n"
            "float t.s.a  1\n"
            "color t.s.c  [ 2 2 2 ]\n"
            "int[2] t.k nodefault\n"
            "unknown[2] t.sa nodefault\n"
            "float[2] t.sa.a nodefault\n"
            "color[2] t.sa.c nodefault\n"
            "output float fout  0\n"
            "output struct S sout fields: {float a, color c}\n"
            "output float sout.a  0\n"
            "output color sout.c  [ 0 0 0 ]\n");
}

// oslinfo -v --param t.s q; oslinfo --param sa q; oslinfo --param t.sa q; oslinfo --param x q
TEST(Query, OneParameterWithoutTheShaderLine) {
  lobe::ir::Shader sh = shader();
  EXPECT_EQ(lobe::ir::describe(sh, {.verbose = true, .param = "t.s"}),
            "    \"t.s\" \"struct S\"\n\t\tfields: {float a, color c}\n");
  EXPECT_EQ(lobe::ir::describe(sh, {.verbose = false, .param = "sa"}),
            "string[2] sa \"x\" \"y\" \n");
  EXPECT_EQ(lobe::ir::describe(sh, {.verbose = false, .param = "t.sa"}),
            "unknown[2] t.sa nodefault\n");
  EXPECT_EQ(lobe::ir::describe(sh, {.verbose = true, .param = "x"}), "");
}

// IR text without the struct table (written before Lobe kept one): the struct is still
// announced, without a fields line.
TEST(Query, StructWithoutItsTable) {
  lobe::ir::ParseResult r = lobe::ir::parse("lobe-ir 1\nshader s\nsymbols\n"
                                            "  param float st.a = 1 struct=S\nmain\nend\n");
  ASSERT_TRUE(r.shader) << r.error.to_string();
  EXPECT_EQ(
      lobe::ir::describe(*r.shader),
      "shader \"s\"\n    \"st\" \"struct S\"\n    \"st.a\" \"float\"\n\t\tDefault value: 1\n");
}

} // namespace
