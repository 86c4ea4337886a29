// build_group (see group_build.h).
#include "group_build.h"

#include "env.h"
#include "group_links.h"
#include "ir/edit.h"
#include "ir/opcodes.h"
#include "keyword_args.h"
#include "lobe/memory.h"
#include "lobe/shading.h"
#include "lobe/shadingsys.h"
#include "passes/derivs.h"
#include "passes/optimize.h"
#include "public_diag.h"

#include <algorithm>
#include <cstring>
#include <map>
#include <set>

namespace lobe::group {
namespace {

using ir::SymKind;

// The group's own diagnostics: rows of the one table (compiler/diag/diag_ids.cpp; the runtime's
// are listed in docs/diagnostics.md, "The runtime's ids").
using diag::DiagId;
Diagnostic err(const std::string& msg, DiagId id) {
  return runtime_diag(id, msg, diag::Severity::Error);
}
Diagnostic warn(const std::string& msg, DiagId id) {
  return runtime_diag(id, msg, diag::Severity::Warning);
}

// "c[1]", "a[2][0]", "s.a", or a whole struct "s" (one endpoint per field, keyed by the
// field's suffix). Empty result: not found — also for an index that is not a number in range
// (an element of a sized array, a component of a triple or matrix; none on a scalar).
std::map<std::string, Endpoint> resolve(const ir::Shader& sh, const std::string& path) {
  std::map<std::string, Endpoint> out;
  size_t br = path.find('[');
  std::string base = path.substr(0, br);
  std::vector<int> idx;
  for (size_t p = br; p != std::string::npos && p < path.size(); p = path.find('[', p + 1)) {
    size_t close = path.find(']', p);
    std::string digits = path.substr(p + 1, close == std::string::npos ? 0 : close - p - 1);
    if (digits.empty() || digits.size() > 9 ||
        digits.find_first_not_of("0123456789") != std::string::npos)
      return out;
    idx.push_back(std::stoi(digits));
  }
  int s = sh.find_symbol(base);
  if (s >= 0) {
    const ir::Symbol& sym = sh.symbols[size_t(s)];
    Endpoint e{base};
    size_t next = 0;
    if (sym.type.is_array() && !idx.empty()) {
      if (sym.type.arraylen > 0 && idx[0] >= sym.type.arraylen) return out;
      e.elem = idx[next++];
    }
    if (next < idx.size()) {
      int comps = sym.type.base == ir::BaseType::Matrix ? 16 : sym.type.is_triple() ? 3 : 0;
      if (idx[next] >= comps) return out;
      e.comp = idx[next++];
    }
    if (next < idx.size()) return out;
    out[""] = e;
    return out;
  }
  for (const ir::Symbol& sym : sh.symbols)
    if ((sym.kind == SymKind::Param || sym.kind == SymKind::OutputParam) &&
        sym.name.rfind(base + ".", 0) == 0)
      out[sym.name.substr(base.size())] = Endpoint{sym.name};
  return out;
}

bool is_param(const ir::Symbol& s) {
  return s.kind == SymKind::Param || s.kind == SymKind::OutputParam;
}

// "" when the layers' arrays fit codegen::kMaxLocalBytes (all layers together), else the
// error, naming the largest and its place. Summed in double: an array of 2^31 elements with
// derivatives must not wrap.
std::string check_storage(const std::vector<std::unique_ptr<ir::Shader>>& shaders,
                          const std::vector<std::string>& layer_names) {
  double total = 0, largest = -1;
  const ir::Symbol* big = nullptr;
  size_t big_layer = 0;
  for (size_t li = 0; li < shaders.size(); ++li)
    for (const ir::Symbol& s : shaders[li]->symbols) {
      if (s.kind == SymKind::Const || !s.type.is_array()) continue;
      double b = double(codegen::storage_bytes(s));
      total += b;
      if (b > largest) largest = b, big = &s, big_layer = li;
    }
  if (!big || total <= double(codegen::kMaxLocalBytes)) return "";
  std::string where =
      "shader '" + shaders[big_layer]->name + "' (layer '" + layer_names[big_layer] + "'";
  if (big->loc.line > 0)
    where.append(", ").append(big->loc.file).append(":").append(std::to_string(big->loc.line));
  return "the material's arrays need " + format_bytes(total) +
         " of stack while it shades, more than the limit of " +
         format_bytes(double(codegen::kMaxLocalBytes)) + "; the largest is '" + big->name + "' (" +
         ir::to_string(big->type) + (big->derivs ? " with derivatives" : "") + ", " +
         format_bytes(largest) + ") in " + where + ")";
}

// The type a connection end carries: the symbol's, less the array for an element and the
// triple for a component.
ir::Type endpoint_type(const ir::Shader& sh, const Endpoint& e) {
  ir::Type t = sh.symbols[size_t(sh.find_symbol(e.symbol))].type;
  if (e.elem >= 0) t.arraylen = 0;
  if (e.comp >= 0 && (t.is_triple() || t.base == ir::BaseType::Matrix))
    t = ir::Type{ir::BaseType::Float, 0};
  return t;
}

// OSL's rule for a connection src -> dst: the same type (any two triples count as the same,
// for arrays of them too; closures, and arrays of equal length), or a number into a float,
// triple or matrix. (A float into an int, a triple into a float, arrays of other lengths,
// strings and numbers are refused.)
bool connectable(const ir::Type& src, const ir::Type& dst) {
  using B = ir::BaseType;
  if (src.is_array() != dst.is_array()) return false;
  // An unsized array (`float a[]`) takes the connected array's length.
  bool same_base = src.base == dst.base || (src.is_triple() && dst.is_triple());
  if (src.is_array() &&
      (!same_base || (src.arraylen != dst.arraylen && src.arraylen >= 0 && dst.arraylen >= 0)))
    return false;
  if (src.base == dst.base || (src.is_triple() && dst.is_triple())) return true;
  bool number = src.base == B::Float || src.base == B::Int;
  bool float_based = dst.base == B::Float || dst.is_triple() || dst.base == B::Matrix;
  return !src.is_array() && number && float_based;
}

// A param the renderer may bind to user data: `[[ int lockgeom = 0 ]]` in the shader, unless
// the instance value says otherwise (`lockgeom` of InstanceValue, -1: as the shader says).
bool interpolated(const ir::Symbol& s, int instance_lockgeom, bool lockgeom_default) {
  if ((s.kind != SymKind::Param && s.kind != SymKind::OutputParam) ||
      s.type.base == ir::BaseType::Closure)
    return false;
  if (instance_lockgeom >= 0) return instance_lockgeom == 0;
  if (int said = metadata_lockgeom(s); said >= 0) return said == 0;
  return !lockgeom_default;
}

std::set<int> written_symbols(const ir::Shader& sh) {
  std::set<int> w;
  for (size_t i = size_t(sh.main_begin); i < sh.ops.size(); ++i)
    for (size_t a = 0; a < sh.ops[i].args.size(); ++a)
      if (sh.ops[i].writes(int(a))) w.insert(sh.ops[i].args[a]);
  return w;
}

// A query op (isconstant, isconnected) answered before shading: `dst = value`.
void answer_with(ir::Shader& sh, ir::Op& op, int value) {
  op.opcode = ir::Opcode::Assign;
  op.args = {op.args[0], ir::intern_int(sh, value)};
  op.written_mask = 1;
}

// Instance values -> constants; unconnected, unwritten params with known values -> Const.
void specialize_layer(ir::Shader& sh,
                      const std::map<std::string, std::vector<ir::ConstValue>>& values,
                      const std::set<std::string>& connected, const passes::EvalOptions& math,
                      bool osl_o2) {
  // isconstant answers for the shader before specialisation (docs/language.md), as codegen
  // does without it: resolve it now, before params become constants.
  for (ir::Op& op : sh.ops)
    if (op.opcode == ir::Opcode::IsConstant && op.args.size() == 2)
      answer_with(sh, op, sh.symbols[size_t(op.args[1])].kind == SymKind::Const ? 1 : 0);
  std::set<int> written = written_symbols(sh);
  for (size_t i = 0; i < sh.symbols.size(); ++i) {
    ir::Symbol& s = sh.symbols[i];
    if (s.kind != SymKind::Param || connected.count(s.name) || written.count(int(i))) continue;
    auto it = values.find(s.name);
    if (it != values.end())
      s.init = it->second;
    else if (s.init_begin >= 0)
      continue; // computed default: stays a parameter
    if (s.init.empty()) continue;
    s.kind = SymKind::Const;
    s.init_begin = s.init_end = -1;
    s.derivs = false;
  }
  passes::OptimizeOptions opt;
  opt.math = math;
  opt.math.c_compares = osl_o2; // OSL's -O2 folds float comparisons as C computes them
  opt.algebraic = true;         // as OSL's runtime optimizer, which oslc's folding is not
  opt.part_stores = osl_o2;
  passes::optimize(sh, opt);
  // A parameter no op reads any more (its reads were dead and went) is no longer used: its
  // useparam goes too, so an upstream layer that only fed dead code does not run, as at OSL's
  // -O2 (`oo = x` into an output nothing reads, `float t = x` never read).
  std::vector<bool> read(sh.symbols.size(), false);
  for (const ir::Op& op : sh.ops)
    if (op.opcode != ir::Opcode::UseParam)
      for (size_t a = 0; a < op.args.size(); ++a)
        if (ir::op_reads(op, int(a))) read[size_t(op.args[a])] = true;
  for (ir::Op& op : sh.ops) {
    if (op.opcode != ir::Opcode::UseParam) continue;
    std::erase_if(op.args, [&](int a) { return !read[size_t(a)]; });
    if (op.args.empty()) op.opcode = ir::Opcode::Nop;
  }
}

// Closes existing derivative flags backwards through kPropagates ops (after a downstream
// layer asked for the derivatives of one of this layer's outputs).
void extend_derivatives(ir::Shader& sh) {
  auto can_carry = [](const ir::Symbol& s) {
    return s.kind != SymKind::Const && (s.type.base == ir::BaseType::Float || s.type.is_triple());
  };
  for (bool grew = true; grew;) {
    grew = false;
    for (const ir::Op& op : sh.ops) {
      const ir::OpcodeInfo* info = &ir::info(op.opcode);
      if (!(info->flags & ir::kPropagates)) continue;
      bool needs = false;
      for (size_t a = 0; a < op.args.size(); ++a)
        needs |= op.writes(int(a)) && sh.symbols[size_t(op.args[a])].derivs;
      if (!needs) continue;
      for (size_t a = 0; a < op.args.size(); ++a) {
        ir::Symbol& s = sh.symbols[size_t(op.args[a])];
        if (ir::op_reads(op, int(a)) && !s.derivs && can_carry(s)) s.derivs = grew = true;
      }
    }
  }
}

// Whether a layer's result is the same at every point of a shape and for every ray: it reads
// no global but Ci (which it writes), and each of its operations is pure (a function of its
// operands), control flow, surfacearea() (one value per shape) or useparam (the layers it
// runs are checked themselves). Anything else (texture lookups, attributes, messages,
// printf, raytype(), backfacing(), derivatives) may vary or have an effect, and rules it out.
bool uniform_layer(const ir::Shader& sh, uint64_t globals) {
  static const uint64_t ci = [] {
    for (size_t g = 0; g < std::size(kGlobalFields); ++g)
      if (!std::strcmp(kGlobalFields[g].name, "Ci")) return uint64_t(1) << g;
    return uint64_t(0);
  }();
  if (globals & ~ci) return false;
  for (const ir::Op& op : sh.ops) {
    const ir::OpcodeInfo& info = ir::info(op.opcode);
    if ((info.flags & (ir::kPure | ir::kJump)) && !(info.flags & ir::kEffect)) continue;
    // useparam runs upstream layers, which are checked in their turn.
    if (op.opcode == ir::Opcode::SurfaceArea || op.opcode == ir::Opcode::UseParam ||
        op.opcode == ir::Opcode::Nop)
      continue;
    return false;
  }
  return true;
}

uint64_t globals_mask(const ir::Shader& sh) {
  uint64_t mask = 0;
  auto set = [&](const char* name) {
    for (size_t g = 0; g < std::size(kGlobalFields); ++g)
      if (name && !std::strcmp(name, kGlobalFields[g].name)) mask |= uint64_t(1) << g;
  };
  std::set<int> used;
  for (const ir::Op& op : sh.ops) {
    used.insert(op.args.begin(), op.args.end());
    if (op.opcode == ir::Opcode::RayType) mask |= Material::kReadsRaytype;
  }
  for (int i : used) {
    const ir::Symbol& s = sh.symbols[size_t(i)];
    if (s.kind != SymKind::Global) continue;
    set(s.name.c_str());
    for (const GlobalField& f : kGlobalFields)
      if (s.derivs && s.name == f.name) {
        set(f.dx);
        set(f.dy);
      }
  }
  return mask;
}

// Unsized array parameters (`float[]`) get their length per instance, here, before
// specialisation and layout: a connection's source length, else the instance value's, else
// the default's (its value count, or `default_len` for a computed default). The layer's copy
// then has only sized arrays, so layout and codegen need no run-time lengths.
void size_unsized_params(ir::Shader& sh, const std::map<std::string, int>& lengths) {
  for (ir::Symbol& s : sh.symbols) {
    if (!is_param(s) || s.type.arraylen >= 0) continue;
    auto it = lengths.find(s.name);
    int len = it != lengths.end() ? it->second : 0;
    if (len <= 0) len = s.init.empty() ? s.default_len : int(s.init.size()) / s.type.components();
    if (len <= 0) continue; // no default to size it (the layout falls back to one element)
    s.type.arraylen = len;
    s.default_len = 0;
  }
}

// Writes at most the symbol's storage (a connection may have fixed a length other than the
// instance value's).
void write_value(unsigned char* p, const ir::Symbol& s, const std::vector<ir::ConstValue>& v,
                 shadeops::RuntimeEnv* env) {
  size_t cap = size_t(s.type.components()) * size_t(std::max(1, s.type.arraylen));
  for (size_t k = 0; k < v.size() && k < cap; ++k) {
    if (s.type.base == ir::BaseType::Int)
      std::memcpy(p + 4 * k, &v[k].i, 4);
    else if (s.type.base == ir::BaseType::String) {
      const char* str = env->strings.intern(v[k].s);
      std::memcpy(p + 8 * k, &str, 8);
    } else if (s.type.base != ir::BaseType::Closure)
      std::memcpy(p + 4 * k, &v[k].f, 4);
  }
}

// A constant converted as an assignment converts it: equal types (any triple to any triple),
// int to float, int or float to a triple. Empty: not one of those.
std::vector<ir::ConstValue> convert_const(const std::vector<ir::ConstValue>& v,
                                          const ir::Type& from, const ir::Type& to) {
  using ir::BaseType;
  if (from.arraylen != to.arraylen) return {};
  bool same = same_kind(from, to);
  if (same) return v;
  if (from.is_array() || v.size() != 1) return {};
  float f = from.base == BaseType::Int ? float(v[0].i) : v[0].f;
  if (from.base != BaseType::Int && from.base != BaseType::Float) return {};
  if (to.base == BaseType::Float) return {ir::ConstValue::of_float(f)};
  if (to.is_triple()) return std::vector<ir::ConstValue>(3, ir::ConstValue::of_float(f));
  return {};
}

// What OSL's -O2 knows of an upstream layer's output param at the end of the layer: written by
// one `assign` of a constant or of a shading global (that the layer never writes; a copy as
// written, not one the optimiser made of x * 1 or x + 0, which OSL keeps) outside any
// conditional construct (ir::in_conditional), or never written and holding a constant default. An
// input parameter connected onward is known (a shader cannot write one) from its instance value
// (`given`, when there is one) or its constant default, or from a computed default that is one copy
// (of a constant or a global) when no instance value is given. `runtime_valued`: the param's value
// arrives while shading (user data, a connection into it), so only a write in the layer could make
// it known. `global` names the global of a copy; else `value` is the constant (in the param's
// type). Neither: not known.
struct KnownOutput {
  std::vector<ir::ConstValue> value;
  std::string global;
};

// What `op` gives `s` (symbol `si`) when it is `assign s x` of a constant or of a global the
// layer never writes (`written`), a copy as written (not one the optimiser made).
KnownOutput known_copy(const ir::Shader& sh, const ir::Op& op, int si,
                       const std::set<int>& written) {
  KnownOutput k;
  const ir::Symbol& s = sh.symbols[size_t(si)];
  if (op.opcode != ir::Opcode::Assign || op.args.size() != 2 || op.args[0] != si) return k;
  const ir::Symbol& src = sh.symbols[size_t(op.args[1])];
  if (src.kind == SymKind::Const)
    k.value = convert_const(src.init, src.type, s.type);
  else if (src.kind == SymKind::Global && !op.identity_copy && !written.count(op.args[1]) &&
           !src.type.is_array() && !s.type.is_array() &&
           src.type.components() == s.type.components() && same_kind(src.type, s.type))
    k.global = src.name;
  return k;
}

KnownOutput known_output(const ir::Shader& sh, const std::string& name, bool runtime_valued,
                         const std::vector<ir::ConstValue>* given) {
  KnownOutput k;
  int si = sh.find_symbol(name);
  if (si < 0) return k;
  const ir::Symbol& s = sh.symbols[size_t(si)];
  if (s.type.base == ir::BaseType::Closure) return k;
  if (s.kind == SymKind::Param) {
    std::set<int> written = written_symbols(sh);
    if (runtime_valued || written.count(si)) return k;
    if (s.init_begin < 0) {
      k.value = given ? *given : s.init;
      return k;
    }
    // A computed default: known when it is one copy of a constant or of a global the layer
    // never writes, and no instance value replaces it (OSL 1.13.12 -O2 then keeps the layer).
    if (given || s.init_end - s.init_begin != 1) return k;
    return known_copy(sh, sh.ops[size_t(s.init_begin)], si, written);
  }
  if (s.kind != SymKind::OutputParam) return k;
  int writer = -1, writes = 0;
  std::set<int> written_globals;
  for (size_t i = size_t(sh.main_begin); i < sh.ops.size(); ++i) {
    const ir::Op& op = sh.ops[i];
    for (size_t a = 0; a < op.args.size(); ++a) {
      if (!op.writes(int(a))) continue;
      if (op.args[a] == si) {
        ++writes;
        if (writer < 0) writer = int(i);
      }
      if (sh.symbols[size_t(op.args[a])].kind == SymKind::Global)
        written_globals.insert(op.args[a]);
    }
  }
  if (writes == 0) {
    if (!runtime_valued && s.init_begin < 0 && !s.init.empty()) k.value = s.init;
    return k;
  }
  if (writes > 1 || ir::in_conditional(sh, writer)) return k;
  return known_copy(sh, sh.ops[size_t(writer)], si, written_globals);
}

// OSL -O2's getmessage of a message nothing can have set yet: a getmessage without a source
// whose name is a constant that no setmessage before it set (in an earlier layer, or earlier
// in this one's ops, which is textual order: in a loop, a set after the get in the body does
// not count) becomes `result = 0`, its destination untouched, and no query is remembered, so a
// later set is no error (OSL 1.13.12: "get before set: 0", then "get after set: 1 4").
// `sent` gathers the constant names set so far, `unknown_sent` whether a name only known while
// shading was (then nothing is folded after it).
void fold_impossible_getmessages(ir::Shader& sh, std::set<std::string>& sent, bool& unknown_sent) {
  auto const_string = [&](int sym) { return ir::string_value(sh.symbols[size_t(sym)]); };
  for (size_t i = size_t(sh.main_begin); i < sh.ops.size(); ++i) {
    ir::Op& op = sh.ops[i];
    if (op.opcode == ir::Opcode::SetMessage && !op.args.empty()) {
      if (const std::string* name = const_string(op.args[0]))
        sent.insert(*name);
      else
        unknown_sent = true;
    } else if (op.opcode == ir::Opcode::GetMessage && op.args.size() == 3 && !unknown_sent) {
      const std::string* name = const_string(op.args[2]);
      if (name && !sent.count(*name)) answer_with(sh, op, 0);
    }
  }
}

// isconnected(p) of layer `layer` as codegen answers it (codegen/ops_library.cpp), from the
// connections as made: 1 when one leads into p (or p takes user data, with userdata_isconnected),
// 2 when one leads out of it or the renderer reads it (a renderer output, testshade's -o, Cout
// by default, counts as a connection out, as in OSL), 3 both. Each becomes an assignment of
// that constant.
void resolve_isconnected(ir::Shader& sh, int layer, const std::vector<Link>& links,
                         const std::set<std::string>& userdata, bool userdata_isconnected,
                         const ShaderGroup& group) {
  for (ir::Op& op : sh.ops) {
    if (op.opcode != ir::Opcode::IsConnected || op.args.size() != 2) continue;
    const std::string& name = sh.symbols[size_t(op.args[1])].name;
    int v = 0;
    for (const Link& l : links) {
      if (l.dst_layer == layer && l.dst.symbol == name) v |= 1;
      if (l.src_layer == layer && l.src.symbol == name) v |= 2;
    }
    if (userdata_isconnected && userdata.count(name)) v |= 1;
    if (sh.symbols[size_t(op.args[1])].kind == SymKind::OutputParam &&
        renderer_reads(group, group.layers[size_t(layer)].name, name))
      v |= 2;
    answer_with(sh, op, v);
  }
}

} // namespace

std::string osl_type_name(const ir::Type& t) {
  std::string s = ir::to_string(t);
  if (t.base == ir::BaseType::Closure && s.rfind("closure", 0) == 0 &&
      s.rfind("closure color", 0) != 0)
    s.insert(7, " color");
  return s;
}

bool build_group(const ShaderGroup& group, const std::vector<const ir::Shader*>& sources,
                 bool specialize, GroupBuild& out, DiagnosticList& diags, bool lockgeom_default,
                 bool elide_known_outputs, bool merge_instances, const EagerLayers& eager) {
  size_t n = group.layers.size();
  std::map<std::string, int> layer_index;
  // A name two layers share names the first, as OSL's connections take it.
  for (size_t i = 0; i < n; ++i) layer_index.emplace(group.layers[i].name, int(i));

  // Instance values, parsed against each parameter's declared type.
  std::vector<std::map<std::string, std::vector<ir::ConstValue>>> values(n);
  std::vector<std::map<std::string, int>> lengths(n);
  std::vector<std::map<std::string, int>> lockgeom(n); // instance overrides of lockgeom
  // Values taken with lockgeom=0, per layer: OSL merges no two layers that differ in them.
  std::vector<std::set<std::string>> unlocked(n);
  for (size_t i = 0; i < n; ++i)
    for (const InstanceValue& v : group.layers[i].values) {
      if (v.lockgeom >= 0) lockgeom[i][v.name] = v.lockgeom;
      int s = sources[i]->find_symbol(v.name);
      if (s < 0 && std::any_of(sources[i]->symbols.begin(), sources[i]->symbols.end(),
                               [&](const ir::Symbol& ps) {
                                 return is_param(ps) && ps.name.rfind(v.name + ".", 0) == 0;
                               }))
        continue; // a struct parameter named whole (its fields are the params): OSL ignores it
      if (s < 0 || !is_param(sources[i]->symbols[size_t(s)])) {
        std::vector<std::string> names; // the shader's parameters, as a hint
        for (const ir::Symbol& ps : sources[i]->symbols)
          if (is_param(ps)) names.push_back(ps.name);
        // OSL's warning, then Lobe's hint as a note (a scene reader turns the pair into an
        // error: a misspelt parameter in a scene is a mistake).
        diags.push_back(
            warn("attempting to set nonexistent parameter: " + v.name, DiagId::nonexistent_param));
        diags.push_back(runtime_diag(
            DiagId::nonexistent_param,
            nonexistent_param_note(group.layers[i].name, sources[i]->name, v.name, names),
            diag::Severity::Note));
        continue;
      }
      ValueFit fit = fit_instance_value(v, sources[i]->symbols[size_t(s)].type);
      if (!fit.error.empty()) {
        diags.push_back(
            err("layer '" + group.layers[i].name + "': " + fit.error, DiagId::param_value));
        return false;
      }
      if (!fit.note.empty())
        diags.push_back(
            warn("layer '" + group.layers[i].name + "': " + fit.note, DiagId::param_value));
      if (!fit.ok) {
        diags.push_back(warn(fit.warning, DiagId::param_type));
        continue;
      }
      std::vector<ir::ConstValue>& cv = fit.values;
      int len = fit.arraylen;
      values[i][v.name] = cv;
      lengths[i][v.name] = len;
      if (v.lockgeom == 0 || v.interpolated)
        unlocked[i].insert(v.name);
      else
        unlocked[i].erase(v.name);
    }

  // Params that take user data (before connections, which override them), per layer.
  std::vector<std::set<std::string>> interp(n);
  for (size_t i = 0; i < n; ++i)
    for (const ir::Symbol& sym : sources[i]->symbols) {
      auto lg = lockgeom[i].find(sym.name);
      if (interpolated(sym, lg == lockgeom[i].end() ? -1 : lg->second, lockgeom_default))
        interp[i].insert(sym.name);
    }
  // Interactive params, per layer: never folded (--reparam may change them), never merged. A
  // value refused (of the wrong type) takes its interactive flag with it, as in OSL: the
  // parameter's metadata decides.
  std::vector<std::set<std::string>> interactive(n);
  for (size_t i = 0; i < n; ++i) {
    ShaderGroup::Layer taken = group.layers[i];
    std::erase_if(taken.values, [&](const InstanceValue& v) { return !values[i].count(v.name); });
    for (const ir::Symbol& sym : sources[i]->symbols)
      if (is_param(sym) && interactive_param(taken, sym)) interactive[i].insert(sym.name);
  }

  // Connections, by names.
  std::vector<Link> links;
  // Errors worded as OSL's ConnectShaders words them (testshade prints them so).
  for (const Connection& c : group.connections) {
    auto si = layer_index.find(c.src_layer), di = layer_index.find(c.dst_layer);
    if (si == layer_index.end() || di == layer_index.end()) {
      diags.push_back(
          err(si == layer_index.end()
                  ? "ConnectShaders: source layer \"" + c.src_layer + "\" not found"
                  : "ConnectShaders: destination layer \"" + c.dst_layer + "\" not found",
              DiagId::connect_layer));
      return false;
    }
    if (si->second >= di->second) {
      diags.push_back(err("ConnectShaders: destination layer must follow source layer (tried to "
                          "connect " +
                              c.src_layer + "." + c.src_param + " -> " + c.dst_layer + "." +
                              c.dst_param + ")",
                          DiagId::connect_order));
      return false;
    }
    const ir::Shader& src_sh = *sources[size_t(si->second)];
    const ir::Shader& dst_sh = *sources[size_t(di->second)];
    auto src = resolve(src_sh, c.src_param);
    auto dst = resolve(dst_sh, c.dst_param);
    // A whole struct's fields carry its top-level type's name (Symbol::struct_name); a member
    // that is itself a struct ("so.in") has the type its path leads to in the struct types.
    auto struct_of = [](const ir::Shader& sh, const std::map<std::string, Endpoint>& ends,
                        const std::string& path) {
      if (ends.empty() || (ends.size() == 1 && ends.count(""))) return std::string();
      std::string name =
          sh.symbols[size_t(sh.find_symbol(ends.begin()->second.symbol))].struct_name;
      for (size_t dot = path.find('.'); dot != std::string::npos && !name.empty();) {
        size_t next = path.find('.', dot + 1);
        std::string field = path.substr(dot + 1, next == std::string::npos ? next : next - dot - 1);
        const ir::StructType* st = sh.find_struct(name);
        std::string inner;
        for (const ir::StructField& f : st ? st->fields : std::vector<ir::StructField>{})
          if (f.name == field) inner = f.struct_name;
        name = inner;
        dot = next;
      }
      return name;
    };
    auto type_of = [&](const ir::Shader& sh, const std::map<std::string, Endpoint>& ends,
                       const std::string& path) {
      if (ends.empty()) return std::string("unknown");
      if (ends.size() > 1 || !ends.count("")) return "struct " + struct_of(sh, ends, path);
      return osl_type_name(endpoint_type(sh, ends.at("")));
    };
    if (src.empty() || dst.empty()) {
      const bool src_missing = src.empty();
      const std::string& layer = src_missing ? c.src_layer : c.dst_layer;
      const std::string& param = src_missing ? c.src_param : c.dst_param;
      diags.push_back(err("ConnectShaders: \"" + param +
                              "\" is not a parameter or global of layer \"" + layer +
                              "\" (shader \"" + (src_missing ? src_sh : dst_sh).name + "\")",
                          DiagId::connect_param));
      diags.push_back(err("ConnectShaders: cannot connect a " + type_of(src_sh, src, c.src_param) +
                              " (" + c.src_param + ") to a " + type_of(dst_sh, dst, c.dst_param) +
                              " (" + c.dst_param + "), invalid connection",
                          DiagId::connect_param));
      return false;
    }
    // Structs connect only to the same struct type, as in OSL.
    bool fits = src.size() == dst.size() &&
                struct_of(src_sh, src, c.src_param) == struct_of(dst_sh, dst, c.dst_param);
    if (fits && src.size() == 1 && src.count("") && dst.count(""))
      fits = connectable(endpoint_type(src_sh, src.at("")), endpoint_type(dst_sh, dst.at("")));
    if (!fits) {
      diags.push_back(err("ConnectShaders: cannot connect a " + type_of(src_sh, src, c.src_param) +
                              " (" + c.src_param + ") to a " + type_of(dst_sh, dst, c.dst_param) +
                              " (" + c.dst_param + ")",
                          DiagId::connect_type));
      return false;
    }
    for (auto& [suffix, e] : src) {
      auto d = dst.find(suffix);
      if (d == dst.end()) {
        diags.push_back(err("connect: struct field '" + suffix + "' missing in " + c.dst_param,
                            DiagId::connect_param));
        return false;
      }
      if (!connectable(endpoint_type(src_sh, e), endpoint_type(dst_sh, d->second))) {
        diags.push_back(err(
            "ConnectShaders: cannot connect a " + osl_type_name(endpoint_type(src_sh, e)) + " (" +
                c.src_param + suffix + ") to a " + osl_type_name(endpoint_type(dst_sh, d->second)) +
                " (" + c.dst_param + suffix + ")",
            DiagId::connect_type));
        return false;
      }
      links.push_back({si->second, di->second, e, d->second});
    }
  }

  // OSL -O1/-O2 (its opt_merge_instances): a layer identical to an earlier one is merged into
  // it, so that the earlier one runs once where both ran (its printf shows once).
  std::vector<int> merged_into(n, -1); // per layer: the earlier one it was merged into
  if (specialize && merge_instances)
    merged_into =
        merge_identical_layers(group, sources, values, interp, interactive, unlocked, links);

  // Layers the last one depends on, and layers with a renderer output (which run at every
  // shade) with theirs.
  std::vector<bool> needed(n, false), entry(n, false);
  needed[n - 1] = true;
  entry[n - 1] = group.entry_layers.empty();
  // An entry layer's name names the first layer of that name, as OSL's layer look-up.
  auto first_named = [&](const std::string& name) {
    auto it = layer_index.find(name);
    return it == layer_index.end() ? -1 : it->second;
  };
  for (const std::string& e : group.entry_layers)
    if (int i = first_named(e); i >= 0) needed[size_t(i)] = entry[size_t(i)] = true;
  for (size_t i = 0; i + 1 < n && group.entry_layers.empty(); ++i)
    for (const ir::Symbol& s : sources[i]->symbols)
      if (s.kind == ir::SymKind::OutputParam && renderer_reads(group, group.layers[i].name, s.name))
        needed[i] = entry[i] = true;
  // Layers OSL's lazyglobals=0, lazyunconnected=0 or lazyerror=0 runs at every shade (not one
  // merged into another: that one stands for it).
  const bool any_eager = eager.global_writers || eager.unconnected || eager.error_callers;
  for (size_t i = 0; any_eager && i + 1 < n && group.entry_layers.empty(); ++i) {
    if (merged_into[i] >= 0) continue;
    const ir::Shader& sh = *sources[i];
    auto eager_op = [&](const ir::Op& op) {
      if (eager.error_callers && op.opcode == ir::Opcode::Error) return true;
      for (size_t a = 0; eager.global_writers && a < op.args.size() && a < 32; ++a)
        if (op.writes(int(a)) && sh.symbols[size_t(op.args[a])].kind == SymKind::Global)
          return true;
      return false;
    };
    bool unread = eager.unconnected && !needed[i] &&
                  std::none_of(links.begin(), links.end(),
                               [&](const Link& l) { return l.src_layer == int(i); });
    if (unread || std::any_of(sh.ops.begin(), sh.ops.end(), eager_op)) needed[i] = entry[i] = true;
  }
  for (size_t i = n; i-- > 0;)
    for (const Link& l : links)
      if (l.dst_layer == int(i) && needed[i]) needed[size_t(l.src_layer)] = true;

  // Specialise copies of the needed layers.
  std::vector<int> new_index(n, -1);
  std::set<std::string> messages_sent; // constant names set by the layers so far (-O2)
  bool unknown_message_sent = false;
  for (size_t i = 0; i < n; ++i) {
    if (!needed[i]) continue;
    auto sh = std::make_unique<ir::Shader>(*sources[i]);
    drop_misfit_keywords(*sh, diags);
    std::map<std::string, int> len = lengths[i];
    for (const Link& l : links) { // a whole array connected: the source's (already sized) length
      if (l.dst_layer != int(i) || l.dst.elem >= 0 || l.src.elem >= 0) continue;
      const ir::Shader& src = *out.shaders[size_t(new_index[size_t(l.src_layer)])];
      int ss = src.find_symbol(l.src.symbol);
      if (ss >= 0 && src.symbols[size_t(ss)].type.arraylen > 0)
        len[l.dst.symbol] = src.symbols[size_t(ss)].type.arraylen;
    }
    size_unsized_params(*sh, len);
    // OSL answers isconnected() for the connections as made, also those a known value is about
    // to replace at -O2 (whose upstream layer then may not run at all) and those into layers
    // that never run: resolve it now, at every level.
    resolve_isconnected(*sh, int(i), links, interp[i], out.plan.userdata_isconnected, group);
    // OSL -O2: whole connections from outputs of known value become that value.
    if (specialize && elide_known_outputs)
      for (Link& l : links) {
        if (l.dst_layer != int(i) || l.dead || l.src.elem >= 0 || l.src.comp >= 0 ||
            l.dst.elem >= 0 || l.dst.comp >= 0)
          continue;
        // An output the renderer reads (-o) keeps its connection: OSL 1.13.12 runs the upstream
        // layer for it (`--entry D -o out` with U.out -> D.x prints U's printf).
        if (renderer_reads(group, group.layers[size_t(l.src_layer)].name, l.src.symbol)) continue;
        const ir::Shader& src = *out.shaders[size_t(new_index[size_t(l.src_layer)])];
        bool src_runtime = interp[size_t(l.src_layer)].count(l.src.symbol) > 0;
        for (const Link& up : links)
          src_runtime |= !up.dead && up.dst_layer == l.src_layer && up.dst.symbol == l.src.symbol;
        auto given = values[size_t(l.src_layer)].find(l.src.symbol);
        KnownOutput k =
            known_output(src, l.src.symbol, src_runtime,
                         given == values[size_t(l.src_layer)].end() ? nullptr : &given->second);
        int ds = sh->find_symbol(l.dst.symbol);
        if (ds < 0 || (k.value.empty() && k.global.empty())) continue;
        ir::Symbol& dsym = sh->symbols[size_t(ds)];
        if (dsym.kind != SymKind::Param) continue;
        if (!k.value.empty()) {
          const ir::Symbol& ssym = src.symbols[size_t(src.find_symbol(l.src.symbol))];
          std::vector<ir::ConstValue> v = convert_const(k.value, ssym.type, dsym.type);
          if (v.empty()) continue;
          values[i][l.dst.symbol] = v;
          interp[i].erase(l.dst.symbol);
        } else {
          const ir::Symbol& g = src.symbols[size_t(src.find_symbol(k.global))];
          if (g.type.components() != dsym.type.components() || dsym.type.is_array() ||
              !same_kind(g.type, dsym.type))
            continue;
          dsym.kind = SymKind::Global;
          dsym.name = k.global;
          dsym.init.clear();
          dsym.init_begin = dsym.init_end = -1;
          dsym.metadata.clear();
          for (ir::Op& op : sh->ops) // its reads need no fetch now
            if (op.opcode == ir::Opcode::UseParam) {
              op.args.erase(std::remove(op.args.begin(), op.args.end(), ds), op.args.end());
              if (op.args.empty()) op.opcode = ir::Opcode::Nop;
            }
        }
        l.dead = true;
      }
    std::set<std::string> connected;
    for (const Link& l : links)
      if (l.dst_layer == int(i) && !l.dead) connected.insert(l.dst.symbol);
    // User data arrives at run time: those params stay params, as connected ones do.
    std::set<std::string> runtime_valued = connected;
    runtime_valued.insert(interp[i].begin(), interp[i].end());
    // OSL -O2's unconnected outputs: with renderer outputs named (and no entry layers), an
    // output no connection takes downstream and no renderer output names is computed only for
    // what else reads it in its layer.
    if (specialize && elide_known_outputs && !group.renderer_outputs.empty() &&
        group.entry_layers.empty())
      for (ir::Symbol& s : sh->symbols) {
        if (s.kind != SymKind::OutputParam) continue;
        bool read = false;
        for (const Link& l : links) read |= l.src_layer == int(i) && l.src.symbol == s.name;
        s.unread = !read && !renderer_reads(group, group.layers[i].name, s.name);
      }
    // A parameter a connection reads from (an input parameter connected onward) keeps its
    // storage: the downstream layer reads it there, so it does not become a constant. (Whether
    // a downstream layer will replace the connection by a known value is decided later, when
    // that layer is built, so every onward source is kept.)
    std::set<std::string> kept = runtime_valued;
    for (const Link& l : links)
      if (l.src_layer == int(i)) kept.insert(l.src.symbol);
    // An interactive parameter (--reparam may change it) is not folded either, so neither is
    // what it computes: OSL 1.13.12 runs a layer whose output is `x * 2` of an interactive x
    // where it elides the same layer with a plain x.
    kept.insert(interactive[i].begin(), interactive[i].end());
    if (specialize)
      specialize_layer(*sh, values[i], kept, {out.plan.fast_math}, elide_known_outputs);
    if (specialize && elide_known_outputs)
      fold_impossible_getmessages(*sh, messages_sent, unknown_message_sent);
    new_index[i] = int(out.shaders.size());
    out.shaders.push_back(std::move(sh));
    out.layer_names.push_back(group.layers[i].name);
  }

  // Upstream layers that no remaining connection reads are dropped (OSL -O2's unused layers).
  if (std::any_of(links.begin(), links.end(), [](const Link& l) { return l.dead; })) {
    links.erase(std::remove_if(links.begin(), links.end(), [](const Link& l) { return l.dead; }),
                links.end());
    std::vector<bool> alive(n, false);
    for (size_t i = 0; i < n; ++i) alive[i] = needed[i] && (entry[i] || i + 1 == n);
    for (size_t i = n; i-- > 0;)
      for (const Link& l : links)
        if (l.dst_layer == int(i) && alive[i]) alive[size_t(l.src_layer)] = true;
    std::vector<std::unique_ptr<ir::Shader>> kept;
    std::vector<std::string> kept_names;
    for (size_t i = 0; i < n; ++i) {
      if (!needed[i]) continue;
      if (!alive[i]) {
        needed[i] = false;
        new_index[i] = -1;
        continue;
      }
      size_t at = size_t(new_index[i]);
      new_index[i] = int(kept.size());
      kept.push_back(std::move(out.shaders[at]));
      kept_names.push_back(out.layer_names[at]);
    }
    out.shaders = std::move(kept);
    out.layer_names = std::move(kept_names);
    links.erase(std::remove_if(links.begin(), links.end(),
                               [&](const Link& l) { return !needed[size_t(l.dst_layer)]; }),
                links.end());
  }

  // Derivatives, then across connections from the last layer back.
  for (auto& sh : out.shaders) passes::analyze_derivatives(*sh);
  for (size_t i = n; i-- > 0;) {
    if (!needed[i]) continue;
    const ir::Shader& dst = *out.shaders[size_t(new_index[i])];
    for (const Link& l : links) {
      if (l.dst_layer != int(i)) continue;
      int ds = dst.find_symbol(l.dst.symbol);
      ir::Shader& src = *out.shaders[size_t(new_index[size_t(l.src_layer)])];
      int ss = src.find_symbol(l.src.symbol);
      if (ds >= 0 && ss >= 0 && dst.symbols[size_t(ds)].derivs && !src.symbols[size_t(ss)].derivs &&
          src.symbols[size_t(ss)].type.base != ir::BaseType::Int) {
        src.symbols[size_t(ss)].derivs = true;
        extend_derivatives(src);
      }
    }
  }

  // A global with derivative fields (P or I: the writable ones) whose derivatives one layer
  // reads and another writes: the writer carries them, so that its write reaches ShaderGlobals'
  // derivative fields too (OSL's layers share P's derivatives: a displacement layer's P = P * 2
  // doubles Dx(P) and calculatenormal(P) in the layers after it). Once, after the connections:
  // as in OSL 1.13.12, an upstream output the write reads does not get derivatives for it (P +=
  // N * amt with a connected amt = u * 2 leaves Dx(P) 1 0 0).
  std::set<std::string> wanted;
  for (const auto& sh : out.shaders)
    for (const ir::Symbol& s : sh->symbols)
      if (s.kind == SymKind::Global && s.derivs) wanted.insert(s.name);
  for (auto& sh : out.shaders) {
    bool grew = false;
    for (int w : written_symbols(*sh)) {
      ir::Symbol& s = sh->symbols[size_t(w)];
      if (s.kind != SymKind::Global || s.derivs || !wanted.count(s.name)) continue;
      for (const GlobalField& f : kGlobalFields)
        if (f.dx && s.name == f.name) s.derivs = grew = true;
    }
    if (grew) extend_derivatives(*sh);
  }

  // Layout: per layer a ran flag, then each parameter, 8-byte aligned, and each global a
  // connection reads from it (`--connect A P B p`: A's P as A leaves it).
  std::set<std::pair<int, std::string>> global_sources; // (kept layer, global)
  for (const Link& l : links) {
    int src = new_index[size_t(l.src_layer)];
    if (src < 0 || l.dead) continue;
    int si = out.shaders[size_t(src)]->find_symbol(l.src.symbol);
    if (si >= 0 && out.shaders[size_t(src)]->symbols[size_t(si)].kind == SymKind::Global)
      global_sources.insert({src, l.src.symbol});
  }
  size_t off = 0;
  auto align8 = [](size_t x) { return (x + 7) / 8 * 8; };
  for (size_t li = 0; li < out.shaders.size(); ++li) {
    const ir::Shader& sh = *out.shaders[li];
    codegen::LayerPlan lp;
    lp.shader = &sh;
    lp.function_name = "layer_" + std::to_string(li) + "_" + sh.name;
    lp.ran_offset = int(off);
    off += 8;
    lp.layer_name = out.layer_names[li];
    for (const ir::Symbol& s : sh.symbols) {
      bool stored =
          is_param(s) || (s.kind == SymKind::Global && global_sources.count({int(li), s.name}));
      lp.symbol_offset.push_back(stored ? int(off) : -1);
      lp.run_default.push_back(false);
      lp.userdata.push_back(false);
      if (stored) off = align8(off + codegen::storage_bytes(s));
    }
    out.plan.layers.push_back(lp);
  }
  out.plan.loop_count_offset = int(off); // the shade's loop iterations (codegen.h)
  off += 8;
  if (std::string e = check_storage(out.shaders, out.layer_names); !e.empty()) {
    diags.push_back(err(e, DiagId::storage_size));
    return false;
  }
  out.groupdata.assign(off, 0);
  out.plan.group_name = group.name;
  out.plan.explicit_entries = !group.entry_layers.empty();
  for (const std::string& e : group.entry_layers) {
    int i = first_named(e);
    if (i >= 0 && needed[size_t(i)] && new_index[size_t(i)] >= 0 &&
        std::find(out.plan.entry_order.begin(), out.plan.entry_order.end(), new_index[size_t(i)]) ==
            out.plan.entry_order.end())
      out.plan.entry_order.push_back(new_index[size_t(i)]);
  }
  bool uniform = true; // every layer run is uniform (uniform_layer), none takes user data
  for (size_t i = 0; i < n; ++i) {
    if (!needed[i]) continue;
    size_t li = size_t(new_index[i]);
    const ir::Shader& sh = *out.shaders[li];
    codegen::LayerPlan& lp = out.plan.layers[li];
    lp.group_index = int(i);
    lp.entry = entry[i];
    std::set<std::string> connected;
    for (const Link& l : links)
      if (l.dst_layer == int(i)) {
        connected.insert(l.dst.symbol);
        codegen::ConnectionPlan c;
        c.dst_symbol = sh.find_symbol(l.dst.symbol);
        c.dst_element = l.dst.elem;
        c.dst_component = l.dst.comp;
        c.src_layer = new_index[size_t(l.src_layer)];
        c.src_symbol = out.shaders[size_t(c.src_layer)]->find_symbol(l.src.symbol);
        c.src_element = l.src.elem;
        c.src_component = l.src.comp;
        if (c.dst_symbol < 0 || c.src_symbol < 0) continue; // specialised away: never read
        lp.connections.push_back(c);
      }
    for (size_t s = 0; s < sh.symbols.size(); ++s) {
      const ir::Symbol& sym = sh.symbols[s];
      if (!is_param(sym)) continue;
      auto v = values[i].find(sym.name);
      bool has_value = v != values[i].end();
      if (has_value)
        write_value(out.groupdata.data() + lp.symbol_offset[s], sym, v->second, out.plan.env);
      else
        write_value(out.groupdata.data() + lp.symbol_offset[s], sym, sym.init, out.plan.env);
      lp.run_default[s] = !has_value && !connected.count(sym.name) && sym.init_begin >= 0;
      lp.userdata[s] = !connected.count(sym.name) && interp[i].count(sym.name);
      if (sym.kind == SymKind::OutputParam) {
        bool read_down = lp.run_default[s] || renderer_reads(group, group.layers[i].name, sym.name);
        for (const Link& l : links) // connected from, or into
          read_down |= (l.src_layer == int(i) && l.src.symbol == sym.name) ||
                       (l.dst_layer == int(i) && l.dst.symbol == sym.name);
        lp.osl_output_useparam |= read_down;
      }
    }
    const uint64_t layer_globals = globals_mask(sh);
    out.globals_read |= layer_globals;
    uniform = uniform && uniform_layer(sh, layer_globals & ~Material::kReadsRaytype) &&
              std::none_of(lp.userdata.begin(), lp.userdata.end(), [](auto u) { return bool(u); });
  }
  if (uniform) out.globals_read |= Material::kUniform;
  return true;
}

} // namespace lobe::group
