// The one matching of a closure call (closure_call.h), over a small table made for the test:
// which entry binds, where positional arguments end, which keyword each pair sets, and the
// first problem of the entry that got furthest when none fits.
#include "closure_call.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace lobe::registry {
namespace {

using T = ArgType;
constexpr ClosureParam kOne[] = {{"N", T::Vector, false, nullptr, ""},
                                 {"tag", T::String, true, "\"\"", ""}};
constexpr ClosureParam kTwo[] = {{"N", T::Vector, false, nullptr, ""},
                                 {"x", T::Float, false, nullptr, ""},
                                 {"tag", T::String, true, "\"\"", ""},
                                 {"k", T::Int, true, "0", ""}};
constexpr ClosureEntry kTable[] = {{"f1", "f", kOne, kReflect, ""},
                                   {"f2", "f", kTwo, kReflect, ""},
                                   {"g", "g", kTwo, kReflect, ""}};

// Arguments by kind: 'v' a vector, 'f' a float, 'i' an int, or a string literal's text.
CallArgs args_of(const std::vector<std::string>& a) {
  CallArgs c;
  c.count = a.size();
  auto kind = [a](size_t i) { return a[i] == "v" || a[i] == "f" || a[i] == "i" ? a[i][0] : 's'; };
  c.cost = [kind](size_t i, ArgType t) {
    char k = kind(i);
    if (t == T::Vector) return k == 'v' ? 0 : kNoFit;
    if (t == T::Float) return k == 'f' ? 0 : k == 'i' ? 2 : kNoFit;
    if (t == T::Int) return k == 'i' ? 0 : kNoFit;
    if (t == T::String) return k == 's' ? 0 : kNoFit;
    return kNoFit;
  };
  c.is_string = [kind](size_t i) { return kind(i) == 's'; };
  c.literal = [a, kind](size_t i) -> std::optional<std::string_view> {
    if (kind(i) != 's') return std::nullopt;
    return std::string_view(a[i]);
  };
  return c;
}

TEST(ClosureCall, PositionalCountPicksTheEntryAndKeywordsMapToParams) {
  ClosureMatch one = match_closure_call(kTable, "f", args_of({"v", "tag", "abc"}));
  ASSERT_TRUE(one.entry);
  EXPECT_STREQ(one.entry->key, "f1");
  EXPECT_EQ(one.positional, 1u);
  ASSERT_EQ(one.keywords.size(), 1u);
  EXPECT_EQ(one.keywords[0].name_arg, 1u);
  EXPECT_EQ(one.keywords[0].param, 1); // "tag" is kOne[1]
  EXPECT_EQ(one.candidates.size(), 2u);

  // (v, f, "k", i): f1 would read "f" as a keyword name and fail; f2 takes it.
  ClosureMatch two = match_closure_call(kTable, "f", args_of({"v", "f", "k", "i", "nope", "i"}));
  ASSERT_TRUE(two.entry);
  EXPECT_STREQ(two.entry->key, "f2");
  EXPECT_EQ(two.positional, 2u);
  ASSERT_EQ(two.keywords.size(), 2u);
  EXPECT_EQ(two.keywords[0].param, 3); // "k" is kTwo[3]
  EXPECT_EQ(two.keywords[1].param, kUnknownKeyword);
}

TEST(ClosureCall, TheFurthestProblemIsReported) {
  ClosureMatch unknown = match_closure_call(kTable, "h", args_of({"v"}));
  EXPECT_FALSE(unknown.entry);
  EXPECT_EQ(unknown.problem, CallProblem::UnknownClosure);

  ClosureMatch few = match_closure_call(kTable, "g", args_of({"v"}));
  EXPECT_FALSE(few.entry);
  EXPECT_EQ(few.problem, CallProblem::TooFewArguments);
  EXPECT_EQ(few.problem_arg, 1u);

  // f1 fails at argument 1 (a float is no keyword name), f2 only at the end (the name "k"
  // has no value): f2's problem is reported.
  ClosureMatch odd = match_closure_call(kTable, "f", args_of({"v", "f", "k"}));
  EXPECT_FALSE(odd.entry);
  EXPECT_EQ(odd.problem, CallProblem::KeywordWithoutValue);
  EXPECT_EQ(odd.problem_arg, 3u);
  EXPECT_STREQ(odd.problem_entry->key, "f2");

  ClosureMatch type = match_closure_call(kTable, "g", args_of({"v", "v"}));
  EXPECT_FALSE(type.entry);
  EXPECT_EQ(type.problem, CallProblem::ArgumentType);
  EXPECT_EQ(type.problem_arg, 1u);

  ClosureMatch name = match_closure_call(kTable, "g", args_of({"v", "f", "i", "i"}));
  EXPECT_FALSE(name.entry);
  EXPECT_EQ(name.problem, CallProblem::KeywordName);
  EXPECT_EQ(name.problem_arg, 2u);
}

TEST(ClosureCall, CheapestConversionWinsFirstAmongEquals) {
  static constexpr ClosureParam kF[] = {{"x", T::Float, false, nullptr, ""}};
  static constexpr ClosureParam kI[] = {{"x", T::Int, false, nullptr, ""}};
  static constexpr ClosureEntry t[] = {
      {"a", "p", kF, kReflect, ""}, {"b", "p", kI, kReflect, ""}, {"c", "p", kI, kReflect, ""}};
  EXPECT_STREQ(match_closure_call(t, "p", args_of({"i"})).entry->key, "b"); // int: 0 beats 2
  EXPECT_STREQ(match_closure_call(t, "p", args_of({"f"})).entry->key, "a");
}

} // namespace
} // namespace lobe::registry
