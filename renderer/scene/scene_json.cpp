// The JSON scene format (docs/scene-format.md): camera, settings, materials as shader groups,
// shapes, lights and environment. Every error names the file, the JSON pointer and what was
// expected; unknown keys are errors, so a misspelt setting is never silently ignored.
#include "json_reader.h"
#include "light_kinds.h"
#include "mesh_io.h"
#include "scene.h"
#include "scene_group.h"
#include "shape_kinds.h"

#include <cctype>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

namespace lobe::scene {
namespace {

using json = JsonReader::json;

class JsonSceneLoader {
public:
  JsonSceneLoader(const std::string& path)
      : r_(path), dir_(std::filesystem::path(path).parent_path()) {}

  SceneDesc load(const json& root) {
    SceneDesc s;
    s.path = r_.file();
    r_.object(root, "");
    r_.check_keys(root, "", {"camera", "settings", "materials", "shapes", "lights", "environment"});
    if (root.contains("materials")) materials(root.at("materials"), s);
    if (root.contains("camera")) s.camera = camera(root.at("camera"));
    if (root.contains("settings")) s.settings = settings(root.at("settings"));
    if (root.contains("shapes")) {
      const json& sh = root.at("shapes");
      if (!sh.is_array()) r_.fail("/shapes", "expected an array of shapes");
      for (size_t i = 0; i < sh.size(); ++i)
        s.shapes.push_back(shape(sh[i], "/shapes/" + std::to_string(i)));
    }
    if (root.contains("lights")) {
      const json& li = root.at("lights");
      if (!li.is_array()) r_.fail("/lights", "expected an array of lights");
      for (size_t i = 0; i < li.size(); ++i)
        s.lights.push_back(light(li[i], "/lights/" + std::to_string(i)));
    }
    if (root.contains("environment")) s.environment = environment(root.at("environment"));
    return s;
  }

private:
  Camera camera(const json& j) {
    const std::string p = "/camera";
    r_.object(j, p);
    r_.check_keys(j, p, {"eye", "look_at", "up", "fov", "aperture", "focus_distance"});
    Camera c;
    r_.opt(j, p, "eye", c.eye, &JsonReader::vec3);
    r_.opt(j, p, "look_at", c.look_at, &JsonReader::vec3);
    r_.opt(j, p, "up", c.up, &JsonReader::vec3);
    r_.opt(j, p, "fov", c.fov, &JsonReader::number);
    r_.opt(j, p, "aperture", c.aperture, &JsonReader::number);
    r_.opt(j, p, "focus_distance", c.focus_distance, &JsonReader::number);
    if (!(c.fov > 0 && c.fov < 180))
      r_.fail(p + "/fov", "expected a field of view in (0, 180) degrees");
    if (c.aperture < 0) r_.fail(p + "/aperture", "expected a lens radius >= 0");
    if (is_zero(c.look_at - c.eye)) r_.fail(p + "/look_at", "expected a point different from eye");
    if (is_zero(cross(c.look_at - c.eye, c.up)))
      r_.fail(p + "/up", "expected an up vector not parallel to the view direction");
    return c;
  }

  Settings settings(const json& j) {
    const std::string p = "/settings";
    r_.object(j, p);
    r_.check_keys(j, p,
                  {"resolution", "spp", "max_depth", "seed", "exposure", "clamp", "light_paths",
                   "pixel_filter", "output"});
    Settings s;
    if (j.contains("resolution")) {
      const json& res = j.at("resolution");
      if (!res.is_array() || res.size() != 2)
        r_.fail(p + "/resolution", "expected [width, height]");
      s.width = r_.integer(res[0], p + "/resolution/0", 1, 16384);
      s.height = r_.integer(res[1], p + "/resolution/1", 1, 16384);
    }
    if (j.contains("spp")) s.spp = r_.integer(j.at("spp"), p + "/spp", 1, 1 << 20);
    if (j.contains("max_depth"))
      s.max_depth = r_.integer(j.at("max_depth"), p + "/max_depth", 1, 1024);
    if (j.contains("seed")) { // the range of `lobe render --seed`: [0, 2^40]
      const json& v = j.at("seed");
      if (!v.is_number_integer() || v.get<long long>() < 0 || v.get<long long>() > (1LL << 40))
        r_.fail(p + "/seed", "expected an integer in [0, 1099511627776]");
      s.seed = static_cast<uint64_t>(v.get<long long>());
    }
    r_.opt(j, p, "exposure", s.exposure, &JsonReader::number);
    r_.opt(j, p, "clamp", s.clamp, &JsonReader::number);
    if (!(s.clamp >= 0) || !std::isfinite(s.clamp))
      r_.fail(p + "/clamp", "expected a finite number >= 0 (0: no clamp)");
    r_.opt(j, p, "light_paths", s.light_paths, &JsonReader::number);
    if (!(s.light_paths >= 0 && s.light_paths <= 64))
      r_.fail(p + "/light_paths", "expected a number in [0, 64] (0: none)");
    std::string filter = "box";
    r_.opt(j, p, "pixel_filter", filter, &JsonReader::string);
    if (!pixel_filter_named(filter, s.pixel_filter))
      r_.fail(p + "/pixel_filter", "expected \"box\" or \"tent\" (testrender's)");
    r_.opt(j, p, "output", s.output, &JsonReader::string);
    return s;
  }

  // One instance value: a number is a float, 3 numbers a color, N numbers float[N], a string
  // a string; {"type": T, "value": V} says the type explicitly.
  InstanceValue param(const std::string& name, const json& j, const std::string& p) {
    InstanceValue iv{"", name, ""};
    const json* v = &j;
    if (j.is_object()) {
      r_.check_keys(j, p, {"type", "value"});
      if (!j.contains("type") || !j.contains("value"))
        r_.fail(p, "expected {\"type\": ..., \"value\": ...}");
      iv.type = r_.string(j.at("type"), p + "/type");
      if (!is_param_type(iv.type))
        r_.fail(p + "/type",
                "expected an OSL type (int, float, color, point, vector, normal, string, matrix)");
      v = &j.at("value");
    }
    std::ostringstream text;
    if (v->is_string()) {
      if (iv.type.empty()) iv.type = "string";
      text << v->get<std::string>();
    } else if (v->is_number()) {
      if (iv.type.empty()) iv.type = "float";
      if (v->is_number_integer())
        text << v->get<long long>();
      else
        text << r_.number(*v, p);
    } else if (v->is_array() && !v->empty()) {
      if (iv.type.empty())
        iv.type = v->size() == 3 ? "color" : "float[" + std::to_string(v->size()) + "]";
      for (size_t i = 0; i < v->size(); ++i)
        text << (i ? " " : "") << r_.number((*v)[i], p + "/" + std::to_string(i));
    } else {
      r_.fail(p, "expected a number, an array of numbers, a string or {\"type\", \"value\"}");
    }
    iv.value = text.str();
    return iv;
  }

  ShaderGroup::Layer layer(const json& j, const std::string& p, const std::string& default_name) {
    r_.object(j, p);
    r_.check_keys(j, p, {"shader", "name", "params"});
    ShaderGroup::Layer l;
    if (!j.contains("shader")) r_.fail(p, "expected a \"shader\" name");
    l.shader = r_.string(j.at("shader"), p + "/shader");
    l.name = j.contains("name") ? r_.string(j.at("name"), p + "/name") : default_name;
    if (j.contains("params")) {
      const json& ps = r_.object(j.at("params"), p + "/params");
      for (auto it = ps.begin(); it != ps.end(); ++it)
        l.values.push_back(param(it.key(), it.value(), p + "/params/" + it.key()));
    }
    return l;
  }

  MaterialDesc material(const std::string& name, const json& j, const std::string& p) {
    r_.object(j, p);
    r_.check_keys(j, p, {"shader", "params", "group", "layers", "connections"});
    MaterialDesc m;
    m.name = name;
    m.where = r_.file() + ": " + p;
    int forms = j.contains("shader") + j.contains("group") + j.contains("layers");
    if (forms != 1)
      r_.fail(p, "expected exactly one of \"shader\", \"group\" (OSL group text) or \"layers\"");
    if (j.contains("group")) {
      std::string err;
      auto g =
          parse_group_text(r_.string(j.at("group"), p + "/group"), m.where + "/group", false, err);
      if (!g) throw SceneError(err);
      m.group = std::move(*g);
    } else if (j.contains("shader")) {
      json one = {{"shader", j.at("shader")}};
      if (j.contains("params")) one["params"] = j.at("params");
      m.group.layers.push_back(layer(one, p, name));
    } else {
      const json& ls = j.at("layers");
      if (!ls.is_array() || ls.empty())
        r_.fail(p + "/layers", "expected a non-empty array of layers");
      for (size_t i = 0; i < ls.size(); ++i)
        m.group.layers.push_back(
            layer(ls[i], p + "/layers/" + std::to_string(i), "layer" + std::to_string(i)));
      if (j.contains("connections")) connections(j.at("connections"), p + "/connections", m.group);
    }
    m.group.name = name;
    return m;
  }

  void connections(const json& j, const std::string& p, ShaderGroup& g) {
    if (!j.is_array()) r_.fail(p, "expected an array of [\"layer.out\", \"layer.in\"] pairs");
    for (size_t i = 0; i < j.size(); ++i) {
      std::string pi = p + "/" + std::to_string(i);
      if (!j[i].is_array() || j[i].size() != 2)
        r_.fail(pi, "expected [\"layer.out\", \"layer.in\"]");
      Connection c;
      std::string a = r_.string(j[i][0], pi + "/0"), b = r_.string(j[i][1], pi + "/1");
      size_t da = a.find('.'), db = b.find('.');
      if (da == std::string::npos || db == std::string::npos)
        r_.fail(pi, "expected \"layer.param\" on both sides");
      c.src_layer = a.substr(0, da), c.src_param = a.substr(da + 1);
      c.dst_layer = b.substr(0, db), c.dst_param = b.substr(db + 1);
      g.connections.push_back(c);
    }
  }

  void materials(const json& j, SceneDesc& s) {
    r_.object(j, "/materials");
    for (auto it = j.begin(); it != j.end(); ++it) {
      index_[it.key()] = static_cast<int>(s.materials.size());
      s.materials.push_back(material(it.key(), it.value(), "/materials/" + it.key()));
    }
  }

  int material_ref(const json& j, const std::string& p) {
    std::string name = r_.string(j, p);
    auto it = index_.find(name);
    if (it == index_.end()) r_.fail(p, "no material named '" + name + "' in /materials");
    return it->second;
  }

  // {"name": number | [numbers] | "text", ...}
  std::vector<UserValue> userdata(const json& j, const std::string& p) {
    r_.object(j, p);
    std::vector<UserValue> out;
    for (auto it = j.begin(); it != j.end(); ++it) {
      std::string q = p + "/" + it.key();
      UserValue u;
      u.name = it.key();
      if (it.value().is_string()) {
        u.text = r_.string(it.value(), q);
        u.is_text = true;
      } else if (it.value().is_number()) {
        u.numbers = {r_.number(it.value(), q)};
      } else if (it.value().is_array() && !it.value().empty()) {
        for (size_t k = 0; k < it.value().size(); ++k)
          u.numbers.push_back(r_.number(it.value()[k], q + "/" + std::to_string(k)));
      } else {
        r_.fail(q, "expected a number, an array of numbers or a string");
      }
      out.push_back(std::move(u));
    }
    return out;
  }

  Shape shape(const json& j, const std::string& p) {
    r_.object(j, p);
    if (!j.contains("type")) r_.fail(p, "expected \"type\": " + shape_types());
    std::string type = r_.string(j.at("type"), p + "/type");
    Shape s;
    s.where = r_.file() + ": " + p;
    Mat4 xf;
    if (j.contains("transform")) xf = r_.transform(j.at("transform"), p + "/transform");
    if (j.contains("material")) s.material = material_ref(j.at("material"), p + "/material");
    if (j.contains("userdata")) s.userdata = userdata(j.at("userdata"), p + "/userdata");
    if (type == "sphere") {
      r_.check_keys(j, p, {"type", "center", "radius", "material", "transform", "userdata"});
      s.kind = Shape::Kind::Sphere;
      r_.opt(j, p, "center", s.center, &JsonReader::vec3);
      r_.opt(j, p, "radius", s.radius, &JsonReader::number);
      if (!(s.radius > 0)) r_.fail(p + "/radius", "expected a radius > 0");
      float sx = length(xf.vector({1, 0, 0})), sy = length(xf.vector({0, 1, 0})),
            sz = length(xf.vector({0, 0, 1}));
      if (std::abs(sx - sy) > 1e-4f * sx || std::abs(sx - sz) > 1e-4f * sx)
        r_.fail(p + "/transform", "spheres take only uniform scales");
      s.center = xf.point(s.center);
      s.radius *= sx;
    } else if (type == "quad") {
      r_.check_keys(j, p,
                    {"type", "corner", "edge_x", "edge_y", "material", "transform", "userdata"});
      s.kind = Shape::Kind::Quad;
      for (const char* k : {"corner", "edge_x", "edge_y"})
        if (!j.contains(k)) r_.fail(p, std::string("expected \"") + k + "\"");
      s.corner = xf.point(r_.vec3(j.at("corner"), p + "/corner"));
      s.edge_x = xf.vector(r_.vec3(j.at("edge_x"), p + "/edge_x"));
      s.edge_y = xf.vector(r_.vec3(j.at("edge_y"), p + "/edge_y"));
      if (is_zero(cross(s.edge_x, s.edge_y))) r_.fail(p, "quad edges are parallel or zero");
    } else if (type == "mesh") {
      r_.check_keys(j, p, {"type", "file", "material", "transform", "userdata"});
      s.kind = Shape::Kind::Mesh;
      if (!j.contains("file")) r_.fail(p, "expected \"file\": an .obj or .ply path");
      std::filesystem::path f = r_.string(j.at("file"), p + "/file");
      if (f.is_relative()) f = dir_ / f;
      if (std::string e = load_mesh(f.string(), s.mesh); !e.empty()) r_.fail(p + "/file", e);
      transform_mesh(s.mesh, xf);
    } else if (const ShapeKind* k = find_shape_kind(type)) {
      generated_shape(j, p, *k, xf, s);
    } else {
      r_.fail(p + "/type", "expected " + shape_types() + ", found \"" + type + "\"");
    }
    return s;
  }

  // "sphere", "quad", "mesh" and the kinds of the shape table, as a list for messages.
  static std::string shape_types() {
    std::string out = "\"sphere\", \"quad\", \"mesh\"";
    std::span<const ShapeKind> kinds = shape_kinds();
    for (size_t i = 0; i < kinds.size(); ++i)
      out += std::string(i + 1 == kinds.size() ? " or " : ", ") + "\"" + kinds[i].name + "\"";
    return out;
  }

  // A kind of the shape table (shape_kinds.h): its parameters, read and checked as its row
  // says, build its mesh, which the transform then places.
  // A table row's parameters (shape_kinds.h, light_kinds.h), read and checked as the row says.
  ShapeArgs row_args(const json& j, const std::string& p, const std::vector<ShapeParam>& params) {
    ShapeArgs args;
    for (const ShapeParam& q : params) {
      const std::string qp = p + "/" + q.name;
      Vec3 v;
      bool given = j.contains(q.name);
      if (given) {
        const json& x = j.at(q.name);
        if (q.type == ShapeParam::Type::Point || q.type == ShapeParam::Type::Vector)
          v = r_.vec3(x, qp);
        else if (q.type == ShapeParam::Type::Number)
          v.x = r_.number(x, qp);
        else
          v.x = float(r_.integer(x, qp, 1, 1 << 20));
      } else if (!q.default_value) {
        r_.fail(p, std::string("expected \"") + q.name + "\"");
      } else if (*q.default_value) {
        parse_shape_value(q, q.default_value, v);
      }
      args.values.push_back(v);
      args.given.push_back(given);
    }
    return args;
  }

  // A kind of the shape table (shape_kinds.h): its parameters, read and checked as its row
  // says, build its mesh, which the transform then places.
  void generated_shape(const json& j, const std::string& p, const ShapeKind& k, const Mat4& xf,
                       Shape& s) {
    std::vector<const char*> allowed = {"type", "material", "transform", "userdata"};
    for (const ShapeParam& q : k.params) allowed.push_back(q.name);
    r_.check_keys(j, p, allowed);
    ShapeArgs args = row_args(j, p, k.params);
    s.kind = Shape::Kind::Mesh;
    if (std::string e = k.build(args, s.mesh); !e.empty()) r_.fail(p, k.name + (": " + e));
    transform_mesh(s.mesh, xf);
  }

  // The kinds of the light table, as a list for messages: "point" or "spot".
  static std::string light_types() {
    std::string out;
    std::span<const LightKind> kinds = light_kinds();
    for (size_t i = 0; i < kinds.size(); ++i)
      out += std::string(i == 0                  ? ""
                         : i + 1 == kinds.size() ? " or "
                                                 : ", ") +
             "\"" + kinds[i].name + "\"";
    return out;
  }

  // A light: its kind's row (light_kinds.h) says what it takes beyond position, intensity and
  // color.
  Light light(const json& j, const std::string& p) {
    r_.object(j, p);
    if (!j.contains("type")) r_.fail(p, "expected \"type\": " + light_types());
    std::string type = r_.string(j.at("type"), p + "/type");
    Light l;
    l.where = r_.file() + ": " + p;
    l.kind = find_light_kind(type);
    if (!l.kind) r_.fail(p + "/type", "expected " + light_types() + ", found \"" + type + "\"");
    std::vector<const char*> allowed = {"type", "position", "intensity", "color"};
    for (const ShapeParam& q : l.kind->params) allowed.push_back(q.name);
    r_.check_keys(j, p, allowed);
    if (!j.contains("position")) r_.fail(p, "expected \"position\"");
    l.position = r_.vec3(j.at("position"), p + "/position");
    Color3 tint{1, 1, 1};
    r_.opt(j, p, "intensity", l.intensity, &JsonReader::emission);
    r_.opt(j, p, "color", tint, &JsonReader::emission);
    l.intensity = l.intensity * tint;
    if (!(std::isfinite(l.intensity.x) && std::isfinite(l.intensity.y) &&
          std::isfinite(l.intensity.z)))
      r_.fail(p, "intensity x color overflows a 32-bit float");
    ShapeArgs args = row_args(j, p, l.kind->params);
    std::string key;
    if (std::string e = l.kind->build(args, l.position, key); !e.empty())
      r_.fail(key.empty() ? p : p + "/" + key, e);
    l.values = std::move(args.values);
    return l;
  }

  Environment environment(const json& j) {
    const std::string p = "/environment";
    r_.object(j, p);
    Environment e;
    e.where = r_.file() + ": " + p;
    if (!j.contains("type"))
      r_.fail(p, "expected \"type\": \"none\", \"constant\", \"map\", \"sky\" or \"shader\"");
    std::string type = r_.string(j.at("type"), p + "/type");
    r_.opt(j, p, "intensity", e.intensity, &JsonReader::emission_scale);
    r_.opt(j, p, "rotation", e.rotation, &JsonReader::number);
    if (type == "none") {
      r_.check_keys(j, p, {"type"});
      e.kind = Environment::Kind::None;
    } else if (type == "constant") {
      r_.check_keys(j, p, {"type", "color", "intensity"});
      e.kind = Environment::Kind::Constant;
      r_.opt(j, p, "color", e.color, &JsonReader::emission);
    } else if (type == "map") {
      r_.check_keys(j, p, {"type", "file", "intensity", "rotation"});
      e.kind = Environment::Kind::Map;
      if (!j.contains("file")) r_.fail(p, "expected \"file\": a lat-long .exr or .hdr");
      std::filesystem::path f = r_.string(j.at("file"), p + "/file");
      e.file = (f.is_relative() ? dir_ / f : f).string();
    } else if (type == "sky") {
      r_.check_keys(j, p,
                    {"type", "sun_direction", "sun_size", "intensity", "rotation", "resolution"});
      e.kind = Environment::Kind::Sky;
      r_.opt(j, p, "sun_direction", e.sun_direction, &JsonReader::vec3);
      r_.opt(j, p, "sun_size", e.sun_size, &JsonReader::number);
      if (is_zero(normalize(e.sun_direction)))
        r_.fail(p + "/sun_direction", "expected a non-zero direction");
      if (!(e.sun_size > 0 && e.sun_size < 45))
        r_.fail(p + "/sun_size", "expected degrees in (0, 45)");
    } else if (type == "shader") {
      r_.check_keys(j, p, {"type", "material", "intensity", "rotation", "resolution"});
      e.kind = Environment::Kind::Shader;
      if (!j.contains("material"))
        r_.fail(p, "expected \"material\": a material whose Ci is background()");
      e.material = material_ref(j.at("material"), p + "/material");
    } else {
      r_.fail(p + "/type",
              "expected \"none\", \"constant\", \"map\", \"sky\" or \"shader\", found \"" + type +
                  "\"");
    }
    if (j.contains("resolution"))
      e.resolution = r_.integer(j.at("resolution"), p + "/resolution", 4, 8192);
    return e;
  }

  JsonReader r_;
  std::filesystem::path dir_;
  std::map<std::string, int> index_;
};

} // namespace

std::optional<SceneDesc> parse_json_scene(const std::string& text, const std::string& path,
                                          std::string& error) {
  json root;
  try {
    root = json::parse(text);
  } catch (const json::parse_error& e) {
    // nlohmann reports a byte offset; turn it into a line and column.
    size_t off = std::min(e.byte, text.size()), line = 1, col = 1;
    for (size_t i = 0; i + 1 < off; ++i) text[i] == '\n' ? (++line, col = 1) : ++col;
    // e.what() is "[json.exception.parse_error.101] parse error at line L, column C: <what>";
    // the position is ours already, so keep only <what>.
    std::string what = e.what();
    if (size_t at = what.find(" parse error"); at != std::string::npos) {
      size_t colon = what.find(": ", at);
      if (colon != std::string::npos) what = what.substr(colon + 2);
    }
    error =
        path + ":" + std::to_string(line) + ":" + std::to_string(col) + ": invalid JSON: " + what;
    return std::nullopt;
  } catch (const json::out_of_range& e) {
    // A number too big for a double ("1e999"): nlohmann names the text but not its place, so
    // find the first occurrence of that text standing as a number token.
    std::string what = e.what(), token;
    if (size_t q = what.find('\''); q != std::string::npos)
      if (size_t q2 = what.find('\'', q + 1); q2 != std::string::npos)
        token = what.substr(q + 1, q2 - q - 1);
    size_t line = 1, col = 1;
    if (!token.empty()) {
      for (size_t at = text.find(token); at != std::string::npos; at = text.find(token, at + 1)) {
        auto num = [](char ch) {
          return std::isalnum(static_cast<unsigned char>(ch)) || ch == '.';
        };
        bool starts = at == 0 || !(num(text[at - 1]) || text[at - 1] == '-' || text[at - 1] == '+');
        bool ends = at + token.size() >= text.size() || !num(text[at + token.size()]);
        if (!starts || !ends) continue;
        for (size_t i = 0; i < at; ++i) text[i] == '\n' ? (++line, col = 1) : ++col;
        break;
      }
    }
    error = path + ":" + std::to_string(line) + ":" + std::to_string(col) + ": number " +
            (token.empty() ? std::string("") : token + " ") + "is too large for a double";
    return std::nullopt;
  }
  try {
    return JsonSceneLoader(path).load(root);
  } catch (const SceneError& e) {
    error = e.what();
  } catch (const json::exception& e) {
    error = path + ": " + e.what();
  }
  return std::nullopt;
}

std::optional<SceneDesc> load_json_scene(const std::string& path, std::string& error) {
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    error = path + ": cannot open scene file";
    return std::nullopt;
  }
  std::stringstream ss;
  ss << in.rdbuf();
  return parse_json_scene(ss.str(), path, error);
}

} // namespace lobe::scene
