// Piecewise-constant distributions: sampled frequencies match the tabulated function, and
// pdf() agrees with what sample_continuous() reports.
#include "distribution.h"
#include "sampling.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace lobe::render;

TEST(Distribution1D, DiscreteFrequenciesMatchWeights) {
  Distribution1D d({1, 0, 3, 4});
  std::vector<int> count(4, 0);
  const int n = 80000;
  for (int i = 0; i < n; ++i) {
    float p;
    count[d.sample_discrete((i + 0.5f) / n, p)]++;
  }
  EXPECT_EQ(count[1], 0);
  EXPECT_NEAR(count[0] / double(n), 1 / 8.0, 1e-3);
  EXPECT_NEAR(count[2] / double(n), 3 / 8.0, 1e-3);
  EXPECT_NEAR(d.discrete_prob(3), 0.5f, 1e-6);
  EXPECT_FLOAT_EQ(d.integral(), 2.0f);
}

TEST(Distribution1D, ContinuousPdfIsFunctionOverIntegral) {
  Distribution1D d({2, 6});
  float pdf;
  int idx;
  float x = d.sample_continuous(0.5f, pdf, idx); // cdf: 0, .25, 1 -> cell 1
  EXPECT_EQ(idx, 1);
  EXPECT_FLOAT_EQ(pdf, 6.0f / 4.0f);
  EXPECT_NEAR(x, 0.5f + 0.5f * (0.25f / 0.75f), 1e-6);
  EXPECT_FLOAT_EQ(d.pdf(0), 0.5f);
}

TEST(Distribution1D, RemappedUniformStaysUniform) {
  Distribution1D d({1, 1, 2});
  float p, rest;
  int i = d.sample_discrete(0.75f + 0.5f * 0.25f, p, rest); // middle of cell 2 ([0.5, 1))
  EXPECT_EQ(i, 2);
  EXPECT_NEAR(rest, 0.75f, 1e-6);
}

TEST(Distribution1D, GuidedSearchFindsTheCellAtEveryBoundary) {
  // Weights summing to 8: the CDF is exact in float (0, 1/8, 1/8, 1/8, 4/8, 6/8, 6/8, 1), so
  // the cell of u is known: the last i with cdf[i] <= u, zero-width cells skipped. Checked at
  // every multiple of 1/64 (all boundaries included) and just below each.
  Distribution1D d({1, 0, 0, 3, 2, 0, 2});
  const float cdf[8] = {0, 0.125f, 0.125f, 0.125f, 0.5f, 0.75f, 0.75f, 1};
  auto expected = [&](float u) {
    int i = 0;
    for (int k = 0; k < 7; ++k)
      if (cdf[k] <= u) i = k;
    return i;
  };
  for (int k = 0; k < 64; ++k)
    for (float u : {k / 64.0f, std::nextafter(k / 64.0f, 0.0f), std::nextafter(k / 64.0f, 1.0f)}) {
      if (!(u >= 0 && u < 1)) continue;
      float prob;
      EXPECT_EQ(d.sample_discrete(u, prob), expected(u)) << u;
    }
  float prob;
  EXPECT_EQ(d.sample_discrete(0x1.fffffep-1f, prob), 6);
  EXPECT_FLOAT_EQ(prob, 0.25f);
}

TEST(Distribution1D, AllZeroIsUniform) {
  Distribution1D d({0, 0});
  EXPECT_FLOAT_EQ(d.discrete_prob(0), 0.5f);
}

TEST(Distribution2D, PdfIntegratesToOneAndMatchesSamples) {
  std::vector<float> f = {1, 2, 3, 0, 5, 1};
  Distribution2D d(f, 3, 2);
  // Integral of the pdf over the unit square: sum over cells of pdf * cell area (1/6).
  double sum = 0;
  for (int y = 0; y < 2; ++y)
    for (int x = 0; x < 3; ++x) sum += d.pdf((x + 0.5f) / 3, (y + 0.5f) / 2) / 6.0;
  EXPECT_NEAR(sum, 1.0, 1e-5);
  // Expected pdf of cell (1, 1): f / mean(f) = 5 / 2.
  EXPECT_NEAR(d.pdf(0.5f, 0.75f), 2.5f, 1e-5);
  lobe::render::RandomStream s(1, 2, 3);
  for (int i = 0; i < 1000; ++i) {
    float u, v, pdf;
    d.sample(s.next(), s.next(), u, v, pdf);
    ASSERT_GT(pdf, 0);
    EXPECT_NEAR(pdf, d.pdf(u, v), 1e-4 * pdf);
  }
}

TEST(Distribution2D, ARowOfZerosIsNeverSampled) {
  // Rows 0 and 2 of three are zero: they have density 0 and no sample lands in them; the
  // middle row then holds all the mass (density 3 over its third of the square, times f / mean
  // within the row: 3 * 3 / 2 for the cell of weight 3 in {1, 3, 2}).
  std::vector<float> f = {0, 0, 0, 1, 3, 2, 0, 0, 0};
  Distribution2D d(f, 3, 3);
  EXPECT_EQ(d.pdf(0.5f, 0.1f), 0.0f);
  EXPECT_EQ(d.pdf(0.5f, 0.9f), 0.0f);
  EXPECT_NEAR(d.pdf(0.5f, 0.5f), 4.5f, 1e-5);
  lobe::render::RandomStream s(3, 1, 4);
  for (int i = 0; i < 1000; ++i) {
    float u, v, pdf;
    d.sample(s.next(), s.next(), u, v, pdf);
    ASSERT_GE(v, 1.0f / 3) << i;
    ASSERT_LT(v, 2.0f / 3) << i;
    EXPECT_NEAR(pdf, d.pdf(u, v), 1e-4 * pdf);
  }
}

// The row search through the coarse guides finds the cell a plain scan of the row's CDF finds
// (the last i with cdf[i] <= u, skipping zero-width cells), on rows wider than the guide with
// dark runs and a spike: the whole of a row's mass in one cell makes every other cell's guide
// range wide or empty. The continuous position and density follow from the cell.
TEST(Distribution2D, GuidedRowSearchFindsTheScannedCell) {
  const int w = 300, h = 3;
  std::vector<float> f(size_t(w) * h, 0.0f);
  for (int x = 0; x < w; ++x) f[size_t(x)] = 1.0f + float(x % 7);     // row 0: ragged
  f[size_t(w) + 123] = 1000.0f;                                       // row 1: one spike
  f[size_t(w) + 200] = 1e-3f;                                         // and a faint cell
  for (int x = 0; x < w; x += 2) f[size_t(2 * w + x)] = float(x) + 1; // row 2: every other 0
  Distribution2D d(f, w, h);
  std::vector<Distribution1D> rows;
  for (int y = 0; y < h; ++y)
    rows.emplace_back(std::vector<float>(f.begin() + y * w, f.begin() + (y + 1) * w));
  Distribution1D marginal({rows[0].integral(), rows[1].integral(), rows[2].integral()});
  auto scan = [&](int y, float u) {
    int i = 0;
    for (int k = 0; k <= w; ++k)
      if (rows[size_t(y)].cdf(k) <= u) i = k;
    return std::min(i, w - 1);
  };
  lobe::render::RandomStream s(7, 8, 9);
  int checked = 0;
  for (int i = 0; i < 20000; ++i) {
    float u1 = i < 3 ? (i == 0 ? 0.0f : i == 1 ? 0x1.fffffep-1f : 0.5f) : s.next();
    float u2 = s.next();
    float u, v, pdf;
    int x, y;
    d.sample_cell(u1, u2, u, v, x, y);
    float pv;
    int yy;
    marginal.sample_continuous(u2, pv, yy);
    ASSERT_EQ(y, yy);
    ASSERT_EQ(x, scan(y, u1)) << "u1 " << u1 << " row " << y;
    EXPECT_GT(f[size_t(y) * w + x], 0.0f); // never a zero-width cell
    EXPECT_GE(u, float(x) / w);
    EXPECT_LE(u, float(x + 1) / w);
    d.sample(u1, u2, u, v, pdf);
    EXPECT_EQ(pdf, pv * rows[size_t(y)].pdf(x)); // marginal times conditional, as computed
    ++checked;
  }
  EXPECT_EQ(checked, 20000);
}
