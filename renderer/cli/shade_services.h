// `lobe shade`'s renderer, answering shaders as OSL's testshade does (measured against 1.13.12):
// - user data: "s" and "t", u and v with their derivatives; then the --userdata values, of
//   exactly the asked type;
// - attributes: "camera:resolution" (the grid), testshade's camera (a 90 degree perspective
//   camera, clip 0.1 to 1000, shutter 0 to 1), whole (no element by index) and for any object,
//   "options"/"blahblah" (3.14159, testshade's probe), and any other name without an object or
//   index from the user data;
// - spaces: testshade's "object" (translated by (0, 1, 0) then turned 90 degrees about z),
//   "shader" (translated by (1, 0, 0) then turned 45 degrees), "myspace" (scaled by 2 in y),
//   "screen", "NDC" and "raster" of its camera, and "camera" (= common = world), these four only
//   as a destination: as a source they are unknown spaces (an error; transform leaves the
//   value, getmatrix returns 0), as in testshade.
// - trace(P, R): no scene; a hit when u / dot(P, R) > 0.5 (mindist and maxdist unused), and
//   getmessage("trace", name) answers by u alone, whatever was traced: for u > 0.5 every name
//   gives 1, writing "hitdist" (a float) 0.5, "hit" (an int) 1, "geom:name" (a string)
//   "teapot" and "N" (a normal) (1 - v, 0.25, 1 - u); else "hit" writes 0 and all give 0.
#pragma once

#include "lobe/renderer_services.h"
#include "shade_args.h"

#include <string>
#include <vector>

namespace lobe::cli {

class ShadeServices final : public RendererServices {
public:
  ShadeServices(std::vector<ShadeUserDatum> data, int xres, int yres);

  bool get_userdata(const ShaderGlobals& sg, std::string_view name, DataType type, bool derivatives,
                    void* val) const override;
  bool get_attribute(const ShaderGlobals& sg, std::string_view object, std::string_view name,
                     int index, DataType type, bool derivatives, void* val) const override;
  bool get_matrix(const ShaderGlobals& sg, std::string_view space, float* m) const override;
  bool get_inverse_matrix(const ShaderGlobals& sg, std::string_view space, float* m) const override;
  bool camera_spaces_default_to_identity() const override { return false; }
  bool trace(const ShaderGlobals& sg, const TraceOptions& opt, const Vec3& P, const Vec3& dPdx,
             const Vec3& dPdy, const Vec3& R, const Vec3& dRdx, const Vec3& dRdy,
             TraceHit& hit) const override;
  std::optional<bool> trace_message(const ShaderGlobals& sg, std::string_view name, DataType type,
                                    bool derivatives, void* val) const override;

  bool has_userdata(std::string_view name) const;

private:
  std::vector<ShadeUserDatum> data_;
  int xres_, yres_;
  struct Space {
    std::string_view name;
    float m[16]; // spaces_: space -> common; camera_spaces_: common -> space
    // spaces_: common -> space, as the shadeops would invert `m` at every point otherwise
    // (lobe_get_matrix: math::mat_invert, so the same bits).
    float inv[16];
  };
  std::vector<Space> spaces_;
  // common -> camera, screen, NDC, raster: testshade knows these only as destinations.
  std::vector<Space> camera_spaces_;
};

} // namespace lobe::cli
