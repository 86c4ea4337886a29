// Round trips through real files: EXR keeps every channel exactly (32-bit float), PNG applies
// exposure, tone curve and the sRGB transfer function (checked against the IEC 61966-2-1
// formula evaluated here in double precision).
#include "image.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>

#include <unistd.h>

using namespace lobe::image;

namespace {
std::string temp_path(const std::string& name) {
  return (std::filesystem::temp_directory_path() /
          ("lobe_image_test_" + std::to_string(::getpid()) + "." + name))
      .string();
}
double srgb_reference(double x) {
  return x <= 0.0031308 ? 12.92 * x : 1.055 * std::pow(x, 1 / 2.4) - 0.055;
}
} // namespace

TEST(Image, ExrRoundTripKeepsAovChannels) {
  Image img(3, 2, {"R", "G", "B", "albedo.R", "albedo.G", "albedo.B", "Z"});
  for (size_t i = 0; i < img.pixels.size(); ++i) img.pixels[i] = 0.37f * float(i) - 3.0f;
  std::string path = temp_path("aov.exr");
  ASSERT_EQ(write_image(path, img), "");
  Image back;
  ASSERT_EQ(read_image(path, back), "");
  EXPECT_EQ(back.width, 3);
  EXPECT_EQ(back.height, 2);
  ASSERT_EQ(back.nchannels(), 7);
  // OpenEXR stores channels sorted by name; find each by name rather than by position.
  for (int c = 0; c < 7; ++c) {
    int bc = back.channel(img.channels[c]);
    ASSERT_GE(bc, 0) << img.channels[c];
    for (int y = 0; y < 2; ++y)
      for (int x = 0; x < 3; ++x) EXPECT_EQ(back.pixel(x, y)[bc], img.pixel(x, y)[c]);
  }
  std::remove(path.c_str());
}

TEST(Image, PngIsSrgbEncodedAndClamped) {
  Image img(4, 1, {"R", "G", "B"});
  const float values[4] = {0.0f, 0.002f, 0.214f, 7.0f};
  for (int x = 0; x < 4; ++x)
    for (int c = 0; c < 3; ++c) img.pixel(x, 0)[c] = values[x];
  std::string path = temp_path("srgb.png");
  ASSERT_EQ(write_image(path, img), "");
  Image back;
  ASSERT_EQ(read_image(path, back), "");
  ASSERT_EQ(back.nchannels(), 3);
  // read_image decodes sRGB back to linear: compare in the encoded domain at 8-bit precision.
  for (int x = 0; x < 4; ++x) {
    double expected = std::round(255.0 * srgb_reference(std::min(values[x], 1.0f))) / 255.0;
    EXPECT_NEAR(srgb_encode(back.pixel(x, 0)[0]), expected, 1e-5) << x;
  }
  std::remove(path.c_str());
}

TEST(Image, ExposureScalesBeforeEncoding) {
  Image img(1, 1, {"Y"});
  img.pixels[0] = 0.1f;
  std::string path = temp_path("exposure.png");
  WriteOptions opt;
  opt.exposure = 1; // x2
  ASSERT_EQ(write_image(path, img, opt), "");
  Image back;
  ASSERT_EQ(read_image(path, back), "");
  double expected = std::round(255.0 * srgb_reference(0.2)) / 255.0;
  EXPECT_NEAR(srgb_encode(back.pixel(0, 0)[1]), expected, 1e-5);
  std::remove(path.c_str());
}

TEST(Image, FilmicCurveIsMonotoneAndBounded) {
  float prev = 0;
  for (float x = 0; x < 100; x = x * 1.3f + 0.01f) {
    float y = tonemap_value(x, ToneMap::Filmic);
    EXPECT_GE(y, prev);
    EXPECT_LE(y, 1.0f);
    prev = y;
  }
  EXPECT_EQ(tonemap_value(NAN, ToneMap::Filmic), 0.0f);
}

TEST(Image, ErrorsNameTheFile) {
  Image img;
  std::string err = read_image("/nonexistent/dir/x.exr", img);
  EXPECT_NE(err.find("/nonexistent/dir/x.exr"), std::string::npos);
  Image bad(2, 2, {"R"});
  bad.pixels.resize(1);
  EXPECT_NE(write_image(temp_path("bad.exr"), bad), "");
}

// testshade's output files (write_channels) as OSL 1.13.12's testshade writes them (`testshade -g
// 3 1 -d float -o o o.tif i`, `-d uint8 -o f f.exr i`, with o = (int)(u * 10), f = u * 0.5 +
// 0.25): int values in a file of another pixel type are scaled by 1/INT_MAX (5 is
// 2.3283064e-09), and -d uint8 in an EXR is half from the values as they are (1.25 stays).
TEST(Image, TestshadeOutputsConvertAsOpenImageIO) {
  Image ints(3, 1, {"o"});
  ints.pixels = {0.0f, 5.0f, 10.0f};
  std::string tif = temp_path("ints.tif");
  ASSERT_EQ(write_channels(tif, ints, "float", /*ints=*/true), "");
  Image back;
  ASSERT_EQ(read_image(tif, back), "");
  ASSERT_EQ(back.pixels.size(), 3u);
  EXPECT_EQ(back.pixels[0], 0.0f);
  EXPECT_FLOAT_EQ(back.pixels[1], 2.3283064365386963e-09f);
  EXPECT_FLOAT_EQ(back.pixels[2], 4.6566128730773926e-09f);
  Image floats(3, 1, {"f"});
  floats.pixels = {0.25f, 0.75f, 1.25f};
  std::string exr = temp_path("uint8.exr");
  ASSERT_EQ(write_channels(exr, floats, "uint8"), "");
  ASSERT_EQ(read_image(exr, back), "");
  ASSERT_EQ(back.pixels.size(), 3u);
  EXPECT_EQ(back.pixels[0], 0.25f);
  EXPECT_EQ(back.pixels[1], 0.75f);
  EXPECT_EQ(back.pixels[2], 1.25f);
  std::remove(tif.c_str());
  std::remove(exr.c_str());
}
