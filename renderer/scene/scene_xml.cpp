// The XML scene form of OSL's test renderer (testrender 1.13), read with pugixml and read as
// testrender reads it (docs/scene-format.md lists every element and attribute):
//
//   <World>
//     <Option max_bounces="int 4" aa="int 4"/>
//     <Camera eye="0, 0, 5" look_at="0 0 0" up="0 1 0" fov="40" />
//     <ShaderGroup> color Cs 0.8 0.2 0.2; shader matte m; </ShaderGroup>
//     <Sphere center="0,0,0" radius="1" />
//     <Quad corner="-1,-1,-1" edge_x="2,0,0" edge_y="0,0,2" is_light="1" />
//     <ShaderGroup> shader envmap bg; </ShaderGroup>
//     <Background resolution="512" />
//   </World>
//
// A ShaderGroup applies to the shapes after it; the one right before <Background> is the
// background shader (its Ci holds background()). Group text takes `param` lines or bare
// `type name value;` lines, or <Parameter>/<Shader>/<ConnectShaders> children. testrender's
// camera: defaults eye 0, dir (0,0,1), up +Y, fov 90; `look_at` overrides `dir`; the image
// plane spans tan(fov/2) in height at distance 2 (so Lobe's vertical field of view is
// 2 atan(tan(fov/2) / 2)). Lobe adds <Settings resolution="W H" spp max_depth seed exposure/>
// and the light kinds (<PointLight position intensity/>, <SpotLight ...>: light_kinds.h). Unknown
// attributes and options become warnings; unknown elements are errors. Every message names the file
// and line.
#include "light_kinds.h"
#include "scene.h"
#include "scene_group.h"
#include "shape_kinds.h"

#include <pugixml.hpp>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>

namespace lobe::scene {
namespace {

class XmlSceneLoader {
public:
  XmlSceneLoader(const std::string& text, const std::string& path) : text_(text), path_(path) {}

  bool load(const pugi::xml_node& world, SceneDesc& s) {
    s.path = path_;
    // testrender's defaults: a camera at the origin looking down +Z with fov 90, 640x480,
    // -aa 1 (one sample per pixel), max_bounces unlimited (Lobe: 1024, Russian roulette ends
    // paths long before).
    s.camera = Camera{};
    s.camera.eye = {0, 0, 0};
    s.camera.look_at = {0, 0, 1};
    s.camera.fov = testrender_fov(90);
    s.settings.width = 640, s.settings.height = 480, s.settings.spp = 1;
    s.settings.max_depth = 1024;
    s.settings.pixel_filter = PixelFilter::Tent; // testrender's, two pixels wide
    for (pugi::xml_node n : world.children()) {
      if (n.type() != pugi::node_element) continue;
      std::string name = n.name();
      bool ok = name == "Camera"        ? camera(n, s.camera)
                : name == "ShaderGroup" ? group(n, s)
                : name == "Sphere"      ? sphere(n, s)
                : name == "Quad"        ? quad(n, s)
                : name == "Background"  ? background(n, s)
                : name == "Option"      ? option(n, s.settings)
                : name == "Settings"    ? settings(n, s.settings)
                : xml_light(name)       ? light(n, *xml_light(name), s)
                : xml_kind(name)        ? generated_shape(n, *xml_kind(name), s)
                                        : fail(n, "unknown element <" + name +
                                                      "> (expected Option, Camera, ShaderGroup, "
                                                             "Sphere, Quad, " +
                                                      xml_kind_names() + "Background, Settings, " +
                                                      xml_light_names() + ")");
      if (!ok) return false;
    }
    return true;
  }
  // testrender spans tan(fov/2) across the image height at distance 2 from the eye (its
  // screen runs from -0.5 to 0.5 times tan(fov/2)); Lobe's fov is the full vertical angle.
  static float testrender_fov(float fov) {
    const double pi = 3.14159265358979323846;
    return float(2 * std::atan(0.5 * std::tan(0.5 * fov * pi / 180)) * 180 / pi);
  }
  std::string error;
  std::vector<std::string> warnings;

private:
  int line_of(ptrdiff_t off) const {
    int line = 1;
    for (ptrdiff_t i = 0; i < off && i < ptrdiff_t(text_.size()); ++i) line += text_[i] == '\n';
    return line;
  }
  std::string at(const pugi::xml_node& n) const {
    return path_ + ":" + std::to_string(line_of(n.offset_debug()));
  }
  bool fail(const pugi::xml_node& n, const std::string& msg) {
    error = at(n) + ": " + msg;
    return false;
  }
  // Reports attributes this loader does not read (kept as warnings: testrender has grown
  // attributes over the years, and a scene should still load).
  void check_attrs(const pugi::xml_node& n, std::initializer_list<const char*> known) {
    for (pugi::xml_attribute a : n.attributes()) {
      bool ok = false;
      for (const char* k : known) ok |= std::string(a.name()) == k;
      if (!ok)
        warnings.push_back(at(n) + ": <" + n.name() + "> attribute '" + a.name() + "' ignored");
    }
  }
  bool floats(const pugi::xml_node& n, const char* attr, float* out, int count, bool required) {
    pugi::xml_attribute a = n.attribute(attr);
    if (!a)
      return !required || fail(n, std::string("<") + n.name() + "> needs attribute '" + attr + "'");
    std::string v = a.value();
    for (char& c : v) c = c == ',' ? ' ' : c;
    std::istringstream in(v);
    for (int i = 0; i < count; ++i)
      if (!(in >> out[i]) || !std::isfinite(out[i]))
        return fail(n, std::string("attribute '") + attr + "' expects " + std::to_string(count) +
                           " number(s), found \"" + a.value() + "\"");
    std::string extra;
    if (in >> extra)
      return fail(n, std::string("attribute '") + attr + "' has more than " +
                         std::to_string(count) + " number(s)");
    return true;
  }
  bool vec(const pugi::xml_node& n, const char* attr, Vec3& v, bool required) {
    float f[3] = {v.x, v.y, v.z};
    if (!floats(n, attr, f, 3, required)) return false;
    v = {f[0], f[1], f[2]};
    return true;
  }

  bool camera(const pugi::xml_node& n, Camera& c) {
    check_attrs(n, {"eye", "dir", "look_at", "up", "fov", "aperture", "focus_distance"});
    // testrender's defaults for what the element leaves out.
    c.eye = {0, 0, 0};
    c.up = {0, 1, 0};
    Vec3 dir{0, 0, 1};
    float fov = 90;
    if (!vec(n, "eye", c.eye, false) || !vec(n, "dir", dir, false) || !vec(n, "up", c.up, false) ||
        !floats(n, "fov", &fov, 1, false) || !floats(n, "aperture", &c.aperture, 1, false) ||
        !floats(n, "focus_distance", &c.focus_distance, 1, false))
      return false;
    if (n.attribute("look_at")) { // look_at overrides dir, as in testrender
      Vec3 at;
      if (!vec(n, "look_at", at, true)) return false;
      dir = at - c.eye;
    }
    if (is_zero(dir)) return fail(n, "the camera direction (dir, or look_at - eye) is zero");
    if (!(fov > 0 && fov < 180)) return fail(n, "fov expects degrees in (0, 180)");
    if (is_zero(cross(dir, c.up))) return fail(n, "the view direction and up must not be parallel");
    c.look_at = c.eye + dir;
    c.fov = testrender_fov(fov);
    return true;
  }
  // <Option name="int 4"/>-style values: testrender's "int N", "float X" or "string S"
  // (a bare number is read as a number too).
  bool option(const pugi::xml_node& n, Settings& st) {
    for (pugi::xml_attribute a : n.attributes()) {
      std::string name = a.name(), v = a.value();
      for (const char* p : {"int ", "float ", "string "})
        if (v.rfind(p, 0) == 0) v = v.substr(std::strlen(p));
      char* end = nullptr;
      double x = std::strtod(v.c_str(), &end);
      bool number = end != v.c_str() && std::isfinite(x);
      auto need = [&](double lo, double hi) {
        if (number && x >= lo && x <= hi && x == std::floor(x)) return true;
        error = at(n) + ": <Option> " + name + " expects an integer in [" +
                std::to_string(int64_t(lo)) + ", " + std::to_string(int64_t(hi)) + "], found \"" +
                a.value() + "\"";
        return false;
      };
      if (name == "aa") { // -aa N: N x N samples per pixel
        if (!need(1, 1024)) return false;
        st.spp = int(x) * int(x);
      } else if (name == "max_bounces") {
        if (!need(0, 1e9)) return false;
        st.max_depth = int(std::min(x, 1024.0));
      } else if (name == "rr_depth") {
        // Russian roulette depth: Lobe's own roulette (from the fourth vertex) stands in; the
        // image's expectation is the same.
        if (!need(0, 1e9)) return false;
      } else if (name == "show_albedo_scale") {
        if (number && x > 0)
          return fail(n, "<Option> show_albedo_scale (testrender's -albedo view) is not "
                         "supported by lobe render; write an .exr for its albedo AOV");
      } else {
        warnings.push_back(at(n) + ": <Option> '" + name + "' ignored");
      }
    }
    return true;
  }
  bool group(const pugi::xml_node& n, SceneDesc& s) {
    check_attrs(n, {"name", "type", "commands"});
    MaterialDesc m;
    m.where = at(n);
    m.unknown_params_warn = true; // testrender warns and renders
    m.name = n.attribute("name") ? n.attribute("name").value()
                                 : "group" + std::to_string(s.materials.size());
    if (pugi::xml_attribute t = n.attribute("type");
        t && std::string(t.value()) != "surface" && std::string(t.value()) != "shader")
      return fail(n, std::string("<ShaderGroup> type '") + t.value() +
                         "' is not supported (lobe render shades surfaces)");
    // The commands: the `commands` attribute, else the element's text, else <Parameter>,
    // <Shader> and <ConnectShaders> children.
    std::string text;
    int first = line_of(n.offset_debug());
    if (pugi::xml_attribute c = n.attribute("commands")) {
      text = c.value();
    } else {
      // Errors carry the file line of the mistake: the group text starts on the line of its
      // first text node (right after <ShaderGroup>).
      pugi::xml_node t = n.first_child();
      if (t && t.type() == pugi::node_pcdata) first = line_of(t.offset_debug());
      text = n.child_value();
    }
    bool children = false;
    for (pugi::xml_node c : n.children()) children |= c.type() == pugi::node_element;
    if (text.find_first_not_of(" \t\r\n") == std::string::npos && children) {
      if (!group_children(n, m.group)) return false;
    } else {
      std::string err;
      auto g = parse_group_text(text, path_, true, err, first);
      if (!g) {
        error = err;
        return false;
      }
      m.group = std::move(*g);
    }
    if (m.group.layers.empty()) return fail(n, "<ShaderGroup> has no shader");
    m.group.name = m.name;
    current_ = static_cast<int>(s.materials.size());
    s.materials.push_back(std::move(m));
    return true;
  }
  // testrender's element form of a group: <Parameter name="float 0.5"/> (prefix int, float,
  // vector, point or color; anything else is a string) before the <Shader type name layer/>
  // it applies to, and <ConnectShaders srclayer srcparam dstlayer dstparam/>.
  bool group_children(const pugi::xml_node& g, ShaderGroup& out) {
    std::vector<InstanceValue> pending;
    for (pugi::xml_node c : g.children()) {
      if (c.type() != pugi::node_element) continue;
      std::string name = c.name();
      if (name == "Parameter") {
        for (pugi::xml_attribute a : c.attributes()) {
          InstanceValue v;
          v.name = a.name();
          std::string val = a.value();
          v.type = "string";
          v.value = val;
          for (const char* p : {"int ", "float ", "vector ", "point ", "color "})
            if (val.rfind(p, 0) == 0) {
              v.type = std::string(p, std::strlen(p) - 1);
              v.value = val.substr(std::strlen(p));
              for (char& ch : v.value) ch = ch == ',' ? ' ' : ch;
            }
          pending.push_back(std::move(v));
        }
      } else if (name == "Shader") {
        check_attrs(c, {"type", "name", "layer"});
        if (!c.attribute("name") || !c.attribute("layer"))
          return fail(c, "<Shader> needs attributes 'name' and 'layer'");
        out.layers.push_back(
            {c.attribute("name").value(), c.attribute("layer").value(), std::move(pending)});
        pending.clear();
      } else if (name == "ConnectShaders") {
        check_attrs(c, {"srclayer", "srcparam", "dstlayer", "dstparam"});
        Connection k;
        for (auto [attr, field] : {std::pair{"srclayer", &k.src_layer},
                                   {"srcparam", &k.src_param},
                                   {"dstlayer", &k.dst_layer},
                                   {"dstparam", &k.dst_param}}) {
          if (!c.attribute(attr))
            return fail(c, std::string("<ConnectShaders> needs attribute '") + attr + "'");
          *field = c.attribute(attr).value();
        }
        out.connections.push_back(std::move(k));
      } else {
        return fail(c, "unknown element <" + name +
                           "> in <ShaderGroup> (expected Parameter, Shader, ConnectShaders)");
      }
    }
    if (!pending.empty()) return fail(g, "<Parameter> after the last <Shader>");
    return true;
  }
  // is_light="1" (or "yes"): the shape is sampled as a light (testrender's light list).
  bool light_flag(const pugi::xml_node& n, Shape& sh) {
    pugi::xml_attribute a = n.attribute("is_light");
    if (!a) return true;
    std::string v = a.value();
    sh.is_light = v == "1" || v == "yes";
    if (!sh.is_light && v != "0" && v != "no")
      warnings.push_back(at(n) + ": is_light \"" + v + "\" read as 0 (testrender takes 1 or yes)");
    return true;
  }
  bool sphere(const pugi::xml_node& n, SceneDesc& s) {
    check_attrs(n, {"center", "radius", "is_light"});
    Shape sh;
    sh.kind = Shape::Kind::Sphere;
    sh.where = at(n);
    sh.material = current_;
    if (!vec(n, "center", sh.center, true) || !floats(n, "radius", &sh.radius, 1, true) ||
        !light_flag(n, sh))
      return false;
    if (!(sh.radius > 0)) return fail(n, "radius expects a number > 0");
    s.shapes.push_back(sh);
    return true;
  }
  bool quad(const pugi::xml_node& n, SceneDesc& s) {
    check_attrs(n, {"corner", "edge_x", "edge_y", "is_light"});
    Shape sh;
    sh.kind = Shape::Kind::Quad;
    sh.where = at(n);
    sh.material = current_;
    if (!vec(n, "corner", sh.corner, true) || !vec(n, "edge_x", sh.edge_x, true) ||
        !vec(n, "edge_y", sh.edge_y, true) || !light_flag(n, sh))
      return false;
    if (is_zero(cross(sh.edge_x, sh.edge_y))) return fail(n, "quad edges are parallel or zero");
    s.shapes.push_back(sh);
    return true;
  }
  // The kinds of the shape table (shape_kinds.h) as elements: the name capitalised (<Disk>).
  static const ShapeKind* xml_kind(const std::string& element) {
    for (const ShapeKind& k : shape_kinds())
      if (shape_element(k) == element) return &k;
    return nullptr;
  }
  static std::string xml_kind_names() {
    std::string out;
    for (const ShapeKind& k : shape_kinds()) out += shape_element(k) + ", ";
    return out;
  }
  // Attributes neither `known` nor read are reported (as check_attrs does).
  void warn_unknown_attrs(const pugi::xml_node& n, const std::vector<std::string>& known) {
    for (pugi::xml_attribute a : n.attributes())
      if (std::find(known.begin(), known.end(), a.name()) == known.end())
        warnings.push_back(at(n) + ": <" + n.name() + "> attribute '" + a.name() + "' ignored");
  }
  // A table row's parameters as attributes (shape_kinds.h, light_kinds.h), defaults where
  // left out.
  bool row_args(const pugi::xml_node& n, const std::vector<ShapeParam>& params, ShapeArgs& args) {
    for (const ShapeParam& q : params) {
      pugi::xml_attribute a = n.attribute(q.name);
      if (!a && !q.default_value)
        return fail(n, std::string("<") + n.name() + "> needs attribute '" + q.name + "'");
      Vec3 v;
      if (a || *q.default_value)
        if (std::string e = parse_shape_value(q, a ? a.value() : q.default_value, v); !e.empty())
          return fail(n, std::string("attribute '") + q.name + "' " + e + ", found \"" + a.value() +
                             "\"");
      args.values.push_back(v);
      args.given.push_back(bool(a));
    }
    return true;
  }
  // <Disk center="..." .../>: the row's parameters as attributes (defaults where left out).
  bool generated_shape(const pugi::xml_node& n, const ShapeKind& k, SceneDesc& s) {
    std::vector<std::string> known = {"is_light"};
    for (const ShapeParam& q : k.params) known.push_back(q.name);
    warn_unknown_attrs(n, known);
    Shape sh;
    sh.kind = Shape::Kind::Mesh;
    sh.where = at(n);
    sh.material = current_;
    ShapeArgs args;
    if (!row_args(n, k.params, args) || !light_flag(n, sh)) return false;
    if (std::string e = k.build(args, sh.mesh); !e.empty()) return fail(n, e);
    s.shapes.push_back(std::move(sh));
    return true;
  }
  bool background(const pugi::xml_node& n, SceneDesc& s) {
    check_attrs(n, {"resolution"});
    Environment& e = s.environment;
    e.where = at(n);
    // testrender's resolution R sizes its importance-sampling table (R x R texels); Lobe's
    // lat-long table (2:1) gets about as many texels, R / sqrt(2) rows, so set-up runs the
    // shader as often as testrender's. The table also answers rays that escape after diffuse
    // or glossy bounces (camera and specular rays run the shader), so it keeps at least 256
    // rows whatever is asked (OSL's own scenes say 1).
    float res = 256;
    if (!floats(n, "resolution", &res, 1, false)) return false;
    if (!(res >= 0 && res <= 8192)) return fail(n, "resolution expects a number in [0, 8192]");
    e.resolution = std::max(int(std::lround(res / std::sqrt(2.0f))), 256);
    if (current_ < 0)
      return fail(n, "<Background> needs a <ShaderGroup> before it (the background shader)");
    e.kind = Environment::Kind::Shader;
    e.material = current_;
    return true;
  }
  bool settings(const pugi::xml_node& n, Settings& st) {
    check_attrs(n, {"resolution", "spp", "max_depth", "seed", "exposure"});
    float res[2] = {float(st.width), float(st.height)}, spp = float(st.spp),
          depth = float(st.max_depth), seed = float(st.seed);
    if (!floats(n, "resolution", res, 2, false) || !floats(n, "spp", &spp, 1, false) ||
        !floats(n, "max_depth", &depth, 1, false) || !floats(n, "seed", &seed, 1, false) ||
        !floats(n, "exposure", &st.exposure, 1, false))
      return false;
    if (!(res[0] >= 1 && res[1] >= 1 && res[0] <= 16384 && res[1] <= 16384))
      return fail(n, "resolution expects two sizes in [1, 16384]");
    // The JSON scene's spp range (beyond it int(spp) would be undefined: found by
    // fuzz_scene_xml); max_depth 0 shows only emission and background, as testrender's.
    if (!(spp >= 1 && spp <= float(1 << 20) && depth >= 0 && depth <= 1024 && seed >= 0))
      return fail(n, "spp expects [1, 1048576], max_depth [0, 1024], seed >= 0");
    st.width = int(res[0]), st.height = int(res[1]), st.spp = int(spp), st.max_depth = int(depth);
    if (pugi::xml_attribute a = n.attribute("seed")) { // exactly (a float loses digits > 2^24)
      char* end = nullptr;
      long long v = std::strtoll(a.value(), &end, 10);
      if (end == a.value() || *end || v < 0 || v > (1LL << 40))
        return fail(n, "seed expects an integer in [0, 1099511627776]");
      st.seed = uint64_t(v);
    }
    return true;
  }
  // The kinds of the light table (light_kinds.h) as elements: <PointLight>, <SpotLight>.
  static const LightKind* xml_light(const std::string& element) {
    for (const LightKind& k : light_kinds())
      if (light_element(k) == element) return &k;
    return nullptr;
  }
  static std::string xml_light_names() {
    std::string out;
    for (const LightKind& k : light_kinds()) out += (out.empty() ? "" : ", ") + light_element(k);
    return out;
  }
  // <PointLight position="..." intensity="..." .../>: position and intensity, then the kind's
  // parameters (defaults where left out).
  bool light(const pugi::xml_node& n, const LightKind& k, SceneDesc& s) {
    std::vector<std::string> known = {"position", "intensity"};
    for (const ShapeParam& q : k.params) known.push_back(q.name);
    warn_unknown_attrs(n, known);
    Light l;
    l.kind = &k;
    l.where = at(n);
    if (!vec(n, "position", l.position, true) || !vec(n, "intensity", l.intensity, true))
      return false;
    if (!(l.intensity.x >= 0 && l.intensity.y >= 0 && l.intensity.z >= 0))
      return fail(n, "intensity expects components >= 0 (emitted light cannot be negative)");
    ShapeArgs args;
    if (!row_args(n, k.params, args)) return false;
    std::string key;
    if (std::string e = k.build(args, l.position, key); !e.empty())
      return fail(n, (key.empty() ? "" : key + ": ") + e);
    l.values = std::move(args.values);
    s.lights.push_back(std::move(l));
    return true;
  }

  const std::string& text_;
  std::string path_;
  int current_ = -1;
};

} // namespace

std::optional<SceneDesc> parse_xml_scene(const std::string& text, const std::string& path,
                                         std::string& error) {
  pugi::xml_document doc;
  pugi::xml_parse_result r = doc.load_buffer(text.data(), text.size());
  if (!r) {
    int line = 1;
    for (ptrdiff_t i = 0; i < r.offset && i < ptrdiff_t(text.size()); ++i) line += text[i] == '\n';
    error = path + ":" + std::to_string(line) + ": invalid XML: " + r.description();
    return std::nullopt;
  }
  pugi::xml_node world = doc.child("World");
  if (!world) {
    error = path + ": expected a <World> root element";
    return std::nullopt;
  }
  SceneDesc s;
  XmlSceneLoader loader(text, path);
  if (!loader.load(world, s)) {
    error = loader.error;
    return std::nullopt;
  }
  s.warnings = std::move(loader.warnings);
  return s;
}

std::optional<SceneDesc> load_xml_scene(const std::string& path, std::string& error) {
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    error = path + ": cannot open scene file";
    return std::nullopt;
  }
  std::stringstream ss;
  ss << in.rdbuf();
  return parse_xml_scene(ss.str(), path, error);
}

std::optional<SceneDesc> load_scene(const std::string& path, std::string& error) {
  size_t dot = path.find_last_of('.');
  std::string ext = dot == std::string::npos ? "" : path.substr(dot + 1);
  if (ext == "json") return load_json_scene(path, error);
  if (ext == "xml") return load_xml_scene(path, error);
  error = path + ": unknown scene format (expected .json or .xml)";
  return std::nullopt;
}

} // namespace lobe::scene
