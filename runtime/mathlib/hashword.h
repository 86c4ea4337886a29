// hash() of numbers, as OSL 1.13 computes it: Bob Jenkins' lookup3 hashword() (public domain,
// burtleburtle.net/bob/c/lookup3.c) over the 32-bit patterns of the arguments, with initval 13;
// the result is the hash as a signed int. Ints hash as they are, floats by their bits (so
// hash(-0.0) != hash(0.0)), a point as x, y, z and hash(point, float) as x, y, z, t.
// Example: hash(0.25) = hashword({0x3e800000}, 13) = -1518044388.
#pragma once

#include <cstdint>
#include <cstring>

namespace lobe::math {

// lookup3's mix() and final() are templates over the word type U: uint32_t, or lanes of words (a
// GCC/Clang vector of uint32_t, e.g. the corners of a noise cell hashed at once), whose
// operations wrap lane by lane as uint32_t does. They work in place, with the rotations written
// out, so that no function passes or returns a vector by value (an ABI that differs between
// SSE and AVX builds).

// lookup3's mix(): three words in, three words out, every input bit affecting every output.
template <class U> inline void lookup3_mix(U& a, U& b, U& c) {
  a -= c, a ^= (c << 4) | (c >> 28), c += b;
  b -= a, b ^= (a << 6) | (a >> 26), a += c;
  c -= b, c ^= (b << 8) | (b >> 24), b += a;
  a -= c, a ^= (c << 16) | (c >> 16), c += b;
  b -= a, b ^= (a << 19) | (a >> 13), a += c;
  c -= b, c ^= (b << 4) | (b >> 28), b += a;
}

// lookup3's final(): the last mixing of (a, b, c), result in c.
template <class U> inline void lookup3_final_in_place(U& a, U& b, U& c) {
  c ^= b, c -= (b << 14) | (b >> 18);
  a ^= c, a -= (c << 11) | (c >> 21);
  b ^= a, b -= (a << 25) | (a >> 7);
  c ^= b, c -= (b << 16) | (b >> 16);
  a ^= c, a -= (c << 4) | (c >> 28);
  b ^= a, b -= (a << 14) | (a >> 18);
  c ^= b, c -= (b << 24) | (b >> 8);
}
inline uint32_t lookup3_final(uint32_t a, uint32_t b, uint32_t c) {
  lookup3_final_in_place(a, b, c);
  return c;
}

inline uint32_t hashword(const uint32_t* k, int n, uint32_t initval) {
  uint32_t a = 0xdeadbeefu + (uint32_t(n) << 2) + initval, b = a, c = a;
  for (; n > 3; n -= 3, k += 3) {
    a += k[0], b += k[1], c += k[2];
    lookup3_mix(a, b, c);
  }
  if (n == 0) return c;
  if (n == 3) c += k[2];
  if (n >= 2) b += k[1];
  a += k[0];
  return lookup3_final(a, b, c);
}

// OSL's hash() of 1 to 4 words (the arguments' bit patterns, in order).
inline int32_t osl_hash(const uint32_t* words, int n) { return int32_t(hashword(words, n, 13)); }

inline uint32_t word_of(float f) {
  uint32_t u;
  std::memcpy(&u, &f, 4);
  return u;
}

} // namespace lobe::math
