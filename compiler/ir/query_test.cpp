// `lobe info` text (describe) for a hand-written shader, against hand-written expected text.
#include "ir/parser.h"
#include "ir/query.h"

#include <gtest/gtest.h>

namespace {

TEST(Query, DescribesParametersLikeOslinfo) {
  const char* ir = R"(lobe-ir 1
surface plastic [[ string help = "A plastic" ]]
symbols
  param float Kd = 0.5 [[ float min = 0, float max = 1 ]]
  param color Cs = 1 0.5 0
  param string dist = "ggx" [[ string widget = "popup", string options = "ggx|beckmann" ]]
  param normal Nn init=0:1
  param float[2] s.a = 1 2 struct=S
  oparam float out = 0
  global normal N
  local float x
init
  assign Nn N
main
end
)";
  lobe::ir::ParseResult r = lobe::ir::parse(ir);
  ASSERT_TRUE(r.shader) << r.error.to_string();
  EXPECT_EQ(lobe::ir::describe(*r.shader), "surface \"plastic\"\n"
                                           "    metadata: string help = \"A plastic\"\n"
                                           "    \"Kd\" \"float\"\n"
                                           "\t\tDefault value: 0.5\n"
                                           "\t\tmetadata: float min = 0\n"
                                           "\t\tmetadata: float max = 1\n"
                                           "    \"Cs\" \"color\"\n"
                                           "\t\tDefault value: [ 1 0.5 0 ]\n"
                                           "    \"dist\" \"string\"\n"
                                           "\t\tDefault value: \"ggx\"\n"
                                           "\t\tmetadata: string widget = \"popup\"\n"
                                           "\t\tmetadata: string options = \"ggx|beckmann\"\n"
                                           "    \"Nn\" \"normal\"\n"
                                           "\t\tDefault value: (computed at run time)\n"
                                           "    \"s\" \"struct S\"\n"
                                           "    \"s.a\" \"float[2]\"\n"
                                           "\t\tDefault value: [ 1 2 ]\n"
                                           "    \"out\" \"output float\"\n"
                                           "\t\tDefault value: 0\n");
}

} // namespace
