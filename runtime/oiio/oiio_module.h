// OpenImageIO, loaded when first used. OpenImageIO and the ~260 shared libraries it depends on
// cost a quarter of a second of dynamic linking at every process start, which is most of a 1x1
// `lobe shade` (docs/runtime.md, "Start-up"); most runs read no texture and write no image. So
// the one module that links OpenImageIO (liblobe_oiio.so, oiio_module.cpp) is dlopen'ed on the
// first texture lookup, image read or image write, and everything else links only this loader.
//
// The module is found, in order, at $LOBE_OIIO_MODULE; beside the binary (or plugin library)
// that contains this loader; in the installed <libdir>/lobe relative to it; at the build
// location (runtime/install/install_paths.h). When none loads, module() returns null and `why` says
// what was tried; callers turn that into their own error (a texture lookup fails as a missing file
// does, an image write names the file).
//
// The interface is C++ (std::string, std::vector): the module is built with the project, by the
// same compiler against the same standard library, and kAbi is checked on load.
#pragma once

#include "lobe/memory.h"

#include <cstdint>
#include <string>
#include <vector>

namespace lobe::shadeops {
struct TextureArgs;
}

namespace lobe::oiio {

// Pixel types of image files and buffers.
enum class Pixel { Float, Half, UInt8, Int32 };

struct ImageData {
  int width = 0, height = 0;
  std::vector<std::string> channels; // one name per channel
  // Interleaved, rows top to bottom. Allocated in the module and freed by the caller: both
  // sides' LargeAllocator run the same code (memory.cpp is compiled into the module too, with
  // the same flags, so the two agree on which blocks are mapped).
  LargeVector<float> pixels;
  bool integer_file = false; // the file held 8- or 16-bit integers
  std::string colorspace;    // the file's "oiio:ColorSpace" ("" if none)
};

struct Api {
  int abi;
  // Texture system: one per RuntimeEnv ("automip" on, as testshade's and testrender's).
  void* (*create_texture_system)();
  void (*destroy_texture_system)(void* ts);
  // Filtered lookups: false when the file cannot be read; error() then says why.
  bool (*texture)(void* ts, const char* file, const shadeops::TextureArgs* a, float s, float t,
                  float dsdx, float dtdx, float dsdy, float dtdy, int n, float* out, float* dds,
                  float* ddt);
  bool (*texture3d)(void* ts, const char* file, const shadeops::TextureArgs* a, const float* p,
                    const float* dpdx, const float* dpdy, const float* dpdz, int n, float* out);
  bool (*environment)(void* ts, const char* file, const shadeops::TextureArgs* a, const float* r,
                      const float* drdx, const float* drdy, int n, float* out);
  // gettextureinfo into `val` of Lobe base type `base` (int float color point vector normal
  // matrix string) with `arraylen` (0: not an array): 1 answered, 0 no UDIM tile at (s, t) (not
  // an error, as in OSL), -1 not answered (texture_error() says why, if anything). A string result
  // is written as a const char* of interned text.
  int (*texture_info)(void* ts, const char* file, bool udim, float s, float t, const char* query,
                      int base, int arraylen, void* val);
  // Why the last failed lookup on this thread failed, for a shade of `order`
  // (ShadingContext::order); kNoExplanation for a file that could not be opened and whose
  // failure was explained by a shade of a smaller or equal order before (OpenImageIO explains
  // one once, so OSL prints it once and gives later "errormessage" outputs "unknown"). After a
  // failed gettextureinfo: OpenImageIO's error, and the file counts as explained for lookups.
  std::string (*texture_error)(void* ts, uint64_t order);
  // Images: "" on success, else "path: why".
  bool (*can_write)(const std::string& path);
  std::string (*write)(const std::string& path, int width, int height,
                       const std::vector<std::string>& channels, Pixel file_pixel, const void* data,
                       Pixel data_pixel, const char* compression, const char* colorspace);
  std::string (*read)(const std::string& path, ImageData& out);
};

// 2: TextureArgs::site; 3: texture_error's order, TextureArgs::subimage; 4: ImageData::pixels a
// LargeVector
constexpr int kAbi = 4;
inline constexpr const char* kNoExplanation = "\n";

// The loaded module (loaded once, thread-safe), or null with `why` set.
const Api* module(std::string* why = nullptr);

} // namespace lobe::oiio
