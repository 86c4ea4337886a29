// The renderer's answers to shaders (lobe/renderer_services.h): each shape's "userdata" from
// the scene for `lockgeom = 0` parameters, and the camera's attributes for getattribute.
// The shape being shaded comes in ShaderGlobals::renderstate (a const scene::Shape*, set by
// the renderer next to fill_globals).
#pragma once

#include "scene.h"

#include "lobe/renderer_services.h"

namespace lobe::render {

class SceneServices final : public RendererServices {
public:
  SceneServices() = default;
  SceneServices(const scene::Camera& camera, int width, int height)
      : camera_(camera), width_(width), height_(height) {}

  // A value of the shape's userdata named `name`, if it can be read as `type`.
  bool get_userdata(const ShaderGlobals& sg, std::string_view name, DataType type, bool derivatives,
                    void* val) const override;
  // "camera:resolution" (int[2]), "camera:fov" (float, degrees, vertical),
  // "camera:projection" ("perspective"), "camera:pixelaspect" (1); then, for the shaded
  // object and no index, the shape's userdata (as OSL's testshade does).
  bool get_attribute(const ShaderGlobals& sg, std::string_view object, std::string_view name,
                     int index, DataType type, bool derivatives, void* val) const override;

  // Writes `v` as `type`: text as a string; numbers as int (whole numbers only), float,
  // triple, matrix or an array, when their count is the type's (one number is also a grey
  // triple, as colours are in scenes); false otherwise.
  static bool write(const scene::UserValue& v, DataType type, void* val);

private:
  scene::Camera camera_;
  int width_ = 0, height_ = 0;
};

} // namespace lobe::render
