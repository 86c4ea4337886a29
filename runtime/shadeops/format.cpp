// OSL printf formatting (see format.h).
#include "format.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

namespace lobe::shadeops {
namespace {

struct ArgDesc {
  char code = 'f';
  int count = 1; // array length (1 for a scalar)
};

// Splits "f{3}ts" into argument descriptions.
ArgDesc next_arg(std::string_view codes, size_t& pos) {
  ArgDesc d;
  if (pos >= codes.size()) return {0, 0};
  d.code = codes[pos++];
  if (pos < codes.size() && codes[pos] == '{') {
    d.count = std::atoi(std::string(codes.substr(pos + 1)).c_str());
    pos = codes.find('}', pos) + 1;
  }
  return d;
}

int components(char code) { return code == 't' ? 3 : (code == 'm' ? 16 : 1); }

// C's printf of one value with `spec`, whatever its length (a width or precision of hundreds
// prints in full, as OSL's does).
template <class T> std::string printf1(const std::string& spec, T v) {
  char buf[512];
  int n = std::snprintf(buf, sizeof buf, spec.c_str(), v);
  if (n < int(sizeof buf)) return n < 0 ? std::string() : std::string(buf, size_t(n));
  std::string out(size_t(n) + 1, '\0');
  std::snprintf(out.data(), out.size(), spec.c_str(), v);
  out.resize(size_t(n));
  return out;
}

std::string closure_text(const RuntimeEnv& env, const ClosureNode* c) {
  if (env.closure_printer) return env.closure_printer(c);
  if (!c) return "(null)";
  return "closure#" + std::to_string(c->id);
}

// Where the flags of a conversion spec (`head`, from its `%`) end: the width follows.
size_t flags_end(const std::string& head) {
  size_t k = 1;
  while (k < head.size() && std::strchr("-+ #0", head[k])) ++k;
  return k;
}

// Pads `body` to the spec's width: left-aligned unless `right`, with zeros when `zeros`; a
// right-aligned body's zeros go after its first `sign` characters (a sign, a 0x prefix).
std::string pad(const std::string& head, std::string body, bool right, bool zeros,
                size_t sign = 0) {
  size_t w = size_t(std::atoi(head.c_str() + flags_end(head)));
  if (body.size() >= w) return body;
  size_t n = w - body.size();
  char fill = zeros ? '0' : ' ';
  return right ? body.insert(zeros ? std::min(sign, body.size()) : 0, n, fill)
               : body.append(n, fill);
}

// A string through OSL's printf: truncated to the precision and, unlike C, left-aligned in its
// width (OSL 1.13 prints "%10s" of "str" as "str       "); a 0 flag pads with zeros on the left.
// Through format() it is right-aligned, as in C, unless the - flag says otherwise.
// Width and precision count UTF-8 characters, not bytes, as OSL's printf and folded format()
// do ("%5s" of "é" pads four spaces, "%.1s" keeps the whole "é"); format() run while shading
// counts bytes, as OSL's does (its "%.1s" of "日本" is one byte of 日).
std::string format_string(const std::string& head, const char* s, FormatRule rule) {
  std::string body = s ? s : "";
  auto continuation = [rule](char c) {
    return rule != FormatRule::Format && (static_cast<unsigned char>(c) & 0xC0) == 0x80;
  };
  size_t dot = head.find('.');
  if (dot != std::string::npos) {
    size_t keep = size_t(std::max(0, std::atoi(head.c_str() + dot + 1))), at = 0;
    for (size_t chars = 0; at < body.size() && chars < keep; ++chars)
      for (++at; at < body.size() && continuation(body[at]);) ++at;
    body.resize(at);
  }
  size_t extra = size_t(std::count_if(body.begin(), body.end(), continuation));
  bool left = head.find('-') != std::string::npos;
  bool zeros = head.find('0') != std::string::npos && !left &&
               head.find_first_of("0") < head.find_first_of("123456789.");
  std::string h = head.substr(0, dot);
  if (extra) { // widen the field by the bytes that are not characters of their own
    size_t k = flags_end(h);
    if (k < h.size()) h = h.substr(0, k) + std::to_string(std::atoi(h.c_str() + k) + int(extra));
  }
  return pad(h, body, zeros || (rule != FormatRule::Printf && !left), zeros);
}

// Whether `v` lies exactly halfway between two values of the conversion's precision: its exact
// decimal expansion (a float's has at most 149 fractional digits and 112 significant ones) has
// a 5 and nothing after it at the first digit the conversion drops.
bool exact_tie(const std::string& head, char conv, double v) {
  if (!std::isfinite(v)) return false;
  size_t dot = head.find('.');
  int prec = dot == std::string::npos ? 6 : std::max(0, std::atoi(head.c_str() + dot + 1));
  char buf[400];
  std::string digits; // the exact digits, without the point, and where the conversion cuts them
  size_t cut;
  if (conv == 'f' || conv == 'F') { // after `prec` fractional digits
    std::snprintf(buf, sizeof buf, "%.160f", std::fabs(v));
    const char* point = std::strchr(buf, '.');
    if (!point) return false;
    digits = point + 1;
    cut = size_t(prec);
  } else { // e, E, g, G: after prec + 1 significant digits for e, prec (1 for 0) for g
    std::snprintf(buf, sizeof buf, "%.160e", std::fabs(v));
    digits.assign(buf, std::strcspn(buf, "eE"));
    digits.erase(std::remove(digits.begin(), digits.end(), '.'), digits.end());
    cut = size_t((conv == 'e' || conv == 'E') ? prec + 1 : std::max(prec, 1));
  }
  if (cut >= digits.size() || digits[cut] != '5') return false;
  return digits.find_first_not_of('0', cut + 1) == std::string::npos;
}

// A float through format() while shading: C's conversion, but an exact tie rounds away from
// zero (C rounds it to even) and the # flag is ignored.
std::string format_float_runtime(std::string head, char conv, double v) {
  head.erase(std::remove(head.begin(), head.end(), '#'), head.end());
  if (exact_tie(head, conv, v)) // the next double away from zero is past the tie, not on it
    v = std::nextafter(v, v < 0 ? -INFINITY : INFINITY);
  return printf1(head + conv, v);
}

// An int through OSL's format() (printf's are printf_value's): ints are 32 bits, %x and %X
// print them unsigned (-1 is ffffffff), %o too (-8 is 37777777770), and every other conversion
// prints a decimal with C's width and precision ("%8.3f" of -1 is "    -001"). Unlike C, an
// explicit zero precision prints a zero through %d as "0"; folded (a constant format() at -O2)
// also through %x and %o, and the + and space flags sign %x and %X ("%+x" of 5 is "+5", of -5
// "+fffffffb", "%+05X" of 5 "+0005"), which format() run while shading ignores, as C does.
std::string format_int(const std::string& head, char conv, int32_t v, FormatRule rule) {
  const bool folded = rule == FormatRule::FormatFolded;
  std::string h = head;
  if (size_t dot = h.find('.'); v == 0 && dot != std::string::npos &&
                                std::atoi(h.c_str() + dot + 1) == 0 && rule != FormatRule::Printf &&
                                (folded || std::strchr("di", conv)))
    h.erase(dot);
  const size_t fe = flags_end(h);
  const std::string flags = h.substr(1, fe - 1);
  if (conv == 'x' || conv == 'X' || conv == 'o') {
    unsigned u = unsigned(uint32_t(v));
    bool plus = flags.find('+') != std::string::npos, space = flags.find(' ') != std::string::npos;
    if (conv == 'o' || !folded || (!plus && !space)) return printf1(h + conv, u);
    std::string rest = "%"; // the spec without its sign flags and width
    if (flags.find('#') != std::string::npos) rest += '#';
    if (size_t dot = h.find('.'); dot != std::string::npos) rest += h.substr(dot);
    std::string body(1, plus ? '+' : ' ');
    body += printf1(rest + conv, u);
    bool left = flags.find('-') != std::string::npos;
    bool zeros = !left && flags.find('0') != std::string::npos && h.find('.') == std::string::npos;
    // Zeros go after the sign and a 0x prefix ("%+#08x" of 5 is "+0x00005").
    size_t sign = body.compare(1, 2, conv == 'x' ? "0x" : "0X") == 0 ? 3 : 1;
    return pad(h, body, !left, zeros, sign);
  }
  return printf1(h + 'd', int(v));
}

// C's %#g, but with a digit after a point that ends the number, as OSL's folded format() prints
// it ("%#g" of 100000 is "100000.0", "%#.1g" of 2 is "2.0"; with an exponent C's "1.e+10" stays);
// also a %#G that a format string known only while shading gives printf.
std::string alt_general(const std::string& head, char conv, double v) {
  size_t fe = flags_end(head), dot = head.find('.', fe);
  std::string bare = head.substr(0, fe) + (dot == std::string::npos ? "" : head.substr(dot));
  std::string body = printf1(bare + conv, v);
  if (!body.empty() && body.back() == '.') body += '0';
  return pad(head, body, head.find('-') == std::string::npos, false);
}

// An infinity or NaN through a float conversion: C's text ("inf", "-nan", with the + and space
// flags), but OSL's printf aligns it left in its width unless the 0 flag is given ("%5g" of inf
// is "inf  ", "%05g" is "  inf"), and its format() run while shading spells it "Inf", "NaN"
// (right-aligned, as C); its folded format() prints C's text.
std::string format_nonfinite(const std::string& head, char conv, double v, FormatRule rule) {
  std::string flags = head.substr(1, flags_end(head) - 1), spec = "%";
  spec += flags;
  spec += conv;
  std::string body = printf1(spec, v);
  if (rule == FormatRule::Format)
    for (const char* word : {"inf", "nan", "INF", "NAN"})
      if (size_t at = body.find(word); at != std::string::npos)
        body.replace(at, 3, std::isinf(v) ? "Inf" : "NaN");
  bool left = flags.find('-') != std::string::npos ||
              (rule == FormatRule::Printf && flags.find('0') == std::string::npos);
  return pad(head, body, !left, false);
}

// The length modifiers of a conversion: none, a lone L (which OSL's printf ignores), or any
// other (l, h, ll, j, z, t, q, ...), after which OSL's printf drops the conversion's type.
// format() knows only whether there is one (a float through an int conversion after one prints
// as %g, format_scalar).
enum class Length { None, LoneL, Other };

// One value through OSL's printf (and warning(), error(), fprintf()), which formats as the fmt
// library (9.x, OSL's) does a spec made of the printf one: its flags in their order with '-' as
// '<' (so "%-05d" of 5 is "50000" and "%+-5d" is "5++++"), the width, the precision and the
// conversion's type, or no type after a length modifier other than a lone L ("%lf" of 2.25 is
// the shortest "2.25", "%.2lf" two significant digits, "%lx" of -5 the unsigned value in
// decimal). Hence fmt's own rules: strings align left and their widths count display columns
// (two for East Asian wide characters), infinities and NaNs align left, + and space apply to
// %x, "%#x" of 0 is "0x0", "%#g" keeps a ".0". An int's 32 bits print unsigned through %x and
// %X, with sign and magnitude through %o. Where fmt has no such spec OSL's printf differs: a 0
// flag pads a string with zeros (on the right after '-'); an int's precision is its least
// number of digits, as in C, but the 0 flag still pads ("%08.3d" of 5 is "00000005") and
// "%.0d" of 0 is "0". A spec fmt refuses prints the value as fmt's "{}" (OSL 1.13.12's
// output, probed flag by flag; a '.' without digits is dropped).
std::string printf_value(std::string head, char conv, Length length, char code, const void* p) {
  const size_t fe = flags_end(head);
  // A '.' without digits is no precision at all ("%.f" of 2.5 is 2.500000).
  if (size_t d = head.find('.', fe); d != std::string::npos && d + 1 == head.size()) head.erase(d);
  const std::string flags = head.substr(1, fe - 1);
  const size_t dot = head.find('.', fe);
  const std::string width =
      head.substr(fe, dot == std::string::npos ? std::string::npos : dot - fe);
  const bool general = length == Length::Other, minus = flags.find('-') != std::string::npos,
             zero = flags.find('0') != std::string::npos;
  auto run = [](const std::string& spec, auto v) {
    try {
      return fmt::format(fmt::runtime("{:" + spec + "}"), v);
    } catch (const std::exception&) {
      return fmt::format("{}", v);
    }
  };
  if (code == 's') {
    const char* s = *static_cast<const char* const*>(p);
    std::string rest;
    for (char c : flags)
      if (c != '-' && c != '0') rest += c;
    std::string spec = (zero ? (minus ? "0<" : "0>") : (minus ? "<" : "")) + rest + head.substr(fe);
    if (!general) spec += 's';
    return run(spec, s ? s : "");
  }
  std::string spec;
  for (char c : flags) spec += c == '-' ? '<' : c;
  if (code == 'i') {
    int32_t v = *static_cast<const int32_t*>(p);
    bool as_unsigned = conv == 'x' || conv == 'X';
    int64_t wide = as_unsigned ? int64_t(uint32_t(v)) : int64_t(v);
    char type = conv == 'x' || conv == 'X' || conv == 'o' ? conv : 'd';
    if (general) return run(spec + width, wide);
    if (dot == std::string::npos) return run(spec + width + type, wide);
    // A precision: C's least number of digits, then OSL's padding.
    uint64_t mag =
        as_unsigned ? uint64_t(uint32_t(v)) : (v < 0 ? 0 - uint64_t(int64_t(v)) : uint64_t(v));
    std::string digits = fmt::format(fmt::runtime(std::string("{:") + type + "}"), mag);
    size_t prec = size_t(std::max(0, std::atoi(head.c_str() + dot + 1)));
    if (digits.size() < prec) digits.insert(0, prec - digits.size(), '0');
    std::string prefix = !as_unsigned && v < 0                  ? "-"
                         : flags.find('+') != std::string::npos ? "+"
                         : flags.find(' ') != std::string::npos ? " "
                                                                : "";
    if (flags.find('#') != std::string::npos) {
      if (conv == 'x' || conv == 'X') prefix += conv == 'x' ? "0x" : "0X";
      if (conv == 'o' && digits[0] != '0') digits.insert(0, 1, '0');
    }
    return pad(head, prefix + digits, !minus, zero, prefix.size());
  }
  float v = *static_cast<const float*>(p);
  return run(spec + head.substr(fe) + (general ? std::string() : std::string(1, conv)), v);
}

// Formats one scalar component with conversion `conv` and the spec's flags (`head` is the
// spec without its conversion character). A literal format string was checked by the type
// checker (OSL's rules); one known only at run time may pair any conversion with any value,
// which converts as OSL does: a float to an int conversion truncates, an int to a float one
// widens, and %s prints a number as %g would.
std::string format_scalar(const RuntimeEnv& env, const std::string& head, char conv,
                          Length length_kind, char code, const void* p, FormatRule rule) {
  const bool length = length_kind != Length::None;
  bool int_conv = conv == 'd' || conv == 'i' || conv == 'x' || conv == 'X' || conv == 'o' ||
                  conv == 'u' || conv == 'c';
  if (rule == FormatRule::Printf && code != 'c' &&
      (length_kind == Length::Other || code == 's' ||
       (code == 'i' ? std::strchr("dioxX", conv) : std::strchr("feg", conv))))
    return printf_value(head, conv, length_kind, code, p);
  if (code == 's') return format_string(head, *static_cast<const char* const*>(p), rule);
  if (code == 'c') { // a closure prints its whole tree, ignoring width and precision (as OSL)
    auto* node = *static_cast<const ClosureNode* const*>(p);
    return closure_text(env, node);
  }
  if (code == 'i') return format_int(head, conv, *static_cast<const int32_t*>(p), rule);
  // A float: its own conversions as in C; any other prints as %f, or %g after a length
  // modifier ("%ld" of -3.75 is -3.75), as OSL 1.13 does.
  double v = *static_cast<const float*>(p);
  if (!std::isfinite(v) && std::strchr("fFgGeE", conv))
    return format_nonfinite(head, conv, v, rule);
  if (rule == FormatRule::Format && std::strchr("fFgGeE", conv))
    return format_float_runtime(head, conv, v);
  if ((conv == 'g' || conv == 'G') && head.find('#') != std::string::npos)
    return alt_general(head, conv, v);
  if (std::strchr("fFgGeEaA", conv)) return printf1(head + conv, v);
  return printf1(head + (int_conv && length ? 'g' : 'f'), v);
}

// A flag, width or precision character of a conversion spec: one of "-+ #0123456789.*".
bool is_spec_char(char c) {
  return (c >= '0' && c <= '9') || c == '-' || c == '+' || c == ' ' || c == '#' || c == '.' ||
         c == '*';
}

// A length modifier: one of "hlLqjzt".
bool is_length_char(char c) {
  return c == 'h' || c == 'l' || c == 'L' || c == 'q' || c == 'j' || c == 'z' || c == 't';
}

// The conversions shaders use most, a bare "%d" of an int or "%s" of a string (no flags,
// width, precision or length), appended without snprintf or temporaries; false for any other,
// which takes the general path. The text is the general path's: "%d" (and every conversion
// but %x, %X and %o) of an int is its decimal, "%s" of a string the string itself.
bool append_bare(std::string& out, char conv, char code, const void* p) {
  if (code == 's') {
    const char* s = *static_cast<const char* const*>(p);
    out += s ? s : "";
    return true;
  }
  if (code != 'i' || conv == 'x' || conv == 'X' || conv == 'o') return false;
  char buf[16];
  auto r = std::to_chars(buf, buf + sizeof buf, *static_cast<const int32_t*>(p));
  out.append(buf, size_t(r.ptr - buf));
  return true;
}

// Appends a whole argument: every component of every element, space-separated (the elements of
// a closure array run together, as OSL prints them). `head` is the spec without its length
// modifier and conversion ("%08.3").
// Out of line: its general path's temporaries would burden the bare conversions' caller.
__attribute__((noinline)) void append_arg(std::string& out, const RuntimeEnv& env,
                                          std::string_view head, char conv, Length length,
                                          ArgDesc d, const void* p, FormatRule rule) {
  size_t stride = (d.code == 's' || d.code == 'c') ? sizeof(void*) : 4;
  int n = components(d.code) * d.count;
  bool bare = head.size() == 1;
  std::string spec;
  for (int k = 0; k < n; ++k) {
    if (k && d.code != 'c') out += ' ';
    const void* c = static_cast<const char*>(p) + k * stride;
    if (bare && append_bare(out, conv, d.code, c)) continue;
    if (spec.empty()) spec = head;
    out += format_scalar(env, spec, conv, length, d.code, c, rule);
  }
}

// The whole format when it is plain text and bare conversions of scalars the bare path takes
// ("tile_%d_%d", "%s_%s"), built in a stack buffer and appended once; false, having appended
// nothing, when it holds anything else (flags, arrays, floats, a missing argument, more than
// the buffer holds), which the general loop then formats.
bool append_all_bare(std::string& out, std::string_view fmt, std::string_view codes,
                     const void* const* args) {
  char buf[256];
  size_t n = 0, argi = 0;
  for (size_t i = 0; i < fmt.size(); ++i) {
    char c = fmt[i];
    if (c == '%') {
      if (i + 1 == fmt.size()) return false;
      c = fmt[++i];
      if (c != '%') { // a conversion: c is its character
        char code = argi < codes.size() ? codes[argi] : 0;
        if (argi + 1 < codes.size() && codes[argi + 1] == '{') return false; // an array
        if (code == 'i' && (c == 'd' || c == 'i')) {
          if (n + 11 > sizeof buf) return false;
          n = size_t(
              std::to_chars(buf + n, buf + sizeof buf, *static_cast<const int32_t*>(args[argi]))
                  .ptr -
              buf);
        } else if (code == 's' && c == 's') {
          const char* s = *static_cast<const char* const*>(args[argi]);
          if (!s) s = "";
          size_t len = std::strlen(s);
          if (len > sizeof buf - n) return false;
          std::memcpy(buf + n, s, len);
          n += len;
        } else {
          return false;
        }
        ++argi;
        continue;
      }
    }
    if (n == sizeof buf) return false;
    buf[n++] = c;
  }
  out.append(buf, n);
  return true;
}

} // namespace

void append_formatted(std::string& out, const RuntimeEnv& env, std::string_view fmt,
                      std::string_view codes, const void* const* args, FormatRule rule) {
  if (append_all_bare(out, fmt, codes, args)) return;
  size_t argpos = 0;
  int argi = 0;
  for (size_t i = 0; i < fmt.size(); ++i) {
    if (fmt[i] != '%') { // a run of plain text, up to the next conversion
      size_t next = std::min(fmt.find('%', i), fmt.size());
      out.append(fmt.substr(i, next - i));
      i = next - 1;
      continue;
    }
    if (i + 1 < fmt.size() && fmt[i + 1] == '%') {
      out += '%';
      ++i;
      continue;
    }
    // %[flags][width][.precision][length]conversion
    size_t j = i + 1;
    while (j < fmt.size() && is_spec_char(fmt[j])) ++j;
    std::string_view head = fmt.substr(i, j - i);
    size_t length_at = j;
    while (j < fmt.size() && is_length_char(fmt[j]))
      ++j; // length modifiers are meaningless for shader types
    std::string_view mods = fmt.substr(length_at, j - length_at);
    Length length = mods.empty() ? Length::None : mods == "L" ? Length::LoneL : Length::Other;
    if (j >= fmt.size()) {
      out += fmt.substr(i);
      break;
    }
    char conv = fmt[j];
    ArgDesc d = next_arg(codes, argpos);
    if (d.code == 0) {
      out += fmt.substr(i, j - i + 1); // more conversions than arguments: print them verbatim
    } else if (head.size() == 1 && d.count == 1 && append_bare(out, conv, d.code, args[argi])) {
      ++argi;
    } else {
      append_arg(out, env, head, conv, length, d, args[argi++], rule);
    }
    i = j;
  }
}

std::string format_values(const RuntimeEnv& env, std::string_view fmt, std::string_view codes,
                          const void* const* args, FormatRule rule) {
  std::string out;
  append_formatted(out, env, fmt, codes, args, rule);
  return out;
}

namespace {
// A remembered format (format_interned): `serial` names the string table (0: empty slot).
struct FormatMemo {
  uint64_t serial = 0;
  const char* fmt = nullptr;
  FormatRule rule = FormatRule::Format;
  std::string fmt_text;
  int count = 0;
  std::array<int32_t, kMemoInts> ints{};
  const char* result = nullptr;
};
constexpr size_t kFormatMemoSlots = 256;
} // namespace

const char* format_interned(RuntimeEnv& env, const char* fmt, const char* codes,
                            const void* const* args) {
  thread_local std::string text; // keeps its capacity
  FormatRule rule = FormatRule::Format;
  if (codes[0] == kFormatRuntimeCode || codes[0] == kFormatFoldedCode)
    rule = *codes++ == kFormatFoldedCode ? FormatRule::FormatFolded : FormatRule::Format;
  // The memo's key: up to kMemoInts scalar ints ("", "i", "ii", ...), the format and the rule
  // (folded, "%+x" of 5 is "+5"; run while shading, "5").
  int count = 0;
  std::array<int32_t, kMemoInts> ints{};
  while (count < kMemoInts && codes[count] == 'i' && codes[count + 1] != '{') {
    ints[size_t(count)] = *static_cast<const int32_t*>(args[count]);
    ++count;
  }
  FormatMemo* memo = nullptr;
  if (codes[count] == 0) {
    thread_local std::array<FormatMemo, kFormatMemoSlots> memos;
    uint64_t h = uint64_t(uintptr_t(fmt)) * 0x9E3779B97F4A7C15ull;
    for (int k = 0; k < count; ++k) h = (h ^ uint32_t(ints[size_t(k)])) * 0x9E3779B97F4A7C15ull;
    memo = &memos[(h >> 32) % kFormatMemoSlots];
    if (memo->serial == env.strings.serial() && memo->fmt == fmt && memo->rule == rule &&
        memo->count == count && memo->ints == ints && memo->fmt_text == fmt)
      return memo->result;
  }
  text.clear();
  append_formatted(text, env, fmt, codes, args, rule);
  const char* result = env.strings.intern(text);
  if (memo) {
    memo->serial = env.strings.serial();
    memo->fmt = fmt;
    memo->rule = rule;
    memo->fmt_text = fmt;
    memo->count = count;
    memo->ints = ints;
    memo->result = result;
  }
  return result;
}

} // namespace lobe::shadeops
