// Unidirectional path tracer with next-event estimation and multiple importance sampling.
//
// At each vertex: emission found by a BSDF-sampled ray is weighted against light sampling
// (power heuristic); one light is sampled (point, spot, area, environment) and weighted
// against BSDF sampling; delta lobes and delta lights are exact (weight 1). Russian roulette
// after three bounces. transparent() closures are followed straight through, chosen against
// scattering in proportion to transparency and albedo. Strategy::BsdfOnly and Strategy::LightOnly
// switch one technique off (for the benchmark's comparison): BsdfOnly cannot see point and spot
// lights.
//
// Caustics of the environment (set_caustics): light reaching a surface seen by the camera
// through delta lobes alone (a floor lit through a glass sphere) is found by a path only when
// its BSDF sample happens to leave through the sphere towards a bright part of the
// environment: rare samples of great weight (fireflies). Those paths are traced from the
// other end as well: trace_light() starts a ray in the environment, importance-sampled by its
// table, aimed at a sphere round a caustic target (RenderScene::caustic_targets), follows it
// through delta lobes of targets and, at each surface it reaches, connects to the camera (the
// camera's path's first vertex) and bounces once more, cosine-distributed, to connect the
// point it reaches (its second vertex), splatting into a LightFilm. A camera path whose first
// one or two vertices scattered by non-delta lobes and every later one by a delta lobe of an
// opaque target, and which then reaches the environment, is one both make (with at most
// max_depth - 1 delta vertices after its first vertex, max_depth - 2 after its second, as the
// camera's paths allow): the two weigh it by the power heuristic, pixel by pixel, so the
// weights sum to one and the image is unbiased. The light path shades a target from the
// light's side, so a target's shader is taken to be reciprocal (glass and mirrors written as
// OSL's are); one that reads raytype is not a target, nor a second vertex.
#pragma once

#include "sampling.h"
#include "scene_setup.h"

#if defined(__x86_64__) || defined(__i386__)
#include <x86intrin.h>
#endif

#include <atomic>
#include <chrono>
#include <cstdint>
#include <vector>

namespace lobe::render {

enum class Strategy { Mis, BsdfOnly, LightOnly };

struct PathResult {
  Color3 L;
  // First-hit AOVs: albedo (BSDF directional albedo + emission), shading normal, distance.
  Color3 albedo, normal;
  float depth = 0;
};

// The clock of `--stats`' time split: the processor's time-stamp counter where there is one.
inline uint64_t phase_ticks() {
#if defined(__x86_64__) || defined(__i386__)
  return __rdtsc();
#else
  return uint64_t(std::chrono::steady_clock::now().time_since_epoch().count());
#endif
}

// Where a path's time goes (RenderOptions::profile, `lobe render --stats`): timestamp-counter
// ticks per phase, summed over the paths traced with timing on (a fixed subset of samples, so
// the clock reads cost next to nothing). Phases partition each timed path.
struct PhaseTicks {
  uint64_t traverse = 0; // Embree closest-hit and occlusion queries
  uint64_t hit = 0;      // surface data at each hit (position, normals, uv, tangents)
  uint64_t shade = 0;    // fill_globals and Material::shade (the shader code)
  uint64_t bsdf = 0;     // Bsdf::build, eval, sample and albedo
  uint64_t lights = 0;   // light selection and sampling, environment lookups, MIS pdfs
  uint64_t other = 0;    // the rest of the integrator (throughput, roulette, ray set-up)
  uint64_t paths = 0;
  uint64_t total() const { return traverse + hit + shade + bsdf + lights + other; }
  void add(const PhaseTicks& o) {
    traverse += o.traverse, hit += o.hit, shade += o.shade, bsdf += o.bsdf, lights += o.lights;
    other += o.other, paths += o.paths;
  }
};

// Per-thread counters (summed by the renderer).
struct TraceCounters {
  uint64_t rays = 0;        // closest-hit queries
  uint64_t shadow_rays = 0; // occlusion queries
  uint64_t shades = 0;      // Material::shade calls
  double shade_seconds = 0; // time inside Material::shade + Bsdf::build (when timed)
  PhaseTicks phases;        // time split of the timed paths (RenderOptions::profile)
  ShaderMessages messages;  // what shader code reported (texture errors, error(), printf)
  // The first shade stopped in a loop (ShadingContext::stopped) past max_loop_iterations:
  // RenderScene::stop_reason's text; the renderer then stops.
  std::string stopped;
  uint64_t light_paths = 0; // light paths traced (trace_light), splats they made
  uint64_t splats = 0;
  double light_seconds = 0; // thread time in light paths (RenderOptions::profile)
};

// What light paths add to the image: per pixel, the sum of their splats, filtered as the
// camera's samples are (a box over the pixel, or testrender's tent two pixels wide). Sums are
// kept in fixed point (2^-20), so that they come out the same whatever order threads add
// them in: the image depends on the seed alone, as the camera's samples do.
class LightFilm {
public:
  LightFilm(int width, int height, scene::PixelFilter filter)
      : w_(width), h_(height), filter_(filter), sum_(size_t(width) * height * 3) {}
  // Adds `v` (per unit of film area, in pixels) at film position (fx, fy), to each pixel by
  // its filter weight h times the light path's MIS weight there: the power heuristic of
  // `ratio`, the light paths' density over the camera's at h = 1 (the camera's scales with h).
  void splat(float fx, float fy, const Color3& v, float ratio = INFINITY);
  // The sum of the splats of pixel p (divide by the number of light paths).
  Color3 sum(size_t p) const;

private:
  void add(int x, int y, float w, const Color3& v);
  int w_, h_;
  scene::PixelFilter filter_;
  std::vector<std::atomic<int64_t>> sum_;
};

// The Sampler groups of a path: the camera's (its pixel position, then its lens position), then
// kVertexGroups for each vertex, one per use, so that each use at each depth is stratified
// over a pixel's samples whichever other uses a sample skipped.
namespace path_groups {
inline constexpr uint64_t kPixel = 1, kLens = 2, kFirstVertex = 3;
// Offsets within a vertex's groups.
inline constexpr uint64_t kLight = 0;        // 2-D: the light sample's position
inline constexpr uint64_t kBsdf = 1;         // 3-D: the BSDF sample (lobe choice, direction)
inline constexpr uint64_t kRoulette = 2;     // 1-D: Russian roulette
inline constexpr uint64_t kLightChoice = 3;  // 1-D: which light, when there is a choice
inline constexpr uint64_t kTransparency = 4; // 1-D: through a transparent surface or not
inline constexpr uint64_t kVertexGroups = 5;
} // namespace path_groups

class PathTracer {
public:
  PathTracer(const RenderScene& scene, int max_depth, Strategy strategy, bool time_shading)
      : scene_(scene), max_depth_(max_depth), strategy_(strategy), time_(time_shading) {}

  // `ctx` holds the closures of the path's vertices; `light_ctx` is where emitters are shaded
  // for next-event estimation, so that shading a light never resets the arena holding the
  // closure of the point it lights. One pair per thread. `timed`: add this path's time split
  // to counters.phases.
  // Luminance cap on each contribution of light reaching the path after its first bounce
  // (NEE from the second vertex on, emission and environment found by the second and later
  // BSDF rays); 0: none. Biased (loses the energy above the cap); direct light is exact.
  void set_clamp(float c) { clamp_ = c; }
  // First-hit AOVs (PathResult::albedo, normal, depth): computed only when wanted.
  void set_aovs(bool on) { aovs_ = on; }
  // Caustics of the environment by light paths (top of this file): on only where the scene
  // allows them (caustics_possible); the caller then traces light paths with trace_light.
  // `light_paths`: light paths per camera sample, `pixels` the image's: the two techniques'
  // sample counts, in their MIS weights (infinite: the light paths take every caustic path
  // they can make, with weight 1).
  void set_caustics(bool on, float light_paths = 1, uint64_t pixels = 1) {
    caustics_ = on && caustics_possible(scene_);
    light_share_ = light_paths * float(pixels);
  }
  bool caustics() const { return caustics_; }
  // An environment, caustic targets and a pinhole camera.
  static bool caustics_possible(const RenderScene& scene);

  // `film_density`: the pixel filter's density at the camera ray's film position (the tent's
  // (1 - |dx|)(1 - |dy|), a box's 1), for the MIS weights of caustics.
  // `first`: the camera ray's hit when already traced (Geometry::traverse_packet), else null;
  // `first_ticks`: this ray's share of that traversal's phase_ticks(), for a timed path.
  PathResult trace(const Ray& camera_ray, const Sampler& sampler, ShadingContext& ctx,
                   ShadingContext& light_ctx, TraceCounters& counters, bool timed = false,
                   float film_density = 1, const Geometry::RawHit* first = nullptr,
                   uint64_t first_ticks = 0) const;
  // One light path from the environment (numbers from `rng`), its camera connections splatted
  // into `film`; the image adds film.sum(p) / (light paths traced). Needs caustics().
  // `ctx` holds the target being crossed, `link_ctx` shades the camera's connections.
  void trace_light(RandomStream& rng, ShadingContext& ctx, ShadingContext& link_ctx,
                   TraceCounters& counters, LightFilm& film) const;

private:
  struct CameraLink {
    float fx = 0, fy = 0; // film position
    float to_area = 0;    // film_to_area (integrator.cpp)
    float dist = 0;       // to the camera
    BsdfEval f;           // towards the camera, light from wi
  };
  bool link_camera(const SurfaceHit& hit, const Vec3& wi, ShadingContext& ctx,
                   TraceCounters& counters, CameraLink& out) const;
  void splat(const CameraLink& link, const Color3& radiance, float camera, float light,
             TraceCounters& counters, LightFilm& film) const;
  void bounce_to_camera(const SurfaceHit& y, const Vec3& d, const Color3& beta, float light_pdf,
                        RandomStream& rng, ShadingContext& ctx, TraceCounters& counters,
                        LightFilm& film) const;

  const RenderScene& scene_;
  int max_depth_;
  Strategy strategy_;
  bool time_;
  float clamp_ = 0;
  bool aovs_ = true;
  bool caustics_ = false;
  float light_share_ = 1; // light paths per camera sample of a pixel (set_caustics)
};

} // namespace lobe::render
