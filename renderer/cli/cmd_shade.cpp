// `lobe shade`: runs a shader group over a grid of points, like OSL's testshade.
//
//   lobe shade [options] shadername [more layers]
//     -g W H                  grid size (default 1 1)
//     -param[:type=T][:lockgeom=0] N V
//                             instance value for the next layer (also --param); lockgeom=0
//                             lets user data override it
//     --userdata[:type=T] N V user data N (constant over the grid); "s" and "t" are always
//                             there: u and v with their derivatives, as in testshade
//     -layer NAME shader      add a layer with a name (also --layer)
//     -connect A out B in     connect layer A's `out` to layer B's `in` (also --connect)
//     -group file|text        read the group from a file (or take the text itself)
//     --center                sample pixel centres: u = (x + 0.5) / W
//     --raytype name          the ray type (default camera)
//     --colorspace NAME       the RGB space of shader colours (default Rec709; see
//                             lobe::colorspace_names); an unknown name prints testshade's
//                             `ERROR: Unknown color space "NAME"` and shades in Rec709
//     -o var file.exr|png     write output variable `var` over the grid as an image
//     -O0 | -O1 | -O2         optimisation (-O0 also turns specialisation off)
//     --stats                 compile time per stage and shading time per point
//     -I dir, -D NAME[=val]   include/search path, preprocessor definition
//     -U NAME                 undefine a preprocessor macro
//
// Shaders are found by name on the search path (name.osl, name.lir) or by path. Printed output
// follows OSL's formatting; each connection is announced as `Connect A.out to B.in` first.
#include "command.h"

#include "grid.h"
#include "image.h"
#include "lobe/renderer_services.h"
#include "lobe/shadingsys.h"
#include "shader_source.h"

#include <chrono>
#include <climits>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>

namespace {

struct Output {
  std::string var, file;
};

struct UserDatum {
  std::string name;
  lobe::DataType type;
  std::vector<std::string> words; // the value's words; one broadcasts to every component
  std::vector<float> floats;      // the words as numbers, parsed once (not for strings)
  std::vector<int32_t> ints;
};

// lobe shade's renderer: testshade's "s" and "t" user data (u and v with their derivatives),
// the --userdata values, and "camera:resolution" (the grid size). As in testshade, a
// getattribute of a name it does not know, for the shaded object and without an index, is
// answered from the user data.
class ShadeServices final : public lobe::RendererServices {
public:
  ShadeServices(std::vector<UserDatum> data, int w, int h) : data_(std::move(data)), w_(w), h_(h) {}

  bool get_userdata(const lobe::ShaderGlobals& sg, std::string_view name, lobe::DataType type,
                    bool derivatives, void* val) const override {
    for (const UserDatum& d : data_) // the user's values first, even for "s" and "t"
      if (d.name == name) return write(d, type, val);
    auto* f = static_cast<float*>(val);
    if ((name == "s" || name == "t") && type == lobe::DataType{}) {
      bool s = name == "s";
      f[0] = s ? sg.u : sg.v;
      if (derivatives) {
        f[1] = s ? sg.dudx : sg.dvdx;
        f[2] = s ? sg.dudy : sg.dvdy;
      }
      return true;
    }
    return false;
  }

  bool get_attribute(const lobe::ShaderGlobals& sg, std::string_view object, std::string_view name,
                     int index, lobe::DataType type, bool derivatives, void* val) const override {
    if (object.empty() && name == "camera:resolution") {
      int32_t res[2] = {w_, h_};
      if (index < 0 && type == lobe::DataType{lobe::DataType::Base::Int, 2}) {
        std::memcpy(val, res, sizeof(res));
        return true;
      }
      if (index >= 0 && index < 2 && type == lobe::DataType{lobe::DataType::Base::Int, 0}) {
        std::memcpy(val, &res[index], sizeof(int32_t));
        return true;
      }
      return false;
    }
    if (object.empty() && index < 0) return get_userdata(sg, name, type, derivatives, val);
    return false;
  }

private:
  // A value of the declared type, asked for as the same type (any triple kind for a triple).
  static bool write(const UserDatum& d, lobe::DataType want, void* val) {
    bool same = d.type.arraylen == want.arraylen &&
                (d.type.base == want.base || (d.type.is_triple() && want.is_triple()));
    if (!same) return false;
    int n = want.elements() * want.components();
    for (int k = 0; k < n; ++k) {
      size_t at = d.words.size() == 1 ? 0 : size_t(k);
      if (want.base == lobe::DataType::Base::Int)
        static_cast<int32_t*>(val)[k] = d.ints[at];
      else if (want.base == lobe::DataType::Base::String)
        static_cast<const char**>(val)[k] = d.words[at].c_str();
      else
        static_cast<float*>(val)[k] = d.floats[at];
    }
    return true;
  }

  std::vector<UserDatum> data_;
  int w_, h_;
};

struct Options {
  lobe::ShaderGroup group;
  std::vector<lobe::InstanceValue> pending;
  std::vector<UserDatum> userdata;
  std::string group_source;
  int w = 1, h = 1;
  bool center = false, stats = false;
  std::string raytype = "camera";
  std::vector<Output> outputs;
  lobe::CompileOptions compile;
};

void usage(FILE* f) {
  std::fprintf(f,
               "usage: lobe shade [options] shadername [more layers]\n"
               "  -g W H  -param[:type=T][:lockgeom=0] name value  --userdata[:type=T] name value\n"
               "  -layer NAME shader  -connect A out B in\n"
               "  -group file  --center  --raytype name  --colorspace NAME\n"
               "  -o var file.exr|png  -O0|-O1|-O2\n"
               "  --stats  -I dir  -D NAME[=val]  -U NAME\n");
}

std::string layer_name_for(const std::string& shader) {
  return std::filesystem::path(shader).stem().string();
}

void add_layer(Options& o, const std::string& shader, const std::string& name) {
  o.group.layers.push_back({shader, name, std::move(o.pending)});
  o.pending.clear();
}

bool is_opt(const std::string& a, const char* name) { // -name or --name
  return a == std::string("-") + name || a == std::string("--") + name;
}

// Returns 0 to continue, 2 on a usage error, -1 after --help.
int parse_args(int argc, char** argv, Options& o) {
  for (int i = 1; i < argc; ++i) {
    std::string a = argv[i];
    auto need = [&](int n) { return i + n < argc; };
    if (a == "-h" || a == "--help") {
      usage(stdout);
      return -1;
    }
    if (a == "-g" && need(2)) {
      o.w = std::atoi(argv[i + 1]);
      o.h = std::atoi(argv[i + 2]);
      i += 2;
    } else if ((a.rfind("-param", 0) == 0 || a.rfind("--param", 0) == 0) && need(2)) {
      lobe::InstanceValue v{"float", argv[i + 1], argv[i + 2]};
      size_t colon = a.find(':');
      std::string mods = colon == std::string::npos ? "" : a.substr(colon); // ":type=T:..."
      for (size_t p = 0; p < mods.size();) {
        size_t q = mods.find(':', p + 1);
        std::string m = mods.substr(p, q == std::string::npos ? std::string::npos : q - p);
        p = q == std::string::npos ? mods.size() : q;
        if (m.rfind(":type=", 0) == 0)
          v.type = m.substr(6);
        else if (m == ":lockgeom=0" || m == ":lockgeom=1")
          v.lockgeom = m.back() - '0';
        else {
          std::fprintf(stderr, "lobe shade: unknown modifier '%s' in '%s'\n", m.c_str(), a.c_str());
          return 2;
        }
      }
      o.pending.push_back(v);
      i += 2;
    } else if ((a.rfind("-userdata", 0) == 0 || a.rfind("--userdata", 0) == 0) && need(2)) {
      std::string type = "float";
      size_t c = a.find(":type=");
      if (c != std::string::npos) type = a.substr(c + 6);
      std::optional<lobe::DataType> t = lobe::DataType::parse(type);
      UserDatum d{argv[i + 1], t.value_or(lobe::DataType{}), {}};
      bool one_string = t && t->base == lobe::DataType::Base::String && t->arraylen == 0;
      std::istringstream words(argv[i + 2]);
      for (std::string w; words >> w;) d.words.push_back(w);
      if (one_string) d.words = {argv[i + 2]}; // a string keeps its spaces
      size_t n = t ? size_t(t->elements() * t->components()) : 0;
      bool fits = t && (d.words.size() == n ||
                        (d.words.size() == 1 && t->base != lobe::DataType::Base::String));
      for (const std::string& w : d.words) { // numbers must be numbers
        if (!fits || t->base == lobe::DataType::Base::String) break;
        char* end = nullptr;
        if (t->base == lobe::DataType::Base::Int) {
          long v = std::strtol(w.c_str(), &end, 10);
          fits = *end == 0 && v >= INT32_MIN && v <= INT32_MAX;
          d.ints.push_back(int32_t(v));
        } else {
          d.floats.push_back(std::strtof(w.c_str(), &end));
          fits = *end == 0;
        }
      }
      if (!fits) {
        std::fprintf(stderr, "lobe shade: %s: '%s' is not a value of type %s\n", a.c_str(),
                     argv[i + 2], type.c_str());
        return 2;
      }
      o.userdata.push_back(std::move(d));
      i += 2;
    } else if (is_opt(a, "layer") && need(2)) {
      add_layer(o, argv[i + 2], argv[i + 1]);
      i += 2;
    } else if (is_opt(a, "connect") && need(4)) {
      o.group.connections.push_back({argv[i + 1], argv[i + 2], argv[i + 3], argv[i + 4]});
      i += 4;
    } else if (is_opt(a, "group") && need(1))
      o.group_source = argv[++i];
    else if (is_opt(a, "center"))
      o.center = true;
    else if (is_opt(a, "raytype") && need(1))
      o.raytype = argv[++i];
    else if (is_opt(a, "colorspace") && need(1))
      o.compile.colorspace = argv[++i];
    else if (a == "-o" && need(2)) {
      o.outputs.push_back({argv[i + 1], argv[i + 2]});
      i += 2;
    } else if (a == "-O0" || a == "-O1" || a == "-O2") {
      o.compile.opt_level = a[2] - '0';
      o.compile.specialize = o.compile.opt_level > 0;
    } else if (is_opt(a, "stats"))
      o.stats = true;
    else if (a.rfind("-I", 0) == 0) {
      std::string d = a.size() > 2 ? a.substr(2) : (need(1) ? argv[++i] : "");
      o.compile.include_dirs.push_back(d);
    } else if (a.rfind("-D", 0) == 0) {
      std::string d = a.size() > 2 ? a.substr(2) : (need(1) ? argv[++i] : "");
      o.compile.defines.push_back(d);
    } else if (a.rfind("-U", 0) == 0) {
      std::string d = a.size() > 2 ? a.substr(2) : (need(1) ? argv[++i] : "");
      o.compile.undefines.push_back(d);
    } else if (!a.empty() && a[0] == '-') {
      std::fprintf(stderr, "lobe shade: unknown or incomplete option '%s'\n", a.c_str());
      return 2;
    } else
      add_layer(o, a, layer_name_for(a));
  }
  if (o.w < 1 || o.h < 1) {
    std::fprintf(stderr, "lobe shade: bad grid size\n");
    return 2;
  }
  return 0;
}

lobe::ShaderGlobals grid_point(const Options& o, int x, int y, lobe::ShadingContext& ctx) {
  lobe::group::GridSpec g{o.w, o.h, o.center, lobe::group::raytype_from_name(o.raytype)};
  return lobe::group::grid_globals(g, x, y, &ctx);
}

bool read_text(const std::string& path, std::string& out) {
  std::ifstream in(path);
  if (!in) return false;
  std::stringstream ss;
  ss << in.rdbuf();
  out = ss.str();
  return true;
}

// Each diagnostic's text is already a complete block ending in a newline (as lobe compile
// prints them): no blank line between them.
void print_diags(const lobe::DiagnosticList& d) {
  for (const auto& x : d)
    std::fprintf(stderr, "%s%s", x.text.c_str(),
                 !x.text.empty() && x.text.back() == '\n' ? "" : "\n");
}

// Finds `var` among the layers' parameters, last layer first.
bool read_var(const lobe::Material& m, const lobe::ShadingContext& ctx, const lobe::ShaderGroup& g,
              const std::string& var, std::vector<float>& v) {
  for (size_t i = g.layers.size(); i-- > 0;)
    if (m.read_output(ctx, g.layers[i].name, var, v)) return true;
  return false;
}

int run_shade(int argc, char** argv) {
  Options o;
  int st = parse_args(argc, argv, o);
  if (st) return st < 0 ? 0 : st;
  lobe::ShadingSystem ss;
  std::string cs_error = lobe::colorspace_error(o.compile.colorspace);
  if (!cs_error.empty()) std::fprintf(stderr, "ERROR: %s\n", cs_error.c_str()); // keeps Rec709
  ss.options() = o.compile;
  lobe::DiagnosticList diags;
  if (!o.group_source.empty()) {
    std::string text = o.group_source;
    read_text(o.group_source, text); // a file, else the text itself
    auto g = ss.parse_group(text, o.group_source, diags);
    if (!g) {
      print_diags(diags);
      return 1;
    }
    for (auto& l : o.group.layers) g->layers.push_back(l);
    for (auto& c : o.group.connections) g->connections.push_back(c);
    o.group = *g;
  }
  if (o.group.layers.empty()) {
    usage(stderr);
    return 2;
  }
  // Shaders named without a path resolve on the search path here, so that one found in the
  // working directory is `x.osl` (as for lobe compile and OSL) in diagnostics and __FILE__,
  // not `./x.osl`.
  for (auto& l : o.group.layers) {
    std::string p = lobe::group::find_shader_file(l.shader, o.compile);
    if (p.rfind("./", 0) == 0) p.erase(0, 2);
    if (!p.empty()) l.shader = p;
  }
  for (const auto& c : o.group.connections)
    std::printf("Connect %s.%s to %s.%s\n", c.src_layer.c_str(), c.src_param.c_str(),
                c.dst_layer.c_str(), c.dst_param.c_str());
  auto mat = ss.compile(o.group, diags);
  print_diags(diags);
  if (!mat) return 1;

  std::vector<lobe::image::Image> images;
  for (size_t i = 0; i < o.outputs.size(); ++i)
    images.emplace_back(o.w, o.h, std::vector<std::string>{"R", "G", "B"});
  lobe::ShadingContext ctx;
  ctx.print = [](const std::string& s) { std::fputs(s.c_str(), stdout); };
  ShadeServices services(o.userdata, o.w, o.h);
  ctx.renderer = &services;
  auto t0 = std::chrono::steady_clock::now();
  std::vector<float> v;
  for (int y = 0; y < o.h; ++y)
    for (int x = 0; x < o.w; ++x) {
      ctx.reset();
      lobe::ShaderGlobals sg = grid_point(o, x, y, ctx);
      mat->shade(sg);
      for (size_t k = 0; k < o.outputs.size(); ++k) {
        if (!read_var(*mat, ctx, o.group, o.outputs[k].var, v) || v.empty()) continue;
        float* px = images[k].pixel(x, y);
        for (int c = 0; c < 3; ++c) px[c] = v[v.size() >= 3 ? size_t(c) : 0];
      }
    }
  double shade_ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  std::fflush(stdout);
  int status = 0;
  for (size_t k = 0; k < o.outputs.size(); ++k) {
    if (!read_var(*mat, ctx, o.group, o.outputs[k].var, v)) {
      std::fprintf(stderr, "lobe shade: no output variable '%s'\n", o.outputs[k].var.c_str());
      status = 1;
      continue;
    }
    std::string err = lobe::image::write_image(o.outputs[k].file, images[k]);
    if (!err.empty()) {
      std::fprintf(stderr, "lobe shade: %s\n", err.c_str());
      status = 1;
    }
  }
  if (o.stats) {
    const lobe::CompileStats& s = mat->stats();
    std::printf(
        "stats: preprocess %.3f ms, parse %.3f ms, sema %.3f ms, ir %.3f ms, specialize %.3f ms,"
        " llvm-ir %.3f ms, optimize %.3f ms, codegen %.3f ms%s\n",
        s.preprocess_ms, s.parse_ms, s.sema_ms, s.ir_ms, s.specialize_ms, s.llvm_ir_ms,
        s.optimize_ms, s.codegen_ms, s.cache_hit ? " (cache hit)" : "");
    std::printf("stats: %d points, %.3f us per point\n", o.w * o.h,
                1000.0 * shade_ms / (o.w * o.h));
  }
  return status;
}

} // namespace

LOBE_COMMAND(shade, "run a shader group over a grid of points (OSL testshade)", run_shade);
