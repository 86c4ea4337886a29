// RegexCache (see regex_cache.h).
#include "regex_cache.h"

#include <cstring>

namespace lobe::shadeops {
namespace {
// Equal text (string_view's == calls an out-of-line compare).
bool same(std::string_view a, std::string_view b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size()) == 0;
}
} // namespace

RegexCache& RegexCache::local() {
  thread_local RegexCache cache;
  return cache;
}

const RegexCache::Patterns::value_type& RegexCache::entry(const char* pattern) {
  std::string_view text(pattern);
  if (last_ && same(last_->first, text)) return *last_;
  auto it = patterns_.find(text);
  if (it == patterns_.end()) {
    if (patterns_.size() >= kMaxPatterns) {
      patterns_.clear();
      ++generation_;
    }
    std::unique_ptr<std::regex> re;
    try {
      re = std::make_unique<std::regex>(pattern);
    } catch (...) { // std::regex_error: an invalid pattern stays null
    }
    it = patterns_.emplace(std::string(text), std::move(re)).first;
  }
  last_ = &*it;
  return *last_;
}

const std::regex* RegexCache::compiled(const char* pattern) { return entry(pattern).second.get(); }

int RegexCache::matches(const char* s, const char* pattern, bool full) {
  std::string_view subject(s), text(pattern);
  // The slot: the subject's hash mixed with the pattern's address (an index only: the answer
  // is checked against the pattern's text), so a remembered answer needs no pattern lookup.
  size_t h = std::hash<std::string_view>{}(subject) ^
             size_t((uintptr_t(pattern) * 0x9E3779B97F4A7C15ull) >> 20) ^ size_t(full);
  Answer& a = answers_[h % kAnswerSlots];
  if (a.generation == generation_ && a.full == full && same(a.subject, subject) &&
      same(*a.pattern, text))
    return a.result;
  const auto& [key, re] = entry(pattern);
  int result = 0;
  if (re) {
    try {
      result = full ? std::regex_match(s, *re) : std::regex_search(s, *re);
    } catch (...) { // std::regex_error from the matcher (complexity, stack)
      result = 0;
    }
  }
  a.generation = generation_; // entry() may have cleared the patterns: the current generation
  a.pattern = &key;
  a.full = full;
  a.subject.assign(subject);
  a.result = result;
  return result;
}

} // namespace lobe::shadeops
