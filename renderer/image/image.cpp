// Image reading and writing through OpenImageIO; see image.h for the conventions.
#include "image.h"

#include <OpenImageIO/imageio.h>

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>

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

std::string check_writable(const std::string& path) {
  namespace fs = std::filesystem;
  std::string ext = lower_extension(path);
  if (ext.empty() || fs::path(path).filename().string().find('.') == std::string::npos)
    return path + ": no image extension (expected .exr, .png, .jpg, .tif or .hdr)";
  if (!OIIO::ImageOutput::create(path)) {
    OIIO::geterror(); // clear it
    return path + ": cannot write ." + ext + " images (expected .exr, .png, .jpg, .tif or .hdr)";
  }
  fs::path dir = fs::path(path).parent_path();
  if (dir.empty()) dir = ".";
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) return path + ": folder " + dir.string() + " does not exist";
  if (fs::exists(path, ec) ? access(path.c_str(), W_OK) != 0 : access(dir.c_str(), W_OK) != 0)
    return path + ": not writable";
  return "";
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

// Writes `data`, pixels of type `buffer` (default: the file's own), converted to spec.format.
static std::string write_with(const std::string& path, const OIIO::ImageSpec& spec,
                              const void* data, OIIO::TypeDesc buffer = OIIO::TypeUnknown) {
  auto out = OIIO::ImageOutput::create(path);
  if (!out) return path + ": cannot write this format (" + OIIO::geterror() + ")";
  if (!out->open(path, spec)) return path + ": cannot open for writing: " + out->geterror();
  bool ok = out->write_image(buffer == OIIO::TypeUnknown ? spec.format : buffer, data);
  std::string err = ok ? "" : path + ": write failed: " + out->geterror();
  if (!out->close() && err.empty()) err = path + ": close failed: " + out->geterror();
  return err;
}

std::string write_image(const std::string& path, const Image& img, const WriteOptions& opt) {
  if (img.width <= 0 || img.height <= 0 || img.channels.empty()) return path + ": empty image";
  if (img.pixels.size() != size_t(img.width) * img.height * img.channels.size())
    return path + ": pixel buffer size does not match the image size";
  if (is_float_format(path)) {
    if (keeps_all_channels(path)) {
      OIIO::ImageSpec spec(img.width, img.height, img.nchannels(), OIIO::TypeDesc::FLOAT);
      spec.channelnames = img.channels;
      spec.attribute("compression", "zip");
      return write_with(path, spec, img.pixels.data());
    }
    // .hdr and the like: the first three channels (one repeated).
    std::vector<float> rgb(size_t(img.width) * img.height * 3);
    for (size_t p = 0; p < size_t(img.width) * img.height; ++p)
      for (int c = 0; c < 3; ++c)
        rgb[p * 3 + c] = img.pixels[p * img.nchannels() + std::min(c, img.nchannels() - 1)];
    OIIO::ImageSpec spec(img.width, img.height, 3, OIIO::TypeDesc::FLOAT);
    return write_with(path, spec, rgb.data());
  }
  std::vector<uint8_t> rgb = to_display(img, opt);
  OIIO::ImageSpec spec(img.width, img.height, 3, OIIO::TypeDesc::UINT8);
  spec.attribute("oiio:ColorSpace", "sRGB");
  return write_with(path, spec, rgb.data());
}

std::string write_channels(const std::string& path, const Image& img, const std::string& format) {
  if (img.width <= 0 || img.height <= 0 || img.channels.empty()) return path + ": empty image";
  std::string ext = lower_extension(path);
  size_t n = img.pixels.size();
  OIIO::ImageSpec spec(img.width, img.height, img.nchannels(), OIIO::TypeDesc::FLOAT);
  spec.channelnames = img.channels;
  if (ext == "png" || ext == "jpg" || ext == "jpeg") {
    std::vector<uint8_t> enc(n);
    for (size_t k = 0; k < n; ++k)
      enc[k] = static_cast<uint8_t>(std::lround(srgb_encode(img.pixels[k]) * 255.0f));
    spec.set_format(OIIO::TypeDesc::UINT8);
    spec.attribute("oiio:ColorSpace", "sRGB");
    return write_with(path, spec, enc.data());
  }
  if (ext == "exr") spec.attribute("compression", "zip");
  if (format == "int" && ext != "exr") {
    std::vector<int32_t> ints(n);
    for (size_t k = 0; k < n; ++k) ints[k] = static_cast<int32_t>(img.pixels[k]);
    spec.set_format(OIIO::TypeDesc::INT32);
    return write_with(path, spec, ints.data());
  }
  spec.set_format(format == "half" || format == "int" ? OIIO::TypeDesc::HALF
                  : format == "uint8"                 ? OIIO::TypeDesc::UINT8
                                                      : OIIO::TypeDesc::FLOAT);
  if (spec.format == OIIO::TypeDesc::UINT8) { // linear 8 bits, as testshade's -d uint8
    std::vector<uint8_t> q(n);
    for (size_t k = 0; k < n; ++k)
      q[k] = static_cast<uint8_t>(std::lround(std::clamp(img.pixels[k], 0.0f, 1.0f) * 255.0f));
    return write_with(path, spec, q.data());
  }
  return write_with(path, spec, img.pixels.data(), OIIO::TypeDesc::FLOAT);
}

std::string read_image(const std::string& path, Image& out) {
  auto in = OIIO::ImageInput::open(path);
  if (!in) return path + ": cannot read image: " + OIIO::geterror();
  const OIIO::ImageSpec& spec = in->spec();
  Image img(spec.width, spec.height, spec.channelnames);
  if (img.channels.size() != size_t(spec.nchannels)) {
    img.channels.resize(spec.nchannels);
    img.pixels.resize(size_t(spec.width) * spec.height * spec.nchannels);
  }
  if (!in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, img.pixels.data()))
    return path + ": read failed: " + in->geterror();
  // 8- and 16-bit files hold display-encoded values unless they say they are linear.
  std::string cs = spec.get_string_attribute("oiio:ColorSpace", "");
  bool integer = spec.format.basetype == OIIO::TypeDesc::UINT8 ||
                 spec.format.basetype == OIIO::TypeDesc::UINT16;
  if (integer && cs != "Linear" && cs != "linear") {
    for (size_t p = 0; p < size_t(spec.width) * spec.height; ++p)
      for (int c = 0; c < std::min(spec.nchannels, 3); ++c)
        img.pixels[p * spec.nchannels + c] = srgb_decode(img.pixels[p * spec.nchannels + c]);
  }
  in->close();
  out = std::move(img);
  return "";
}

} // namespace lobe::image
