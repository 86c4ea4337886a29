// The renderer's answers to shaders (lobe/renderer_services.h): each shape's "userdata" from
// the scene for `lockgeom = 0` parameters, the camera's attributes for getattribute, and
// trace() through the Embree scene.
// The shape being shaded comes in ShaderGlobals::renderstate (a const scene::Shape*, set by
// the renderer next to fill_globals).
#pragma once

#include "scene.h"

#include "lobe/renderer_services.h"

namespace lobe::render {

class Geometry;

class SceneServices final : public RendererServices {
public:
  SceneServices() = default;
  SceneServices(const scene::Camera& camera, int width, int height, const Geometry* geometry)
      : camera_(camera), width_(width), height_(height), geometry_(geometry) {}

  // A value of the shape's userdata named `name`, if it can be read as `type`.
  bool get_userdata(const ShaderGlobals& sg, std::string_view name, DataType type, bool derivatives,
                    void* val) const override;
  // "camera:resolution" (int[2]), "camera:fov" (float, degrees, vertical),
  // "camera:projection" ("perspective"), "camera:pixelaspect" (1); then, for the shaded
  // object and no index, the shape's userdata (as OSL's testshade does).
  bool get_attribute(const ShaderGlobals& sg, std::string_view object, std::string_view name,
                     int index, DataType type, bool derivatives, void* val) const override;

  // A ray through the scene's geometry from P along R, between mindist and maxdist (in units
  // of |R|), starting off the surface at P (along sg.Ng) so it does not hit where it starts.
  // "shade" and "traceset" are not supported (every shape is traced; nothing is shaded).
  bool trace(const ShaderGlobals& sg, const TraceOptions& opt, const Vec3& P, const Vec3& dPdx,
             const Vec3& dPdy, const Vec3& R, const Vec3& dRdx, const Vec3& dRdy,
             TraceHit& hit) const override;

  // Writes `v` as `type`: text as a string; numbers as int (whole numbers only), float,
  // triple, matrix or an array, when their count is the type's (one number is also a grey
  // triple, as colours are in scenes); false otherwise.
  static bool write(const scene::UserValue& v, DataType type, void* val);

private:
  scene::Camera camera_;
  int width_ = 0, height_ = 0;
  const Geometry* geometry_ = nullptr;
};

} // namespace lobe::render
