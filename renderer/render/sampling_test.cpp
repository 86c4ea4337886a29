// The path sampler (Owen-scrambled Sobol, sampling.h) against closed-form properties: the
// unscrambled points are Sobol's published ones, the scramble is a bijection that keeps
// aligned blocks, and the first 2^m samples of a pixel put exactly one point in every
// elementary interval of area 2^-m in each 2-D group ((0,m,2)-nets), whatever the pixel,
// seed and group. A random sampler fails these with near certainty.
#include "sampling.h"

#include <gtest/gtest.h>

#include <cmath>
#include <set>
#include <vector>

using namespace lobe::render;

TEST(Sobol, FirstPointsAreSobols) {
  // Sobol's sequence in its first two dimensions, direct (not Gray-code) order: dimension 0
  // is van der Corput's radical inverse, dimension 1 applies Pascal's matrix mod 2 (columns
  // 1/2, 3/4, 5/8, ...): (0,0) (1/2,1/2) (1/4,3/4) (3/4,1/4) (1/8,5/8) (5/8,1/8) (3/8,3/8)
  // (7/8,7/8).
  const double want[8][2] = {{0, 0},         {0.5, 0.5},     {0.25, 0.75},   {0.75, 0.25},
                             {0.125, 0.625}, {0.625, 0.125}, {0.375, 0.375}, {0.875, 0.875}};
  for (uint32_t i = 0; i < 8; ++i) {
    EXPECT_EQ(sobol::point(i, 0) * 0x1p-32, want[i][0]) << i;
    EXPECT_EQ(sobol::point(i, 1) * 0x1p-32, want[i][1]) << i;
  }
  // Dimensions 2 and 3 (Joe and Kuo's x^2+x+1, m = {1, 3}; x^3+x+1, m = {1, 3, 1}):
  // points 1..3 are (1/2, 1/2), (3/4, 3/4) / (1/4, 1/4) and (1/4, 3/4) for index 3.
  EXPECT_EQ(sobol::point(1, 2) * 0x1p-32, 0.5);
  EXPECT_EQ(sobol::point(2, 2) * 0x1p-32, 0.75);
  EXPECT_EQ(sobol::point(3, 2) * 0x1p-32, 0.25);
  EXPECT_EQ(sobol::point(1, 3) * 0x1p-32, 0.5);
  EXPECT_EQ(sobol::point(2, 3) * 0x1p-32, 0.75);
  EXPECT_EQ(sobol::point(3, 3) * 0x1p-32, 0.25);
}

TEST(Sobol, OwenScrambleMapsAlignedBlocksOntoAlignedBlocks) {
  // A nested uniform scramble permutes the digits of a fraction: values sharing their top k
  // bits still share them (possibly other ones) afterwards, and distinct values stay distinct.
  for (uint32_t seed : {0u, 1u, 0xdeadbeefu}) {
    std::set<uint32_t> seen;
    for (uint32_t hi = 0; hi < 16; ++hi) {
      uint32_t top = sobol::owen_scramble(hi << 28, seed) >> 28;
      for (uint32_t lo = 0; lo < 64; ++lo) {
        uint32_t x = (hi << 28) | (lo * 0x0400001u & 0x0fffffffu);
        uint32_t y = sobol::owen_scramble(x, seed);
        EXPECT_EQ(y >> 28, top) << seed << " " << x;
        seen.insert(y);
      }
    }
    EXPECT_EQ(seen.size(), 16u * 64u);
  }
}

TEST(Sobol, ReversedDomainIsTheReversedPoint) {
  // point_reversed(y) = reverse(point(reverse(y))), checked bit by bit from the matrices' own
  // columns (not the byte tables either side uses) at indices spread over all 32 bits.
  for (int d = 0; d < 4; ++d)
    for (uint32_t k = 0; k < 4096; ++k) {
      uint32_t index = k * 0x9e3779b9u ^ (k << 20);
      uint32_t want = 0;
      for (int bit = 0; bit < 32; ++bit)
        if ((index >> bit) & 1) want ^= sobol::kMatrices.v[d][bit];
      EXPECT_EQ(sobol::point(index, d), want) << d << " " << index;
      EXPECT_EQ(sobol::point_reversed(sobol::reverse_bits(index), d), sobol::reverse_bits(want))
          << d << " " << index;
    }
}

TEST(Sampler, NumbersAreTheScrambledSobolPointsOfItsDefinition) {
  // Each group: owen_scramble(point(owen_scramble(sample, h), d), seed_d), with h and seed_d the
  // hashes documented in sampling.h, recomputed here in the plain (not reversed) domain.
  for (uint64_t pixel : {0ull, 99ull})
    for (uint64_t s : {0ull, 1ull, 5ull, 1000ull, 65537ull}) {
      Sampler smp(pixel, s, 3);
      uint64_t key = mix64(pixel * 0x9e3779b97f4a7c15ull + mix64(3));
      for (uint64_t g = 1; g <= 3; ++g) {
        lobe::Vec3 got = smp.next3();
        uint64_t h = mix64(key + g * 0xd1b54a32d192ed03ull);
        uint32_t shuffled = sobol::owen_scramble(uint32_t(s), uint32_t(h));
        for (int d = 0; d < 3; ++d) {
          uint32_t seed = uint32_t((d == 0 ? h : mix64(h + uint64_t(d))) >> 32);
          uint32_t x = sobol::owen_scramble(sobol::point(shuffled, d), seed);
          EXPECT_EQ(got[d], float(x >> 8) * 0x1p-24f) << pixel << " " << s << " " << g << " " << d;
        }
      }
    }
}

namespace {

// True when the points fill every elementary interval of shape 2^-a x 2^-(m-a) exactly once.
bool is_net(const std::vector<std::pair<float, float>>& pts, int m) {
  for (int a = 0; a <= m; ++a) {
    std::vector<int> count(size_t(1) << m, 0);
    for (const auto& [x, y] : pts) {
      int i = int(x * float(1 << a)), j = int(y * float(1 << (m - a)));
      if (++count[size_t(i) << (m - a) | size_t(j)] > 1) return false;
    }
  }
  return true;
}

} // namespace

TEST(Sampler, EveryTwoDimensionalGroupIsANetOverAPixelsSamples) {
  const int m = 6; // 64 samples
  for (uint64_t pixel : {0ull, 7ull, 123456ull})
    for (uint64_t seed : {0ull, 42ull})
      for (int group = 0; group < 5; ++group) {
        std::vector<std::pair<float, float>> pts;
        for (uint64_t s = 0; s < (1u << m); ++s) {
          Sampler smp(pixel, s, seed);
          for (int g = 0; g < group; ++g) smp.next();
          float a, b;
          smp.next2(a, b);
          ASSERT_GE(a, 0.0f);
          ASSERT_LT(a, 1.0f);
          ASSERT_LT(b, 1.0f);
          pts.push_back({a, b});
        }
        EXPECT_TRUE(is_net(pts, m)) << pixel << " " << seed << " group " << group;
      }
  // Independent uniforms make a 64-point net with probability about 64!/64^64 (1e-27).
  std::vector<std::pair<float, float>> rnd;
  RandomStream r(1, 2, 3);
  for (int s = 0; s < 64; ++s) {
    float a = r.next();
    rnd.push_back({a, r.next()});
  }
  EXPECT_FALSE(is_net(rnd, m));
}

TEST(Sampler, OneDimensionalGroupsAreStratifiedAndThreeDimensionalPairsAreNets) {
  // 1-D: the first 2^m samples put one number in each interval [k/2^m, (k+1)/2^m).
  // 3-D groups: dimensions (x, y) of next3 (the BSDF's direction pair) form a net too.
  const int m = 5;
  std::vector<int> bins(1u << m, 0);
  std::vector<std::pair<float, float>> xy;
  for (uint64_t s = 0; s < (1u << m); ++s) {
    Sampler smp(99, s, 5);
    ++bins[size_t(smp.next() * float(1 << m))];
    lobe::Vec3 u = smp.next3();
    xy.push_back({u.x, u.y});
  }
  for (int b : bins) EXPECT_EQ(b, 1);
  EXPECT_TRUE(is_net(xy, m));
}

TEST(Sampler, NumbersArePureFunctionsOfPixelSampleSeedAndGroup) {
  Sampler a(3, 9, 1), b(3, 9, 1), c(4, 9, 1), d(3, 9, 2);
  float x = a.next(), y = b.next();
  EXPECT_EQ(x, y);
  EXPECT_NE(x, c.next()); // another pixel is scrambled differently
  EXPECT_NE(x, d.next()); // and so is another seed
  EXPECT_NE(a.next(), x); // the next group is not the same number
}

TEST(Sampler, GroupsDrawnTogetherAreTheGroupsDrawnInTurn) {
  // groups<K>(first, dims) is the numbers of groups first.. first + K - 1 that next(),
  // next2() and next3() give one group at a time (they take groups 1, 2, 3, ...).
  for (uint64_t s : {0ull, 3ull, 77ull}) {
    Sampler turn(12, s, 4), together(12, s, 4);
    float want[7];
    turn.next2(want[0], want[1]);
    lobe::Vec3 u = turn.next3();
    want[2] = u.x, want[3] = u.y, want[4] = u.z;
    want[5] = turn.next();
    want[6] = turn.next();
    float got[7];
    together.groups<4>(1, {2, 3, 1, 1}, got);
    for (int i = 0; i < 7; ++i) EXPECT_EQ(got[i], want[i]) << s << " " << i;
    float third[3];
    together.groups<1>(2, {3}, third); // a group alone, out of turn
    EXPECT_EQ(third[0], want[2]);
    EXPECT_EQ(third[2], want[4]);
  }
}

// fast_atan2 against atan2 in double: within 3e-7 radians at angles spread over the circle
// (every octant, the octant edges tan(pi/8) and 1 where the reduction switches, the axes) and
// over lengths from 1e-30 to 1e30; the exact values at the axes and diagonals; zeros,
// infinities and NaN as std::atan2 gives them.
TEST(FastAtan2, WithinThreeTenthsOfAMicroradian) {
  double worst = 0;
  for (int i = 0; i <= 200000; ++i) {
    const double angle = -M_PI + 2 * M_PI * i / 200000.0;
    for (double len : {1e-30, 1e-3, 1.0, 7.5e4, 1e30}) {
      const float y = float(len * std::sin(angle)), x = float(len * std::cos(angle));
      const double want = std::atan2(double(y), double(x));
      worst = std::max(worst, std::abs(double(fast_atan2(y, x)) - want));
    }
  }
  for (float a : {0.414213562f, 0.41421357f, 0.41421354f, 1.0f, 0.99999994f})
    for (float sy : {-1.0f, 1.0f})
      for (float sx : {-1.0f, 1.0f}) {
        worst = std::max(worst, std::abs(double(fast_atan2(sy * a, sx)) -
                                         std::atan2(double(sy * a), double(sx))));
        worst = std::max(worst, std::abs(double(fast_atan2(sy, sx * a)) -
                                         std::atan2(double(sy), double(sx * a))));
      }
  EXPECT_LT(worst, 3e-7);
  EXPECT_FLOAT_EQ(fast_atan2(0, 1), 0);
  EXPECT_FLOAT_EQ(fast_atan2(1, 0), float(M_PI / 2));
  EXPECT_FLOAT_EQ(fast_atan2(0, -1), float(M_PI));
  EXPECT_FLOAT_EQ(fast_atan2(-1, 0), float(-M_PI / 2));
  EXPECT_FLOAT_EQ(fast_atan2(2, 2), float(M_PI / 4));
  EXPECT_FLOAT_EQ(fast_atan2(-3, -3), float(-3 * M_PI / 4));
  EXPECT_EQ(fast_atan2(0.0f, 0.0f), std::atan2(0.0f, 0.0f));
  EXPECT_EQ(fast_atan2(0.0f, -0.0f), std::atan2(0.0f, -0.0f));
  EXPECT_EQ(fast_atan2(INFINITY, 1.0f), std::atan2(INFINITY, 1.0f));
  EXPECT_EQ(fast_atan2(-INFINITY, -INFINITY), std::atan2(-INFINITY, -INFINITY));
  EXPECT_TRUE(std::isnan(fast_atan2(NAN, 1.0f)));
}
