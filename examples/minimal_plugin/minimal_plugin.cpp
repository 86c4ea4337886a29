// minimal_plugin: the smallest renderer-side program over Lobe's installed SDK.
//
// It does, in order, what a renderer plugin does with Lobe (README.md walks through each step):
//   1. create a ShadingSystem and point it at the stdlib shaders;
//   2. add a shader from source text;
//   3. describe a shader group (two layers and a connection) in OSL's group text;
//   4. compile the group into a Material;
//   5. shade a few points, each with its ShaderGlobals and a per-thread ShadingContext;
//   6. read an output parameter of a layer;
//   7. turn the closure the shader returned into a Bsdf, and evaluate and sample it;
//   8. see a shader's run-time error arrive through the ShadingContext's message sink;
//   9. give a closure the shader declares `[[ int builtin = 1 ]]` the renderer's own
//      implementation (registered in step 0, before anything compiles).
// Every value it prints is one a reader can check by hand (README.md gives the formulas).
#include <lobe/bsdf.h>
#include <lobe/closure_plugin.h>
#include <lobe/context.h>
#include <lobe/install.h>
#include <lobe/shadingsys.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace {

// Step 2's shader: scales a colour by 0.5 + 0.5 u, so each point shades differently.
const char* kTintSource = R"(
shader tint(color c = 1, output color Cout = 0)
{
    Cout = c * (0.5 + 0.5 * u);
}
)";

// Step 3's group: `tint` feeds the stdlib `matte` (stdlib_shaders/matte.osl), whose closure
// is Kd * Cs * diffuse(N). Instance values (`param`) come before the layer they set.
const char* kGroupText = "param color c 0.2 0.4 0.6 ; shader tint t ;"
                         "param float Kd 0.5 ; shader matte m ;"
                         "connect t.Cout m.Cs ;";

// Step 8's shader: a texture lookup of a file that does not exist.
const char* kMissingTextureSource = R"(
shader missing_texture(output color Cout = 0)
{
    Cout = texture("no_such_texture.exr", u, v);
}
)";

// Diagnostics (compile errors, warnings) come back as data; the library never prints.
void print_diagnostics(const lobe::DiagnosticList& diags) {
  for (const lobe::Diagnostic& d : diags) std::fprintf(stderr, "%s\n", d.text.c_str());
}

void print_color(const char* label, const lobe::Color3& c) {
  std::printf("%s %.6f %.6f %.6f\n", label, c.x, c.y, c.z);
}

// Step 0 and 9: the renderer's own closure, `renderer_lambert(normal N, color albedo)`: a
// Lambertian lobe, f = albedo / pi, sampled with density cos / pi about N. Its functions get
// the component's parameter block; where each parameter sits comes from the registry.
constexpr float kPi = 3.14159265358979f;
long g_off_N = -1, g_off_albedo = -1;

lobe::Vec3 param_vec3(const unsigned char* params, long offset) {
  lobe::Vec3 v;
  std::memcpy(&v, params + offset, sizeof v);
  return v;
}

lobe::BsdfEval lambert_eval(const unsigned char* p, const lobe::Vec3&, const lobe::Vec3& wi,
                            lobe::Transport, void*) {
  float cos_i = lobe::dot(lobe::normalize(param_vec3(p, g_off_N)), wi);
  if (cos_i <= 0) return {};
  lobe::BsdfEval e;
  e.value = param_vec3(p, g_off_albedo) * (cos_i / kPi); // f |cos|, the cosine included
  e.pdf = cos_i / kPi;
  return e;
}

float lambert_pdf(const unsigned char* p, const lobe::Vec3&, const lobe::Vec3& wi, void*) {
  return std::fmax(0.0f, lobe::dot(lobe::normalize(param_vec3(p, g_off_N)), wi)) / kPi;
}

lobe::BsdfSample lambert_sample(const unsigned char* p, const lobe::Vec3&, const lobe::Vec3& u,
                                lobe::Transport, void*) {
  // A cosine-weighted direction on the unit disk lifted to the hemisphere, then turned from
  // z to N with an orthonormal frame (Duff et al. 2017).
  lobe::Vec3 n = lobe::normalize(param_vec3(p, g_off_N));
  float sign = std::copysign(1.0f, n.z), a = -1.0f / (sign + n.z), b = n.x * n.y * a;
  lobe::Vec3 t = {1 + sign * n.x * n.x * a, sign * b, -sign * n.x};
  lobe::Vec3 bt = {b, sign + n.y * n.y * a, -n.y};
  float r = std::sqrt(u.x), phi = 2 * kPi * u.y, z = std::sqrt(std::fmax(0.0f, 1 - u.x));
  lobe::BsdfSample s;
  s.wi = t * (r * std::cos(phi)) + bt * (r * std::sin(phi)) + n * z;
  s.pdf = z / kPi;
  s.weight = param_vec3(p, g_off_albedo); // f cos / pdf = albedo
  s.flags = lobe::kLobeReflect | lobe::kLobeDiffuse;
  return s;
}

lobe::Color3 lambert_albedo(const unsigned char* p, const lobe::Vec3&, void*) {
  return param_vec3(p, g_off_albedo);
}

bool register_renderer_closures() {
  lobe::CustomClosure c;
  c.name = "renderer_lambert";
  c.params = {{"N", lobe::ClosureParamType::Vector}, {"albedo", lobe::ClosureParamType::Color}};
  c.lobe_flags = lobe::kLobeReflect | lobe::kLobeDiffuse;
  c.doc = "the renderer's Lambertian lobe (minimal_plugin)";
  c.eval = lambert_eval;
  c.pdf = lambert_pdf;
  c.sample = lambert_sample;
  c.albedo = lambert_albedo;
  std::string err;
  if (lobe::register_closure(c, &err) < 0) {
    std::fprintf(stderr, "register_closure: %s\n", err.c_str());
    return false;
  }
  g_off_N = lobe::closure_param_offset("renderer_lambert", "N");
  g_off_albedo = lobe::closure_param_offset("renderer_lambert", "albedo");
  return true;
}

// Step 9's shader declares the closure as OSL shaders declare renderer closures; the
// registration above is what implements it.
const char* kRendererClosureSource = R"(
closure color renderer_lambert(normal N, color albedo) [[ int builtin = 1 ]];
surface uses_renderer_closure(color tint = color(0.25, 0.5, 0.75))
{
    Ci = 0.8 * renderer_lambert(N, tint);
}
)";

} // namespace

int main() {
  std::printf("lobe %s\n", lobe::version());

  // 0. The renderer's own closures are registered first, before anything compiles (they last
  //    for the process).
  if (!register_renderer_closures()) return 1;

  // 1. One ShadingSystem per process. Its options are read when a group compiles; the
  //    stdlib shaders were installed beside the library, which knows where.
  lobe::ShadingSystem ss;
  std::string stdlib = lobe::stdlib_shader_dir();
  std::printf("stdlib shaders: %s\n", stdlib.c_str());
  ss.options().include_dirs.push_back(stdlib);

  // 2. A shader from source text: from now on the name `tint` finds it (before any file of
  //    that name on the search path).
  lobe::DiagnosticList diags;
  if (!ss.add_shader_source("tint", kTintSource, "tint.osl", diags)) {
    print_diagnostics(diags);
    return 1;
  }

  // 3. The group: layers in execution order, the last one is the material.
  std::unique_ptr<lobe::ShaderGroup> group = ss.parse_group(kGroupText, "minimal_plugin", diags);
  if (!group) {
    print_diagnostics(diags);
    return 1;
  }

  // 4. Compile: instance values become constants, the group is specialised, turned into
  //    LLVM IR and JIT-compiled. The Material is immutable and callable from any thread.
  std::shared_ptr<const lobe::Material> material = ss.compile(*group, diags);
  if (!material) {
    print_diagnostics(diags);
    return 1;
  }
  // The closure functions (eval, sample) of this material's closures, JIT-compiled from the
  // closure library's bitcode; null would mean the Bsdf falls back to the native library.
  const lobe::ClosureKernels* kernels = material->closure_kernels();
  std::printf("closure kernels: %s\n", kernels ? "jit" : material->closure_kernels_error().c_str());

  // 5. One ShadingContext per thread: the arena the closures are built in, and the sink for
  //    the shaders' messages. A flat patch facing +z, seen from straight above.
  lobe::ShadingContext ctx;
  const float us[] = {0.0f, 0.5f, 1.0f};
  for (float u : us) {
    lobe::ShaderGlobals sg{};
    sg.P = {u, 0, 0};
    sg.N = sg.Ng = {0, 0, 1};
    sg.I = {0, 0, -1}; // from the eye towards P
    sg.dPdu = {1, 0, 0};
    sg.dPdv = {0, 1, 0};
    sg.u = u;
    sg.raytype = lobe::kRayCamera;
    sg.context = &ctx;
    ctx.reset(); // frees the previous point's closures
    material->shade(sg);
    std::printf("point u=%.2f\n", u);

    // 6. An output parameter of a layer, after shade(), from this thread's context.
    std::vector<float> cout;
    if (material->read_output(ctx, "t", "Cout", cout) && cout.size() == 3)
      print_color("  t.Cout", {cout[0], cout[1], cout[2]});

    // 7. The closure tree in sg.Ci, flattened into a Bsdf for this point. wo points to the
    //    viewer (-I), wi to the light; eval() returns f(wo, wi) |cos theta_i| and the pdf of
    //    sample() producing wi.
    std::printf("  Ci = %s\n", lobe::closure_to_string(sg.Ci).c_str());
    lobe::Bsdf bsdf;
    lobe::Vec3 wo = -sg.I;
    bsdf.build(sg.Ci, wo, sg.Ng, kernels);
    print_color("  albedo", bsdf.albedo(wo));
    lobe::Vec3 wi = {0.8f, 0.0f, 0.6f}; // cos theta_i = 0.6
    lobe::BsdfEval e = bsdf.eval(wo, wi);
    print_color("  eval", e.value);
    std::printf("  eval pdf %.6f\n", e.pdf);
    // Three uniform numbers choose a lobe and a direction.
    if (std::optional<lobe::BsdfSample> s = bsdf.sample(wo, {0.3f, 0.4f, 0.5f})) {
      std::printf("  sample wi %.6f %.6f %.6f\n", s->wi.x, s->wi.y, s->wi.z);
      print_color("  sample weight", s->weight);
      std::printf("  sample pdf %.6f\n", s->pdf);
    }
  }

  // 8. Shader run-time messages (errors, warnings, printf) go to the context: to `report` when
  //    set. A texture lookup loads OpenImageIO on first use (the library does not link it), so
  //    the error says what OpenImageIO made of the missing file.
  if (!ss.add_shader_source("missing_texture", kMissingTextureSource, "missing_texture.osl",
                            diags)) {
    print_diagnostics(diags);
    return 1;
  }
  lobe::ShaderGroup tex;
  tex.layers.push_back({"missing_texture", "tex", {}});
  std::shared_ptr<const lobe::Material> tex_material = ss.compile(tex, diags);
  if (!tex_material) {
    print_diagnostics(diags);
    return 1;
  }
  ctx.report = [](lobe::ShadingContext::MessageKind kind, const std::string& text) {
    std::printf("shader %s: %s\n",
                kind == lobe::ShadingContext::MessageKind::Error ? "error" : "message",
                text.c_str());
  };
  lobe::ShaderGlobals sg{};
  sg.N = sg.Ng = {0, 0, 1};
  sg.I = {0, 0, -1};
  sg.context = &ctx;
  ctx.reset();
  tex_material->shade(sg);
  std::printf("errors reported: %d\n", ctx.errors);

  // 9. A shader that calls the renderer's closure: compiled and shaded as any other, and the
  //    Bsdf calls the registered functions for its lobe (weighted by the shader's 0.8).
  if (!ss.add_shader_source("uses_renderer_closure", kRendererClosureSource,
                            "uses_renderer_closure.osl", diags)) {
    print_diagnostics(diags);
    return 1;
  }
  lobe::ShaderGroup own;
  own.layers.push_back({"uses_renderer_closure", "own", {}});
  std::shared_ptr<const lobe::Material> own_material = ss.compile(own, diags);
  if (!own_material) {
    print_diagnostics(diags);
    return 1;
  }
  lobe::ShaderGlobals osg{};
  osg.N = osg.Ng = {0, 0, 1};
  osg.I = {0, 0, -1};
  osg.context = &ctx;
  ctx.reset();
  own_material->shade(osg);
  std::printf("renderer closure Ci = %s\n", lobe::closure_to_string(osg.Ci).c_str());
  lobe::Bsdf own_bsdf;
  own_bsdf.build(osg.Ci, -osg.I, osg.Ng, own_material->closure_kernels());
  lobe::BsdfEval oe = own_bsdf.eval(-osg.I, {0.8f, 0.0f, 0.6f});
  print_color("renderer closure eval", oe.value);
  std::printf("renderer closure eval pdf %.6f\n", oe.pdf);
  print_color("renderer closure albedo", own_bsdf.albedo(-osg.I));
  return 0;
}
