// The scene description: what a scene file says, before anything is compiled or built.
//
// Loaders (JSON: scene_json.cpp, OSL testrender XML: scene_xml.cpp) fill a SceneDesc; the
// renderer (renderer/render) turns it into an Embree scene, compiled materials and lights.
// Nothing here touches Embree, LLVM or images, so loading is cheap and testable alone. Every
// element keeps `where` (file and JSON pointer or line) so later stages can name it in errors.
#pragma once

#include "transform.h"

#include "lobe/memory.h"
#include "lobe/shadingsys.h"
#include "lobe/vec.h"

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace lobe::scene {

struct Camera {
  Vec3 eye{0, 1, 5}, look_at{0, 0, 0}, up{0, 1, 0};
  float fov = 40;           // vertical field of view, degrees
  float aperture = 0;       // lens radius in scene units; 0 = pinhole
  float focus_distance = 0; // 0 = distance from eye to look_at
};

// A material is a shader group; the last layer's Ci is the surface closure.
struct MaterialDesc {
  std::string name;
  std::string where;
  ShaderGroup group;
  // An instance value for a parameter the shader lacks: a warning (testrender XML, as OSL's
  // testrender) rather than an error (JSON, where it is most likely a misspelt name).
  bool unknown_params_warn = false;
};

// Triangle mesh in world space (transforms are applied at load). Its arrays are LargeVectors:
// a large mesh's are on huge pages (lobe/memory.h).
struct Mesh {
  LargeVector<Vec3> positions;
  LargeVector<Vec3> normals;     // per vertex, or empty
  LargeVector<float> uvs;        // 2 per vertex, or empty
  LargeVector<uint32_t> indices; // 3 per triangle
};

// A value a shape gives the shaders that shade it: user data of a `lockgeom = 0` parameter of
// the same name (and getattribute of that name). Numbers answer int (when whole), float,
// triple (3, or 1 for grey), matrix (16) or array parameters of their count; text answers
// string.
struct UserValue {
  std::string name;
  std::vector<float> numbers;
  std::string text;
  bool is_text = false;
};

struct Shape {
  enum class Kind { Mesh, Sphere, Quad } kind = Kind::Sphere;
  Mesh mesh;   // Kind::Mesh
  Vec3 center; // Kind::Sphere
  float radius = 1;
  Vec3 corner, edge_x, edge_y; // Kind::Quad: corner + s*edge_x + t*edge_y, s,t in [0,1]
  int material = -1;           // index into SceneDesc::materials; -1 = default grey matte
  bool is_light = false; // sampled as a light even when a probe of its material finds no emission
  std::vector<UserValue> userdata;
  std::string where;
};

struct LightKind; // light_kinds.h

struct Light {
  const LightKind* kind = nullptr; // a row of light_kinds.cpp; null: a point light
  Vec3 position;
  Color3 intensity{1, 1, 1}; // radiant intensity (W/sr per channel) where it is strongest
  std::vector<Vec3> values;  // the kind's parameters, in its row's order, after its build
  std::string where;
};

struct Environment {
  enum class Kind { None, Constant, Map, Sky, Shader } kind = Kind::None;
  Color3 color{1, 1, 1}; // Constant
  std::string file;      // Map: lat-long .exr/.hdr, +Y up, u = 0 towards -Z... see docs
  float intensity = 1;   // multiplies every kind
  float rotation = 0;    // degrees about +Y
  Vec3 sun_direction{0.4f, 0.7f, 0.3f}; // Sky: towards the sun
  float sun_size = 2.0f;                // Sky: sun's angular diameter, degrees
  int material = -1;                    // Shader: a material whose Ci holds background()
  int resolution = 256;                 // Shader/Sky: lat-long table height (width = 2x)
  std::string where;
};

// How a pixel weighs the image plane around its centre: Box, uniformly over the pixel's own
// square; Tent, by (1 - |dx|) (1 - |dy|) over the square of side 2 pixels around its centre,
// as OSL's testrender does (an edge on a pixel boundary shows 1/8 and 7/8 in the pixels beside
// it, where Box shows 0 and 1). Either way the sample positions are drawn from the filter, so
// a pixel is the plain mean of its samples.
enum class PixelFilter { Box, Tent };

// The filter of a name ("box", "tent"), as scene files and `lobe render --filter` give it;
// false for any other name.
inline bool pixel_filter_named(std::string_view name, PixelFilter& out) {
  if (name != "box" && name != "tent") return false;
  out = name == "tent" ? PixelFilter::Tent : PixelFilter::Box;
  return true;
}

struct Settings {
  int width = 640, height = 360;
  int spp = 16;
  int max_depth = 8; // scattering events; 0: only what the camera sees (emission, background)
  uint64_t seed = 0;
  float exposure = 0;
  // Luminance cap on each indirect contribution (light reaching a path after its first
  // bounce; 0: none). Biased: removes fireflies from caustic paths (e.g. a diffuse surface
  // seeing the sun in a glossy metal) at the cost of energy; direct light is never clamped.
  float clamp = 0;
  // Light paths from the environment per camera sample, for caustics of glass and mirrors
  // (RenderOptions::light_paths, `lobe render --light-paths`); 0: none.
  float light_paths = 0.1f;
  PixelFilter pixel_filter = PixelFilter::Box; // XML scenes (testrender's): Tent
  std::string output;
};

struct SceneDesc {
  std::string path; // file the scene came from ("<built-in>" for the default scene)
  Camera camera;
  Settings settings;
  std::vector<MaterialDesc> materials;
  std::vector<Shape> shapes;
  std::vector<Light> lights;
  Environment environment;
  std::vector<std::string> warnings; // things the file said that the loader did not use
};

// Loads a .json or .xml scene. On failure returns nullopt and sets `error` to
// "file: place: what was expected".
std::optional<SceneDesc> load_scene(const std::string& path, std::string& error);
std::optional<SceneDesc> load_json_scene(const std::string& path, std::string& error);
std::optional<SceneDesc> load_xml_scene(const std::string& path, std::string& error);
// Same, from text in memory (`path` is used for messages and relative file names).
std::optional<SceneDesc> parse_json_scene(const std::string& text, const std::string& path,
                                          std::string& error);
std::optional<SceneDesc> parse_xml_scene(const std::string& text, const std::string& path,
                                         std::string& error);

} // namespace lobe::scene
