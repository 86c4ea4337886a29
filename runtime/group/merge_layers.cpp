// Merging identical layers, OSL's opt_merge_instances (see group_links.h).
#include "group_links.h"

#include "ir/printer.h"

#include <bit>
#include <cstdint>

namespace lobe::group {
namespace {

using ir::SymKind;

// Whether two instance-value lists give a shader the same parameter values: a parameter given
// in one only must hold that value as its constant default (a computed default is not known
// here). Each value compares by its parameter's type, floats by their bits.
bool same_values(const ir::Shader& sh, const std::map<std::string, std::vector<ir::ConstValue>>& a,
                 const std::map<std::string, std::vector<ir::ConstValue>>& b) {
  auto same = [](const ir::Type& t, const std::vector<ir::ConstValue>& x,
                 const std::vector<ir::ConstValue>& y) {
    if (x.size() != y.size()) return false;
    for (size_t k = 0; k < x.size(); ++k) {
      bool eq = t.base == ir::BaseType::String ? x[k].s == y[k].s
                : t.base == ir::BaseType::Int
                    ? x[k].i == y[k].i
                    : std::bit_cast<uint32_t>(x[k].f) == std::bit_cast<uint32_t>(y[k].f);
      if (!eq) return false;
    }
    return true;
  };
  auto param = [&](const std::string& name) -> const ir::Symbol* {
    int si = sh.find_symbol(name);
    return si < 0 ? nullptr : &sh.symbols[size_t(si)];
  };
  auto given_only = [&](const std::string& name, const std::vector<ir::ConstValue>& v) {
    const ir::Symbol* sym = param(name);
    return sym && sym->init_begin < 0 && same(sym->type, sym->init, v);
  };
  for (const auto& [name, v] : a) {
    auto it = b.find(name);
    const ir::Symbol* sym = param(name);
    if (!sym) return false;
    if (it == b.end() ? !given_only(name, v) : !same(sym->type, v, it->second)) return false;
  }
  for (const auto& [name, v] : b)
    if (!a.count(name) && !given_only(name, v)) return false;
  return true;
}

} // namespace

bool renderer_reads(const ShaderGroup& group, const std::string& layer, const std::string& var) {
  for (const std::string& ro : group.renderer_outputs) {
    size_t dot = ro.find('.');
    if (dot == std::string::npos) {
      if (ro == var) return true;
    } else if ((dot == 0 || ro.compare(0, dot, layer) == 0) &&
               ro.compare(dot + 1, std::string::npos, var) == 0) {
      return true;
    }
  }
  return false;
}

// OSL's merging of identical instances (its opt_merge_instances, on at -O1 and -O2): layer j is
// merged into an earlier layer i running the same shader with the same parameter values (and
// the same of them given with lockgeom=0), the same parameters taking user data and the same
// connections into it: j's connections out then
// leave from i, and j, needed by nothing, is not built (a named entry layer still runs, its
// outputs connected to nothing: isconnected() says 0). Neither the last layer, nor layers the
// renderer reads outputs of, or layers with an interactive parameter (--reparam may change it
// later) take part. As OSL 1.13.12 does all this. Returns, per layer, the earlier layer it was
// merged into, or -1.
std::vector<int> merge_identical_layers(
    const ShaderGroup& group, const std::vector<const ir::Shader*>& sources,
    const std::vector<std::map<std::string, std::vector<ir::ConstValue>>>& values,
    const std::vector<std::set<std::string>>& interp,
    const std::vector<std::set<std::string>>& interactive,
    const std::vector<std::set<std::string>>& unlocked, std::vector<Link>& links) {
  const size_t n = group.layers.size();
  // Per layer, once: whether it takes no part, and the connections into it in the order made
  // (pointers: a merge redirects their sources in place).
  std::vector<bool> pinned(n, false);
  std::vector<std::vector<const Link*>> inputs(n);
  for (size_t l = 0; l < n; ++l) {
    pinned[l] = l + 1 == n || !interactive[l].empty();
    for (const ir::Symbol& s : sources[l]->symbols)
      pinned[l] = pinned[l] || (s.kind == SymKind::OutputParam &&
                                renderer_reads(group, group.layers[l].name, s.name));
  }
  for (const Link& k : links) inputs[size_t(k.dst_layer)].push_back(&k);
  auto same_endpoint = [](const Endpoint& a, const Endpoint& b) {
    return a.symbol == b.symbol && a.elem == b.elem && a.comp == b.comp;
  };
  std::vector<std::string> text(n); // each layer's shader printed, when first compared
  auto shader_text = [&](size_t l) -> const std::string& {
    if (text[l].empty()) text[l] = ir::print(*sources[l]);
    return text[l];
  };
  std::vector<int> merged_into(n, -1);
  for (size_t j = 1; j < n; ++j) {
    if (pinned[j]) continue;
    for (size_t i = 0; i < j; ++i) {
      if (merged_into[i] >= 0 || pinned[i] || sources[i]->name != sources[j]->name) continue;
      if (sources[i] != sources[j] && shader_text(i) != shader_text(j)) continue;
      if (interp[i] != interp[j] || unlocked[i] != unlocked[j]) continue;
      if (!same_values(*sources[i], values[i], values[j])) continue;
      const std::vector<const Link*>&a = inputs[i], &b = inputs[j];
      bool same_in = a.size() == b.size();
      for (size_t k = 0; same_in && k < a.size(); ++k)
        same_in = a[k]->src_layer == b[k]->src_layer && same_endpoint(a[k]->src, b[k]->src) &&
                  same_endpoint(a[k]->dst, b[k]->dst);
      if (!same_in) continue;
      merged_into[j] = int(i);
      for (Link& k : links)
        if (k.src_layer == int(j)) k.src_layer = int(i);
      break;
    }
  }
  return merged_into;
}

} // namespace lobe::group
