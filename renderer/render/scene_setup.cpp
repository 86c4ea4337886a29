// Scene setup: materials compiled in parallel (oneTBB), emitters found by probing, the
// environment tabulated (see scene_setup.h).
#include "scene_setup.h"

#include "image.h"
#include "sampling.h"
#include "sky.h"

#include "lobe/bsdf.h"
#include "lobe/context.h"
#include "lobe/memory.h"

#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <mutex>
#include <set>

namespace lobe::render {

uint64_t global_bit(const char* name) {
  for (size_t i = 0; i < std::size(kGlobalFields); ++i)
    if (std::strcmp(kGlobalFields[i].name, name) == 0) return uint64_t(1) << i;
  return 0;
}

void collect_messages(ShadingContext& ctx, int material, ShaderMessages& out) {
  size_t start = 0;
  const std::string& t = ctx.output;
  while (start < t.size()) {
    size_t end = t.find('\n', start);
    if (end == std::string::npos) end = t.size();
    if (end > start) {
      // Distinct lines are kept up to kMaxDistinctMessages per thread (a printf of varying
      // values at every point would otherwise keep them all); the rest are counted under "".
      std::pair<int, std::string> key{material, t.substr(start, end - start)};
      auto it = out.find(key);
      if (it != out.end())
        ++it->second;
      else if (out.size() < kMaxDistinctMessages)
        out.emplace(std::move(key), 1);
      else
        ++out[{material, ""}];
    }
    start = end + 1;
  }
  ctx.output.clear();
}

void merge_messages(const ShaderMessages& from, ShaderMessages& into) {
  for (const auto& [key, n] : from) into[key] += n;
}

std::vector<std::string> RenderScene::describe(const ShaderMessages& all) const {
  // (A texture that cannot be opened is told once, by its first failed lookup, as in OSL.)
  const ShaderMessages& messages = all;
  // Per material: the first kMaxMessageLines distinct lines (each with its count), then one
  // summary line for the rest.
  std::vector<std::string> lines;
  std::map<int, std::pair<uint64_t, uint64_t>> more; // material -> (distinct lines, lines)
  std::map<int, int> shown;
  for (const auto& [key, n] : messages) {
    if (key.second.empty() || shown[key.first] >= kMaxMessageLines) {
      more[key.first].first += key.second.empty() ? 0 : 1;
      more[key.first].second += n;
      continue;
    }
    ++shown[key.first];
    std::string where = material_place(key.first);
    std::string text = key.second;
    for (const char* p : {"ERROR: ", "WARNING: "})
      if (text.rfind(p, 0) == 0) text = text.substr(std::strlen(p));
    lines.push_back(where + ": " + text + (n > 1 ? " (" + std::to_string(n) + " times)" : ""));
  }
  for (const auto& [m, count] : more)
    lines.push_back(material_place(m) + ": ... and " + std::to_string(count.second) +
                    " more message line" + (count.second == 1 ? "" : "s") +
                    (count.first ? " (" + std::to_string(count.first) + "+ different)" : "") +
                    " not shown");
  return lines;
}

std::string RenderScene::material_place(int m) const {
  return m >= 0 ? desc_.materials[size_t(m)].where + ": material '" +
                      desc_.materials[size_t(m)].name + "'"
                : desc_.path + ": the default material";
}

std::string RenderScene::stop_reason(const ShadingContext& ctx, int material,
                                     const char* stage) const {
  // The loop's error is the "ERROR: shader ..." line the shade sent last.
  std::string found;
  size_t start = 0;
  while (ctx.errors && start < ctx.output.size()) {
    size_t end = ctx.output.find('\n', start);
    if (end == std::string::npos) end = ctx.output.size();
    std::string line = ctx.output.substr(start, end - start);
    if (line.rfind("ERROR: shader ", 0) == 0 && line.find("max_loop_iterations") != line.npos)
      found = line.substr(7);
    start = end + 1;
  }
  if (!found.empty()) return material_place(material) + ": " + found + " (while " + stage + ")";
  return std::string("interrupted (Ctrl-C) while ") + stage;
}

// Constants computed once (name lookups are too slow for every shading point).
uint64_t derivative_bits() {
  static const uint64_t bits = [] {
    uint64_t b = 0;
    for (const char* n : {"dPdx", "dPdy", "dIdx", "dIdy", "dudx", "dudy", "dvdx", "dvdy"})
      b |= global_bit(n);
    return b;
  }();
  return bits;
}

uint64_t tangent_bits() {
  static const uint64_t bits = global_bit("dPdu") | global_bit("dPdv");
  return bits;
}

// Screen derivatives: the footprint's screen axes projected into the tangent plane, scaled to
// the pixel width there; u,v derivatives by least squares against dPdu, dPdv.
static void fill_derivatives(ShaderGlobals& sg, const Footprint& fp) {
  auto project = [&](const Vec3& a) { return normalize(a - sg.Ng * dot(a, sg.Ng)) * fp.width; };
  sg.dPdx = project(fp.right);
  sg.dPdy = project(-fp.up); // raster y grows downwards
  float a = dot(sg.dPdu, sg.dPdu), b = dot(sg.dPdu, sg.dPdv), c = dot(sg.dPdv, sg.dPdv);
  float det = a * c - b * b;
  if (std::abs(det) > 1e-20f) {
    auto solve = [&](const Vec3& d, float& du, float& dv) {
      float p = dot(d, sg.dPdu), q = dot(d, sg.dPdv);
      du = (c * p - b * q) / det;
      dv = (a * q - b * p) / det;
    };
    solve(sg.dPdx, sg.dudx, sg.dvdx);
    solve(sg.dPdy, sg.dudy, sg.dvdy);
  }
  sg.dIdx = fp.right * fp.angle;
  sg.dIdy = -fp.up * fp.angle;
}

void fill_globals(ShaderGlobals& sg, const SurfaceHit& hit, const Vec3& dir, int raytype,
                  ShadingContext& ctx, uint64_t reads, const Footprint& fp) {
  sg = ShaderGlobals{};
  sg.P = hit.P;
  sg.I = dir;
  // N and Ng face the viewer, as OSL's testrender gives them (backfacing() says which side
  // was hit; OSL's shaders pass 1/eta to refraction() from inside).
  sg.backfacing = dot(dir, hit.Ng) > 0;
  sg.N = sg.backfacing ? -hit.N : hit.N;
  sg.Ng = sg.backfacing ? -hit.Ng : hit.Ng;
  sg.u = hit.u;
  sg.v = hit.v;
  if (reads & (tangent_bits() | derivative_bits())) {
    sg.dPdu = hit.dPdu;
    sg.dPdv = hit.dPdv;
  }
  if ((reads & derivative_bits()) && fp.width > 0) fill_derivatives(sg, fp);
  sg.raytype = raytype;
  sg.surfacearea = 0;
  sg.context = &ctx;
}

std::string RenderScene::compile_materials(const MaterialCompiler& compile) {
  std::set<int> used;
  for (const scene::Shape& s : desc_.shapes)
    if (s.material >= 0) used.insert(s.material);
  if (desc_.environment.kind == scene::Environment::Kind::Shader)
    used.insert(desc_.environment.material);
  std::vector<int> todo(used.begin(), used.end());
  std::vector<std::string> errors(todo.size());
  materials_.assign(desc_.materials.size(), nullptr);
  auto t0 = std::chrono::steady_clock::now();
  tbb::parallel_for(size_t(0), todo.size(), [&](size_t i) {
    const scene::MaterialDesc& m = desc_.materials[todo[i]];
    std::string err;
    materials_[todo[i]] = compile(m, err);
    if (!materials_[todo[i]])
      errors[i] = m.where + ": material '" + m.name + "': " + err;
    else if (kernel_mode_ == KernelMode::AtSetup)
      materials_[todo[i]]->closure_kernels(); // compiled here, in parallel
  });
  stats_.compile_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  stats_.materials_compiled = static_cast<int>(todo.size());
  for (const std::string& e : errors)
    if (!e.empty()) return e;
  for (int i : todo) stats_.materials_cached += materials_[size_t(i)]->stats().object_from_disk;
  // Shapes without a material are grey: the stdlib matte with Cs 0.5, compiled like any other
  // material (only when some shape needs it).
  bool need_default = false;
  for (const scene::Shape& s : desc_.shapes) need_default |= s.material < 0;
  if (need_default) {
    scene::MaterialDesc grey;
    grey.name = "default";
    grey.group.layers.push_back({"matte", "default", {{"color", "Cs", "0.5 0.5 0.5"}}});
    std::string err;
    default_material_ = compile(grey, err);
    if (!default_material_) return "default material (matte, Cs 0.5): " + err;
  }
  shape_kernels_ = std::make_unique<std::atomic<const ClosureKernels*>[]>(desc_.shapes.size());
  for (const scene::Shape& s : desc_.shapes) {
    shape_material_.push_back(s.material >= 0 ? materials_[s.material].get()
                                              : default_material_.get());
    shape_reads_.push_back(shape_material_.back()->globals_read());
  }
  if (kernel_mode_ == KernelMode::AtSetup) {
    KernelStats k;
    compile_kernels(nullptr, k);
    k.ready_seconds = 0; // in use from the first sample
    merge(k);
  }
  // Triangle tangents only for materials that read them (or screen derivatives built on them).
  std::vector<char> tangents;
  for (uint64_t r : shape_reads_)
    tangents.push_back((r & (tangent_bits() | derivative_bits())) != 0);
  geo_.set_tangents_needed(std::move(tangents));
  return "";
}

bool RenderScene::compile_kernels(const std::atomic<bool>* stop, KernelStats& out) {
  std::vector<const Material*> used;
  for (const Material* m : shape_material_)
    if (std::find(used.begin(), used.end(), m) == used.end()) used.push_back(m);
  for (const Material* m : used) {
    if (stop && stop->load()) return false;
    const ClosureKernels* k = m->closure_kernels();
    if (k) {
      ++out.kernels;
      out.cached += m->closure_kernels_cached();
      for (size_t s = 0; s < shape_material_.size(); ++s)
        if (shape_material_[s] == m) shape_kernels_[s].store(k, std::memory_order_release);
    }
    std::string ke = m->closure_kernels_error();
    if (!ke.empty()) {
      std::string name = "default";
      for (size_t i = 0; i < materials_.size(); ++i)
        if (materials_[i].get() == m) name = desc_.materials[i].name;
      out.warnings.push_back("material '" + name +
                             "': closure kernels unavailable, native closures used: " + ke);
    }
  }
  return true;
}

void RenderScene::merge(const KernelStats& k) {
  stats_.closure_kernels += k.kernels;
  stats_.closure_kernels_cached += k.cached;
  stats_.warnings.insert(stats_.warnings.end(), k.warnings.begin(), k.warnings.end());
  stats_.kernels_ready_seconds = k.ready_seconds;
}

std::vector<std::string> RenderScene::finish_kernels() {
  if (!kernel_thread_.joinable()) return {};
  stop_kernels_.store(true);
  kernel_thread_.join();
  merge(kernel_stats_);
  return kernel_stats_.warnings;
}

std::string RenderScene::build_environment() {
  const scene::Environment& e = desc_.environment;
  const float k = e.intensity;
  const int res = e.resolution;
  switch (e.kind) {
  case scene::Environment::Kind::None:
    return "";
  case scene::Environment::Kind::Constant: {
    // One texel: a constant table takes EnvironmentLight's constant path (no table lookups,
    // cosine-weighted light samples about the normal).
    env_ = EnvironmentLight({e.color.x * k, e.color.y * k, e.color.z * k}, 1, 1, 0);
    return "";
  }
  case scene::Environment::Kind::Map: {
    image::Image img;
    if (std::string err = image::read_image(e.file, img); !err.empty()) return e.where + ": " + err;
    LargeVector<float> rgb(size_t(img.width) * img.height * 3);
    size_t bad = 0; // NaN or infinite values (or ones the intensity makes infinite): read as 0
    for (size_t p = 0; p < size_t(img.width) * img.height; ++p)
      for (int c = 0; c < 3; ++c) {
        float v = k * img.pixels[p * img.nchannels() + std::min(c, img.nchannels() - 1)];
        bad += !std::isfinite(v);
        rgb[p * 3 + c] = std::isfinite(v) ? v : 0.0f;
      }
    if (bad)
      stats_.warnings.push_back(e.where + ": environment map '" + e.file +
                                "': " + std::to_string(bad) +
                                " values are not finite numbers (NaN or infinite); read as 0");
    env_ = EnvironmentLight(rgb, img.width, img.height, e.rotation);
    return "";
  }
  case scene::Environment::Kind::Sky: {
    Vec3 sun = e.sun_direction;
    float size = e.sun_size;
    int h = std::max(res, 256);
    env_ = EnvironmentLight::from_function(
        [&](const Vec3& d) { return procedural_sky(d, sun, size) * k; }, 2 * h, h, e.rotation);
    return "";
  }
  case scene::Environment::Kind::Shader: {
    // Tabulate the background shader at texel centres, rows in parallel, one shading context
    // and message list per thread. The table serves light sampling and rays that escape after
    // a diffuse or glossy bounce; camera rays and rays after a specular bounce run the shader
    // itself (shade_background), so the picture's background is exact at any table size.
    tbb::enumerable_thread_specific<ShadingContext> contexts;
    tbb::enumerable_thread_specific<ShaderMessages> messages;
    std::mutex mu;
    std::string stopped;
    std::atomic<bool> stop{false};
    env_ = EnvironmentLight::from_function(
        [&](const Vec3& d) {
          if (stop.load(std::memory_order_relaxed)) return Color3{};
          ShadingContext& ctx = contexts.local();
          ctx.cancel = cancel_;
          Color3 L = shade_background(d, kRayCamera, ctx, messages.local());
          if (ctx.stopped) {
            std::lock_guard<std::mutex> lock(mu);
            if (stopped.empty())
              stopped = stop_reason(ctx, e.material, "tabulating the background");
            stop.store(true);
          }
          return L;
        },
        2 * res, res, e.rotation, 1);
    for (const ShaderMessages& m : messages) merge_messages(m, stats_.messages);
    return stopped;
  }
  }
  return "";
}

Color3 RenderScene::shade_background(const Vec3& d, int raytype, ShadingContext& ctx,
                                     ShaderMessages& messages) const {
  const scene::Environment& e = desc_.environment;
  SurfaceHit h;
  h.N = h.Ng = -d;
  ShaderGlobals sg;
  fill_globals(sg, h, d, raytype, ctx);
  ctx.renderer = &services_;
  ctx.reset();
  materials_[e.material]->shade(sg);
  if (!ctx.output.empty()) collect_messages(ctx, e.material, messages);
  if (ctx.stopped) return {};
  Bsdf b;
  b.build(sg.Ci, -d, h.Ng);
  return b.background * e.intensity;
}

// An emitter is a shape whose material emits at a probe point; its power estimate
// (pi * area * luminance of the probe's emission) decides how often it is sampled.
std::string RenderScene::find_emitters(std::vector<LightSet::Emitter>& out,
                                       std::vector<int>& specular, ShaderMessages& messages) {
  shape_uniform_.assign(desc_.shapes.size(), 0);
  shape_emission_.assign(desc_.shapes.size(), Color3{});
  ShadingContext ctx;
  ctx.renderer = &services_;
  ctx.cancel = cancel_;
  for (size_t i = 0; i < desc_.shapes.size(); ++i) {
    const scene::Shape& s = desc_.shapes[i];
    SurfaceHit h;
    if (s.kind == scene::Shape::Kind::Sphere) {
      h.P = s.center + Vec3{0, s.radius, 0};
      geo_.surface(int(i), 0, 0, 0, h);
    } else {
      geo_.surface(int(i), 0, 1.0f / 3, 1.0f / 3, h);
    }
    const float area = surface_area(int(i));
    ShaderGlobals sg;
    fill_globals(sg, h, -h.Ng, kRayShadow, ctx, globals_read(int(i)));
    sg.renderstate = renderstate(int(i));
    sg.surfacearea = area;
    ctx.reset();
    material(int(i)).shade(sg);
    if (ctx.stopped) return stop_reason(ctx, material_index(int(i)), "finding emitters");
    if (!ctx.output.empty()) collect_messages(ctx, material_index(int(i)), messages);
    Bsdf b;
    b.build(sg.Ci, h.Ng, h.Ng);
    float lum = luminance(b.emission);
    // is_light (testrender XML): sampled as a light even if the probe point does not emit.
    if (!(lum > 0) && s.is_light) lum = 1;
    if (lum > 0) out.push_back({int(i), kPi * area * lum});
    if (b.has_delta()) specular.push_back(int(i));
    if ((globals_read(int(i)) & Material::kUniform) && !b.has_delta() && !b.has_non_delta() &&
        is_zero(b.transparency) && ctx.output.empty()) {
      shape_uniform_[i] = 1;
      shape_emission_[i] = b.emission;
    }
  }
  return "";
}

void RenderScene::find_caustic_targets(const std::vector<int>& specular) {
  shape_caustic_.assign(desc_.shapes.size(), 0);
  caustic_targets_.clear();
  const uint64_t raytype = Material::kReadsRaytype;
  float total = 0;
  for (int i : specular) {
    if (shape_reads_[size_t(i)] & raytype) continue;
    const scene::Shape& s = desc_.shapes[size_t(i)];
    CausticTarget t;
    t.shape = i;
    if (s.kind == scene::Shape::Kind::Sphere) {
      t.center = s.center;
      t.radius = s.radius;
    } else {
      // The centre of the bounding box and the farthest vertex from it (a quad's mesh is
      // Geometry's).
      const auto& pts = geo_.mesh(i).positions;
      if (pts.empty()) continue;
      Vec3 lo = pts[0], hi = pts[0];
      for (const Vec3& p : pts)
        for (int k = 0; k < 3; ++k) lo[k] = std::min(lo[k], p[k]), hi[k] = std::max(hi[k], p[k]);
      t.center = (lo + hi) * 0.5f;
      for (const Vec3& p : pts) t.radius = std::max(t.radius, length(p - t.center));
    }
    // Room for hit points a little off the surface (Embree's, the sphere's re-projection).
    t.radius = t.radius * 1.001f + 1e-6f * (1 + length(t.center));
    if (!(t.radius > 0) || !std::isfinite(t.radius)) continue;
    t.select = t.radius * t.radius;
    total += t.select;
    caustic_targets_.push_back(t);
    shape_caustic_[size_t(i)] = 1;
  }
  for (CausticTarget& t : caustic_targets_) t.select /= total;
  // Many targets (a field of glass beads): one sphere round them all, so that a line's density
  // (the light paths' and the camera's, per environment hit) is one test, not one per target.
  if (caustic_targets_.size() > kMaxCausticSpheres) {
    Vec3 lo = caustic_targets_[0].center, hi = lo;
    for (const CausticTarget& t : caustic_targets_)
      for (int k = 0; k < 3; ++k)
        lo[k] = std::min(lo[k], t.center[k] - t.radius),
        hi[k] = std::max(hi[k], t.center[k] + t.radius);
    CausticTarget all;
    all.center = (lo + hi) * 0.5f;
    for (const CausticTarget& t : caustic_targets_)
      all.radius = std::max(all.radius, length(t.center - all.center) + t.radius);
    all.select = 1;
    caustic_targets_ = {all};
  }
}

// Embree traces in single precision and asserts that ray origins lie within about 1.8e18; far
// below that a float has no room left for the scene's detail. Every position the scene gives is
// checked against this bound (and for finiteness) before anything is built, with its place named.
constexpr float kMaxCoordinate = 1e15f;

static bool point_in_range(const Vec3& p) {
  for (float c : {p.x, p.y, p.z})
    if (!std::isfinite(c) || std::fabs(c) > kMaxCoordinate) return false;
  return true;
}

static std::string check_point(const Vec3& p, const std::string& where, const char* what) {
  if (point_in_range(p)) return "";
  char buf[160];
  std::snprintf(buf, sizeof buf,
                "%s (%g, %g, %g) is not finite or lies farther than %g from the origin", what, p.x,
                p.y, p.z, kMaxCoordinate);
  return where + ": " + buf;
}

std::string check_scene_extent(const scene::SceneDesc& d) {
  const std::string at = d.path.empty() ? "<scene>" : d.path;
  const scene::Camera& c = d.camera;
  if (std::string e = check_point(c.eye, at + ": camera", "eye"); !e.empty()) return e;
  if (std::string e = check_point(c.look_at, at + ": camera", "look_at"); !e.empty()) return e;
  if (std::string e = check_point(c.up, at + ": camera", "up"); !e.empty()) return e;
  for (const scene::Shape& s : d.shapes) {
    const std::string w = s.where.empty() ? at + ": shape" : s.where;
    std::string e;
    switch (s.kind) {
    case scene::Shape::Kind::Sphere:
      e = check_point(s.center, w, "centre");
      if (e.empty() && !(std::isfinite(s.radius) && s.radius > 0 && s.radius <= kMaxCoordinate))
        e = w + ": radius " + std::to_string(s.radius) + " is not in (0, 1e15]";
      break;
    case scene::Shape::Kind::Quad:
      e = check_point(s.corner, w, "corner");
      if (e.empty()) e = check_point(s.edge_x, w, "edge");
      if (e.empty()) e = check_point(s.edge_y, w, "edge");
      break;
    case scene::Shape::Kind::Mesh:
      for (size_t i = 0; i < s.mesh.positions.size() && e.empty(); ++i)
        if (!point_in_range(s.mesh.positions[i])) // the vertex is named only when it is bad
          e = check_point(s.mesh.positions[i], w, ("vertex " + std::to_string(i)).c_str());
      break;
    }
    if (!e.empty()) return e;
  }
  for (const scene::Light& l : d.lights)
    if (std::string e =
            check_point(l.position, l.where.empty() ? at + ": light" : l.where, "position");
        !e.empty())
      return e;
  return "";
}

// Embree's acceleration structure and the render's own copies of a mesh, per triangle and per
// vertex, measured: `/usr/bin/time -f %M lobe render spheres.json --res 16 16 --spp 1` on
// bench/embree_compare's scene (524 290 triangles, 262 276 vertices) peaks at 292 MB resident,
// the same scene without its mesh at 189 MB: 103 MB, about 196 bytes a triangle with its share
// of vertices. The estimate rounds up to 256 a triangle and 64 a vertex (151 MB there).
constexpr double kBytesPerTriangle = 256, kBytesPerVertex = 64;

double geometry_bytes(const scene::SceneDesc& d) {
  double triangles = 0, vertices = 0;
  for (const scene::Shape& s : d.shapes)
    if (s.kind == scene::Shape::Kind::Mesh) {
      triangles += double(s.mesh.indices.size() / 3);
      vertices += double(s.mesh.positions.size());
    }
  return triangles * kBytesPerTriangle + vertices * kBytesPerVertex;
}

namespace {
// "" when the scene's meshes fit in the memory with their acceleration structure, else the
// error with the figures (checked before Embree allocates anything).
std::string check_geometry_memory(const scene::SceneDesc& d) {
  size_t triangles = 0;
  for (const scene::Shape& s : d.shapes)
    if (s.kind == scene::Shape::Kind::Mesh) triangles += s.mesh.indices.size() / 3;
  return check_memory((d.path.empty() ? std::string("<scene>") : d.path) + ": " +
                          std::to_string(triangles) + " triangles",
                      geometry_bytes(d), "the meshes and their BVH");
}
} // namespace

std::string RenderScene::setup(scene::SceneDesc desc, const MaterialCompiler& compile, int width,
                               int height) {
  if (std::string e = check_scene_extent(desc); !e.empty()) return e;
  desc_ = std::move(desc);
  camera_ = Camera(desc_.camera, width, height);
  services_ = SceneServices(desc_.camera, width, height, &geo_);
  using clock = std::chrono::steady_clock;
  auto since = [](clock::time_point t) {
    return std::chrono::duration<double>(clock::now() - t).count();
  };
  auto t0 = clock::now();
  if (std::string e = check_geometry_memory(desc_); !e.empty()) return e;
  if (std::string e = geo_.build(desc_.shapes); !e.empty()) return desc_.path + ": " + e;
  shape_area_.clear();
  for (size_t i = 0; i < desc_.shapes.size(); ++i) {
    const scene::Shape& s = desc_.shapes[i];
    float area = 0;
    if (s.kind == scene::Shape::Kind::Sphere) {
      area = 4 * kPi * s.radius * s.radius;
    } else {
      const scene::Mesh& m = geo_.mesh(int(i));
      for (size_t t = 0; t + 2 < m.indices.size(); t += 3)
        area += 0.5f * length(cross(m.positions[m.indices[t + 1]] - m.positions[m.indices[t]],
                                    m.positions[m.indices[t + 2]] - m.positions[m.indices[t]]));
    }
    shape_area_.push_back(area);
  }
  stats_.geometry_seconds = since(t0);
  if (std::string e = compile_materials(compile); !e.empty()) return e;
  if (cancelled()) return "interrupted (Ctrl-C) after compiling the materials";
  t0 = clock::now();
  if (std::string e = build_environment(); !e.empty()) return e;
  stats_.environment_seconds = since(t0);
  if (cancelled()) return "interrupted (Ctrl-C) after tabulating the background";
  t0 = clock::now();
  std::vector<LightSet::Emitter> emitters;
  std::vector<int> specular;
  if (std::string e = find_emitters(emitters, specular, stats_.messages); !e.empty()) return e;
  find_caustic_targets(specular);
  stats_.emitters = static_cast<int>(emitters.size());
  lights_.build(geo_, desc_.lights, emitters, env_.valid() ? &env_ : nullptr);
  stats_.lights_seconds = since(t0);
  if (kernel_mode_ == KernelMode::Background) {
    // One thread, one material at a time: the render keeps the cores; finish_kernels() waits
    // for at most the material being compiled.
    kernel_thread_ = std::thread([this, since, start = clock::now()] {
      if (compile_kernels(&stop_kernels_, kernel_stats_))
        kernel_stats_.ready_seconds = since(start);
    });
  }
  return "";
}

} // namespace lobe::render
