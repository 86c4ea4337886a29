// oslc 1.13's overload scores and choice rules (sema/types.h match_score and return_rank,
// sema/overload.h choose_overload), with cases from the experiments run on oslc 1.13.12 that
// docs/language.md summarises ("Calls and overload resolution"): the figures are oslc's.
#include "sema/overload.h"

#include <gtest/gtest.h>

#include <vector>

using namespace lobe::sema;
using lobe::ast::BaseType;
using lobe::ast::Type;

namespace {

Type arr(BaseType b, int len) { return Type(b, len); }

struct Case {
  std::vector<int> scores;
  std::vector<Type> returns; // newest declaration first
};

OverloadChoice choose(const Case& c, const Type* expected = nullptr) {
  return choose_overload(c.scores, c.returns, expected);
}

} // namespace

// Single arguments: oslc accepts exactly these conversions (its acceptance tables) and ranks
// them exact > int->float > T[N]->T[] > spatial<->spatial > color<->spatial > int/float->triple.
TEST(Overload, ArgumentScores) {
  EXPECT_EQ(match_score(t_float(), t_float()), 100);
  EXPECT_EQ(match_score(t_float(), t_int()), 77);
  EXPECT_EQ(match_score(t_vector(), t_point()), 32);
  EXPECT_EQ(match_score(t_point(), t_normal()), 32);
  EXPECT_EQ(match_score(t_color(), t_point()), 27);
  EXPECT_EQ(match_score(t_normal(), t_color()), 27);
  EXPECT_EQ(match_score(t_color(), t_int()), 23);
  EXPECT_EQ(match_score(t_point(), t_float()), 23);
  EXPECT_EQ(match_score(t_matrix(), t_int()), 23);
  EXPECT_EQ(match_score(t_matrix(), t_float()), 23);
  // Not accepted at all: float -> int, triples -> float, matrix <-> triple, strings, closures.
  EXPECT_EQ(match_score(t_int(), t_float()), 0);
  EXPECT_EQ(match_score(t_float(), t_color()), 0);
  EXPECT_EQ(match_score(t_color(), t_matrix()), 0);
  EXPECT_EQ(match_score(t_string(), t_int()), 0);
  EXPECT_EQ(match_score(t_float(), t_string()), 0);
  EXPECT_EQ(match_score(t_closure(), t_int()), 0); // not even the literal 0 (gV:cl1)
  EXPECT_EQ(match_score(t_closure(), t_color()), 0);
  EXPECT_EQ(match_score(t_closure(), t_closure()), 100);
}

TEST(Overload, ArrayScores) {
  EXPECT_EQ(match_score(arr(BaseType::Float, 3), arr(BaseType::Float, 3)), 100);
  EXPECT_EQ(match_score(arr(BaseType::Float, -1), arr(BaseType::Float, 3)), 44);
  EXPECT_EQ(match_score(arr(BaseType::Float, 4), arr(BaseType::Float, 3)), 0);
  EXPECT_EQ(match_score(arr(BaseType::Float, 2), arr(BaseType::Float, 3)), 0); // gV:arr2
  EXPECT_EQ(match_score(arr(BaseType::Float, -1), arr(BaseType::Int, 3)), 0);  // gV:arr4
  EXPECT_EQ(match_score(arr(BaseType::Int, -1), arr(BaseType::Float, 3)), 0);  // gV:arr3
  EXPECT_EQ(match_score(arr(BaseType::Vector, -1), arr(BaseType::Point, 3)), 32);
  EXPECT_EQ(match_score(arr(BaseType::Vector, 3), arr(BaseType::Point, 3)), 32);
  EXPECT_EQ(match_score(arr(BaseType::Color, -1), arr(BaseType::Point, 3)), 23); // not 27
  EXPECT_EQ(match_score(arr(BaseType::Point, -1), arr(BaseType::Color, 3)), 23);
  EXPECT_EQ(match_score(arr(BaseType::Vector, 4), arr(BaseType::Point, 2)), 0); // gV:arr8
  EXPECT_EQ(match_score(t_float(), arr(BaseType::Float, 2)), 0);                // gV:arr6
  EXPECT_EQ(match_score(arr(BaseType::Float, -1), t_int()), 0);                 // gV:arr5
}

TEST(Overload, ReturnRanks) {
  const Type order[] = {t_float(),  t_int(),    t_color(),  t_vector(),  t_point(),
                        t_normal(), t_matrix(), t_string(), t_closure(), Type(BaseType::Struct),
                        t_void()};
  for (size_t i = 0; i + 1 < std::size(order); ++i)
    EXPECT_LT(return_rank(order[i]), return_rank(order[i + 1])) << i;
}

// Sums are compared exactly, and the argument score comes before the expected type.
TEST(Overload, ArgumentSumsDecideFirst) {
  // `color f(float,float,float,point)` and `float f(int,int,int,vector)` for
  // `color c = f(1,1,1,vp)`: 331 against 332, so the float one although the other returns the
  // expected color (gK:lx1).
  Case c{{77 * 3 + 100, 100 * 3 + 32}, {t_color(), t_float()}};
  Type color = t_color();
  OverloadChoice r = choose(c, &color);
  EXPECT_EQ(r.kind, OverloadChoice::Kind::Unique);
  EXPECT_EQ(r.chosen, 1u);
  // Nothing applies.
  EXPECT_EQ(choose({{kNotViable, kNotViable}, {t_float(), t_int()}}).kind,
            OverloadChoice::Kind::NoMatch);
}

TEST(Overload, ExpectedTypeDecidesOnlyWhenUnique) {
  // `vector x = f()` over {normal, point, color, float} declared in that order: normal and
  // point both score 32 for vector, so the expected type is ignored; float by rank (gK:wl1).
  Case four{{0, 0, 0, 0}, {t_float(), t_color(), t_point(), t_normal()}};
  Type vec = t_vector();
  OverloadChoice r = choose(four, &vec);
  EXPECT_EQ(r.kind, OverloadChoice::Kind::ByRank);
  EXPECT_EQ(r.chosen, 0u);
  EXPECT_EQ(r.others, (std::vector<size_t>{1, 2, 3})); // color, point, normal
  // {float, point} with `color x = f()`: point scores 27 against float's 23 (gK:wl3).
  Type col = t_color();
  r = choose({{0, 0}, {t_point(), t_float()}}, &col);
  EXPECT_EQ(r.kind, OverloadChoice::Kind::ByExpectedType);
  EXPECT_EQ(r.chosen, 0u);
  // Two exact matches are no unique best either: {point f(int,float), point f(float,int),
  // float f(float,int)} with `point x = f(1,1)` gives float (gY:fb2).
  Type pnt = t_point();
  r = choose({{177, 177, 177}, {t_float(), t_point(), t_point()}}, &pnt);
  EXPECT_EQ(r.kind, OverloadChoice::Kind::ByRank);
  EXPECT_EQ(r.chosen, 0u);
  // `int x = f()` over {float, color}: nothing scores above 0 (gJ:rs_none4).
  Type i = t_int();
  r = choose({{0, 0}, {t_color(), t_float()}}, &i);
  EXPECT_EQ(r.kind, OverloadChoice::Kind::ByRank);
  EXPECT_EQ(r.chosen, 1u);
}

TEST(Overload, RankThenNewest) {
  // `color f(); int f(); point f(); float f();` with `f();`: float, then int, color, point
  // (gH:w4). Newest first: float, point, int, color.
  OverloadChoice r = choose({{0, 0, 0, 0}, {t_float(), t_point(), t_int(), t_color()}});
  EXPECT_EQ(r.kind, OverloadChoice::Kind::ByRank);
  EXPECT_EQ(r.chosen, 0u);
  EXPECT_EQ(r.others, (std::vector<size_t>{2, 3, 1}));
  // Equal ranks go to the newest declaration, the others newest first (gX:fm2).
  r = choose({{5, 5, 5, 5}, {t_int(), t_float(), t_int(), t_float()}});
  EXPECT_EQ(r.chosen, 1u);
  EXPECT_EQ(r.others, (std::vector<size_t>{3, 0, 2}));
}

TEST(Overload, StructTies) {
  Type s(BaseType::Struct), t(BaseType::Struct);
  // `S f(); T f(); float f();` with `f();`: an error listing float, T, S (gM:st7).
  OverloadChoice r = choose({{0, 0, 0}, {t_float(), t, s}});
  EXPECT_EQ(r.kind, OverloadChoice::Kind::StructTie);
  EXPECT_EQ(r.others, (std::vector<size_t>{0, 1, 2}));
  // One struct ranks like any type: [S, void] takes S, [S, float] float (gN).
  r = choose({{0, 0}, {t_void(), s}});
  EXPECT_EQ(r.kind, OverloadChoice::Kind::ByRank);
  EXPECT_EQ(r.chosen, 1u);
  r = choose({{0, 0}, {s, t_float()}});
  EXPECT_EQ(r.chosen, 1u);
}
