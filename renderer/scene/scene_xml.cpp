// The XML scene form of OSL's test renderer (testrender), read with pugixml:
//
//   <World>
//     <Camera eye="0, 0, 5" look_at="0 0 0" up="0 1 0" fov="40" />
//     <ShaderGroup> color Cs 0.8 0.2 0.2; shader matte m; </ShaderGroup>
//     <Sphere center="0,0,0" radius="1" />
//     <Quad corner="-1,-1,-1" edge_x="2,0,0" edge_y="0,0,2" />
//     <ShaderGroup> shader envmap bg; </ShaderGroup>
//     <Background resolution="512" />
//   </World>
//
// A ShaderGroup applies to the shapes after it; the one right before <Background> is the
// background shader (its Ci holds background()). Group text takes `param` lines or bare
// `type name value;` lines. Lobe adds <Settings resolution="W H" spp max_depth seed
// exposure/> and <PointLight position intensity/>. Unknown attributes become warnings;
// unknown elements are errors. Every message names the file and line.
#include "scene.h"
#include "scene_group.h"

#include <pugixml.hpp>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>

namespace lobe::scene {
namespace {

class XmlSceneLoader {
public:
  XmlSceneLoader(const std::string& text, const std::string& path) : text_(text), path_(path) {}

  bool load(const pugi::xml_node& world, SceneDesc& s) {
    s.path = path_;
    for (pugi::xml_node n : world.children()) {
      if (n.type() != pugi::node_element) continue;
      std::string name = n.name();
      bool ok = name == "Camera"        ? camera(n, s.camera)
                : name == "ShaderGroup" ? group(n, s)
                : name == "Sphere"      ? sphere(n, s)
                : name == "Quad"        ? quad(n, s)
                : name == "Background"  ? background(n, s)
                : name == "Settings"    ? settings(n, s.settings)
                : name == "PointLight"  ? point_light(n, s)
                                        : fail(n, "unknown element <" + name +
                                                      "> (expected Camera, ShaderGroup, Sphere, "
                                                       "Quad, Background, Settings, PointLight)");
      if (!ok) return false;
    }
    return true;
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
    check_attrs(n, {"eye", "look_at", "up", "fov", "aperture", "focus_distance"});
    if (!vec(n, "eye", c.eye, false) || !vec(n, "look_at", c.look_at, false) ||
        !vec(n, "up", c.up, false) || !floats(n, "fov", &c.fov, 1, false) ||
        !floats(n, "aperture", &c.aperture, 1, false) ||
        !floats(n, "focus_distance", &c.focus_distance, 1, false))
      return false;
    if (!(c.fov > 0 && c.fov < 180)) return fail(n, "fov expects degrees in (0, 180)");
    if (is_zero(cross(c.look_at - c.eye, c.up)))
      return fail(n, "eye, look_at and up must not be collinear");
    return true;
  }
  bool group(const pugi::xml_node& n, SceneDesc& s) {
    check_attrs(n, {"name"});
    MaterialDesc m;
    m.where = at(n);
    m.name = n.attribute("name") ? n.attribute("name").value()
                                 : "group" + std::to_string(s.materials.size());
    std::string err;
    // Errors carry the file line of the mistake: the group text starts on the line of its
    // first text node (right after <ShaderGroup>).
    pugi::xml_node text = n.first_child();
    int first =
        line_of(text && text.type() == pugi::node_pcdata ? text.offset_debug() : n.offset_debug());
    auto g = parse_group_text(n.child_value(), path_, true, err, first);
    if (!g) {
      error = err;
      return false;
    }
    m.group = std::move(*g);
    m.group.name = m.name;
    current_ = static_cast<int>(s.materials.size());
    s.materials.push_back(std::move(m));
    return true;
  }
  bool sphere(const pugi::xml_node& n, SceneDesc& s) {
    check_attrs(n, {"center", "radius"});
    Shape sh;
    sh.kind = Shape::Kind::Sphere;
    sh.where = at(n);
    sh.material = current_;
    if (!vec(n, "center", sh.center, true) || !floats(n, "radius", &sh.radius, 1, true))
      return false;
    if (!(sh.radius > 0)) return fail(n, "radius expects a number > 0");
    s.shapes.push_back(sh);
    return true;
  }
  bool quad(const pugi::xml_node& n, SceneDesc& s) {
    check_attrs(n, {"corner", "edge_x", "edge_y"});
    Shape sh;
    sh.kind = Shape::Kind::Quad;
    sh.where = at(n);
    sh.material = current_;
    if (!vec(n, "corner", sh.corner, true) || !vec(n, "edge_x", sh.edge_x, true) ||
        !vec(n, "edge_y", sh.edge_y, true))
      return false;
    if (is_zero(cross(sh.edge_x, sh.edge_y))) return fail(n, "quad edges are parallel or zero");
    s.shapes.push_back(sh);
    return true;
  }
  bool background(const pugi::xml_node& n, SceneDesc& s) {
    check_attrs(n, {"resolution"});
    Environment& e = s.environment;
    e.where = at(n);
    float res = 256;
    if (!floats(n, "resolution", &res, 1, false)) return false;
    if (!(res >= 4 && res <= 8192)) return fail(n, "resolution expects a number in [4, 8192]");
    e.resolution = int(res);
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
    // The JSON scene's ranges; beyond them int(spp) would be undefined (found by fuzz_scene_xml).
    if (!(spp >= 1 && spp <= float(1 << 20) && depth >= 1 && depth <= 1024 && seed >= 0))
      return fail(n, "spp expects [1, 1048576], max_depth [1, 1024], seed >= 0");
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
  bool point_light(const pugi::xml_node& n, SceneDesc& s) {
    check_attrs(n, {"position", "intensity"});
    Light l;
    l.where = at(n);
    return vec(n, "position", l.position, true) && vec(n, "intensity", l.intensity, true) &&
           (s.lights.push_back(l), true);
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
