// Lobe's public runtime API: what a renderer (Lobe's own, or a plugin) links against.
//
//   ShadingSystem ss;                          // one per process; thread-safe after setup
//   auto group = ss.parse_group("param float Kd 0.8; shader matte m1;", "scene.json:12", err);
//   auto mat = ss.compile(*group, err);        // specialise, codegen, JIT (cached)
//   ShadingContext ctx;                        // one per thread
//   ShaderGlobals sg = ...; sg.context = &ctx;
//   mat->shade(sg);                            // sg.Ci now holds the closure tree
//   Bsdf bsdf; bsdf.build(sg.Ci, -sg.I, sg.Ng);
#pragma once

#include "lobe/bsdf.h"
#include "lobe/context.h"
#include "lobe/shading.h"

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace lobe {

// One diagnostic. `text` is the rendered form, what a command-line tool prints: for the
// compiler's diagnostics Clang's `file:line:col: error: message`, the source line and a caret
// (ending in '\n'); a one-line diagnostic (the runtime's own: group text, instance values,
// code generation) has no trailing newline. `id` names the kind for callers that act on it:
// the compiler's table name ("err_undeclared", docs/diagnostics.md) or the runtime's
// ("nonexistent_param", "param_type"), else "". `file`, `line` and `column` (1-based) locate
// it when known ("" and 0 otherwise), and `message` is the text without location, severity,
// source line or caret (the compiler's diagnostics; else "").
struct Diagnostic {
  enum class Severity : uint8_t { Note, Warning, Error } severity = Severity::Error;
  std::string text;
  std::string id;
  std::string file;
  int line = 0, column = 0;
  std::string message;
  // How many times OSL's oslc prints the same warning (a warning inside argument i of a call:
  // oslc checks argument i i + 1 times, nested calls multiplying); `text` is printed once.
  int oslc_repeat = 1;
};
using DiagnosticList = std::vector<Diagnostic>;

// A value given to a parameter: an instance value, of `type` ("float", "color", "float[3]",
// "float[]", "string", ...), as text (`value`) or words (`words`, when the caller has split it
// already: group text's quoted strings).
//
// With `osl_rules` (group text, testshade's --param) it follows OSL: the words are that type's
// values, separated by spaces or commas, read as C's atof/atoi read numbers; missing values are
// 0 and extra ones ignored; a scalar string is the whole text. The value then applies if its
// type is the parameter's (any triple for a triple; any length for an unsized array) or is a
// float given to a triple (broadcast); otherwise the default stays, with OSL's warning
// ("attempting to set parameter with wrong type: ..."). Without (scene files), `type` is only
// informative and the words must fill the parameter's type exactly, or be one number
// broadcast to every component and element; anything else is an error.
// `lockgeom`: 0 lets the renderer's user data of the same name and type override the value
// (OSL's interpolated parameters; renderer_services.h), 1 forbids it, -1 (the default) keeps
// what the shader's `[[ int lockgeom = 0 ]]` metadata says (group text's `lockgeom = 0` and
// `interpolated = 1` hints give 0, and its `lockgeom = 1` nothing, as OSL reads them).
// `interpolated`: testshade's `:interpolated=1` or `:lockgeom=0`, which bind nothing (as -v
// prints them; isconnected() may report it connected to user data).
struct InstanceValue {
  std::string type;
  std::string name;
  std::string value;
  int lockgeom = -1;
  std::vector<std::string> words; // the value already split (group text's quoted strings)
  bool osl_rules = false;
  bool interpolated = false;
  bool interactive = false; // testshade's `:interactive=1`: --reparam may change it later
};

struct Connection {
  std::string src_layer, src_param; // param may name a member, element or component: "c[1]"
  std::string dst_layer, dst_param;
};

// A shader group: layers in execution order (the last one is the material), their instance
// values and the connections between them. Built from OSL's group text or by hand.
struct ShaderGroup {
  struct Layer {
    std::string shader; // shader name (found on the search path) or file path
    std::string name;   // layer name
    std::vector<InstanceValue> values;
  };
  std::string name;
  std::vector<Layer> layers;
  std::vector<Connection> connections;
  // OSL's renderer outputs: output parameters the renderer reads ("Cout", or "layer.Cout" for
  // one layer). A layer that has one runs at every shade, in layer order before the last
  // layer, even when nothing downstream reads it (testshade's `-o`; its default is "Cout").
  std::vector<std::string> renderer_outputs;
  // OSL's entry layers: when given, these layers (by name) run at every shade, in layer order,
  // instead of the last layer and the layers with renderer outputs; the others run lazily.
  std::vector<std::string> entry_layers;
};

struct CompileOptions {
  std::vector<std::string> include_dirs; // -I for #include and shader search
  std::vector<std::string> defines;      // "NAME" or "NAME=value"
  std::vector<std::string> undefines;
  int opt_level = 2;      // 0: no specialisation, LLVM -O0; 1/2: specialise, optimise
  bool specialize = true; // fold instance values into constants before LLVM optimises
  // OSL's "lockgeom" option: false lets every parameter without `[[ int lockgeom = 1 ]]` take
  // the renderer's user data (renderer_services.h), as if each said `lockgeom = 0`.
  bool lockgeom_default = true;
  // OSL's "userdata_isconnected": isconnected(p) is 1 for a parameter that takes the renderer's
  // user data (lockgeom = 0), as if the user data were a connection (testshade's
  // --userdata_isconnected).
  bool userdata_isconnected = false;
  // Run-time checks, as OSL's options of the same names, reported as OSL's errors through the
  // ShadingContext: an out-of-range index (range_checking); a NaN or Inf among the float
  // results of an op (debug_nan); a read of a local or temporary before it is written, or of
  // any non-finite float (debug_uninit: locals start as NaN / INT_MIN / a marker string, and a
  // value found so is set to zero). All three are part of the material cache key.
  bool range_checking = true;
  bool debug_nan = false;
  // OSL's "lazylayers": true runs an upstream layer the first time a downstream one reads its
  // output; false runs every layer the group needs, in order, at the start of each shade
  // (testshade's --options lazylayers=0). Part of the material cache key.
  bool lazy_layers = true;
  // OSL's "lazyglobals", "lazyunconnected" and "lazyerror": false runs at every shade, as the
  // group's entry layers run, each layer that writes a shader global (Ci, P, ...), that no
  // connection or renderer output reads, or that calls error(), where otherwise such a layer
  // runs only when another reads it (or never); not when the group names its entry layers.
  // Part of the material cache key.
  bool lazy_globals = true;
  bool lazy_unconnected = true;
  bool lazy_error = true;
  // OSL's "opt_merge_instances": at -O1 and -O2 a layer identical to an earlier one (the same
  // shader, parameter values and connections in) is merged into it and runs once
  // (docs/language.md). Part of the material cache key.
  bool merge_instances = true;
  bool debug_uninit = false;
  // The RGB space shader colours are in (OSL's ShadingSystem "colorspace", testshade's
  // --colorspace): it sets the XYZ matrices of transformc and color("XYZ", ...), luminance's
  // weights, blackbody and wavelength_color, and is the identity name for transformc. One of
  // colorspace_names(); an unknown name compiles as "Rec709" (check it with colorspace_error).
  std::string colorspace = "Rec709";
  // Math builtins (sin, exp, pow, ...): true computes OSL's fast-math values (OIIO's
  // approximations, a few ulp from libm, what OSL 1.13 prints); false the C library's
  // (libm-accurate). Folded constants and run-time values agree in either mode
  // (docs/language.md, "Math").
  bool fast_math = true;
  // Bounded execution: a shade whose loops run more than this many iterations in all (every
  // pass through a loop's back edge counts, in chunks of 65536) is stopped: the running layer
  // returns at once, an error names the shader and the loop ("shader S (layer 0 l): loop at
  // f.osl:3 ran more than N iterations (max_loop_iterations); stopped"), ShadingContext::stopped
  // is set and sg.Ci is null. 0: unlimited (ShadingContext::cancel still stops loops); -1: no
  // checks are generated at all (neither limit nor cancel; what they cost: docs/cli.md).
  int64_t max_loop_iterations = 100000000;
};

// The colour spaces CompileOptions::colorspace accepts: Rec709, sRGB, NTSC, EBU, PAL, SECAM,
// SMPTE, HDTV, CIE, AdobeRGB, ACEScg, ACES2065-1, XYZ (case-sensitive, as OSL's).
const std::vector<std::string>& colorspace_names();
// "" when `name` is one of them (or empty: the default), else OSL's message for it: `Unknown color
// space "NAME"` (testshade prints it once, as "ERROR: " + message, and keeps Rec709).
std::string colorspace_error(const std::string& name);

// Time spent per stage, for --stats and bench/.
struct CompileStats {
  double preprocess_ms = 0, parse_ms = 0, sema_ms = 0, ir_ms = 0;
  double specialize_ms = 0, llvm_ir_ms = 0, optimize_ms = 0, codegen_ms = 0;
  bool cache_hit = false;        // the same group was compiled before in this process
  bool object_from_disk = false; // the machine code came from the disk cache (an earlier run)
  int noise_batched = 0; // noise calls evaluated side by side in vector lanes (0 from the cache)
};

// A compiled material: a specialised shader group turned into machine code. Immutable and
// callable from any thread (each thread brings its own ShadingContext in sg.context).
class Material {
public:
  virtual ~Material() = default;
  // Runs the group at one point; on return sg.Ci holds the closure (null: black).
  virtual void shade(ShaderGlobals& sg) const = 0;
  // Bit i set: the group reads kGlobalFields[i] (so a renderer can skip computing the rest);
  // kReadsRaytype set: it calls raytype() (its result may differ by the ray that hit).
  virtual uint64_t globals_read() const = 0;
  static constexpr uint64_t kReadsRaytype = uint64_t(1) << 63;
  // kUniform set: the group's result is the same at every point of a shape and for every ray
  // and side: it reads no global (but writes Ci), takes no user data, and calls only pure
  // operations and surfacearea(). A renderer may shade such a material once per shape (the
  // emission of an area light at each light sample, say); unset promises nothing.
  static constexpr uint64_t kUniform = uint64_t(1) << 62;
  // Reads an output parameter of a layer (for testshade-style `-o`) as the most recent
  // shade() that used `ctx` left it: each thread reads its own context's results. If `ctx`
  // has shaded another material since (or never shaded this one), the value is the one
  // before any shade (instance value or default). False if the layer has no such parameter.
  // `dst` receives components as floats (ints converted).
  virtual bool read_output(const ShadingContext& ctx, const std::string& layer,
                           const std::string& param, std::vector<float>& dst) const = 0;
  // An output parameter of a layer: its type, or nullopt when the layer has no output
  // parameter of that name. `closure`: a closure output (its value is a pointer into the
  // shading context, not data to copy).
  // `offset`: where the value lives in output_data() (type.bytes() bytes, stored as
  // read_output_bytes() gives them).
  struct OutputInfo {
    DataType type;
    bool closure = false;
    size_t offset = 0;
  };
  virtual std::optional<OutputInfo> output_info(const std::string& layer,
                                                const std::string& param) const {
    (void)layer;
    (void)param;
    return std::nullopt;
  }
  // The value of an output parameter after the most recent shade() with `ctx`, as stored:
  // type.bytes() bytes (int32, float or interned const char* scalars). False if absent.
  virtual bool read_output_bytes(const ShadingContext& ctx, const std::string& layer,
                                 const std::string& param, std::vector<unsigned char>& dst) const {
    (void)ctx;
    (void)layer;
    (void)param;
    (void)dst;
    return false;
  }
  // The storage read_output_bytes() reads: after the most recent shade() with `ctx` (or, if
  // `ctx` has shaded another material since, the values before any shade), an output's value is
  // at output_data(ctx) + output_info(...)->offset. Valid until `ctx` shades again. Lets a
  // caller that reads the same outputs at every point look each up once (output_info) instead
  // of by name per point. Null when the material does not expose its storage (then use
  // read_output_bytes).
  virtual const unsigned char* output_data(const ShadingContext& ctx) const {
    (void)ctx;
    return nullptr;
  }
  // Bytes of per-shade group data (layer parameters and outputs), for testshade's
  // --print-groupdata.
  virtual size_t groupdata_bytes() const { return 0; }
  virtual const CompileStats& stats() const = 0;
  // The closure library's eval/sample/albedo for this material's closures, JIT-compiled and
  // inlined (bsdf.h, ClosureKernels); compiled on the first call, from any thread. Null when
  // the material has no BSDF closures the bitcode provides, or when compiling them failed
  // (closure_kernels_error() says why): Bsdf then uses the native library.
  virtual const ClosureKernels* closure_kernels() const { return nullptr; }
  virtual std::string closure_kernels_error() const { return {}; }
  // True when closure_kernels() came from the disk cache of an earlier run (LOBE_CACHE_DIR,
  // docs/runtime.md "Closure kernels") instead of being compiled.
  virtual bool closure_kernels_cached() const { return false; }
};

class ShadingSystem {
public:
  ShadingSystem();
  ~ShadingSystem();
  ShadingSystem(const ShadingSystem&) = delete;
  ShadingSystem& operator=(const ShadingSystem&) = delete;

  CompileOptions& options();

  // Parses OSL's group text: `param T name value... ; shader S layer ; connect a.x b.y ;`.
  // `where` names the text's origin in diagnostics. Null on error (diagnostics appended).
  std::unique_ptr<ShaderGroup> parse_group(const std::string& text, const std::string& where,
                                           DiagnosticList& diags) const;

  // Makes shader `name` available from its IR text (what `lobe compile --emit=ir` prints), as
  // if compiled from source; it takes precedence over files on the search path. False with
  // diagnostics if the text does not parse.
  bool add_shader_ir(const std::string& name, const std::string& ir_text, DiagnosticList& diags);
  // The same from OSL source text (testshade's --expr and --inbuffer); `where` names the
  // source in diagnostics.
  bool add_shader_source(const std::string& name, const std::string& source,
                         const std::string& where, DiagnosticList& diags);

  // Compiles (or fetches from the in-process cache) a group. Thread-safe. Null on error.
  std::shared_ptr<const Material> compile(const ShaderGroup& group, DiagnosticList& diags);

  // The strings shaders make (concat, format, ...) are kept for the shading system's life,
  // within a quarter of the memory available when it was made; past that a call that makes
  // one gives "" instead. True once that has happened: the results since are wrong, and a
  // command says so (with the budget, strings_budget_bytes()).
  bool strings_exhausted() const;
  uint64_t strings_budget_bytes() const;

private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

} // namespace lobe
