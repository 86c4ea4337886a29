// Lobe's image I/O: the one place OpenImageIO is linked (lobe_image).
//
// An Image is a float buffer of named channels, interleaved, rows top to bottom. EXR output
// keeps every channel in linear 32-bit float (extra channels are AOVs, e.g. "albedo.R");
// PNG/JPEG/TIFF-8 output takes the first three channels (or one, repeated), applies exposure
// and a tone curve, and encodes sRGB 8-bit. Reading accepts anything OpenImageIO reads
// (.exr, .hdr, .png, ...) and returns linear float (8-bit sRGB files are decoded to linear).
//
// Errors are values: each call returns an empty string on success, a message otherwise.
#pragma once

#include "lobe/memory.h"

#include <string>
#include <thread>
#include <vector>

namespace lobe::image {

struct Image {
  int width = 0, height = 0;
  std::vector<std::string> channels; // e.g. {"R","G","B"}; size = channels per pixel
  LargeVector<float> pixels;         // width * height * channels.size(), interleaved

  Image() = default;
  Image(int w, int h, std::vector<std::string> names);
  int nchannels() const { return static_cast<int>(channels.size()); }
  float* pixel(int x, int y) { return pixels.data() + (size_t(y) * width + x) * nchannels(); }
  const float* pixel(int x, int y) const {
    return pixels.data() + (size_t(y) * width + x) * nchannels();
  }
  // Index of the channel called `name`, or -1.
  int channel(const std::string& name) const;
};

// How linear radiance becomes a display value in 8-bit outputs.
enum class ToneMap {
  Clamp,  // min(x, 1): exact for values in [0,1] (shader grids, albedo maps)
  Filmic, // smooth highlight roll-off (ACES fit by Narkowicz), for rendered images
};

struct WriteOptions {
  float exposure = 0; // stops; 8-bit outputs only
  ToneMap tonemap = ToneMap::Clamp;
};

// True when `path`'s extension names a floating-point format we write linearly (.exr, .hdr).
bool is_float_format(const std::string& path);

// True when `path` is an EXR: the only output that keeps every channel (AOVs). Other float
// formats (.hdr) keep the first three.
bool keeps_all_channels(const std::string& path);

// Checks, before anything is rendered, that `path` can be written: an extension this
// OpenImageIO has a writer for, and an existing, writable folder (and file, if it exists).
// "" if so, else "path: why".
std::string check_writable(const std::string& path);
// The two halves of check_writable: the path (an extension, an existing writable folder and
// file; no OpenImageIO needed) and the format (loads OpenImageIO and asks for a writer). A
// command may check the path at once and the format after work that overlaps the loading
// (see prefetch_image_io).
std::string check_output_path(const std::string& path);
std::string check_output_format(const std::string& path);
// True for the extensions every OpenImageIO build writes (.exr .png .jpg .jpeg .tif .tiff
// .hdr): a command may defer check_output_format for them, and should check others at once.
bool is_common_output(const std::string& path);
// Starts loading OpenImageIO on a thread of its own (about 0.25 s of dynamic linking), so that
// work done meanwhile overlaps it; the first image or texture call waits for it to finish.
// Returns the thread (it joins when destroyed), or no thread when none can be
// started (OpenImageIO then loads on first use, as without this call).
std::jthread prefetch_image_io();

// Writes `img` to `path`, format chosen from the extension.
std::string write_image(const std::string& path, const Image& img, const WriteOptions& opt = {});

// testshade's output files: every channel as it is, stored as `format` ("float", "half",
// "uint8", or "int", for `ints`, written as int32), linear, except in PNG and JPEG files, whose
// 8 bits are sRGB-encoded (0.5 is 188) as testshade writes them. EXR is zip-compressed and holds
// "int" and "uint8" as half (it has neither pixel type). `ints`: the values are ints, which in a
// file of another pixel type are scaled by 1/INT_MAX, as OpenImageIO converts int data ("int"
// implies it).
std::string write_channels(const std::string& path, const Image& img, const std::string& format,
                           bool ints = false);

// Reads `path` into `out` as linear float, all channels.
std::string read_image(const std::string& path, Image& out);

// Display encoding used by 8-bit outputs, exposed for tests: linear -> sRGB in [0,1].
float srgb_encode(float linear);
float srgb_decode(float encoded);
float tonemap_value(float linear, ToneMap tm);

} // namespace lobe::image
