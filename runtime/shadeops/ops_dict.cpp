// Shadeops for data the shader looks up by name: XML dictionaries (dict_find, dict_next,
// dict_value; the documents and node ids live in the ShadingContext, lobe/detail/dictionary.h)
// and point clouds, which Lobe does not provide (every call finds and writes nothing, with one
// warning per ShadingSystem).
#include "env.h"
#include "lobe/context.h"
#include "lobe/detail/dictionary.h"
#include "shadeop_decls.h"
#include "typed_value.h"

#include <cctype>
#include <cstdlib>
#include <cstring>
#include <string>
#include <string_view>

using lobe::ShaderGlobals;
using lobe::shadeops::RuntimeEnv;

namespace {

lobe::detail::Dictionaries* dictionaries(ShaderGlobals* sg) {
  return sg && sg->context ? &sg->context->dictionaries() : nullptr;
}

void report(ShaderGlobals* sg, const std::string& error) {
  if (!error.empty() && sg && sg->context) sg->context->error(error);
}

// Reads `count` numbers of the text at `at` into out[], as OSL's dict_value does with OIIO's
// parse_int/parse_float: each number may be followed by a comma; where the text has no number
// left, the previous number repeats (OSL leaves those entries to chance; the first is 0).
template <class T, class Parse> void parse_numbers(const char* at, int count, T* out, Parse parse) {
  T last = 0;
  for (int i = 0; i < count; ++i) {
    char* end = nullptr;
    T v = parse(at, &end);
    if (end != at) {
      last = v;
      at = end;
      const char* p = at;
      while (std::isspace((unsigned char)*p)) ++p;
      if (*p == ',') at = p + 1;
    }
    out[i] = last;
  }
}

} // namespace

extern "C" {

// dict_find(dictionary, query): the first node matching the XPath query in the XML text or
// .xml file `dict`; 0 if none, -1 if the document does not parse.
int lobe_dict_find(ShaderGlobals* sg, const char* dict, const char* query) {
  lobe::detail::Dictionaries* d = dictionaries(sg);
  if (!d) return 0;
  std::string error;
  int r = d->find(dict ? dict : "", query ? query : "", error);
  report(sg, error);
  return r;
}

// dict_find(node, query): the first match of the query relative to a node.
int lobe_dict_find_node(ShaderGlobals* sg, int node, const char* query) {
  lobe::detail::Dictionaries* d = dictionaries(sg);
  if (!d) return 0;
  std::string error;
  int r = d->find(node, query ? query : "", error);
  report(sg, error);
  return r;
}

int lobe_dict_next(ShaderGlobals* sg, int node) {
  lobe::detail::Dictionaries* d = dictionaries(sg);
  return d ? d->next(node) : 0;
}

// dict_value(node, attribute, dest): the attribute's text (the node's own value for "") into
// dest of type `code`: a string as is; ints and floats (one per component) parsed from it.
// 0 for an invalid node or a missing attribute, leaving dest as it was.
int lobe_dict_value(ShaderGlobals* sg, RuntimeEnv* env, int node, const char* attribute, int code,
                    int derivs, void* dest) {
  using lobe::DataType;
  using namespace lobe::shadeops;
  lobe::detail::Dictionaries* d = dictionaries(sg);
  if (!d || code_base(code) == kClosureBase) return 0;
  std::optional<std::string_view> text = d->value(node, attribute ? attribute : "");
  if (!text) return 0;
  // The text is a view into a NUL-terminated pugixml buffer, so strtol/strtof may read it.
  const char* at = text->data();
  DataType t = code_type(code);
  int count = int(t.bytes() / sizeof(float));
  return fetch_value(env, code, derivs, dest, [&](void* val) {
    if (t.base == DataType::Base::String) {
      std::memcpy(val, &at, sizeof(at)); // interned by fetch_value
      return t.arraylen == 0;
    }
    if (t.base == DataType::Base::Int)
      parse_numbers(at, count, static_cast<int*>(val),
                    [](const char* p, char** end) { return int(std::strtol(p, end, 10)); });
    else
      parse_numbers(at, count, static_cast<float*>(val),
                    [](const char* p, char** end) { return std::strtof(p, end); });
    return true;
  });
}

// pointcloud_search / pointcloud_get / pointcloud_write: Lobe reads and writes no point clouds
// (OSL's come from Partio files), so nothing is found and nothing written; the first call
// warns once for the ShadingSystem.
int lobe_pointcloud(ShaderGlobals* sg, RuntimeEnv* env, const char* function) {
  if (!env->pointcloud_warned.exchange(true) && sg && sg->context)
    sg->context->warning(std::string(function) +
                         ": Lobe has no point clouds: pointcloud_search and pointcloud_get find "
                         "nothing, pointcloud_write writes nothing (reported once)");
  return 0;
}

} // extern "C"
