// The closure library's per-lobe API: evaluate, sample, pdf and albedo of one registry
// component with weight 1, addressed by registry id and a parameter block in registry layout.
//
// Used by Bsdf (bsdf.cpp), by the statistical test suites over every registry entry, and by
// `lobe brdf`. Directions are world-space, normalised, pointing away from the surface; wo
// towards the viewer, wi towards the light. eval().value = f(wo, wi) * |cos(N, wi)|. Outputs
// are always finite and >= 0; a degenerate parameter block (zero/NaN normal) gives zero and no
// sample. Non-BSDF entries (emission, layer, holdout, ...) evaluate to zero here: Bsdf::build
// handles them.
#pragma once

#include "lobe/bsdf.h"
#include "lobe/vec.h"

#include <cstdint>
#include <optional>
#include <string_view>

namespace lobe::closures {

// A parameter block for one registry entry. Keyword parameters start at their registry
// defaults; positional ones at neutral test values: N = (0,0,1), other vectors (1,0,0),
// colours (1,1,1), floats and ints 0, distribution "ggx", other strings "". Strings are
// stored as pointers: the caller keeps them alive (literals are fine).
class Params {
public:
  static constexpr size_t kMaxBytes = 256;
  explicit Params(std::string_view key);       // aborts via CHECK if the key is unknown
  Params& set(std::string_view name, float v); // Float (Color: all three, Int: truncated)
  Params& set(std::string_view name, int v);
  Params& set(std::string_view name, const Vec3& v); // Color or Vector
  Params& set(std::string_view name, const char* v); // String
  Params& set_closure(std::string_view name, const ClosureNode* v);
  int id() const { return id_; }
  const unsigned char* data() const { return data_; }
  size_t size() const { return size_; }

private:
  unsigned char* slot(std::string_view name, int expected_type);
  int id_ = -1;
  size_t size_ = 0;
  alignas(8) unsigned char data_[kMaxBytes] = {};
};

BsdfEval eval(int id, const unsigned char* params, const Vec3& wo, const Vec3& wi,
              Transport mode = Transport::Radiance);
float pdf(int id, const unsigned char* params, const Vec3& wo, const Vec3& wi);
// u: three uniform numbers in [0,1). Delta lobes return flags kLobeSpecular, pdf 1.
std::optional<BsdfSample> sample(int id, const unsigned char* params, const Vec3& wo, const Vec3& u,
                                 Transport mode = Transport::Radiance);
Color3 albedo(int id, const unsigned char* params, const Vec3& wo); // directional albedo
uint32_t lobe_flags(int id, const unsigned char* params);           // LobeFlags (bsdf.h)
bool has_implementation(int id);

// The same, set up once and evaluated many times (what Bsdf does per shading point): setup
// writes closure `id`'s lobe for `params` into `state` (Bsdf::kLobeStateBytes bytes, aligned to
// Bsdf::kLobeStateAlign) and returns its LobeFlags, 0 when there is no lobe (state unset); the
// *_prepared calls read it and return exactly what eval/sample/albedo above return.
uint32_t setup(int id, const unsigned char* params, void* state);
BsdfEval eval_prepared(int id, const void* state, const Vec3& wo, const Vec3& wi,
                       Transport mode = Transport::Radiance);
std::optional<BsdfSample> sample_prepared(int id, const void* state, const Vec3& wo, const Vec3& u,
                                          Transport mode = Transport::Radiance);
Color3 albedo_prepared(int id, const void* state, const Vec3& wo);
// A note about a parameter value the library ignores (a negative thin-film thickness), or null.
const char* param_warning(int id, const unsigned char* params);

} // namespace lobe::closures
