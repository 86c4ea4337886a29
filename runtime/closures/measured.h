// measured_bsdf (Lobe extension): measured_bsdf(normal N, string filename, "tint", color):
// an isotropic BRDF tabulated in the MERL format (Matusik et al. 2003).
//
// File: three int32 (90, 90, 180), then all red, all green, all blue values as doubles over
// Rusinkiewicz's half/difference angles; index = phi_d + 180 theta_d + 16200 theta_h with
// theta_h indexed by a square-root mapping, phi_d folded by pi; channel scales 1/1500,
// 1.15/1500, 1.66/1500; negative cells have no data (read as 0). Look-ups interpolate
// trilinearly between cell centres (phi_d wraps with period pi), which keeps f(wi, wo) =
// f(wo, wi): swapping the directions maps phi_d to phi_d + pi. Importance-sampled from
// per-elevation tables of f cos (measured_sampler.h) mixed with 10% cosine sampling, so
// pdf > 0 wherever f > 0; albedo by quadrature. Files load once per process into a shared
// read-only cache (measured.cpp); a file that fails to load makes the lobe evaluate to
// nothing, and load_merl() reports why: cannot open, short header, wrong dimensions, wrong
// size (truncated or trailing bytes), NaN/Inf cells, or no valid cell at all. Negative cells
// are "no data" and read as 0. Native only: not part of the bitcode.
#pragma once

#include "common.h"
#include "measured_sampler.h"
#include "params.h"
#include "quadrature.h"

#include <string>
#include <vector>

namespace lobe::closures {

struct MeasuredTable {
  static constexpr int kThetaH = 90, kThetaD = 90, kPhiD = 180;
  static constexpr int kCells = kThetaH * kThetaD * kPhiD;
  std::vector<float> rgb; // 3 * kCells, already scaled; "no data" stored as 0
  MeasuredSampler sampler;
  Vec3 lookup(const Vec3& wo, const Vec3& wi) const;
};

// Loads a MERL file and builds its sampler; false with a message in `error` for a missing,
// short, long or malformed file.
bool load_merl(const std::string& path, MeasuredTable& table, std::string& error);
// Writes a MERL file tabulating f(wi, wo) (cell centres); false if the file cannot be written.
using BrdfFunction = Vec3 (*)(const Vec3& wi, const Vec3& wo, void* user);
bool write_merl(const std::string& path, BrdfFunction f, void* user);
// The process-wide cache of loaded tables (thread-safe); null if the file does not load.
const MeasuredTable* measured_table(const char* path);

struct Measured {
  const MeasuredTable* table = nullptr;
  Vec3 tint{1, 1, 1};
  uint32_t flags() const { return kLobeReflect | kLobeGlossy; }
  static constexpr float kMix = MeasuredSampler::kCosineShare;
  BsdfEval eval(const Vec3& wo, const Vec3& wi) const {
    if (!(wi.z > 0.0f) || !(wo.z > 0.0f)) return {};
    float pdf = (1.0f - kMix) * table->sampler.pdf(wo, wi) + kMix * wi.z * kInvPi;
    return {tint * table->lookup(wo, wi) * wi.z, pdf};
  }
  BsdfSample sample(const Vec3& wo, const Vec3& u) const {
    BsdfSample s;
    if (!(wo.z > 0.0f)) return s;
    Vec3 wi;
    if (u.z < kMix) {
      wi = sample_cosine_hemisphere(u.x, u.y);
    } else if (!table->sampler.sample(wo, u.x, u.y, wi)) {
      return s;
    }
    BsdfEval e = eval(wo, wi);
    if (!(e.pdf > 0.0f)) return s;
    return {wi, e.value / e.pdf, e.pdf, flags(), 1.0f};
  }
  Vec3 albedo(const Vec3& wo) const { return quadrature_albedo(*this, wo); }
};

// ---- registry entries (params.h) ------------------------------------------------------------

struct MeasuredParams {
  Vec3 N;
  Str filename;
  Color3 tint;
  Str label;
};

// Native only (kNativeOnly in the registry): the table is read from a file; a file that does
// not load gives no lobe.
template <> struct Closure<closure_id::measured_bsdf> {
  using Params = MeasuredParams;
  static constexpr size_t kOffsets[] = {offsetof(Params, N), offsetof(Params, filename),
                                        offsetof(Params, tint), offsetof(Params, label)};
  using Lobe = Measured;
  static bool make(const Params& q, Lobe& l, Frame& f) {
    const MeasuredTable* t = measured_table(q.filename);
    if (!t || !make_frame(q.N, f)) return false;
    l = Measured{t, vmax0(sanitize(q.tint))};
    return true;
  }
};

} // namespace lobe::closures
