// How a closure family implements a registry entry: the Closure<Id> trait.
//
// Each family header (diffuse.h, glossy.h, ...) specialises Closure<closure_id::key> for the
// registry entries it implements, next to its lobes:
//
//   template <> struct Closure<closure_id::diffuse> {
//     using Params = DiffuseParams;      // the parameter block, in registry layout
//     static constexpr size_t kOffsets[] = {offsetof(Params, N), offsetof(Params, label)};
//     using Lobe = Lambert;               // BSDF entries: the lobe in its local frame ...
//     static bool make(const Params& q, Lobe& lobe, Frame& frame);  // ... and its set-up
//   };
//
// kOffsets lists every registry parameter's member in registry order; dispatch.h checks it
// against the registry table at compile time (so a registry edit that is not mirrored in the
// struct does not build), generates the id switch from the registry's X-macro, and checks that
// every BSDF entry has a Lobe. Entries without parameters (emission(), holdout(), ...) need no
// specialisation; non-BSDF entries with parameters declare Params and kOffsets only
// (components.h). make() returns false for degenerate parameters (zero/NaN normal): no lobe.
#pragma once

#include "closure_table.h"
#include "lobe/shading.h"
#include "lobe/vec.h"

#include <cstddef>

namespace lobe::closures {

namespace closure_id = registry::closure_id;

using Str = const char*; // interned string (distribution names, labels, file names)

template <class P> const P& as_params(const unsigned char* p) {
  return *reinterpret_cast<const P*>(p);
}

// Not implemented by any family (entries without parameters, or an id out of range).
template <int Id> struct Closure { using Params = void; };

// A parameter shape several families share (burley_diffuse_bsdf, sheen_bsdf).
struct AlbedoRoughnessParams {
  Vec3 N;
  Color3 albedo;
  float roughness;
  Str label;
};
#define LOBE_ALBEDO_ROUGHNESS_OFFSETS                                                              \
  {                                                                                                \
    offsetof(Params, N), offsetof(Params, albedo), offsetof(Params, roughness),                    \
        offsetof(Params, label)                                                                    \
  }

// True if registry entry `id` has exactly these parameter offsets and a block size that a
// struct of `struct_size` bytes fits.
template <size_t K>
constexpr bool layout_is(int id, const size_t (&offsets)[K], size_t struct_size) {
  if (id < 0 || id >= closure_id::kCount) return false;
  auto params = registry::table::kClosures[id].params;
  if (params.size() != K) return false;
  for (size_t i = 0; i < K; ++i)
    if (registry::param_offset(params, i) != offsets[i]) return false;
  return registry::param_block_size(params) == (struct_size + 7) / 8 * 8;
}

} // namespace lobe::closures
