// A render-ready scene: the Embree geometry, compiled materials (one per scene material that
// a shape or the environment uses; unreferenced ones are never compiled), the camera, the
// environment table and the light set with emissive shapes found by probing each material.
#pragma once

#include <atomic>
#include <chrono>
#include <thread>

#include "camera.h"
#include "environment.h"
#include "geometry.h"
#include "lights.h"
#include "scene.h"
#include "services.h"

#include "lobe/shadingsys.h"

#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

namespace lobe::render {

// "" when every position in the scene (camera, shapes, mesh vertices, lights) is finite and within
// 1e15 of the origin, the range single-precision ray tracing can resolve; else the first one
// that is not, with its place. RenderScene::setup checks this first.
std::string check_scene_extent(const scene::SceneDesc& desc);
// Bytes the scene's meshes will take once built (their copies and Embree's BVH): 256 a triangle
// and 64 a vertex (scene_setup.cpp says where the figures come from). Set-up refuses a scene
// whose meshes need more than the memory available (lobe/memory.h), before building anything.
double geometry_bytes(const scene::SceneDesc& desc);

// Turns one scene material into a compiled Material: the CLI passes one backed by the JIT's
// ShadingSystem (MaterialBackend), tests pass the native twins (renderer/native). Must be
// thread-safe (called in parallel). Shapes without a material get the stdlib matte with
// Cs 0.5 from the same compiler.
using MaterialCompiler =
    std::function<std::shared_ptr<const Material>(const scene::MaterialDesc&, std::string& error)>;

// Bit of kGlobalFields for a global's name (for Material::globals_read), or 0.
uint64_t global_bit(const char* name);

// What shader code sent to a ShadingContext while shading (texture errors, error(),
// warning(), printf): each line counted per scene material (-1: the default material).
using ShaderMessages = std::map<std::pair<int, std::string>, uint64_t>;
// Caps: distinct lines kept per thread (the rest counted under the text ""), and distinct lines
// RenderScene::describe shows per material before its summary line.
constexpr size_t kMaxDistinctMessages = 1000;
constexpr int kMaxMessageLines = 10;
// Moves the lines of ctx.output into `out` under `material` and clears ctx.output.
void collect_messages(ShadingContext& ctx, int material, ShaderMessages& out);
void merge_messages(const ShaderMessages& from, ShaderMessages& into);

struct SetupStats {
  double compile_seconds = 0;     // wall time of the parallel compile of all used materials
  double geometry_seconds = 0;    // Embree scene build (BVH) and shape areas
  double environment_seconds = 0; // environment table (image, sky or background shader)
  double lights_seconds = 0;      // emitter probes and the light set
  int materials_compiled = 0;
  int materials_cached = 0; // of those, machine code read from the disk cache
  int emitters = 0;
  int closure_kernels = 0;        // materials whose closures run as JIT-compiled kernels
  int closure_kernels_cached = 0; // of those, kernels read from the disk cache
  // Seconds from the end of setup() until every material's kernels were in use (background
  // compile; 0 when compiled at setup or not used); < 0: the render ended first (the rest ran
  // on the native library).
  double kernels_ready_seconds = 0;
  std::vector<std::string> warnings; // e.g. closure kernels that failed to compile
  ShaderMessages messages;           // from shading at setup (emitter probes, background table)
};

// When the materials' closure kernels (Material::closure_kernels()) are compiled: never (the
// native closure library), in parallel during setup(), or on a background thread after it while
// the render starts on the native library; each shape switches to its kernels as they are ready.
// Native and kernels compute the same bits (tests/closures/jit_kernels_test.cpp), so the image
// does not depend on when the switch happens.
enum class KernelMode { Native, AtSetup, Background };

class RenderScene {
public:
  RenderScene() = default;
  RenderScene(const RenderScene&) = delete;
  RenderScene& operator=(const RenderScene&) = delete;
  ~RenderScene() { finish_kernels(); }
  // How materials evaluate their closures. Set before setup(); Background by default.
  void set_kernel_mode(KernelMode m) { kernel_mode_ = m; }
  // Background mode: stops compiling kernels (after the material being compiled, if any),
  // waits for the thread and completes stats() (closure_kernels, kernels_ready_seconds,
  // warnings). Called by the destructor; call it when the render is done to report the stats.
  // Returns the warnings the background compile added (kernels that failed to compile).
  std::vector<std::string> finish_kernels();
  // Set (by a Ctrl-C handler) to stop setup between stages and shaders in their loops; setup()
  // then returns "interrupted (Ctrl-C) while <stage>". Set before setup(); null: never.
  void set_cancel(const std::atomic<bool>* cancel) { cancel_ = cancel; }
  // "" on success, else an error naming the scene element.
  // A shader stopped in a loop at setup (CompileOptions::max_loop_iterations) is an error
  // naming the material, the shader and the loop.
  // The scene keeps its own description: pass it by rvalue to move it in (a large mesh's
  // arrays are not copied then).
  std::string setup(scene::SceneDesc desc, const MaterialCompiler& compile, int width, int height);
  // "<material's place>: material 'name'" (-1: "<scene>: the default material").
  std::string material_place(int material) const;
  // Why a shade stopped (ctx.stopped): the loop error with the material's place, or the stage
  // that was interrupted.
  std::string stop_reason(const ShadingContext& ctx, int material, const char* stage) const;

  const scene::SceneDesc& desc() const { return desc_; }
  const Geometry& geometry() const { return geo_; }
  const Camera& camera() const { return camera_; }
  const LightSet& lights() const { return lights_; }
  const EnvironmentLight& environment() const { return env_; }
  // True when the environment is a background shader (shade_background applies).
  bool has_background_shader() const {
    return desc_.environment.kind == scene::Environment::Kind::Shader;
  }
  // Runs the background shader for a ray leaving in direction `d` (the ray type as given):
  // its background() radiance times the environment's intensity (`ctx` gets the scene's
  // services as its renderer). Shader messages go to
  // `messages`; a stopped shader (ctx.stopped) gives black.
  Color3 shade_background(const Vec3& d, int raytype, ShadingContext& ctx,
                          ShaderMessages& messages) const;
  // Material of a shape (a grey matte for shapes without one).
  const Material& material(int shape) const { return *shape_material_[shape]; }
  // Area of a shape (surfacearea() in its shaders, as testrender gives: sphere 4 pi r^2, quad
  // |edge_x x edge_y|, a mesh the sum of its triangles).
  float surface_area(int shape) const { return shape_area_[size_t(shape)]; }
  // What the shape's material reads (Material::globals_read bits, kGlobalFields order).
  uint64_t globals_read(int shape) const { return shape_reads_[shape]; }
  // The emission of an emitter whose material is the same everywhere (Material::kUniform) and
  // gives no lobe (so no layer can tint its emission by direction), from the probe at set-up;
  // null otherwise. Light samples on it take this instead of shading the emitter again.
  const Color3* uniform_emission(int shape) const {
    return shape_uniform_[size_t(shape)] ? &shape_emission_[size_t(shape)] : nullptr;
  }
  // The closure kernels of a shape's material (null: the native closure library).
  const ClosureKernels* closure_kernels(int shape) const {
    return shape_kernels_[size_t(shape)].load(std::memory_order_acquire);
  }
  // Shapes a light path may cross by a delta lobe (light tracing of caustics, integrator.h):
  // a probe point of their material gives a perfect mirror or refraction lobe, and the
  // material does not read raytype (a light path shades a surface from the light's side, with
  // no ray type of the camera's path). Each with a sphere that holds it and its share of the
  // light paths (by cross-section, the shares sum to 1). Past kMaxCausticSpheres targets, one
  // sphere holds them all (its shape -1); is_caustic_target still tells them apart.
  static constexpr size_t kMaxCausticSpheres = 64;
  struct CausticTarget {
    int shape = -1;
    Vec3 center;
    float radius = 0;
    float select = 0;
  };
  const std::vector<CausticTarget>& caustic_targets() const { return caustic_targets_; }
  bool is_caustic_target(int shape) const { return shape_caustic_[size_t(shape)] != 0; }
  const SetupStats& stats() const { return stats_; }
  // Scene material of a shape (-1: the default grey matte).
  int material_index(int shape) const { return desc_.shapes[size_t(shape)].material; }
  // What shaders ask the scene for (user data, camera attributes); set it as every
  // ShadingContext's `renderer`, and renderstate(shape) as ShaderGlobals::renderstate.
  const RendererServices& services() const { return services_; }
  // (ShaderGlobals::renderstate is a void*; SceneServices only reads through it.)
  void* renderstate(int shape) const {
    return const_cast<scene::Shape*>(&desc_.shapes[size_t(shape)]);
  }
  // One line per message: "<material's place>: material 'name': <text>[ (N times)]", the
  // shader's "ERROR: "/"WARNING: " prefix dropped; at most kMaxMessageLines per material, then
  // "<place>: ... and K more message lines (D+ different) not shown".
  std::vector<std::string> describe(const ShaderMessages& messages) const;

private:
  std::string compile_materials(const MaterialCompiler& compile);
  // What compile_kernels found, merged into stats_ by the thread that owns stats_.
  struct KernelStats {
    int kernels = 0, cached = 0;
    std::vector<std::string> warnings;
    double ready_seconds = -1;
  };
  // Compiles (or reads from the cache) the kernels of every used material and publishes them to
  // the shapes that use it; false if `stop` ended it early. Runs in setup() or on kernel_thread_
  // (then `out` is kernel_stats_, which nothing else touches until the thread is joined).
  bool compile_kernels(const std::atomic<bool>* stop, KernelStats& out);
  void merge(const KernelStats& k);
  std::string build_environment();
  // Emitters, and in `specular` the shapes whose probe point gives a delta lobe; notes the
  // uniform emitters' emission (uniform_emission).
  std::string find_emitters(std::vector<LightSet::Emitter>& out, std::vector<int>& specular,
                            ShaderMessages& messages);
  void find_caustic_targets(const std::vector<int>& specular);
  bool cancelled() const { return cancel_ && cancel_->load(); }

  scene::SceneDesc desc_;
  SceneServices services_;
  Geometry geo_;
  Camera camera_;
  EnvironmentLight env_;
  LightSet lights_;
  std::vector<std::shared_ptr<const Material>> materials_; // per scene material (null: unused)
  std::vector<const Material*> shape_material_;
  std::vector<uint64_t> shape_reads_;
  std::vector<float> shape_area_;
  std::vector<CausticTarget> caustic_targets_;
  std::vector<char> shape_caustic_; // per shape: a caustic target
  std::vector<char> shape_uniform_; // per shape: shape_emission_ holds its uniform emission
  std::vector<Color3> shape_emission_;
  std::unique_ptr<std::atomic<const ClosureKernels*>[]> shape_kernels_; // per shape
  KernelMode kernel_mode_ = KernelMode::Background;
  std::thread kernel_thread_;
  std::atomic<bool> stop_kernels_{false};
  KernelStats kernel_stats_;
  const std::atomic<bool>* cancel_ = nullptr;
  std::shared_ptr<const Material> default_material_;
  SetupStats stats_;
};

// Ray footprint for derivative globals: the world-space width of one pixel at the hit
// (pixel angle times the distance travelled along the path) and the camera's screen axes.
struct Footprint {
  float width = 0;
  float angle = 0; // pixel spread in radians (direction derivative)
  Vec3 right{1, 0, 0}, up{0, 1, 0};
};

// Fills the globals of a surface point seen along `dir`. Only what `reads` (globals_read bits)
// asks for beyond the basics is computed: tangents dPdu/dPdv, and the screen derivatives
// (dPdx/dPdy, dudx.., dIdx/dIdy) estimated from the footprint; the rest stays zero.
void fill_globals(ShaderGlobals& sg, const SurfaceHit& hit, const Vec3& dir, int raytype,
                  ShadingContext& ctx, uint64_t reads = ~uint64_t(0), const Footprint& fp = {});

// Bits of kGlobalFields that need screen-space derivatives / surface tangents.
uint64_t derivative_bits();
uint64_t tangent_bits();

} // namespace lobe::render
