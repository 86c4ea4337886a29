// Unidirectional path tracer with next-event estimation and multiple importance sampling.
//
// At each vertex: emission found by a BSDF-sampled ray is weighted against light sampling
// (power heuristic); one light is sampled (point, spot, area, environment) and weighted
// against BSDF sampling; delta lobes and delta lights are exact (weight 1). Russian roulette
// after three bounces. transparent() closures are followed straight through, chosen against
// scattering in proportion to transparency and albedo. Strategy::BsdfOnly and Strategy::LightOnly
// switch one technique off (for the benchmark's comparison): BsdfOnly cannot see point and spot
// lights.
#pragma once

#include "sampling.h"
#include "scene_setup.h"

#include <cstdint>

namespace lobe::render {

enum class Strategy { Mis, BsdfOnly, LightOnly };

struct PathResult {
  Color3 L;
  // First-hit AOVs: albedo (BSDF directional albedo + emission), shading normal, distance.
  Color3 albedo, normal;
  float depth = 0;
};

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

  PathResult trace(const Ray& camera_ray, const Sampler& sampler, ShadingContext& ctx,
                   ShadingContext& light_ctx, TraceCounters& counters, bool timed = false) const;

private:
  const RenderScene& scene_;
  int max_depth_;
  Strategy strategy_;
  bool time_;
  float clamp_ = 0;
  bool aovs_ = true;
};

} // namespace lobe::render
