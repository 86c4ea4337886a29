// Unit tests of RegexCache: cached compilations and answers keep the matcher's meaning.
// Expected answers are worked by hand from the ECMAScript patterns.
#include "regex_cache.h"

#include <gtest/gtest.h>

#include <cstring>
#include <string>

using lobe::shadeops::RegexCache;

TEST(RegexCache, SeveralPatternsAskedInTurn) {
  RegexCache c; // a fresh cache (RegexCache::local() is shared by the thread's tests)
  for (int round = 0; round < 3; ++round) { // the later rounds are answered from the cache
    EXPECT_EQ(c.matches("tile_5_7", "tile_[0-9]_[0-9]$", false), 1);
    EXPECT_EQ(c.matches("tile_5_12", "tile_[0-9]_[0-9]$", false), 0);
    EXPECT_EQ(c.matches("xtile_5_7", "tile_[0-9]_[0-9]$", false), 1); // a search, not anchored
    EXPECT_EQ(c.matches("xtile_5_7", "tile_[0-9]_[0-9]$", true), 0);  // a full match
    EXPECT_EQ(c.matches("foo123", "[0-9]+", false), 1);
    EXPECT_EQ(c.matches("foo123", "[0-9]+", true), 0);
    EXPECT_EQ(c.matches("123", "[0-9]+", true), 1);
    EXPECT_EQ(c.matches("", "^$", true), 1);
    EXPECT_EQ(c.matches("a", "^$", false), 0);
    EXPECT_EQ(c.matches("a(b", "a\\(b", true), 1);
  }
}

// An invalid pattern compiles to null and matches nothing, every time it is asked, without
// throwing; a valid one asked between keeps working.
TEST(RegexCache, InvalidPatternStaysInvalid) {
  RegexCache c;
  for (int round = 0; round < 3; ++round) {
    EXPECT_EQ(c.compiled("("), nullptr);
    EXPECT_EQ(c.compiled("[a-"), nullptr);
    EXPECT_EQ(c.matches("(", "(", false), 0);
    EXPECT_EQ(c.matches("anything", "[a-", true), 0);
    ASSERT_NE(c.compiled("a+"), nullptr);
    EXPECT_EQ(c.matches("caab", "a+", false), 1);
  }
}

// Answers are keyed by text: a buffer rewritten between questions gets the new text's answer.
TEST(RegexCache, KeyedByTextNotAddress) {
  RegexCache c;
  char subject[16], pattern[16];
  std::strcpy(subject, "abc");
  std::strcpy(pattern, "^a");
  EXPECT_EQ(c.matches(subject, pattern, false), 1);
  std::strcpy(subject, "xbc");
  EXPECT_EQ(c.matches(subject, pattern, false), 0);
  std::strcpy(pattern, "c$");
  EXPECT_EQ(c.matches(subject, pattern, false), 1);
  std::strcpy(pattern, "^x");
  EXPECT_EQ(c.matches(subject, pattern, false), 1);
  std::strcpy(subject, "abc");
  EXPECT_EQ(c.matches(subject, pattern, false), 0);
}

// More subjects than answer slots and more patterns than the cache keeps: every answer is
// still right when asked again (the patterns were dropped and compiled anew in between).
TEST(RegexCache, EvictionKeepsMeaning) {
  RegexCache c;
  const int subjects = int(RegexCache::kAnswerSlots) * 3;
  const int patterns = int(RegexCache::kMaxPatterns) + 10;
  for (int round = 0; round < 2; ++round) {
    for (int i = 0; i < subjects; ++i) { // "n<i>" ends in 7 exactly when i % 10 == 7
      std::string s = "n" + std::to_string(i);
      EXPECT_EQ(c.matches(s.c_str(), "7$", false), i % 10 == 7 ? 1 : 0) << s;
    }
    for (int i = 0; i < patterns; ++i) {
      std::string p = "^x" + std::to_string(i) + "$";
      EXPECT_EQ(c.matches(("x" + std::to_string(i)).c_str(), p.c_str(), true), 1) << p;
      EXPECT_EQ(c.matches(("x" + std::to_string(i + 1)).c_str(), p.c_str(), true), 0) << p;
    }
  }
}

TEST(RegexCache, LocalIsPerThreadAndStable) {
  EXPECT_EQ(&RegexCache::local(), &RegexCache::local());
  EXPECT_EQ(RegexCache::local().matches("tile_1_2", "_[0-9]$", false), 1);
}
