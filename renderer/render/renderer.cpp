// Tiled, progressive, deterministic rendering (see renderer.h).
#include "renderer.h"
#include "threads.h"

#include "lobe/context.h"

#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <chrono>
#include <cmath>
#include <memory>
#include <mutex>
#include <optional>

namespace lobe::render {
namespace {

constexpr int kTile = 16;

struct Accum {
  Color3 L, albedo, normal;
  float depth = 0;
  int n = 0;
};

struct ThreadState {
  ShadingContext ctx;
  ShadingContext light_ctx; // emitters shaded for next-event estimation (PathTracer::trace)
  TraceCounters counters;
};

// A uniform number in [0, 1) warped to the tent distribution on [-1, 1) (density 1 - |x|): the
// inverse of its distribution function, left half and right half.
inline float tent_warp(float u) {
  float t = 2 * u;
  return t < 1 ? std::sqrt(t) - 1 : 1 - std::sqrt(2 - t);
}

// Light paths after sample `s` of `pixel` (PathTracer::trace_light): opt.light_paths a sample
// on average, at fixed indices, each with numbers of its own; so the count and the paths
// depend on the image size, sample count and seed alone.
void trace_light_paths(const PathTracer& pt, uint64_t pixel, uint64_t pixels, int s,
                       const RenderOptions& opt, LightFilm& film, ThreadState& ts) {
  uint64_t idx = uint64_t(s) * pixels + pixel;
  double rate = opt.light_paths;
  auto n = uint64_t(std::floor(double(idx + 1) * rate) - std::floor(double(idx) * rate));
  for (uint64_t j = 0; j < n; ++j) {
    RandomStream rng(idx, j, opt.seed ^ 0x6c69676874ull);
    if (ts.ctx.cancel && ts.ctx.cancel->load(std::memory_order_relaxed)) return; // Ctrl-C
    pt.trace_light(rng, ts.ctx, ts.light_ctx, ts.counters, film);
  }
}

// The camera ray of a sample of pixel (x, y), and the pixel filter's density at its film
// position (`density`).
Ray camera_ray(const RenderScene& scene, const RenderOptions& opt, bool lens, int x, int y,
               const Sampler& sampler, float& density) {
  float u[4] = {0, 0, 0.5f, 0.5f}; // pixel position, lens position
  static_assert(path_groups::kLens == path_groups::kPixel + 1);
  if (lens)
    sampler.groups<2>(path_groups::kPixel, {2, 2}, u);
  else // a pinhole draws no lens numbers
    sampler.groups<1>(path_groups::kPixel, {2}, u);
  float jx = u[0], jy = u[1], l1 = u[2], l2 = u[3];
  density = 1;
  if (opt.pixel_filter == scene::PixelFilter::Tent) {
    float tx = tent_warp(jx), ty = tent_warp(jy);
    density = (1 - std::abs(tx)) * (1 - std::abs(ty));
    jx = 0.5f + tx;
    jy = 0.5f + ty;
  }
  return scene.camera().generate(x + jx, y + jy, l1, l2);
}

// Renders samples [s0, s1) of every pixel in tile `t`.
void render_tile(const RenderScene& scene, const PathTracer& pt, int width, int height, int t,
                 int s0, int s1, const RenderOptions& opt, const std::atomic<bool>* cancel,
                 std::atomic<bool>& halt, LargeVector<Accum>& acc, LightFilm* film,
                 ThreadState& ts) {
  ts.ctx.cancel = ts.light_ctx.cancel = cancel; // Ctrl-C reaches shaders in their loops
  int tiles_x = (width + kTile - 1) / kTile;
  int x0 = (t % tiles_x) * kTile, y0 = (t / tiles_x) * kTile;
  const bool lens = scene.camera().has_lens();
  const int tw = std::min(x0 + kTile, width) - x0, th = std::min(y0 + kTile, height) - y0;
  const int per_pixel = s1 - s0, total = tw * th * per_pixel;
  // The tile's camera rays, pixel by pixel and a pixel's samples in order, a packet at a time
  // (Geometry::traverse_packet: the same pixel's or its neighbours'), then their paths one by
  // one in that order.
  constexpr int kPacket = Geometry::kPacket;
  Ray rays[kPacket];
  float densities[kPacket];
  Geometry::RawHit firsts[kPacket];
  uint64_t pixels[kPacket];
  int samples[kPacket];
  std::optional<Sampler> samplers[kPacket]; // each path's, made once for its camera ray and path
  for (int base = 0; base < total; base += kPacket) {
    if (cancel && cancel->load(std::memory_order_relaxed)) return;
    if (halt.load(std::memory_order_relaxed)) return;
    const int n = std::min(kPacket, total - base);
    for (int i = 0; i < n; ++i) {
      const int at = (base + i) / per_pixel, x = x0 + at % tw, y = y0 + at / tw;
      pixels[i] = uint64_t(y) * width + x;
      samples[i] = s0 + (base + i) % per_pixel;
      samplers[i].emplace(pixels[i], uint64_t(samples[i]), opt.seed);
      rays[i] = camera_ray(scene, opt, lens, x, y, *samplers[i], densities[i]);
    }
    const uint64_t t0 = opt.profile ? phase_ticks() : 0;
    scene.geometry().traverse_packet(rays, n, firsts);
    const uint64_t share = opt.profile ? (phase_ticks() - t0) / uint64_t(n) : 0;
    for (int i = 0; i < n; ++i) {
      const uint64_t pixel = pixels[i];
      const int s = samples[i];
      bool timed = opt.profile && (pixel + uint64_t(s)) % kProfileEvery == 0;
      PathResult r = pt.trace(rays[i], *samplers[i], ts.ctx, ts.light_ctx, ts.counters, timed,
                              densities[i], &firsts[i], share);
      if (!ts.counters.stopped.empty()) { // a runaway shader: the render stops (not counted)
        halt.store(true);
        return;
      }
      // Cancelled meanwhile: a shader may have been stopped in this sample (not counted).
      if (cancel && cancel->load(std::memory_order_relaxed)) return;
      // A rare invalid sample must not poison the pixel (counted, then dropped).
      if (!is_finite(r.L)) r.L = {};
      Accum& a = acc[pixel];
      a.L += r.L;
      a.albedo += r.albedo;
      a.normal += r.normal;
      a.depth += r.depth;
      ++a.n;
      if (film) {
        auto l0 = opt.profile ? std::chrono::steady_clock::now()
                              : std::chrono::steady_clock::time_point{};
        trace_light_paths(pt, pixel, uint64_t(width) * height, s, opt, *film, ts);
        if (opt.profile)
          ts.counters.light_seconds +=
              std::chrono::duration<double>(std::chrono::steady_clock::now() - l0).count();
        if (!ts.counters.stopped.empty()) {
          halt.store(true);
          return;
        }
      }
    }
  }
}

// The camera's samples averaged, plus the light paths' splats over their number.
image::Image resolve(const LargeVector<Accum>& acc, int width, int height, bool aovs,
                     const LightFilm* film, uint64_t light_paths) {
  std::vector<std::string> ch = {"R", "G", "B"};
  if (aovs) ch.insert(ch.end(), {"albedo.R", "albedo.G", "albedo.B", "N.X", "N.Y", "N.Z", "Z"});
  image::Image img(width, height, ch);
  for (size_t p = 0; p < acc.size(); ++p) {
    const Accum& a = acc[p];
    if (!a.n) continue;
    float inv = 1.0f / float(a.n);
    float* px = img.pixels.data() + p * ch.size();
    Color3 v[3] = {a.L * inv, a.albedo * inv, a.normal * inv};
    if (film && light_paths) v[0] += film->sum(p) * float(1.0 / double(light_paths));
    for (int k = 0; k < (aovs ? 3 : 1); ++k)
      for (int c = 0; c < 3; ++c) px[3 * k + c] = v[k][c];
    if (aovs) px[9] = a.depth * inv;
  }
  return img;
}

} // namespace

image::Image render_image(const RenderScene& scene, int width, int height, const RenderOptions& opt,
                          const std::atomic<bool>* cancel, const ProgressFn& progress,
                          RenderStats* stats) {
  auto t0 = std::chrono::steady_clock::now();
  PathTracer pt(scene, opt.max_depth, opt.strategy, opt.time_shading);
  pt.set_clamp(opt.clamp);
  pt.set_aovs(opt.aovs);
  // Light paths for the environment's caustics: not with one technique switched off (the
  // comparisons' pure path tracers). With a clamp they run, unclamped: the clamp caps the
  // camera's paths' weighted share of the caustics, which the light paths make up (a clamp
  // alone removes the caustics of glass from the built-in preview).
  // The MIS weights take the light paths' count as it will be (trace_light_paths: the floor of
  // rate x samples x pixels), none when that is 0.
  const double pixels = double(width) * height,
               expected_paths = std::floor(double(opt.light_paths) * opt.spp * pixels);
  pt.set_caustics(expected_paths >= 1 && opt.strategy == Strategy::Mis,
                  opt.light_paths_only ? INFINITY : float(expected_paths / (opt.spp * pixels)),
                  uint64_t(pixels));
  std::unique_ptr<LightFilm> film;
  if (pt.caustics()) film = std::make_unique<LightFilm>(width, height, opt.pixel_filter);
  LargeVector<Accum> acc(size_t(width) * height);
  tbb::enumerable_thread_specific<ThreadState> states;
  int tiles = ((width + kTile - 1) / kTile) * ((height + kTile - 1) / kTile);
  uint64_t total = uint64_t(width) * height * opt.spp;
  std::atomic<uint64_t> done{0};
  std::atomic<bool> halt{false}; // a shade was stopped in a loop
  int threads = opt.threads > 0 ? opt.threads : tbb::this_task_arena::max_concurrency();
  auto allowed = allow_threads(threads);
  tbb::task_arena arena(threads);
  // Passes of 1, 1, 2, 4, ... 16 samples: early passes give a full (noisy) image quickly.
  for (int s0 = 0, pass = 1; s0 < opt.spp; s0 += pass, pass = std::min(pass * 2, 16)) {
    if (s0 == 1) pass = 1;
    int s1 = std::min(opt.spp, s0 + pass);
    arena.execute([&] {
      tbb::parallel_for(0, tiles, [&](int t) {
        render_tile(scene, pt, width, height, t, s0, s1, opt, cancel, halt, acc, film.get(),
                    states.local());
        int tw = std::min(kTile, width - (t % ((width + kTile - 1) / kTile)) * kTile);
        int th = std::min(kTile, height - (t / ((width + kTile - 1) / kTile)) * kTile);
        uint64_t d = done.fetch_add(uint64_t(tw) * th * (s1 - s0)) + uint64_t(tw) * th * (s1 - s0);
        if (progress) progress(std::min(d, total), total);
      });
    });
    if ((cancel && cancel->load()) || halt.load()) break;
  }
  if (stats) {
    *stats = RenderStats{};
    stats->seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    for (const Accum& a : acc) stats->samples += uint64_t(a.n);
    for (const ThreadState& ts : states) {
      stats->counters.rays += ts.counters.rays;
      stats->counters.shadow_rays += ts.counters.shadow_rays;
      stats->counters.shades += ts.counters.shades;
      stats->counters.shade_seconds += ts.counters.shade_seconds;
      stats->counters.light_paths += ts.counters.light_paths;
      stats->counters.splats += ts.counters.splats;
      stats->counters.light_seconds += ts.counters.light_seconds;
      stats->counters.phases.add(ts.counters.phases);
      merge_messages(ts.counters.messages, stats->counters.messages);
      if (stats->stopped.empty()) stats->stopped = ts.counters.stopped;
    }
    stats->cancelled = cancel && cancel->load();
  }
  uint64_t light_paths = 0;
  for (const ThreadState& ts : states) light_paths += ts.counters.light_paths;
  return resolve(acc, width, height, opt.aovs, film.get(), light_paths);
}

// Embree alone: camera rays, then one cosine-distributed bounce from each first hit.
double raw_traversal_rate(const RenderScene& s, int w, int h, int spp, int threads,
                          uint64_t& rays_out) {
  std::vector<Ray> rays;
  rays.reserve(size_t(w) * h * spp * 2);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      for (int k = 0; k < spp; ++k) {
        RandomStream smp(uint64_t(y) * w + x, k, 99);
        Ray r = s.camera().generate(x + smp.next(), y + smp.next(), 0.5f, 0.5f);
        rays.push_back(r);
        SurfaceHit hit;
        if (!s.geometry().intersect(r, hit)) continue;
        Frame f(dot(hit.Ng, r.dir) < 0 ? hit.Ng : -hit.Ng);
        float u1 = smp.next(), u2 = smp.next(), rr = std::sqrt(u1), phi = 2 * kPi * u2;
        Vec3 d = f.to_world({rr * std::cos(phi), rr * std::sin(phi), std::sqrt(1 - u1)});
        rays.push_back({offset_ray_origin(hit.P, hit.Ng, d), d});
      }
  std::atomic<uint64_t> hits{0};
  auto allowed = allow_threads(threads);
  tbb::task_arena arena(threads > 0 ? threads : tbb::this_task_arena::max_concurrency());
  auto t0 = std::chrono::steady_clock::now();
  arena.execute([&] {
    tbb::parallel_for(tbb::blocked_range<size_t>(0, rays.size(), 4096), [&](auto r) {
      uint64_t n = 0;
      for (size_t i = r.begin(); i < r.end(); ++i) {
        float t;
        n += s.geometry().intersect_raw(rays[i], t);
      }
      hits += n;
    });
  });
  double sec = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  rays_out = rays.size();
  return double(rays.size()) / sec;
}

double rel_mse(const image::Image& x, const image::Image& ref) {
  if (x.width != ref.width || x.height != ref.height || x.nchannels() < 3 || ref.nchannels() < 3)
    return -1;
  double sum = 0;
  size_t n = size_t(x.width) * x.height;
  for (size_t p = 0; p < n; ++p)
    for (int c = 0; c < 3; ++c) {
      double a = x.pixels[p * x.nchannels() + c], r = ref.pixels[p * ref.nchannels() + c];
      sum += (a - r) * (a - r) / (r * r + 0.01);
    }
  return sum / double(3 * n);
}

} // namespace lobe::render
