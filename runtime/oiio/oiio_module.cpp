// liblobe_oiio.so: everything Lobe asks of OpenImageIO (texture lookups, image files), behind
// the Api of oiio_module.h. Loaded on first use by oiio_loader.cpp; nothing else links
// OpenImageIO.
#include "oiio_module.h"
#include "lobe/memory.h"
#include "shadeops.h"

#include <Imath/ImathVec.h>
#include <OpenImageIO/imagecache.h>
#include <OpenImageIO/imageio.h>
#include <OpenImageIO/texture.h>

#include <sys/stat.h>

#include <algorithm>
#include <atomic>
#include <cstdint>
#include <cstring>
#include <iterator>
#include <mutex>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

namespace OIIO = OIIO_NAMESPACE;
using lobe::shadeops::TextureArgs;

namespace lobe::oiio {
namespace {

using Perthread = OIIO::TextureSystem::Perthread;
using Handle = OIIO::TextureSystem::TextureHandle;

// A texture system and what Lobe keeps beside it. Every lookup passes OpenImageIO a per-thread
// record that Lobe created (create_thread_info) and destroys with the texture system, rather than
// the one OpenImageIO would keep in a thread_local of its own: that one outlives the texture
// system on a thread that does not end (oneTBB's workers), holding open the files its thread last
// read, and it is freed only at thread exit.
struct Textures {
  OIIO::ImageCache* ic = nullptr;
  OIIO::TextureSystem* ts = nullptr;
  uint64_t id = 0; // unique over the process: a thread's cached records are matched by it
  std::mutex mutex;
  std::vector<Perthread*> threads; // every record created, under `mutex`
  // file -> verdict, under `mutex`. A file that cannot be opened is explained once (as OSL
  // prints it once), by the first lookup or gettextureinfo to fail on it; a lookup of a shade
  // of a smaller order (ShadingContext::order) that fails after it explains it again, so that
  // the shade of the smallest order always has the explanation (lobe shade prints messages in
  // point order and drops a repeated one, so the grid's first point says it, whichever ran
  // first; an "errormessage" output of a larger order that ran earlier keeps its words).
  // `told`: such files, with the smallest order that explained each, under `mutex`.
  struct Verdict {
    std::string refusal; // "": fits; kNoExplanation: unopened, OpenImageIO explained it before
    bool unopened = false;
  };
  std::unordered_map<std::string, Verdict> verdicts;
  std::unordered_map<std::string, uint64_t> told;
};

// Whether the failure of `file` is told by a shade of order `order` (see Textures::told).
bool tell(Textures* t, const std::string& file, uint64_t order) {
  std::lock_guard<std::mutex> lock(t->mutex);
  auto [it, fresh] = t->told.emplace(file, order);
  if (fresh) return true;
  if (order >= it->second) return false;
  it->second = order;
  return true;
}

Textures* textures_of(void* t) { return static_cast<Textures*>(t); }

void* create_texture_system() {
  static std::atomic<uint64_t> next_id{1};
  auto* t = new Textures;
  t->id = next_id++;
  // The image cache is created here and destroyed after the texture system, as OpenImageIO's
  // texture.h documents for a cache the caller passes: one the texture system creates itself
  // is not freed by TextureSystem::destroy in OpenImageIO 2.4 (LeakSanitizer: the cache and
  // every file it opened, 25 kB and up, leaked with each texture system).
  t->ic = OIIO::ImageCache::create(false);
  t->ts = OIIO::TextureSystem::create(false, t->ic);
  // An image without MIP levels gets them built on first use, so that derivatives and blur
  // filter it (as OSL's testshade and testrender set up their TextureSystem).
  t->ts->attribute("automip", 1);
  return t;
}

void destroy_texture_system(void* p) {
  Textures* t = textures_of(p);
  for (Perthread* info : t->threads) t->ts->destroy_thread_info(info);
  OIIO::TextureSystem::destroy(t->ts);
  OIIO::ImageCache::destroy(t->ic);
  delete t;
}

// This thread's record for `t` and the lookup site `site` (TextureArgs::site), created on the
// thread's first lookup from a site. OpenImageIO keeps the last two tiles a record read: with one
// record per thread, a shader that reads three places in turn (a texture, the same one tiled, a
// blurred lookup at a coarser level) missed that cache on every lookup and went to the shared
// tile table, timed with a clock read each time. Sites share kSites records per thread by their
// number modulo kSites. A thread remembers its records for the last few texture systems it used
// (one, unless a plugin runs several).
constexpr size_t kSites = 8;
Perthread* thread_info(Textures* t, int32_t site = 0) {
  struct Slot {
    uint64_t id = 0;
    Perthread* info[kSites] = {};
  };
  thread_local Slot slots[4];
  thread_local size_t next = 0;
  size_t k = size_t(uint32_t(site)) % kSites;
  Slot* slot = nullptr;
  for (Slot& s : slots)
    if (s.id == t->id) slot = &s;
  if (!slot) {
    slot = &slots[next];
    next = (next + 1) % std::size(slots);
    *slot = Slot{t->id, {}};
  }
  if (Perthread* info = slot->info[k]) return t->ts->get_perthread_info(info); // (housekeeping)
  Perthread* info = t->ts->create_thread_info();
  {
    std::lock_guard<std::mutex> lock(t->mutex);
    t->threads.push_back(info);
  }
  slot->info[k] = info;
  return t->ts->get_perthread_info(info);
}

// OpenImageIO's wrap mode of `name`, as TextureOpt::decode_wrapmode reads it (which compares
// the name with each mode's in turn): the common names by their first letter and one comparison.
OIIO::TextureOpt::Wrap wrap_mode(const char* name) {
  using W = OIIO::TextureOpt;
  static constexpr std::pair<const char*, W::Wrap> kModes[] = {{"black", W::WrapBlack},
                                                               {"clamp", W::WrapClamp},
                                                               {"periodic", W::WrapPeriodic},
                                                               {"mirror", W::WrapMirror},
                                                               {"default", W::WrapDefault}};
  for (const auto& [full, mode] : kModes)
    if (full[0] == name[0]) return std::strcmp(name, full) == 0 ? mode : W::decode_wrapmode(name);
  return W::decode_wrapmode(name);
}

OIIO::TextureOpt options(const TextureArgs* a) {
  OIIO::TextureOpt opt;
  opt.sblur = a->blur[0];
  opt.tblur = a->blur[1];
  opt.rblur = a->blur[2];
  opt.swidth = a->width[0];
  opt.twidth = a->width[1];
  opt.rwidth = a->width[2];
  opt.fill = a->fill;
  opt.firstchannel = a->firstchannel;
  opt.subimage = a->subimage;
  if (a->subimagename) opt.subimagename = OIIO::ustring(a->subimagename);
  // "wrap" names all three with one string: decoded once.
  if (a->wrap[0]) opt.swrap = wrap_mode(a->wrap[0]);
  if (a->wrap[1]) opt.twrap = a->wrap[1] == a->wrap[0] ? opt.swrap : wrap_mode(a->wrap[1]);
  if (a->wrap[2]) opt.rwrap = a->wrap[2] == a->wrap[1] ? opt.twrap : wrap_mode(a->wrap[2]);
  if (a->interp) { // OSL's names; any other (e.g. "bilinear") is the default, as in OSL
    std::string m = a->interp;
    opt.interpmode = m == "closest"  ? OIIO::TextureOpt::InterpClosest
                     : m == "linear" ? OIIO::TextureOpt::InterpBilinear
                     : m == "cubic"  ? OIIO::TextureOpt::InterpBicubic
                                     : OIIO::TextureOpt::InterpSmartBicubic;
  }
  return opt;
}

// The refusal of the last lookup on this thread that `find` stopped, and the file when it could
// not be opened (texture_error reports it); the file of the last gettextureinfo that failed.
thread_local std::string t_refused, t_refused_file, t_info_file;

// Bounded memory for textures. OpenImageIO reads a tiled file a tile at a time into its cache
// (256 MB by default), but an untiled one is a single tile: the whole image is read, in its own
// pixel format, and automip builds its MIP levels beside it. So on the first lookup of a file
// its header is read and an untiled image that cannot fit in the memory (lobe/memory.h) is
// refused, with the figure, instead of failing an allocation inside OpenImageIO (which throws
// through the shader and aborts the process).
std::string texture_verdict(OIIO::TextureSystem* ts, Handle* h, Perthread* info, const char* file,
                            bool* unopened) {
  // Null for a file that cannot be opened: refused, with OpenImageIO's error as OSL's texture
  // lookup words it (`Could not open file "x"`, without imagespec's `Invalid image file "x": `).
  if (h && ts->is_udim(h)) return ""; // a UDIM name: OpenImageIO picks the tile per lookup
  const OIIO::ImageSpec* spec = h ? ts->imagespec(h, info) : nullptr;
  if (!spec) {
    std::string err = ts->geterror();
    err = err.substr(0, err.find('\n'));
    std::string prefix = "Invalid image file \"" + std::string(file) + "\": ";
    if (err.rfind(prefix, 0) == 0) err.erase(0, prefix.size());
    *unopened = true;
    return err.empty() ? kNoExplanation : err; // empty: OpenImageIO explained it before
  }
  // OpenImageIO reports an untiled file as one tile the size of the image.
  if (spec->tile_width > 0 && (spec->tile_width < spec->width || spec->tile_height < spec->height))
    return "";
  double bytes = double(spec->width) * double(spec->height) * double(std::max(spec->depth, 1)) *
                 double(spec->nchannels) * double(spec->format.size()) * 4 / 3;
  return check_memory(std::string(file) + " (" + std::to_string(spec->width) + "x" +
                          std::to_string(spec->height) + ", " + std::to_string(spec->nchannels) +
                          " channels, not tiled)",
                      bytes, "read whole into the texture cache, with its MIP levels");
}

// The handle of `file` for a lookup on this thread, or null (with t_refused set) when the file
// does not fit in memory. The verdict is kept per file name; each thread remembers the last few
// names it passed (by pointer, confirmed by content) with their handles, which keeps the shared
// table and its lock off the per-lookup path.
struct Lookup {
  Handle* handle = nullptr;
  Perthread* info = nullptr;
};

// Whether `file` names something that is neither a file nor a folder (a device such as
// /dev/zero, a pipe): OpenImageIO would wait on it, or read it, for ever.
bool special_file(const char* file) {
  struct stat st;
  return file && ::stat(file, &st) == 0 && !S_ISREG(st.st_mode) && !S_ISDIR(st.st_mode);
}

std::string not_a_file(const char* file) {
  return "Could not open file: " + std::string(file) + ": not a regular file";
}

Lookup find(Textures* t, const char* file, int32_t site) {
  struct Passed {
    uint64_t id = 0;
    const char* ptr = nullptr;
    std::string name;
    Handle* handle = nullptr;
  };
  thread_local Passed passed[8];
  thread_local size_t next = 0;
  Lookup l;
  l.info = thread_info(t, site);
  for (const Passed& p : passed)
    if (p.id == t->id && p.ptr == file && p.name == file) return {p.handle, l.info};
  Textures::Verdict verdict;
  bool known = false;
  {
    std::lock_guard<std::mutex> lock(t->mutex);
    auto it = t->verdicts.find(file);
    if (it != t->verdicts.end()) known = true, verdict = it->second;
  }
  if (!known) {               // read the header outside the lock; two threads may both read it
    if (special_file(file)) { // not asked of OpenImageIO: told as a file that cannot be opened
      verdict = {not_a_file(file), true};
    } else {
      l.handle = t->ts->get_texture_handle(OIIO::ustring(file), l.info);
      verdict.refusal = texture_verdict(t->ts, l.handle, l.info, file, &verdict.unopened);
    }
    std::lock_guard<std::mutex> lock(t->mutex);
    auto [it, fresh] = t->verdicts.emplace(file, verdict);
    // OpenImageIO explains a file it cannot open to one reader: keep its words.
    if (!fresh && it->second.refusal == kNoExplanation) it->second = verdict;
    verdict = it->second;
  }
  if (!verdict.refusal.empty()) {
    t_refused = verdict.refusal;
    t_refused_file = verdict.unopened ? file : "";
    return {nullptr, l.info};
  }
  if (!l.handle) l.handle = t->ts->get_texture_handle(OIIO::ustring(file), l.info);
  if (l.handle) {
    passed[next] = Passed{t->id, file, file, l.handle};
    next = (next + 1) % std::size(passed);
  }
  return l;
}

// Whether the subimage `a` asks of `h` by index is one the file has (a name OpenImageIO checks
// itself: "Unknown subimage "x" in texture "f""). OpenImageIO asserts on an index past them (the
// process aborts, as OSL's testshade does): refused here, in the words OpenImageIO uses for a
// name, with the count (Lobe's). A UDIM name is checked at its tile for (s, t).
bool subimage_ok(Textures* x, const Lookup& l, const TextureArgs* a, const char* file, float s = 0,
                 float t = 0) {
  if (a->subimage == 0 || (a->subimagename && *a->subimagename)) return true;
  Handle* h = l.handle;
  if (x->ts->is_udim(h)) h = x->ts->resolve_udim(h, l.info, s, t);
  int n = 0;
  if (!h ||
      !x->ts->get_texture_info(h, l.info, 0, OIIO::ustring("subimages"), OIIO::TypeDesc::INT, &n))
    return true; // no tile there, or no file: the lookup says so
  if (a->subimage >= 0 && a->subimage < n) return true;
  t_refused = "Unknown subimage " + std::to_string(a->subimage) + " in texture \"" +
              std::string(file) + "\" (it has " + std::to_string(n) + ")";
  t_refused_file.clear();
  return false;
}

bool texture(void* tv, const char* file, const TextureArgs* a, float s, float t, float dsdx,
             float dtdx, float dsdy, float dtdy, int n, float* out, float* dds, float* ddt) {
  Textures* x = textures_of(tv);
  Lookup l = find(x, file, a->site);
  if (!l.handle || !subimage_ok(x, l, a, file, s, t)) return false;
  OIIO::TextureOpt opt = options(a);
  return x->ts->texture(l.handle, l.info, opt, s, t, dsdx, dtdx, dsdy, dtdy, n, out, dds, ddt);
}

Imath::V3f v3(const float* p) { return Imath::V3f(p[0], p[1], p[2]); }

bool texture3d(void* tv, const char* file, const TextureArgs* a, const float* p, const float* dpdx,
               const float* dpdy, const float* dpdz, int n, float* out) {
  Textures* x = textures_of(tv);
  Lookup l = find(x, file, a->site);
  if (!l.handle || !subimage_ok(x, l, a, file)) return false;
  OIIO::TextureOpt opt = options(a);
  return x->ts->texture3d(l.handle, l.info, opt, v3(p), v3(dpdx), v3(dpdy), v3(dpdz), n, out);
}

bool environment(void* tv, const char* file, const TextureArgs* a, const float* r,
                 const float* drdx, const float* drdy, int n, float* out) {
  Textures* x = textures_of(tv);
  Lookup l = find(x, file, a->site);
  if (!l.handle || !subimage_ok(x, l, a, file)) return false;
  OIIO::TextureOpt opt = options(a);
  return x->ts->environment(l.handle, l.info, opt, v3(r), v3(drdx), v3(drdy), n, out);
}

int texture_info(void* tv, const char* file, bool udim, float s, float t, const char* query,
                 int base, int arraylen, void* val) {
  // Lobe's base types in order: int float color point vector normal matrix string.
  static const OIIO::TypeDesc kTypes[] = {
      OIIO::TypeDesc::INT, OIIO::TypeDesc::FLOAT, OIIO::TypeColor,  OIIO::TypePoint,
      OIIO::TypeVector,    OIIO::TypeNormal,      OIIO::TypeMatrix, OIIO::TypeDesc::STRING};
  if (base < 0 || base >= int(std::size(kTypes))) return 0;
  OIIO::TypeDesc type = kTypes[base];
  if (arraylen > 0) type.arraylen = arraylen;
  Textures* x = textures_of(tv);
  if (special_file(file)) {
    t_refused = not_a_file(file);
    t_refused_file.clear();
    return -1;
  }
  OIIO::TextureSystem* ts = x->ts;
  Perthread* info = thread_info(x);
  OIIO::ustring name(file ? file : ""), what(query ? query : "");
  Handle* h = ts->get_texture_handle(name, info);
  if (udim) {
    if (h && ts->is_udim(h)) h = ts->resolve_udim(h, info, s, t);
    if (!h) return 0; // no tile at (s, t): not an error, as in OSL
  }
  if (h && ts->get_texture_info(h, info, 0, what, type, val)) return 1;
  t_info_file = name.string(); // texture_error tells it: lookups of it after say no more
  return -1;
}

std::string texture_error(void* tv, uint64_t order) {
  Textures* t = textures_of(tv);
  if (!t_refused.empty()) {
    std::string why = std::exchange(t_refused, std::string());
    std::string file = std::exchange(t_refused_file, std::string());
    if (file.empty()) return why;
    {
      // The file's words as they are now: OpenImageIO gives them to one reader, whose verdict
      // may have been stored after this lookup read its own.
      std::lock_guard<std::mutex> lock(t->mutex);
      why = t->verdicts[file].refusal;
    }
    if (why == kNoExplanation) return why;
    return tell(t, file, order) ? why : std::string(kNoExplanation);
  }
  if (!t_info_file.empty()) tell(t, std::exchange(t_info_file, std::string()), order);
  return t->ts->geterror();
}

OIIO::TypeDesc type_of(Pixel p) {
  switch (p) {
  case Pixel::Half:
    return OIIO::TypeDesc::HALF;
  case Pixel::UInt8:
    return OIIO::TypeDesc::UINT8;
  case Pixel::Int32:
    return OIIO::TypeDesc::INT32;
  case Pixel::Float:
    break;
  }
  return OIIO::TypeDesc::FLOAT;
}

bool can_write(const std::string& path) {
  if (OIIO::ImageOutput::create(path)) return true;
  OIIO::geterror(); // clear it
  return false;
}

std::string write(const std::string& path, int width, int height,
                  const std::vector<std::string>& channels, Pixel file_pixel, const void* data,
                  Pixel data_pixel, const char* compression, const char* colorspace) {
  OIIO::ImageSpec spec(width, height, int(channels.size()), type_of(file_pixel));
  spec.channelnames = channels;
  if (compression) spec.attribute("compression", compression);
  if (colorspace) spec.attribute("oiio:ColorSpace", colorspace);
  auto out = OIIO::ImageOutput::create(path);
  if (!out) return path + ": cannot write this format (" + OIIO::geterror() + ")";
  if (!out->open(path, spec)) return path + ": cannot open for writing: " + out->geterror();
  bool ok = out->write_image(type_of(data_pixel), data);
  std::string err = ok ? "" : path + ": write failed: " + out->geterror();
  if (!out->close() && err.empty()) err = path + ": close failed: " + out->geterror();
  return err;
}

std::string read(const std::string& path, ImageData& img) {
  auto in = OIIO::ImageInput::open(path);
  if (!in) return path + ": cannot read image: " + OIIO::geterror();
  const OIIO::ImageSpec& spec = in->spec();
  img.width = spec.width;
  img.height = spec.height;
  img.channels = spec.channelnames;
  img.channels.resize(size_t(spec.nchannels));
  // The file says how big it is: checked against the memory before the pixels are allocated.
  double bytes = double(spec.width) * double(spec.height) * double(spec.nchannels) * 4;
  if (spec.width <= 0 || spec.height <= 0 || spec.nchannels <= 0)
    return path + ": the image has no pixels (" + std::to_string(spec.width) + "x" +
           std::to_string(spec.height) + ", " + std::to_string(spec.nchannels) + " channels)";
  if (std::string e = check_memory(path + " (" + std::to_string(spec.width) + "x" +
                                       std::to_string(spec.height) + ", " +
                                       std::to_string(spec.nchannels) + " channels)",
                                   bytes, "its pixels as floats");
      !e.empty())
    return e;
  img.pixels.assign(size_t(spec.width) * size_t(spec.height) * size_t(spec.nchannels), 0.0f);
  if (!in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, img.pixels.data()))
    return path + ": read failed: " + in->geterror();
  img.integer_file = spec.format.basetype == OIIO::TypeDesc::UINT8 ||
                     spec.format.basetype == OIIO::TypeDesc::UINT16;
  img.colorspace = spec.get_string_attribute("oiio:ColorSpace", "");
  in->close();
  return "";
}

const Api kApi = {kAbi,        create_texture_system, destroy_texture_system, texture,   texture3d,
                  environment, texture_info,          texture_error,          can_write, write,
                  read};

} // namespace
} // namespace lobe::oiio

extern "C" __attribute__((visibility("default"))) const lobe::oiio::Api* lobe_oiio_module_api() {
  return &lobe::oiio::kApi;
}
