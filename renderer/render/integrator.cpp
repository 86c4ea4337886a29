// The path tracer (see integrator.h).
#include "integrator.h"

#include "lobe/bsdf.h"
#include "lobe/context.h"

#include <algorithm>
#include <chrono>
#include <cmath>
namespace lobe::render {
namespace {

// Attributes the time since the previous lap to a phase; does nothing for untimed paths.
class Laps {
public:
  explicit Laps(PhaseTicks* p) : p_(p), t_(p ? phase_ticks() : 0) {}
  void operator()(uint64_t PhaseTicks::*phase) {
    if (!p_) return;
    uint64_t n = phase_ticks();
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

// The density, over area across the line, of a light path's first ray along the line through
// `p` in direction `d` (PathTracer::trace_light): the shares over the disk areas of the
// caustic targets whose spheres the line crosses.
float line_density(const RenderScene& scene, const Vec3& p, const Vec3& d) {
  float pdf = 0;
  for (const RenderScene::CausticTarget& o : scene.caustic_targets()) {
    Vec3 q = o.center - p;
    Vec3 off = q - d * dot(q, d);
    if (dot(off, off) < o.radius * o.radius) pdf += o.select / (kPi * o.radius * o.radius);
  }
  return pdf;
}

// The camera's paths' MIS weight (power heuristic) against the light paths', from the two
// densities (the camera's with its filter weight): 1 / (1 + (light / camera)^2), in that form
// so that no square overflows (the light paths' weight, LightFilm::splat, is its complement).
float camera_weight(float camera, float light) {
  if (!(light > 0)) return 1;
  if (std::isinf(light) || !(camera > 0)) return 0;
  float r = light / camera;
  return 1 / (1 + r * r);
}

// The area density, on the surface at `p` (geometric normal `ng`), of the camera's rays per
// unit of film area: |ng.wo| / (dist^2 * pixel area at distance 1 * cos^3 of the ray with the
// view axis, `cos_axis` from Camera::project).
float film_to_area(const Camera& cam, const Vec3& p, const Vec3& ng, float cos_axis) {
  Vec3 to_eye = cam.position() - p;
  float dist2 = dot(to_eye, to_eye), spread = cam.pixel_spread();
  if (!(dist2 > 0)) return 0;
  float cos_out = std::abs(dot(ng, to_eye)) / std::sqrt(dist2);
  return cos_out / (dist2 * spread * spread * cos_axis * cos_axis * cos_axis);
}

// The same for a point the pinhole may not see in front (0 then).
float film_to_area(const Camera& cam, const Vec3& p, const Vec3& ng) {
  float fx, fy, cos_axis;
  return cam.project(p, fx, fy, cos_axis) ? film_to_area(cam, p, ng, cos_axis) : 0;
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
                             ShadingContext& light_ctx, TraceCounters& c, bool timed,
                             float film_density, const Geometry::RawHit* first,
                             uint64_t first_ticks) const {
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
  // A caustic of the environment so far (integrator.h): the first vertex (caustic 1), or the
  // first two (caustic 2), scattered by a non-delta lobe and every later one by a delta lobe of
  // an opaque caustic target. The environment such a path reaches is weighed against the
  // light paths' finding it; the densities of the two, over the same variables, but for the
  // factors they share and those known only at the end: caustic_camera (the film's
  // film_density times the BSDF pdfs at the non-delta vertices; film_to_area at the first
  // vertex, caustic_p and caustic_ng, joins it only if the environment is reached), caustic_light
  // (|Ng.wi| at the first vertex, times, for two, |Ng.wi| / pi at the second: the light
  // path's cosine bounce there, its density |Ng.wo| / pi with the |Ng.wo| both share dropped).
  int caustic = 0, caustic_deltas = 0;
  float caustic_camera = 0, caustic_light = 0;
  Vec3 caustic_p, caustic_ng;
  Vertex v;
  for (int depth = 0;; ++depth) {
    ++c.rays;
    Geometry::RawHit raw;
    lap(&P::other);
    bool found;
    if (depth == 0 && first) {
      raw = *first;
      found = raw.geom != RTC_INVALID_GEOMETRY_ID;
      if (timed) c.phases.traverse += first_ticks; // its share of the packet's traversal
    } else {
      found = geo.traverse(ray, raw);
    }
    lap(&P::traverse);
    if (!found) {
      float w = 1; // MIS weight against the light paths (a caustic of the environment)
      if (caustic && caustic_deltas >= 1 && lights.environment()) {
        float light = lights.environment()->pdf(ray.dir) * line_density(scene_, ray.org, ray.dir) *
                      caustic_light;
        w = camera_weight(caustic_camera * film_to_area(scene_.camera(), caustic_p, caustic_ng),
                          light > 0 ? light_share_ * light : 0.0f);
      }
      if (after_delta && scene_.has_background_shader()) {
        // Seen by the camera or through specular bounces (no light sample competes: weight
        // 1): the background shader itself, not its table (as testrender shades camera rays).
        lap(&P::other);
        Color3 Le = scene_.shade_background(ray.dir, raytype, ctx, c.messages);
        if (ctx.stopped && ctx.errors && c.stopped.empty())
          c.stopped = scene_.stop_reason(ctx, scene_.desc().environment.material, "rendering");
        lap(&P::shade);
        Color3 col = beta * Le * w;
        out.L += depth >= 2 ? clamped(col, clamp_) : col;
      } else if (lights.environment()) {
        float lp;
        Color3 Le = lights.environment_hit(ray.dir, prev_n, lp);
        Color3 contrib = beta * Le * (weight_bsdf_hit(strategy_, after_delta, prev_pdf, lp) * w);
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
        caustic = 0;
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
            if (const Color3* e = scene_.uniform_emission(ls.surface.shape)) {
              Le = *e; // the same at every point: shaded once, at set-up
            } else {
              Bsdf eb;
              // Not `ctx`: shading resets the arena, which holds the closure (and lobe
              // parameters) of the vertex being lit, still needed for the BSDF sample below.
              lap(&P::other);
              shade_into(scene_, ls.surface, ls.wi, kRayShadow, light_ctx, eb, c, time_, lap);
              Le = eb.emission;
            }
          }
          Vec3 org = offset_ray_origin(v.hit.P, v.hit.Ng, ls.wi);
          Vec3 shadow_dir = ls.wi;
          float tmax = ls.kind == LightSample::Kind::Environment ? 1e30f : ls.dist * (1 - 1e-4f);
          if (ls.kind == LightSample::Kind::Area) {
            // From offset point to offset point: aimed from the shading point itself, a ray
            // that grazes the light (the ceiling beside a panel just under it) meets the
            // light's plane short of the sampled point by the origin's offset over the slope,
            // and the light would shadow itself.
            Vec3 d = offset_ray_origin(ls.surface.P, ls.surface.Ng, -ls.wi) - org;
            float len = length(d);
            if (len > 0) shadow_dir = d / len, tmax = len * (1 - 1e-4f);
          }
          ++c.shadow_rays;
          bool visible = false;
          if (!is_zero(Le)) {
            lap(&P::other);
            visible = !geo.occluded(org, shadow_dir, tmax);
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
    if (caustics_) {
      const float cos_out = std::abs(dot(v.hit.Ng, s->wi));
      if (depth == 0) {
        caustic = after_delta ? 0 : 1;
        caustic_deltas = 0;
        caustic_camera = film_density * s->pdf;
        caustic_p = v.hit.P, caustic_ng = v.hit.Ng;
        caustic_light = cos_out;
      } else if (caustic && after_delta && is_zero(v.bsdf.transparency) &&
                 scene_.is_caustic_target(v.hit.shape)) {
        ++caustic_deltas;
      } else if (caustic == 1 && caustic_deltas == 0 && !after_delta &&
                 !(scene_.globals_read(v.hit.shape) & Material::kReadsRaytype)) {
        // The light path bounces on the side its light arrives from (bounce_to_camera).
        caustic = 2;
        caustic_camera *= s->pdf;
        caustic_light *= dot(v.hit.Ng, s->wi) * dot(v.hit.Ng, wo) > 0 ? cos_out / kPi : 0;
      } else {
        caustic = 0;
      }
    }
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

bool PathTracer::caustics_possible(const RenderScene& scene) {
  return !scene.caustic_targets().empty() && scene.lights().environment() &&
         !scene.camera().has_lens();
}

void PathTracer::trace_light(RandomStream& rng, ShadingContext& ctx, ShadingContext& link_ctx,
                             TraceCounters& c, LightFilm& film) const {
  const EnvironmentLight* env = scene_.lights().environment();
  const auto& targets = scene_.caustic_targets();
  if (!caustics_ || !env) return;
  ++c.light_paths;
  const Geometry& geo = scene_.geometry();
  // A target by its share, a direction towards the environment by its table, and a point on
  // the disk that is the target's sphere seen along it, moved back out of the scene.
  float us = rng.next();
  size_t t = 0;
  while (t + 1 < targets.size() && us >= targets[t].select) us -= targets[t++].select;
  const RenderScene::CausticTarget& target = targets[t];
  float u1 = rng.next(), u2 = rng.next(), pdf_dir = 0;
  const Vec3 w = env->sample(u1, u2, pdf_dir); // towards the environment
  if (!(pdf_dir > 0) || !std::isfinite(pdf_dir)) return;
  const Vec3 d = -w; // the way the light travels
  Frame frame(d);
  float dx, dy;
  concentric_disk(rng.next(), rng.next(), dx, dy);
  Vec3 on_disk = target.center + (frame.t * dx + frame.b * dy) * target.radius;
  float back = length(target.center - geo.center()) + geo.radius() * 1.01f + target.radius;
  Ray ray{on_disk - d * back, d};
  // The density of this line over the area across it: every target whose disk it crosses.
  const float pdf_line = line_density(scene_, ray.org, d);
  if (!(pdf_line > 0)) return;
  // The MIS weights take the direction's density from pdf(w), as the camera's paths do (the
  // flux below divides by the density sample() drew it with; the two agree but for rounding).
  const float light_pdf = env->pdf(w) * pdf_line;
  Color3 beta; // flux of the path: set at its first vertex, where the ray type is known
  Vertex v;
  Laps untimed(nullptr);
  for (int deltas = 0;;) {
    Geometry::RawHit raw;
    ++c.rays;
    if (!geo.traverse(ray, raw)) return;
    geo.complete(ray, raw, v.hit);
    // The camera's path has at most max_depth - 1 delta vertices after its first.
    const bool go_on = deltas < max_depth_ - 1 && scene_.is_caustic_target(v.hit.shape);
    bool has_delta = false, has_other = true;
    if (go_on) {
      // The target from the light's side (in ctx: its closure stays while the camera's
      // connections shade in link_ctx).
      shade_into(scene_, v.hit, ray.dir, kRayRefraction, ctx, v.bsdf, c, false, untimed);
      if (ctx.stopped) return;
      has_other = v.bsdf.has_non_delta();
      has_delta = v.bsdf.has_delta();
    }
    // A target with delta lobes alone (the inside of a glass sphere) is no one's first or
    // second vertex: nothing to connect.
    if (deltas >= 1 && has_other) {
      // Seen by the camera (its path's first vertex). The radiance towards the camera is
      // f * beta / |Ng.wi| (beta counts area across the ray, the surface's is |Ng.wi| of it).
      // The densities, both over the first vertex's area and the direction there: the
      // camera's film_to_area * pdf, the light's its first ray's times |Ng.wi|.
      const Vec3 wi = -ray.dir;
      const float cos_in = std::abs(dot(v.hit.Ng, wi));
      CameraLink link;
      if (cos_in > 1e-7f && link_camera(v.hit, wi, link_ctx, c, link))
        splat(link, link.f.value * beta / cos_in, link.to_area * link.f.pdf,
              light_share_ * light_pdf * cos_in, c, film);
      // Seen after one more bounce (the camera's path's second vertex).
      if (deltas <= max_depth_ - 2 && !(scene_.globals_read(v.hit.shape) & Material::kReadsRaytype))
        bounce_to_camera(v.hit, ray.dir, beta, light_pdf, rng, link_ctx, c, film);
      if (link_ctx.stopped) return;
    }
    if (!go_on || !is_zero(v.bsdf.transparency) || !has_delta) return;
    float ub[3] = {rng.next(), rng.next(), rng.next()};
    auto s = v.bsdf.sample(-ray.dir, {ub[0], ub[1], ub[2]}, Transport::Importance);
    if (!s || !(s->flags & kLobeSpecular)) return;
    if (deltas == 0) {
      // What the camera's path would find leaving here along w: the background shader for a
      // ray of this lobe's type (as trace() after a delta lobe), else the table.
      int raytype = s->flags & kLobeTransmit ? kRayRefraction : kRayReflection;
      Color3 Le = scene_.has_background_shader()
                      ? scene_.shade_background(w, raytype, ctx, c.messages)
                      : env->eval(w);
      if (ctx.stopped) return;
      beta = Le / (pdf_dir * pdf_line);
    }
    beta *= s->weight;
    if (is_zero(beta) || !is_finite(beta)) return;
    ++deltas;
    ray = Ray{offset_ray_origin(v.hit.P, v.hit.Ng, s->wi), s->wi};
  }
}

// A light path at `y` (arrived along `d`, flux `beta`) scatters once more, in a
// cosine-distributed direction on the side the light came from, and the point it reaches is
// connected to the camera: the caustic seen in a second surface (on the floor, in a glossy
// sphere). `y` is then the camera's path's second vertex, and is shaded as that path shades
// it (from the side of the first, whose BSDF also gives the camera's density).
void PathTracer::bounce_to_camera(const SurfaceHit& y, const Vec3& d, const Color3& beta,
                                  float light_pdf, RandomStream& rng, ShadingContext& ctx,
                                  TraceCounters& c, LightFilm& film) const {
  const Vec3 w2 = -d; // from y towards the light
  const Vec3 n = dot(y.Ng, w2) > 0 ? y.Ng : -y.Ng;
  const float cos2 = dot(n, w2);
  if (!(cos2 > 1e-7f)) return;
  Frame frame(n);
  float u1 = rng.next(), u2 = rng.next();
  Vec3 local = sample_cosine_hemisphere(u1, u2);
  Vec3 wout = normalize(frame.to_world(local)); // from y towards the camera's first vertex
  if (!(dot(n, wout) > 0)) return;
  Ray ray{offset_ray_origin(y.P, y.Ng, wout), wout};
  Geometry::RawHit raw;
  ++c.rays;
  if (!scene_.geometry().traverse(ray, raw)) return;
  SurfaceHit x1;
  scene_.geometry().complete(ray, raw, x1);
  const Vec3 w1 = -wout; // at x1, towards y
  const float cos1 = std::abs(dot(x1.Ng, w1));
  CameraLink link;
  if (!(cos1 > 1e-7f) || !link_camera(x1, w1, ctx, c, link)) return;
  // y as the camera's path shades it: seen from x1, after the camera's distance and this ray's.
  Bsdf b;
  Laps untimed(nullptr);
  shade_into(scene_, y, -wout, kRayDiffuse, ctx, b, c, false, untimed, link.dist + raw.t);
  if (ctx.stopped) return;
  BsdfEval f2 = b.eval(wout, w2);
  if (is_zero(f2.value)) return;
  // Flux leaving y towards x1: beta * f2 / |Ng.w2| * |Ng.wout| / pdf, pdf = |Ng.wout| / pi.
  Color3 beta1 = beta * f2.value * (kPi / std::abs(dot(y.Ng, w2)));
  // Densities over x1's area and direction, y's area and direction (the |Ng_y.w1| / dist^2
  // both share dropped): the camera's film_to_area * pdf at x1 * pdf at y; the light's its
  // first ray's * |Ng_y.w2| * |Ng_y.w1| / pi * |Ng_x1.w1| (with the |Ng_y.w1| dropped).
  splat(link, link.f.value * beta1 / cos1, link.to_area * link.f.pdf * f2.pdf,
        light_share_ * light_pdf * std::abs(dot(y.Ng, w2)) * cos1 / kPi, c, film);
}

// What the camera sees of `hit` lit from direction `wi`: where on the film, the BSDF there
// towards the camera (shaded as the camera's path shades its first vertex), and film_to_area;
// false when the camera does not see the point (behind, outside the view or occluded).
bool PathTracer::link_camera(const SurfaceHit& hit, const Vec3& wi, ShadingContext& ctx,
                             TraceCounters& c, CameraLink& out) const {
  const Camera& cam = scene_.camera();
  float cos_axis;
  if (!cam.project(hit.P, out.fx, out.fy, cos_axis)) return false;
  Vec3 to_eye = cam.position() - hit.P;
  float dist = length(to_eye);
  Vec3 wo = to_eye / dist;
  out.to_area = film_to_area(cam, hit.P, hit.Ng, cos_axis);
  if (!(out.to_area > 0) || !std::isfinite(out.to_area)) return false;
  ++c.shadow_rays;
  if (scene_.geometry().occluded(offset_ray_origin(hit.P, hit.Ng, wo), wo, dist * (1 - 1e-4f)))
    return false;
  Bsdf b;
  Laps untimed(nullptr);
  shade_into(scene_, hit, -wo, kRayCamera, ctx, b, c, false, untimed, dist);
  if (ctx.stopped) return false;
  out.f = b.eval(wo, wi);
  out.dist = dist;
  return !is_zero(out.f.value);
}

// A light path's connection to the camera: radiance `radiance` towards it per unit area of
// the surface, weighed against the camera's paths by the power heuristic pixel by pixel (their
// density holds the pixel filter's): the film takes the ratio of the light paths' density
// `light` to the camera's, `camera` at filter weight 1 (0: the camera's paths cannot make it).
void PathTracer::splat(const CameraLink& link, const Color3& radiance, float camera, float light,
                       TraceCounters& c, LightFilm& film) const {
  Color3 value = radiance * link.to_area;
  if (!is_finite(value) || is_zero(value)) return;
  ++c.splats;
  film.splat(link.fx, link.fy, value, camera > 0 ? light / camera : INFINITY);
}

namespace {
constexpr double kFilmScale = 1048576.0; // 2^20: LightFilm's fixed point
constexpr double kFilmMax = 8e18;        // below INT64_MAX
} // namespace

void LightFilm::add(int x, int y, float w, const Color3& v) {
  if (x < 0 || y < 0 || x >= w_ || y >= h_ || !(w > 0)) return;
  std::atomic<int64_t>* px = &sum_[(size_t(y) * w_ + x) * 3];
  for (int k = 0; k < 3; ++k) {
    // Negative radiance (a background shader may give it) is not splatted.
    double q = double(v[k]) * double(w) * kFilmScale;
    if (!(q > 0)) continue;
    const int64_t add = int64_t(std::min(q, kFilmMax) + 0.5), top = int64_t(kFilmMax);
    // Saturating, so that no sum wraps round (and the order of adds still does not matter).
    int64_t cur = px[k].load(std::memory_order_relaxed);
    while (!px[k].compare_exchange_weak(cur, cur > top - add ? top : cur + add,
                                        std::memory_order_relaxed)) {
    }
  }
}

// The light path's weight at filter weight h, camera_weight's complement for the camera's
// density h * camera: 1 / (1 + (h / ratio)^2), ratio = light / camera (no square overflows).
static float light_weight(float ratio, float h) {
  if (!(h > 0) || !(ratio > 0)) return 0;
  if (std::isinf(ratio)) return 1;
  float q = h / ratio;
  return 1 / (1 + q * q);
}

void LightFilm::splat(float fx, float fy, const Color3& v, float ratio) {
  // Off the film (or not a number): no pixel's filter reaches it.
  if (!(fx > -2 && fx < float(w_) + 2 && fy > -2 && fy < float(h_) + 2)) return;
  if (filter_ == scene::PixelFilter::Box) {
    add(int(std::floor(fx)), int(std::floor(fy)), light_weight(ratio, 1), v);
    return;
  }
  // The tent of radius one pixel round each pixel's centre (x + 0.5, y + 0.5).
  int x0 = int(std::floor(fx - 0.5f)), y0 = int(std::floor(fy - 0.5f));
  for (int y = y0; y <= y0 + 1; ++y)
    for (int x = x0; x <= x0 + 1; ++x) {
      float wx = 1 - std::abs(fx - (float(x) + 0.5f)), wy = 1 - std::abs(fy - (float(y) + 0.5f));
      float h = wx * wy;
      add(x, y, h * light_weight(ratio, h), v);
    }
}

Color3 LightFilm::sum(size_t p) const {
  const std::atomic<int64_t>* px = &sum_[p * 3];
  return {float(double(px[0].load()) / kFilmScale), float(double(px[1].load()) / kFilmScale),
          float(double(px[2].load()) / kFilmScale)};
}

} // namespace lobe::render
