// The group builder's connections once resolved by name, and what its parts share of them
// (group_build.cpp, merge_layers.cpp). Internal to runtime/group.
#pragma once

#include "ir/ir.h"
#include "lobe/shadingsys.h"

#include <map>
#include <set>
#include <string>
#include <vector>

namespace lobe::group {

// One resolved end of a connection: a symbol name and an optional element/component.
struct Endpoint {
  std::string symbol;
  int elem = -1, comp = -1;
};

struct Link { // a resolved connection, by names
  int src_layer, dst_layer;
  Endpoint src, dst;
  bool dead = false; // replaced by the source's known value (elide_known_outputs)
};

// Whether one of the group's renderer outputs ("var", or "layer.var") names `var` of `layer`.
bool renderer_reads(const ShaderGroup& group, const std::string& layer, const std::string& var);

// The merging of identical layers (merge_layers.cpp) for the group's instance `values`, the
// parameters taking user data (`interp`), those interactive and those given with lockgeom=0
// (`unlocked`), per layer: see merge_layers.cpp. Returns, per layer, the earlier layer it was
// merged into, or -1; merged layers' connections out leave from that one (`links`).
std::vector<int> merge_identical_layers(
    const ShaderGroup& group, const std::vector<const ir::Shader*>& sources,
    const std::vector<std::map<std::string, std::vector<ir::ConstValue>>>& values,
    const std::vector<std::set<std::string>>& interp,
    const std::vector<std::set<std::string>>& interactive,
    const std::vector<std::set<std::string>>& unlocked, std::vector<Link>& links);

} // namespace lobe::group
