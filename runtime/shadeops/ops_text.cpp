// Shadeops for text and messages: printf/format/warning/error, run-time range errors, string
// functions (concat, substr, regex, hash, ...). Strings are interned through the RuntimeEnv.
#include "env.h"
#include "format.h"
#include "lobe/context.h"
#include "regex_cache.h"
#include "shadeop_decls.h"

#include <OpenImageIO/strutil.h>

#include <algorithm>
#include <cctype>
#include <climits>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <memory>
#include <mutex>
#include <regex>
#include <string>
#include <string_view>
#include <unordered_map>

using lobe::ShaderGlobals;
using lobe::shadeops::RuntimeEnv;

namespace {
void send(ShaderGlobals* sg, const std::string& text) {
  if (sg && sg->context) sg->context->message(text);
}

// Runs `f`, which builds and sends a message: an exception (out of memory while formatting)
// must not unwind through the shader's frames, so it is caught here and the message counted
// as lost (ShadingContext::messages_lost).
template <class F> void guarded(ShaderGlobals* sg, F&& f) noexcept {
  try {
    f();
  } catch (...) {
    if (sg && sg->context) ++sg->context->messages_lost;
  }
}
} // namespace

extern "C" {

void lobe_printf(ShaderGlobals* sg, RuntimeEnv* env, const char* fmt, const char* codes,
                 const void* const* args) {
  guarded(sg, [&] { send(sg, lobe::shadeops::format_values(*env, fmt, codes, args)); });
}

const char* lobe_format(RuntimeEnv* env, const char* fmt, const char* codes,
                        const void* const* args) {
  return lobe::shadeops::format_interned(*env, fmt, codes, args);
}

// warning() and error() from a shader, worded as OSL words them: "Shader warning [shader]:
// text" (the text as formatted, a trailing newline kept).
void lobe_warning(ShaderGlobals* sg, RuntimeEnv* env, const char* shader, const char* fmt,
                  const char* codes, const void* const* args) {
  if (sg && sg->context)
    guarded(sg, [&] {
      sg->context->warning(std::string("Shader warning [") + shader +
                           "]: " + lobe::shadeops::format_values(*env, fmt, codes, args));
    });
}

void lobe_error(ShaderGlobals* sg, RuntimeEnv* env, const char* shader, const char* fmt,
                const char* codes, const void* const* args) {
  if (sg && sg->context)
    guarded(sg, [&] {
      sg->context->error(std::string("Shader error [") + shader +
                         "]: " + lobe::shadeops::format_values(*env, fmt, codes, args));
    });
}

// fprintf(file, ...): appends to the file (created if missing), as OSL does; one writer at a
// time, so that lines from several shading threads never interleave. A file that cannot be
// opened is an error.
void lobe_fprintf(ShaderGlobals* sg, RuntimeEnv* env, const char* file, const char* fmt,
                  const char* codes, const void* const* args) {
  static std::mutex mutex;
  std::string text = lobe::shadeops::format_values(*env, fmt, codes, args);
  std::lock_guard<std::mutex> lock(mutex);
  std::FILE* f = std::fopen(file ? file : "", "a");
  if (!f) {
    if (sg && sg->context)
      sg->context->error(std::string("fprintf: cannot open \"") + (file ? file : "") + "\"");
    return;
  }
  std::fwrite(text.data(), 1, text.size(), f);
  std::fclose(f);
}

// An out-of-range array or component index (the generated code clamps it), worded as OSL:
// "Index [5] out of range a[0..2]: f.osl:3 (group g, layer 0 l, shader s)". `what` names the
// indexed symbol, `where` is the parenthesised layer description.
void lobe_range_error(ShaderGlobals* sg, int index, int length, const char* what, const char* file,
                      int line, const char* where) {
  if (sg && sg->context)
    guarded(sg, [&] {
      sg->context->error("Index [" + std::to_string(index) + "] out of range " + what + "[0.." +
                         std::to_string(length - 1) + "]: " + file + ":" + std::to_string(line) +
                         " " + where);
    });
}

// A loop's back edges ran out of their chunk (codegen.h, GroupPlan::loop_count_offset): adds
// the chunk to the shade's count and returns the next chunk, or 0 to stop the shade: past
// `limit` (0: none), with an error naming the shader and the loop; when the context is
// cancelled, or the shade was stopped already, silently.
int64_t lobe_loop_check(ShaderGlobals* sg, int64_t* count, int64_t chunk, int64_t limit,
                        const char* shader, const char* where, const char* file, int line) {
  *count += chunk;
  lobe::ShadingContext* ctx = sg ? sg->context : nullptr;
  if (ctx && ctx->stopped) return 0;
  bool cancelled = ctx && ctx->cancel && ctx->cancel->load(std::memory_order_relaxed);
  bool over = limit > 0 && *count >= limit;
  if (!cancelled && !over) return chunk;
  if (ctx) {
    ctx->stopped = true;
    if (over)
      ctx->error("shader " + std::string(shader) + " (" + where + "): loop at " + file + ":" +
                 std::to_string(line) + " ran more than " + std::to_string(limit) +
                 " iterations (max_loop_iterations); stopped");
  }
  return 0;
}

// debug_nan: `vals` is a float-based symbol's storage, `ncomps` floats per plane (all elements'
// components), three planes if `derivs`. Components [first, first + count) of each plane are
// checked; the first NaN or Inf found is reported as OSL words it, "Detected inf value in x at
// f.osl:3 (op mul)" ("the derivatives of x" for a derivative plane), and the check stops.
void lobe_naninf_check(ShaderGlobals* sg, const float* vals, int ncomps, int derivs, int first,
                       int count, const char* symbol, const char* file, int line,
                       const char* opname) {
  for (int d = 0; d < (derivs ? 3 : 1); ++d)
    for (int c = first; c < first + count; ++c) {
      float v = vals[d * ncomps + c];
      if (std::isfinite(v)) continue;
      const char* text =
          std::isnan(v) ? (std::signbit(v) ? "-nan" : "nan") : (v < 0 ? "-inf" : "inf");
      if (sg && sg->context)
        sg->context->error(std::string("Detected ") + text + " value in " +
                           (d ? "the derivatives of " : "") + symbol + " at " + file + ":" +
                           std::to_string(line) + " (op " + opname + ")");
      return;
    }
}

// debug_uninit: before an op reads components [first, first + count) of a symbol's value
// (`kind` 0: floats, 1: ints, 2: strings), those still holding the "uninitialised" marker
// (a non-finite float, INT_MIN, the marker string) are set to zero ("") and the read is
// reported as OSL words it: "Detected possible use of uninitialized value in float x at
// f.osl:5 (group g, layer 0 l, shader s, op 3 'add', arg 1)". `where` is "group g, layer 0 l,
// shader s".
void lobe_uninit_check(ShaderGlobals* sg, RuntimeEnv* env, void* vals, int kind, int first,
                       int count, const char* type, const char* symbol, const char* file, int line,
                       const char* where, int opnum, const char* opname, int argnum) {
  bool found = false;
  for (int c = first; c < first + count; ++c) {
    if (kind == 0) {
      float* f = static_cast<float*>(vals) + c;
      if (!std::isfinite(*f)) *f = 0.0f, found = true;
    } else if (kind == 1) {
      int* i = static_cast<int*>(vals) + c;
      if (*i == std::numeric_limits<int>::min()) *i = 0, found = true;
    } else {
      const char** s = static_cast<const char**>(vals) + c;
      if (*s && std::strcmp(*s, lobe::shadeops::kUninitializedString) == 0)
        *s = env->strings.intern(""), found = true;
    }
  }
  if (found && sg && sg->context)
    sg->context->error(std::string("Detected possible use of uninitialized value in ") + type +
                       " " + symbol + " at " + file + ":" + std::to_string(line) + " (" + where +
                       ", op " + std::to_string(opnum) + " '" + opname + "', arg " +
                       std::to_string(argnum) + ")");
}

const char* lobe_concat(RuntimeEnv* env, const char* a, const char* b) {
  thread_local std::string text; // keeps its capacity
  if (!env->strings.room(std::strlen(a) + std::strlen(b))) return env->strings.empty();
  text.assign(a).append(b);
  return env->strings.intern(text);
}

int lobe_strlen(const char* s) { return int(std::strlen(s)); }

// OSL substr: a negative start counts from the end; the range is clipped to the string.
const char* lobe_substr(RuntimeEnv* env, const char* s, int start, int len) {
  int n = int(std::strlen(s));
  if (start < 0) start += n;
  if (start < 0) start = 0;
  if (start > n) start = n;
  if (len < 0) len = 0;
  if (len > n - start) len = n - start;
  return env->strings.intern(std::string_view(s + start, size_t(len)));
}

// Byte by byte: prefixes are short, shorter than strlen + strncmp's two calls.
int lobe_startswith(const char* s, const char* prefix) {
  for (; *prefix; ++s, ++prefix)
    if (*s != *prefix) return 0;
  return 1;
}

int lobe_endswith(const char* s, const char* suffix) {
  size_t n = std::strlen(s), m = std::strlen(suffix);
  return m <= n && std::strcmp(s + n - m, suffix) == 0;
}

// A number outside int's range saturates (OSL 1.13.12: stoi("3000000000") is 2147483647).
int lobe_stoi(const char* s) {
  long long v = std::strtoll(s, nullptr, 10);
  return int(std::clamp<long long>(v, INT_MIN, INT_MAX));
}
float lobe_stof(const char* s) { return std::strtof(s, nullptr); }
// The byte's value as a signed char, as OSL's (getchar("é", 0) is -61 in OSL 1.13.12).
int lobe_getchar(const char* s, int i) {
  int n = int(std::strlen(s));
  return (i >= 0 && i < n) ? int(static_cast<signed char>(s[i])) : 0;
}

// hash(string): OSL returns int(ustring(s).hash()), and OIIO's ustring hash is
// Strutil::strhash (an inlined farmhash; "" hashes to 0). The header-only function is used, so
// this needs OIIO's headers but not its libraries.
int lobe_strhash(const char* s) {
  return static_cast<int>(static_cast<uint32_t>(OIIO::Strutil::strhash(std::string_view(s))));
}

// split(s, results[n], sep, maxsplit): the pieces of s, as Python's s.split(sep) with at most
// maxsplit pieces (maxsplit clamped to [0, n]; the last piece is the unsplit rest), written to
// results[0..count); the rest of the array is left alone. An empty sep splits at runs of
// whitespace (space, tab, newline, carriage return: not C's vertical tab or form feed, as in
// OSL 1.13.12) and drops empty pieces; an empty s has no pieces (as in OSL).
int lobe_split(RuntimeEnv* env, const char* s, const char* sep, int maxsplit, const char** results,
               int n) {
  std::string_view str(s ? s : ""), by(sep ? sep : "");
  int max = std::clamp(maxsplit, 0, n), count = 0;
  auto emit = [&](std::string_view piece) { results[count++] = env->strings.intern(piece); };
  if (max == 0 || str.empty()) return 0;
  size_t i = 0, len = str.size();
  if (by.empty()) {
    auto space = [&](size_t k) {
      char c = str[k];
      return c == ' ' || c == '\t' || c == '\n' || c == '\r';
    };
    while (count < max - 1) {
      while (i < len && space(i)) ++i;
      if (i == len) break;
      size_t j = i;
      while (i < len && !space(i)) ++i;
      emit(str.substr(j, i - j));
    }
    while (i < len && space(i)) ++i;
    if (i < len) emit(str.substr(i));
    return count;
  }
  size_t j = 0;
  while (count < max - 1 && i + by.size() <= len) {
    if (str.compare(i, by.size(), by) == 0) {
      emit(str.substr(j, i - j));
      i = j = i + by.size();
    } else {
      ++i;
    }
  }
  emit(str.substr(j));
  return count;
}

// regex_search / regex_match (ECMAScript syntax); an invalid pattern matches nothing.
// std::regex throws on bad patterns: caught in RegexCache, never inside LLVM frames.
int lobe_regex(const char* s, const char* pattern, int full_match) {
  return lobe::shadeops::RegexCache::local().matches(s, pattern, full_match != 0);
}

// regex_search / regex_match (subject, int results[n], pattern): results[2k], results[2k+1] are
// the begin and end byte offsets of sub-match k (k = 0 the whole match), as many as fit; entries
// past the last sub-match (all of them when nothing matched) get the pattern's length, as OSL's
// osl_regex_impl writes. An invalid pattern matches nothing.
int lobe_regex_results(const char* s, const char* pattern, int full_match, int* results, int n) {
  int matched = 0, nsub = 0;
  std::cmatch m;
  if (const std::regex* re = lobe::shadeops::RegexCache::local().compiled(pattern)) {
    try {
      matched = full_match ? std::regex_match(s, m, *re) : std::regex_search(s, m, *re);
      nsub = matched ? int(m.size()) : 0;
    } catch (...) {
      matched = 0;
    }
  }
  for (int r = 0; r < n; ++r) {
    const std::csub_match* k = r / 2 < nsub ? &m[size_t(r / 2)] : nullptr;
    results[r] = k ? int(((r & 1) ? k->second : k->first) - s) : int(std::strlen(pattern));
  }
  return matched;
}

} // extern "C"
