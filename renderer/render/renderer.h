// Image rendering: tiles of 16x16 pixels in parallel on oneTBB, in progressive passes so that
// an interrupted render still covers the whole image.
//
// Determinism: sample s of pixel p always uses Sampler(p, s, seed) and each pixel accumulates
// its samples in index order, whichever thread runs it, so the image depends only on scene,
// sample count and seed; the thread count changes nothing (tested bit for bit).
#pragma once

#include "image.h"
#include "integrator.h"
#include "scene_setup.h"

#include <atomic>
#include <cstdint>
#include <functional>

namespace lobe::render {

struct RenderOptions {
  int spp = 16;
  int max_depth = 8;
  uint64_t seed = 0;
  int threads = 0; // 0: all cores
  Strategy strategy = Strategy::Mis;
  bool aovs = true;          // albedo, normal and depth channels
  bool time_shading = false; // measure time inside materials (small overhead)
  // Time split of one path in kProfileEvery (RenderStats::counters.phases; `lobe render
  // --stats`): a few timestamp reads per vertex on those paths only.
  bool profile = false;
  float clamp = 0; // Settings::clamp: luminance cap on indirect contributions (0: none; biased)
  scene::PixelFilter pixel_filter = scene::PixelFilter::Box; // Settings::pixel_filter
  // Light paths traced per camera sample for the environment's caustics (integrator.h; where
  // the scene has them: PathTracer::caustics_possible); 0: none, the camera's paths find them.
  float light_paths = 0.1f;
  // The caustic paths both the light paths and the camera's can make go to the light paths
  // alone, unweighed (their estimator by itself: for tests and measurement).
  bool light_paths_only = false;
};

constexpr int kProfileEvery = 8;

struct RenderStats {
  double seconds = 0;
  uint64_t samples = 0; // pixel samples finished
  TraceCounters counters;
  bool cancelled = false;
  // A shade was stopped in a loop (CompileOptions::max_loop_iterations): why (the material,
  // shader and loop); rendering stopped there.
  std::string stopped;
};

// Called from worker threads after each tile (thread-safe receivers only): pixel samples done
// so far and in total.
using ProgressFn = std::function<void(uint64_t done, uint64_t total)>;

// Renders `scene` (set up for its camera resolution `width` x `height`). Channels: R G B, then
// with aovs: albedo.R/G/B, N.X/Y/Z, Z. Pixels that got no sample before a cancel are black.
image::Image render_image(const RenderScene& scene, int width, int height, const RenderOptions& opt,
                          const std::atomic<bool>* cancel, const ProgressFn& progress,
                          RenderStats* stats);

// Embree's own speed on this scene: camera rays (spp per pixel), then one cosine-distributed
// bounce from each first hit, traced with closest-hit queries only (no surface data, no
// shading) on `threads` (0: all cores). Rays per second; `rays_out`: how many were traced.
double raw_traversal_rate(const RenderScene& scene, int width, int height, int spp, int threads,
                          uint64_t& rays_out);

// relMSE = mean over pixels and RGB of (x - r)^2 / (r^2 + 0.01), the metric in bench/ and
// tests (BSDF_NOTES.md); both images must have the same size, first three channels compared.
double rel_mse(const image::Image& x, const image::Image& ref);

} // namespace lobe::render
