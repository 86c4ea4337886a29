// RegexCache: a thread's compiled patterns and recent answers for regex_search / regex_match.
//
// Compiling a std::regex costs about 100 microseconds and matching even a short string a few
// thousand instructions, while a shader calls regex_search with the same few patterns at every
// point, often on the same few subjects (names built from a tile, object or material id). So
// each thread keeps
//   - the patterns it has compiled, by text (an invalid pattern as null: it matches nothing);
//     they are dropped whole when they reach kMaxPatterns, which only a shader building
//     patterns from varying text would do;
//   - the answers of its recent (subject, pattern, full match) questions, by text, one per slot
//     of a table of kAnswerSlots indexed by hash, a new answer replacing the one in its slot.
// Both are keyed by the strings' text, never their addresses, so an answer is the matcher's
// for any strings, interned or not.
#pragma once

#include "text_hash.h"

#include <array>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <regex>
#include <string>
#include <string_view>
#include <unordered_map>

namespace lobe::shadeops {

class RegexCache {
public:
  static constexpr size_t kMaxPatterns = 64;
  static constexpr size_t kAnswerSlots = 256;

  // The calling thread's cache.
  static RegexCache& local();

  // `pattern` compiled (ECMAScript syntax), or null when it is not a valid pattern.
  const std::regex* compiled(const char* pattern);

  // regex_match (`full`) or regex_search of `s` for `pattern`: 1 or 0. An invalid pattern
  // matches nothing, and nor does a search the matcher gives up on (std::regex_error).
  int matches(const char* s, const char* pattern, bool full);

private:
  using Patterns =
      std::unordered_map<std::string, std::unique_ptr<std::regex>, TextHash, std::equal_to<>>;
  struct Answer {
    uint64_t generation = 0;              // of the patterns (0: empty slot)
    const std::string* pattern = nullptr; // its key in patterns_ (alive in its generation)
    std::string subject;
    bool full = false;
    int result = 0;
  };

  const Patterns::value_type& entry(const char* pattern);

  Patterns patterns_;
  const Patterns::value_type* last_ = nullptr; // the pattern asked for last
  uint64_t generation_ = 1; // counts clears of patterns_: older answers are stale
  std::array<Answer, kAnswerSlots> answers_;
};

} // namespace lobe::shadeops
