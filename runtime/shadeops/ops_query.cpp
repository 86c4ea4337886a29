// Shadeops that move typed values between a shader and the world around it: getattribute,
// user data and trace (answered by the renderer's RendererServices), and
// setmessage/getmessage between the layers of one shade (the ShadingContext's MessageStore).
// Types and values as typed_value.h describes them.
#include "env.h"
#include "lobe/context.h"
#include "lobe/detail/messages.h"
#include "lobe/renderer_services.h"
#include "shadeop_decls.h"
#include "typed_value.h"

#include <algorithm>
#include <climits>
#include <cstring>
#include <initializer_list>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace {

using lobe::shadeops::code_arraylen;
using lobe::shadeops::code_base;
using lobe::shadeops::code_type;
using lobe::shadeops::fetch_value;
using lobe::shadeops::kClosureBase;
using lobe::shadeops::plane_bytes;

std::string type_name(int code) {
  if (code_base(code) == kClosureBase) {
    std::string s = "closure color";
    if (code_arraylen(code) > 0) {
      s += "[";
      s += std::to_string(code_arraylen(code));
      s += "]";
    }
    return s;
  }
  return code_type(code).str();
}

std::string where(const char* file, int line) {
  std::string s = file ? file : "";
  s += ":";
  s += std::to_string(line);
  return s;
}

// A run-time error through the context: the pieces, joined.
void report(lobe::ShaderGlobals* sg, std::initializer_list<std::string_view> pieces) {
  if (!sg || !sg->context) return;
  std::string text;
  for (std::string_view p : pieces) text += p;
  sg->context->error(text);
}

bool builtin_attribute(std::string_view name, int code, void* dest, lobe::shadeops::RuntimeEnv* env,
                       const char* shadername, const char* layername, const char* groupname,
                       int& found) {
  // The shader:* names are answered only for a name known when the shader compiles (null
  // names otherwise, as in OSL, which folds them then): a name computed at run time goes to
  // the renderer.
  const char* text = nullptr;
  if (name == "shader:shadername")
    text = shadername;
  else if (name == "shader:layername")
    text = layername;
  else if (name == "shader:groupname")
    text = groupname;
  else if (name != "osl:version")
    return false;
  if (!text && name != "osl:version") return false;
  found = 0;
  if (text) {
    if (code != int(lobe::DataType::Base::String)) return true;
    const char* s = env->strings.intern(text);
    std::memcpy(dest, &s, sizeof(s));
  } else {
    if (code != int(lobe::DataType::Base::Int)) return true;
    int32_t v = 11312; // OSL_VERSION of the language Lobe accepts (1.13.12, the reference)
    std::memcpy(dest, &v, sizeof(v));
  }
  found = 1;
  return true;
}

// getmessage("trace", name, dest) after a trace(): "hit" (int, also when it missed), and when
// it hit "hitdist", "u", "v" (float), "P", "N", "Ng" (any triple). Derivatives are zero.
int trace_message(const lobe::TraceHit& h, std::string_view name, int code, int derivs,
                  void* dest) {
  if (!h.traced) return 0;
  size_t plane = plane_bytes(code);
  auto put = [&](const float* v, int n) {
    std::memcpy(dest, v, size_t(n) * sizeof(float));
    if (derivs) std::memset(static_cast<unsigned char*>(dest) + plane, 0, 2 * plane);
    return 1;
  };
  bool is_float = code == int(lobe::DataType::Base::Float);
  bool is_triple = code_arraylen(code) == 0 && code_base(code) >= 2 && code_base(code) <= 5;
  if (name == "hit" && code == int(lobe::DataType::Base::Int)) {
    int32_t v = h.hit ? 1 : 0;
    std::memcpy(dest, &v, sizeof(v));
    return 1;
  }
  if (!h.hit) return 0;
  if (is_float && name == "hitdist") return put(&h.hitdist, 1);
  if (is_float && name == "u") return put(&h.u, 1);
  if (is_float && name == "v") return put(&h.v, 1);
  if (is_triple && name == "P") return put(&h.P.x, 3);
  if (is_triple && name == "N") return put(&h.N.x, 3);
  if (is_triple && name == "Ng") return put(&h.Ng.x, 3);
  return 0;
}

} // namespace

extern "C" {

// trace(P, R, "mindist", a, "maxdist", b, "shade", s, "traceset", t): the renderer's ray
// (1 on a hit); its result stays in the context for getmessage("trace", ...). Without a
// renderer nothing is hit, as in OSL's testshade.
int lobe_trace(lobe::ShaderGlobals* sg, const float* p, const float* dpdx, const float* dpdy,
               const float* r, const float* drdx, const float* drdy,
               const lobe::TraceOptions* opt) {
  if (!sg || !sg->context) return 0;
  const lobe::RendererServices* rs = sg->context->renderer;
  auto v3 = [](const float* f) { return lobe::Vec3{f[0], f[1], f[2]}; };
  lobe::TraceHit h;
  h.hit = rs && rs->trace(*sg, *opt, v3(p), v3(dpdx), v3(dpdy), v3(r), v3(drdx), v3(drdy), h);
  h.traced = true;
  sg->context->trace_hit = h;
  return h.hit ? 1 : 0;
}

// raytype(name) for a name known only per shade (a constant one is folded by codegen).
int lobe_raytype_bit(const char* name) {
  static const std::pair<const char*, int> kNames[] = {
      {"camera", lobe::kRayCamera},         {"shadow", lobe::kRayShadow},
      {"reflection", lobe::kRayReflection}, {"refraction", lobe::kRayRefraction},
      {"diffuse", lobe::kRayDiffuse},       {"glossy", lobe::kRayGlossy},
      {"subsurface", lobe::kRaySubsurface}, {"displacement", lobe::kRayDisplacement}};
  for (const auto& [n, bit] : kNames)
    if (name && std::strcmp(name, n) == 0) return bit;
  return 0;
}

// getattribute([object,] name, [index,] dest): OSL's own attributes first, then the renderer.
// `object` is null when the shader named none; `index` is INT_MIN when it gave no index. Returns 1
// when `dest` was written.
int lobe_getattribute(lobe::ShaderGlobals* sg, lobe::shadeops::RuntimeEnv* env, const char* object,
                      const char* name, int index, int code, int derivs, void* dest,
                      const char* shadername, const char* layername, const char* groupname) {
  std::string_view obj = object ? object : "", nm = name ? name : "";
  // Codegen passes INT_MIN for "no index"; an index the shader gave is never negative.
  if (index == INT_MIN)
    index = -1;
  else if (index < 0)
    return 0;
  int found = 0; // OSL answers its own attributes whatever object is named
  if (builtin_attribute(nm, code, dest, env, shadername, layername, groupname, found)) return found;
  if (!sg || !sg->context || !sg->context->renderer || code_base(code) == kClosureBase) return 0;
  const lobe::RendererServices* rs = sg->context->renderer;
  return fetch_value(env, code, derivs, dest, [&](void* val) {
    return rs->get_attribute(*sg, obj, nm, index, code_type(code), derivs != 0, val);
  });
}

// The user data bound to a `lockgeom = 0` parameter, when its layer starts.
int lobe_get_userdata(lobe::ShaderGlobals* sg, lobe::shadeops::RuntimeEnv* env, const char* name,
                      int code, int derivs, void* dest) {
  if (!sg || !sg->context || !sg->context->renderer || code_base(code) == kClosureBase) return 0;
  const lobe::RendererServices* rs = sg->context->renderer;
  return fetch_value(env, code, derivs, dest, [&](void* val) {
    return rs->get_userdata(*sg, name ? name : "", code_type(code), derivs != 0, val);
  });
}

// setmessage(name, value). A name can be set once per shade; setting one that an earlier
// getmessage already asked for is an error too (the answer would depend on the layer order).
// Both errors keep what the store had and name both places, in OSL's words. `layer` is the
// layer's index in the group, for getmessage's check that messages only flow downstream.
void lobe_setmessage(lobe::ShaderGlobals* sg, const char* name, int code, const void* src,
                     const char* file, int line, int layer) {
  if (!sg || !sg->context || !name) return;
  lobe::detail::MessageStore& store = sg->context->messages();
  if (lobe::detail::MessageStore::Entry* e = store.find(name)) {
    if (e->set)
      report(sg, {"message \"", name, "\" already exists (created here: ", where(e->file, e->line),
                  ") cannot set again from ", where(file, line)});
    else
      report(sg, {"message \"", name,
                  "\" was queried before being set (queried here: ", where(e->file, e->line),
                  ") setting it now (", where(file, line), ") would lead to inconsistent results"});
    return;
  }
  size_t bytes = plane_bytes(code); // as OSL: the value only, no derivatives
  lobe::detail::MessageStore::Entry e;
  e.name = name;
  e.type = code;
  e.set = true;
  e.offset = uint32_t(store.data.size());
  e.file = file;
  e.line = line;
  e.layer = layer;
  store.data.insert(store.data.end(), static_cast<const unsigned char*>(src),
                    static_cast<const unsigned char*>(src) + bytes);
  store.entries.push_back(e);
}

// getmessage([source,] name, dest): 1 and `dest` written when this shade set `name` with a
// value of exactly the destination's type (a color is not a vector, as in OSL); another type
// is an error. Source "trace" asks the renderer (RendererServices::trace_message), else reads
// the last trace() (trace_message); any other source is ignored, as OSL ignores it.
int lobe_getmessage(lobe::ShaderGlobals* sg, lobe::shadeops::RuntimeEnv* env, const char* source,
                    const char* name, int code, int derivs, void* dest, const char* file, int line,
                    int layer) {
  if (!sg || !sg->context || !name) return 0;
  if (source && std::string_view(source) == "trace") {
    const lobe::RendererServices* rs = sg->context->renderer;
    if (code_base(code) == kClosureBase) return 0;
    if (std::optional<bool> r =
            rs ? rs->trace_message(*sg, name, code_type(code), derivs != 0, dest) : std::nullopt) {
      lobe::shadeops::intern_strings(env, code, dest);
      return *r ? 1 : 0;
    }
    return trace_message(sg->context->trace_hit, name, code, derivs, dest);
  }
  lobe::detail::MessageStore& store = sg->context->messages();
  lobe::detail::MessageStore::Entry* e = store.find(name);
  if (!e) { // remembered, so that setting it later in this shade is reported
    lobe::detail::MessageStore::Entry q;
    q.name = name;
    q.type = code;
    q.file = file;
    q.line = line;
    q.layer = layer;
    store.entries.push_back(q);
    return 0;
  }
  if (e->set && e->layer > layer) { // a later layer ran first (lazily) and set it
    // Layers numbered as OSL numbers them here, by their shader instance's id, which testshade
    // starts at 2 for a group's first layer (OSL 1.13.12 prints #3 and #2 for layers 1 and 0).
    constexpr int kOslFirstInstanceId = 2;
    report(sg, {"message \"", name, "\" was set by layer #",
                std::to_string(e->layer + kOslFirstInstanceId), " (", where(e->file, e->line),
                ") but is being queried by layer #", std::to_string(layer + kOslFirstInstanceId),
                " (", where(file, line),
                ") - messages may only be transferred from nodes that appear earlier in the "
                "shading network"});
    return 0;
  }
  if (e->type != code) {
    report(sg, {"type mismatch for message \"", name, "\" (", e->set ? "created" : "queried",
                " as ", type_name(e->type), " here: ", where(e->file, e->line),
                ") cannot fetch as ", type_name(code), " from ", where(file, line)});
    return 0;
  }
  if (!e->set) return 0;
  size_t plane = plane_bytes(code);
  const unsigned char* data = store.data.data() + e->offset;
  std::memcpy(dest, data, plane);
  if (derivs) std::memset(static_cast<unsigned char*>(dest) + plane, 0, 2 * plane);
  return 1;
}

} // extern "C"
