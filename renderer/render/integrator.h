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

// Per-thread counters (summed by the renderer).
struct TraceCounters {
  uint64_t rays = 0;        // closest-hit queries
  uint64_t shadow_rays = 0; // occlusion queries
  uint64_t shades = 0;      // Material::shade calls
  double shade_seconds = 0; // time inside Material::shade + Bsdf::build (when timed)
  ShaderMessages messages;  // what shader code reported (texture errors, error(), printf)
  // The first shade stopped in a loop (ShadingContext::stopped) past max_loop_iterations:
  // RenderScene::stop_reason's text; the renderer then stops.
  std::string stopped;
};

class PathTracer {
public:
  PathTracer(const RenderScene& scene, int max_depth, Strategy strategy, bool time_shading)
      : scene_(scene), max_depth_(max_depth), strategy_(strategy), time_(time_shading) {}

  // `ctx` holds the closures of the path's vertices; `light_ctx` is where emitters are shaded
  // for next-event estimation, so that shading a light never resets the arena holding the
  // closure of the point it lights. One pair per thread.
  PathResult trace(const Ray& camera_ray, Sampler& sampler, ShadingContext& ctx,
                   ShadingContext& light_ctx, TraceCounters& counters) const;

private:
  const RenderScene& scene_;
  int max_depth_;
  Strategy strategy_;
  bool time_;
};

} // namespace lobe::render
