// The path tracer (see integrator.h).
#include "integrator.h"

#include "lobe/bsdf.h"
#include "lobe/context.h"

#include <chrono>
#if defined(__x86_64__) || defined(__i386__)
#include <x86intrin.h>
#endif

namespace lobe::render {
namespace {

uint64_t ticks() {
#if defined(__x86_64__) || defined(__i386__)
  return __rdtsc();
#else
  return uint64_t(std::chrono::steady_clock::now().time_since_epoch().count());
#endif
}

// Attributes the time since the previous lap to a phase; does nothing for untimed paths.
class Laps {
public:
  explicit Laps(PhaseTicks* p) : p_(p), t_(p ? ticks() : 0) {}
  void operator()(uint64_t PhaseTicks::*phase) {
    if (!p_) return;
    uint64_t n = ticks();
    p_->*phase += n - t_;
    t_ = n;
  }

private:
  PhaseTicks* p_;
  uint64_t t_;
};

struct Vertex {
  SurfaceHit hit;
  Bsdf bsdf;
};

// MIS weight for emission reached by a BSDF sample of density `bsdf_pdf` that light sampling
// would have produced with density `light_pdf`.
float weight_bsdf_hit(Strategy s, bool after_delta, float bsdf_pdf, float light_pdf) {
  if (after_delta || s == Strategy::BsdfOnly) return 1;
  if (s == Strategy::LightOnly) return light_pdf > 0 ? 0 : 1;
  return power_heuristic(bsdf_pdf, light_pdf);
}

// Whether a lobe transmits and is not a delta: light from behind the surface reaches it, so
// light samples are drawn over the whole sphere (EnvironmentLight::sample with a zero normal).
bool transmits_diffusely(const Bsdf& b) {
  for (int i = 0; i < b.lobe_count(); ++i) {
    uint32_t f = b.lobe(i).flags;
    if ((f & kLobeTransmit) && !(f & kLobeSpecular)) return true;
  }
  return false;
}

// Scales `c` down to luminance `cap` when above it (cap 0: unchanged).
Color3 clamped(const Color3& c, float cap) {
  if (!(cap > 0)) return c;
  float l = luminance(c);
  return l > cap ? c * (cap / l) : c;
}

} // namespace

// Shades `hit` seen along `dir` and flattens its closure into `bsdf`.
// `path_length`: distance travelled from the camera (0 for light-sample points: no footprint).
static void shade_into(const RenderScene& scene, const SurfaceHit& hit, const Vec3& dir,
                       int raytype, ShadingContext& ctx, Bsdf& bsdf, TraceCounters& c, bool timed,
                       Laps& lap, float path_length = 0) {
  ShaderGlobals sg;
  Footprint fp;
  fp.angle = scene.camera().pixel_spread();
  fp.width = fp.angle * path_length;
  fp.right = scene.camera().right();
  fp.up = scene.camera().up();
  fill_globals(sg, hit, dir, raytype, ctx, scene.globals_read(hit.shape), fp);
  sg.renderstate = scene.renderstate(hit.shape);
  sg.surfacearea = scene.surface_area(hit.shape);
  ctx.renderer = &scene.services();
  ctx.reset();
  auto t0 = timed ? std::chrono::steady_clock::now() : std::chrono::steady_clock::time_point{};
  scene.material(hit.shape).shade(sg);
  if (ctx.stopped && ctx.errors && c.stopped.empty())
    c.stopped = scene.stop_reason(ctx, scene.material_index(hit.shape), "rendering");
  // Messages from shader code (a missing texture...), collected per thread, reported after.
  if (!ctx.output.empty()) collect_messages(ctx, scene.material_index(hit.shape), c.messages);
  lap(&PhaseTicks::shade);
  bsdf.build(sg.Ci, -dir, hit.Ng, scene.closure_kernels(hit.shape), sg.backfacing != 0);
  lap(&PhaseTicks::bsdf);
  ++c.shades;
  if (timed)
    c.shade_seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

PathResult PathTracer::trace(const Ray& camera_ray, const Sampler& sampler, ShadingContext& ctx,
                             ShadingContext& light_ctx, TraceCounters& c, bool timed) const {
  Laps lap(timed ? &c.phases : nullptr);
  using P = PhaseTicks;
  const LightSet& lights = scene_.lights();
  const Geometry& geo = scene_.geometry();
  PathResult out;
  Color3 beta{1, 1, 1};
  Ray ray = camera_ray;
  bool after_delta = true; // the camera ray counts as delta: emission seen directly has weight 1
  float prev_pdf = 0;
  Vec3 prev_p, prev_n; // the previous vertex and its normal on the side of the sampled ray
  int raytype = kRayCamera;
  float path_length = 0; // distance from the camera along the path (for ray footprints)
  // The radiance scaling of the refractions so far (product of eta^2): Russian roulette looks
  // at beta * eta_scale, so a path inside glass (beta / eta^2 until it leaves) is not culled
  // for a drop that leaving undoes (a survivor's beta / q would come out eta^2 too high).
  float eta_scale = 1;
  Vertex v;
  for (int depth = 0;; ++depth) {
    ++c.rays;
    Geometry::RawHit raw;
    lap(&P::other);
    bool found = geo.traverse(ray, raw);
    lap(&P::traverse);
    if (!found) {
      if (after_delta && scene_.has_background_shader()) {
        // Seen by the camera or through specular bounces (no light sample competes: weight
        // 1): the background shader itself, not its table (as testrender shades camera rays).
        lap(&P::other);
        Color3 Le = scene_.shade_background(ray.dir, raytype, ctx, c.messages);
        if (ctx.stopped && ctx.errors && c.stopped.empty())
          c.stopped = scene_.stop_reason(ctx, scene_.desc().environment.material, "rendering");
        lap(&P::shade);
        Color3 col = beta * Le;
        out.L += depth >= 2 ? clamped(col, clamp_) : col;
      } else if (lights.environment()) {
        float lp;
        Color3 Le = lights.environment_hit(ray.dir, prev_n, lp);
        Color3 contrib = beta * Le * weight_bsdf_hit(strategy_, after_delta, prev_pdf, lp);
        out.L += depth >= 2 ? clamped(contrib, clamp_) : contrib;
      }
      lap(&P::lights);
      break;
    }
    geo.complete(ray, raw, v.hit);
    lap(&P::hit);
    path_length += v.hit.t;
    shade_into(scene_, v.hit, ray.dir, raytype, ctx, v.bsdf, c, time_, lap, path_length);
    const Vec3 wo = -ray.dir;
    // The shading normal on the viewer's side: the hemisphere the environment is sampled over
    // (none, the whole sphere, for a surface lit through from behind).
    const Vec3 n_lit = transmits_diffusely(v.bsdf) ? Vec3{}
                       : dot(v.hit.N, wo) < 0      ? -v.hit.N
                                                   : v.hit.N;
    if (!is_zero(v.bsdf.emission)) {
      float lp = lights.is_emitter(v.hit.shape) ? lights.pdf_area(prev_p, v.hit) : 0;
      Color3 contrib =
          beta * v.bsdf.emission * weight_bsdf_hit(strategy_, after_delta, prev_pdf, lp);
      out.L += depth >= 2 ? clamped(contrib, clamp_) : contrib;
      lap(&P::lights);
    }
    if (depth == 0 && aovs_) {
      lap(&P::other);
      out.albedo = v.bsdf.albedo(wo) + v.bsdf.emission;
      lap(&P::bsdf);
      out.normal = v.hit.N;
      out.depth = v.hit.t;
    }
    if (depth >= max_depth_) break;
    namespace g = path_groups;
    const uint64_t groups = g::kFirstVertex + uint64_t(depth) * g::kVertexGroups;

    // Transparency (transparent() closures): pass straight through with probability
    // p = T / (T + albedo) (by luminance), else scatter; each branch divides by its probability.
    if (!is_zero(v.bsdf.transparency)) {
      float t = luminance(v.bsdf.transparency), a = luminance(v.bsdf.albedo(wo));
      float p = t > 0 ? std::min(1.0f, t / (t + std::max(a, 0.0f))) : 0.0f;
      float u;
      sampler.groups<1>(groups + g::kTransparency, {1}, &u);
      if (u < p) {
        beta = beta * v.bsdf.transparency / p;
        ray = Ray{offset_ray_origin(v.hit.P, v.hit.Ng, ray.dir), ray.dir};
        // Shadow rays treat transparent surfaces as opaque: light reached through one is
        // found by this path alone, so it counts with weight 1.
        after_delta = true;
        if (is_zero(beta)) break;
        continue;
      }
      beta = beta / (1 - p);
    }

    // The vertex's numbers, drawn together (Sampler::groups): the light sample's two, the BSDF
    // sample's three, Russian roulette's, and the light choice's when there is a choice.
    static_assert(g::kBsdf == g::kLight + 1 && g::kRoulette == g::kLight + 2 &&
                  g::kLightChoice == g::kLight + 3);
    float un[7];
    un[6] = 0.5f;
    if (lights.count() > 1)
      sampler.groups<4>(groups + g::kLight, {2, 3, 1, 1}, un);
    else
      sampler.groups<3>(groups + g::kLight, {2, 3, 1}, un);
    const float u1 = un[0], u2 = un[1], u_roulette = un[5], us = un[6];
    const Vec3 u_bsdf{un[2], un[3], un[4]};

    // Next-event estimation.
    if (strategy_ != Strategy::BsdfOnly && v.bsdf.has_non_delta()) {
      LightSample ls;
      lap(&P::other);
      bool sampled = lights.sample(v.hit.P, n_lit, us, u1, u2, ls);
      lap(&P::lights);
      if (sampled) {
        BsdfEval f = v.bsdf.eval(wo, ls.wi);
        lap(&P::bsdf);
        if (!is_zero(f.value)) {
          Color3 Le = ls.L;
          bool delta = ls.kind == LightSample::Kind::Point;
          if (ls.kind == LightSample::Kind::Area) {
            Bsdf eb;
            // Not `ctx`: shading resets the arena, which holds the closure (and lobe
            // parameters) of the vertex being lit, still needed for the BSDF sample below.
            lap(&P::other);
            shade_into(scene_, ls.surface, ls.wi, kRayShadow, light_ctx, eb, c, time_, lap);
            Le = eb.emission;
          }
          Vec3 org = offset_ray_origin(v.hit.P, v.hit.Ng, ls.wi);
          float tmax = ls.kind == LightSample::Kind::Environment ? 1e30f : ls.dist * (1 - 1e-4f);
          ++c.shadow_rays;
          bool visible = false;
          if (!is_zero(Le)) {
            lap(&P::other);
            visible = !geo.occluded(org, ls.wi, tmax);
            lap(&P::traverse);
          }
          if (visible) {
            float w =
                (delta || strategy_ == Strategy::LightOnly) ? 1 : power_heuristic(ls.pdf, f.pdf);
            Color3 contrib = beta * f.value * Le * (w / ls.pdf);
            out.L += depth >= 1 ? clamped(contrib, clamp_) : contrib;
          }
        }
      }
    }

    // Continue the path by sampling the BSDF.
    lap(&P::other);
    auto s = v.bsdf.sample(wo, u_bsdf);
    lap(&P::bsdf);
    if (!s) break;
    beta *= s->weight;
    if (is_zero(beta) || !is_finite(beta)) break;
    after_delta = (s->flags & kLobeSpecular) != 0;
    prev_pdf = s->pdf;
    prev_p = v.hit.P;
    prev_n = n_lit;
    raytype = after_delta ? (s->flags & kLobeTransmit ? kRayRefraction : kRayReflection)
                          : (s->flags & kLobeDiffuse ? kRayDiffuse : kRayGlossy);
    ray = Ray{offset_ray_origin(v.hit.P, v.hit.Ng, s->wi), s->wi};
    if (s->flags & kLobeTransmit) eta_scale *= s->eta * s->eta;
    if (depth >= 3) {
      float q = std::min(0.95f, max_component(beta) * eta_scale);
      if (u_roulette >= q) break;
      beta = beta / q;
    }
  }
  lap(&P::other);
  if (timed) ++c.phases.paths;
  return out;
}

} // namespace lobe::render
