// Image reading and writing through OpenImageIO (loaded on first use: runtime/oiio); see
// image.h for the conventions.
#include "image.h"
#include "oiio_module.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <system_error>

namespace lobe::image {

Image::Image(int w, int h, std::vector<std::string> names)
    : width(w), height(h), channels(std::move(names)),
      pixels(size_t(w) * size_t(h) * channels.size(), 0.0f) {}

int Image::channel(const std::string& name) const {
  for (size_t i = 0; i < channels.size(); ++i)
    if (channels[i] == name) return static_cast<int>(i);
  return -1;
}

static std::string lower_extension(const std::string& path) {
  size_t dot = path.find_last_of('.');
  if (dot == std::string::npos) return "";
  std::string ext = path.substr(dot + 1);
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext;
}

bool is_float_format(const std::string& path) {
  std::string ext = lower_extension(path);
  return ext == "exr" || ext == "hdr" || ext == "pfm";
}

bool keeps_all_channels(const std::string& path) { return lower_extension(path) == "exr"; }

std::string check_output_path(const std::string& path) {
  namespace fs = std::filesystem;
  std::string ext = lower_extension(path);
  if (ext.empty() || fs::path(path).filename().string().find('.') == std::string::npos)
    return path + ": no image extension (expected .exr, .png, .jpg, .tif or .hdr)";
  fs::path dir = fs::path(path).parent_path();
  if (dir.empty()) dir = ".";
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) return path + ": folder " + dir.string() + " does not exist";
  if (fs::exists(path, ec) ? access(path.c_str(), W_OK) != 0 : access(dir.c_str(), W_OK) != 0)
    return path + ": not writable";
  return "";
}

std::string check_output_format(const std::string& path) {
  std::string why;
  const oiio::Api* io = oiio::module(&why);
  if (!io) return path + ": " + why;
  if (!io->can_write(path))
    return path + ": cannot write ." + lower_extension(path) +
           " images (expected .exr, .png, .jpg, .tif or .hdr)";
  return "";
}

std::string check_writable(const std::string& path) {
  std::string ext = lower_extension(path);
  if (ext.empty()) return check_output_path(path);
  if (std::string e = check_output_format(path); !e.empty()) return e;
  return check_output_path(path);
}

bool is_common_output(const std::string& path) {
  std::string ext = lower_extension(path);
  for (const char* e : {"exr", "png", "jpg", "jpeg", "tif", "tiff", "hdr"})
    if (ext == e) return true;
  return false;
}

std::jthread prefetch_image_io() {
  try {
    return std::jthread([] { oiio::module(); });
  } catch (const std::system_error&) {
    return {};
  }
}

float srgb_encode(float x) {
  if (!(x > 0.0f)) return 0.0f;
  if (x >= 1.0f) return 1.0f;
  return x <= 0.0031308f ? 12.92f * x : 1.055f * std::pow(x, 1.0f / 2.4f) - 0.055f;
}

float srgb_decode(float x) {
  if (!(x > 0.0f)) return 0.0f;
  return x <= 0.04045f ? x / 12.92f : std::pow((x + 0.055f) / 1.055f, 2.4f);
}

float tonemap_value(float x, ToneMap tm) {
  if (!(x > 0.0f)) return 0.0f; // also maps NaN to black
  if (tm == ToneMap::Clamp) return std::min(x, 1.0f);
  // Narkowicz's fit of the ACES filmic curve; maps 0->0 and saturates smoothly at 1.
  float y = (x * (2.51f * x + 0.03f)) / (x * (2.43f * x + 0.59f) + 0.14f);
  return std::clamp(y, 0.0f, 1.0f);
}

// Converts the first three channels (or a single one, repeated) to 8-bit display RGB.
static std::vector<uint8_t> to_display(const Image& img, const WriteOptions& opt) {
  const int nc = img.nchannels();
  const float scale = std::exp2(opt.exposure);
  std::vector<uint8_t> out(size_t(img.width) * img.height * 3);
  for (size_t p = 0; p < size_t(img.width) * img.height; ++p) {
    for (int c = 0; c < 3; ++c) {
      float v = img.pixels[p * nc + std::min(c, nc - 1)] * scale;
      float e = srgb_encode(tonemap_value(v, opt.tonemap));
      out[p * 3 + c] = static_cast<uint8_t>(std::lround(e * 255.0f));
    }
  }
  return out;
}

// A file of `img`'s size and channels (`names`) holding pixels of type `file`, from `data` of
// type `buffer`.
struct FileSpec {
  int width, height;
  const std::vector<std::string>& names;
  oiio::Pixel file;
  const char* compression = nullptr;
  const char* colorspace = nullptr;
};

static std::string write_with(const std::string& path, const FileSpec& f, const void* data,
                              oiio::Pixel buffer) {
  std::string why;
  const oiio::Api* io = oiio::module(&why);
  if (!io) return path + ": " + why;
  return io->write(path, f.width, f.height, f.names, f.file, data, buffer, f.compression,
                   f.colorspace);
}

std::string write_image(const std::string& path, const Image& img, const WriteOptions& opt) {
  if (img.width <= 0 || img.height <= 0 || img.channels.empty()) return path + ": empty image";
  if (img.pixels.size() != size_t(img.width) * img.height * img.channels.size())
    return path + ": pixel buffer size does not match the image size";
  static const std::vector<std::string> kRGB = {"R", "G", "B"};
  if (is_float_format(path)) {
    if (keeps_all_channels(path))
      return write_with(path, {img.width, img.height, img.channels, oiio::Pixel::Float, "zip"},
                        img.pixels.data(), oiio::Pixel::Float);
    // .hdr and the like: the first three channels (one repeated).
    std::vector<float> rgb(size_t(img.width) * img.height * 3);
    for (size_t p = 0; p < size_t(img.width) * img.height; ++p)
      for (int c = 0; c < 3; ++c)
        rgb[p * 3 + c] = img.pixels[p * img.nchannels() + std::min(c, img.nchannels() - 1)];
    return write_with(path, {img.width, img.height, kRGB, oiio::Pixel::Float}, rgb.data(),
                      oiio::Pixel::Float);
  }
  std::vector<uint8_t> rgb = to_display(img, opt);
  return write_with(path, {img.width, img.height, kRGB, oiio::Pixel::UInt8, nullptr, "sRGB"},
                    rgb.data(), oiio::Pixel::UInt8);
}

std::string write_channels(const std::string& path, const Image& img, const std::string& format,
                           bool ints) {
  if (img.width <= 0 || img.height <= 0 || img.channels.empty()) return path + ": empty image";
  ints = ints || format == "int"; // "int" is for int values
  std::string ext = lower_extension(path);
  size_t n = img.pixels.size();
  FileSpec f{img.width, img.height, img.channels, oiio::Pixel::Float};
  bool eight_bit = ext == "png" || ext == "jpg" || ext == "jpeg";
  if (ints && format == "int" && ext != "exr" && !eight_bit) {
    std::vector<int32_t> values(n);
    for (size_t k = 0; k < n; ++k) values[k] = static_cast<int32_t>(img.pixels[k]);
    f.file = oiio::Pixel::Int32;
    return write_with(path, f, values.data(), oiio::Pixel::Int32);
  }
  // Int values in a file of another pixel type: as OpenImageIO converts int32 data (INT_MAX is
  // 1), which is what testshade writes.
  std::vector<float> scaled;
  const float* px = img.pixels.data();
  if (ints) {
    scaled.resize(n);
    for (size_t k = 0; k < n; ++k) scaled[k] = float(double(img.pixels[k]) / 2147483647.0);
    px = scaled.data();
  }
  if (eight_bit) {
    std::vector<uint8_t> enc(n);
    for (size_t k = 0; k < n; ++k)
      enc[k] = static_cast<uint8_t>(std::lround(srgb_encode(px[k]) * 255.0f));
    f.file = oiio::Pixel::UInt8;
    f.colorspace = "sRGB";
    return write_with(path, f, enc.data(), oiio::Pixel::UInt8);
  }
  if (ext == "exr") f.compression = "zip";
  // EXR holds no 8-bit pixels: -d uint8 writes half from the values as they are (OpenImageIO's
  // choice for testshade), not from 8-bit ones.
  f.file = format == "half" || format == "int" || (format == "uint8" && ext == "exr")
               ? oiio::Pixel::Half
           : format == "uint8" ? oiio::Pixel::UInt8
                               : oiio::Pixel::Float;
  if (f.file == oiio::Pixel::UInt8) { // linear 8 bits, as testshade's -d uint8
    std::vector<uint8_t> q(n);
    for (size_t k = 0; k < n; ++k)
      q[k] = static_cast<uint8_t>(std::lround(std::clamp(px[k], 0.0f, 1.0f) * 255.0f));
    return write_with(path, f, q.data(), oiio::Pixel::UInt8);
  }
  return write_with(path, f, px, oiio::Pixel::Float);
}

std::string read_image(const std::string& path, Image& out) {
  std::string why;
  const oiio::Api* io = oiio::module(&why);
  if (!io) return path + ": " + why;
  oiio::ImageData d;
  if (std::string err = io->read(path, d); !err.empty()) return err;
  Image img;
  img.width = d.width;
  img.height = d.height;
  img.channels = std::move(d.channels);
  img.pixels = std::move(d.pixels);
  // 8- and 16-bit files hold display-encoded values unless they say they are linear.
  if (d.integer_file && d.colorspace != "Linear" && d.colorspace != "linear") {
    const int nc = img.nchannels();
    for (size_t p = 0; p < size_t(img.width) * img.height; ++p)
      for (int c = 0; c < std::min(nc, 3); ++c)
        img.pixels[p * nc + c] = srgb_decode(img.pixels[p * nc + c]);
  }
  out = std::move(img);
  return "";
}

} // namespace lobe::image
