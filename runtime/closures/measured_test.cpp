// measured_bsdf: a synthetic MERL file tabulating an analytic BRDF is read back, interpolated
// close to the analytic values, reciprocal; bad files are rejected with a clear error.
#include "closures.h"
#include "measured.h"
#include "test_util.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <unistd.h>

namespace lobe::closures {
namespace {

using test::dir_cos;

// f = 0.1 + 0.5 h_z^8 (reciprocal, smooth): a glossy-ish analytic BRDF.
Vec3 analytic(const Vec3& wi, const Vec3& wo, void*) {
  Vec3 h = normalize(wi + wo);
  float v = 0.1f + 0.5f * std::pow(h.z, 8.0f);
  return {v, 0.5f * v, 0.25f * v};
}

std::string temp_path(const char* tag) {
  return "/tmp/lobe_merl_" + std::to_string(getpid()) + "_" + tag + ".binary";
}

class Measured : public ::testing::Test {
protected:
  static void SetUpTestSuite() {
    path_ = new std::string(temp_path("analytic"));
    ASSERT_TRUE(write_merl(*path_, &analytic, nullptr));
  }
  static void TearDownTestSuite() {
    std::remove(path_->c_str());
    delete path_;
  }
  static std::string* path_;
};
std::string* Measured::path_ = nullptr;

TEST_F(Measured, LoadsAndInterpolates) {
  MeasuredTable t;
  std::string err;
  ASSERT_TRUE(load_merl(*path_, t, err)) << err;
  for (auto [mo, po, mi, pi] : {std::tuple{0.9, 0.1, 0.8, 3.0},
                                {0.5, 0.0, 0.6, 2.5},
                                {0.3, 1.0, 0.7, 4.0},
                                {0.95, 0.0, 0.95, 3.14159}}) {
    Vec3 wo = dir_cos(mo, po), wi = dir_cos(mi, pi);
    Vec3 want = analytic(wi, wo, nullptr), got = t.lookup(wo, wi);
    EXPECT_NEAR(got.x, want.x, 0.02 * want.x) << mo << " " << mi;
    EXPECT_NEAR(got.z, want.z, 0.02 * want.z);
    Vec3 back = t.lookup(wi, wo);
    EXPECT_NEAR(back.y, got.y, 1e-5f * (1 + got.y));
  }
}

TEST_F(Measured, ClosureEvaluatesTheTable) {
  Params p("measured_bsdf");
  p.set("filename", path_->c_str()).set("tint", Vec3{2, 2, 2});
  ASSERT_NE(lobe_flags(p.id(), p.data()), 0u);
  Vec3 wo = dir_cos(0.7, 0.2), wi = dir_cos(0.6, 2.0);
  EXPECT_NEAR(eval(p.id(), p.data(), wo, wi).value.x, 2 * analytic(wi, wo, nullptr).x * wi.z,
              0.04 * analytic(wi, wo, nullptr).x);
  auto s = sample(p.id(), p.data(), wo, {0.3f, 0.6f, 0.1f});
  ASSERT_TRUE(s);
  EXPECT_GT(s->weight.x, 0.0f);
}

// Lambert + normalised Blinn-Phong: f = kd/pi + ks (n + 2)/(8 pi) (n.h)^n, n = 30.
Vec3 lambert_blinn(const Vec3& wi, const Vec3& wo, void*) {
  Vec3 h = normalize(wi + wo);
  double spec = 0.4 * (30.0 + 2.0) / (8.0 * M_PI) * std::pow(std::max(0.0f, h.z), 30.0);
  double v = 0.5 / M_PI + spec;
  return {float(v), float(0.8 * v), float(0.6 * v)};
}

TEST(MeasuredAnalytic, LambertBlinnPhongTableEvaluatesToTheFormula) {
  std::string path = temp_path("lambert_blinn");
  ASSERT_TRUE(write_merl(path, &lambert_blinn, nullptr));
  Params p("measured_bsdf");
  p.set("filename", path.c_str());
  for (auto [mo, po, mi, pi] : {std::tuple{0.9, 0.0, 0.9, 3.14159},
                                {0.7, 0.3, 0.75, 3.3},
                                {0.5, 1.0, 0.4, 2.0},
                                {0.2, 0.0, 0.95, 1.0},
                                {0.6, 0.0, 0.6, 3.0}}) {
    Vec3 wo = dir_cos(mo, po), wi = dir_cos(mi, pi);
    double want = lambert_blinn(wi, wo, nullptr).x * wi.z;
    double got = eval(p.id(), p.data(), wo, wi).value.x;
    EXPECT_NEAR(got, want, 0.03 * want) << mo << " " << mi;
  }
  std::remove(path.c_str());
}

// Overwrites the double at `index` of the data block (after the 12-byte header).
void patch_cell(const std::string& path, long index, double v) {
  FILE* f = std::fopen(path.c_str(), "r+b");
  ASSERT_NE(f, nullptr);
  std::fseek(f, 12 + 8 * index, SEEK_SET);
  std::fwrite(&v, 8, 1, f);
  std::fclose(f);
}

Vec3 all_negative(const Vec3&, const Vec3&, void*) { return {-1, -1, -1}; }

TEST_F(Measured, DataErrorsAreReported) {
  MeasuredTable t;
  std::string err, p = temp_path("patched");
  auto copy = [&] {
    std::string cmd = "cp " + *path_ + " " + p;
    ASSERT_EQ(std::system(cmd.c_str()), 0);
  };
  copy();
  patch_cell(p, 1234567, std::nan(""));
  EXPECT_FALSE(load_merl(p, t, err));
  EXPECT_NE(err.find("non-finite"), std::string::npos) << err;
  copy();
  patch_cell(p, 42, INFINITY);
  EXPECT_FALSE(load_merl(p, t, err));
  EXPECT_NE(err.find("cell 42 of channel 0"), std::string::npos) << err;
  copy();
  FILE* f = std::fopen(p.c_str(), "ab");
  std::fputc(0, f);
  std::fclose(f);
  EXPECT_FALSE(load_merl(p, t, err));
  EXPECT_NE(err.find("wrong size"), std::string::npos) << err;
  ASSERT_TRUE(write_merl(p, &all_negative, nullptr));
  EXPECT_FALSE(load_merl(p, t, err));
  EXPECT_NE(err.find("no valid cell"), std::string::npos) << err;
  // A negative cell is "no data": read as 0, the file loads.
  copy();
  long idx = 3 + 180 * 10 + 16200 * 20; // theta_h 20, theta_d 10, phi_d 3
  patch_cell(p, idx, -1.0);
  ASSERT_TRUE(load_merl(p, t, err)) << err;
  EXPECT_EQ(t.rgb[idx], 0.0f);
  EXPECT_GT(t.rgb[idx + 1], 0.0f);
  std::remove(p.c_str());
}

TEST(MeasuredErrors, BadFilesRejected) {
  MeasuredTable t;
  std::string err;
  EXPECT_FALSE(load_merl("/nonexistent/file.binary", t, err));
  EXPECT_NE(err.find("cannot open"), std::string::npos);
  std::string p = temp_path("bad");
  FILE* f = std::fopen(p.c_str(), "wb");
  int32_t dims[3] = {90, 90, 90};
  std::fwrite(dims, 4, 3, f);
  std::fclose(f);
  EXPECT_FALSE(load_merl(p, t, err));
  EXPECT_NE(err.find("dimensions"), std::string::npos);
  f = std::fopen(p.c_str(), "wb");
  int32_t good[3] = {90, 90, 180};
  std::fwrite(good, 4, 3, f);
  double x = 1.0;
  std::fwrite(&x, 8, 1, f);
  std::fclose(f);
  EXPECT_FALSE(load_merl(p, t, err));
  EXPECT_NE(err.find("truncated"), std::string::npos);
  Params c("measured_bsdf");
  c.set("filename", p.c_str());
  EXPECT_EQ(lobe_flags(c.id(), c.data()), 0u);
  EXPECT_EQ(eval(c.id(), c.data(), dir_cos(0.5), dir_cos(0.5)).value.x, 0.0f);
  std::remove(p.c_str());
}

} // namespace
} // namespace lobe::closures
