// Implements describe(): oslinfo's verbose and plain listings (query.h). The layout rules are
// OSL 1.13's oslinfo.cpp as measured against it; the comments say which quirk each rule keeps.
#include "ir/query.h"

#include <cstdio>
#include <set>

namespace lobe::ir {
namespace {

// A type as OSL's TypeDesc names it, which oslinfo prints: a closure is a `pointer`.
std::string type_name(const Type& t) {
  if (t.base == BaseType::Closure) return "pointer" + array_suffix(t);
  return to_string(t);
}

// " v v v": each value after a space; numbers as iostream prints them (%d, %g).
std::string values(const Type& t, const std::vector<ConstValue>& v) {
  std::string out;
  for (const ConstValue& c : v) {
    char buf[32];
    if (t.base == BaseType::String) {
      out += " " + c_quote(c.s);
      continue;
    }
    if (t.base == BaseType::Int)
      std::snprintf(buf, sizeof buf, " %d", c.i);
    else
      std::snprintf(buf, sizeof buf, " %g", double(c.f));
    out += buf;
  }
  return out;
}

class Lister {
public:
  Lister(const Shader& sh, const DescribeOptions& o) : sh_(sh), o_(o) {}
  std::string run();

private:
  bool wanted(const std::string& name) const { return o_.param.empty() || o_.param == name; }
  void entry(const std::string& name, const std::string& type, bool output);
  void struct_headers(const Symbol& s);
  void struct_header(const std::string& path, const StructType* st, int arraylen,
                     const Symbol& leaf);
  void fields(const std::string& path, const StructType& st);
  void param(const Symbol& s);
  void unknown() { out_ += o_.verbose ? "\t\tUnknown default value\n" : "nodefault\n"; }
  void metadata(const std::vector<Metadata>& md);

  const Shader& sh_;
  const DescribeOptions& o_;
  std::string out_;
  std::set<std::string> announced_; // struct params and nested structs already listed
};

// Verbose: `    "name" "type"` on a line of its own; plain: `type name ` and the value follows.
void Lister::entry(const std::string& name, const std::string& type, bool output) {
  std::string t = (output ? "output " : "") + type;
  if (o_.verbose)
    out_ += "    \"" + name + "\" \"" + t + "\"\n";
  else
    out_ += t + " " + name + " ";
}

// Before a flattened field `st.s.a`: the struct param `st` and the nested struct `st.s`, each
// the first time one of its fields comes.
void Lister::struct_headers(const Symbol& s) {
  size_t dot = s.name.find('.');
  if (s.struct_name.empty() || dot == std::string::npos) return;
  std::string path = s.name.substr(0, dot);
  const StructType* st = sh_.find_struct(s.struct_name);
  int arraylen = 0;
  while (true) {
    if (announced_.insert(path).second) struct_header(path, st, arraylen, s);
    size_t next = s.name.find('.', dot + 1);
    if (!st || next == std::string::npos) return;
    std::string field = s.name.substr(dot + 1, next - dot - 1);
    const StructField* f = nullptr;
    for (const StructField& x : st->fields)
      if (x.name == field) f = &x;
    if (!f || f->struct_name.empty()) return;
    path += "." + field;
    arraylen = f->type.arraylen;
    st = sh_.find_struct(f->struct_name);
    dot = next;
  }
}

// `st` is null for IR text without the struct table: the header then has no fields line.
void Lister::struct_header(const std::string& path, const StructType* st, int arraylen,
                           const Symbol& leaf) {
  if (!wanted(path)) return;
  bool output = leaf.kind == SymKind::OutputParam;
  if (arraylen != 0) {
    // A nested array of structs: the .oso gives it no struct hint, so oslinfo shows an
    // unknown type with an unknown default.
    entry(path, "unknown" + array_suffix(Type{BaseType::Float, arraylen}), output);
    unknown();
  } else {
    entry(path, "struct " + (st ? st->name : leaf.struct_name), output);
    if (st)
      fields(path, *st);
    else if (!o_.verbose)
      out_ += "\n";
  }
  if (o_.verbose) metadata(leaf.metadata);
}

// `fields: {float a, unknown s}`: each field with the type of its flattened param (a nested
// struct's is unknown to oslinfo).
void Lister::fields(const std::string& path, const StructType& st) {
  out_ += o_.verbose ? "\t\tfields: {" : "fields: {";
  for (size_t i = 0; i < st.fields.size(); ++i) {
    const StructField& f = st.fields[i];
    std::string type = "unknown" + array_suffix(f.type);
    if (f.struct_name.empty()) {
      int k = sh_.find_symbol(path + "." + f.name);
      type = type_name(k >= 0 ? sh_.symbols[size_t(k)].type : f.type);
    }
    out_ += (i ? ", " : "") + type + " " + f.name;
  }
  out_ += "}\n";
}

void Lister::param(const Symbol& s) {
  if (!wanted(s.name)) return;
  entry(s.name, type_name(s.type), s.kind == SymKind::OutputParam);
  // No default and no init ops: an unsized array defaulting to `{}`, which oslc writes as one
  // element of zeros.
  std::vector<ConstValue> init = s.init;
  if (init.empty() && s.init_begin < 0) init.resize(size_t(s.type.components()));
  if (init.empty() || s.folded || s.type.base == BaseType::Closure) {
    unknown();
  } else if (s.type.base == BaseType::String) {
    // One line per element when verbose; the plain list ends with a space.
    for (const ConstValue& v : init)
      out_ += o_.verbose ? "\t\tDefault value: " + c_quote(v.s) + "\n" : c_quote(v.s) + " ";
    if (!o_.verbose) out_ += "\n";
  } else {
    // oslc writes -0.0 as "-0", which its reader takes for the integer 0.
    for (ConstValue& c : init)
      if (c.f == 0.0f) c.f = 0.0f;
    std::string text = values(s.type, init);
    if (s.type.is_array() || s.type.components() > 1) text = " [" + text + " ]";
    out_ += (o_.verbose ? "\t\tDefault value:" : "") + text + "\n";
  }
  if (o_.verbose) metadata(s.metadata);
}

// Metadata values without brackets, whatever their count.
void Lister::metadata(const std::vector<Metadata>& md) {
  for (const Metadata& m : md)
    out_ +=
        "\t\tmetadata: " + to_string(m.type) + " " + m.name + " =" + values(m.type, m.value) + "\n";
}

std::string Lister::run() {
  if (o_.param.empty()) {
    out_ = std::string(to_string(sh_.type)) + " \"" + sh_.name + "\"\n";
    if (o_.verbose) metadata(sh_.metadata);
  }
  for (const Symbol& s : sh_.symbols) {
    if (s.kind != SymKind::Param && s.kind != SymKind::OutputParam) continue;
    struct_headers(s);
    param(s);
  }
  return out_;
}

} // namespace

std::string describe(const Shader& shader, const DescribeOptions& options) {
  return Lister(shader, options).run();
}

std::string oslquery_params(const Shader& shader) {
  std::string out;
  std::set<std::string> announced;
  for (const Symbol& s : shader.symbols) {
    if (s.kind != SymKind::Param && s.kind != SymKind::OutputParam) continue;
    std::string output = s.kind == SymKind::OutputParam ? "output " : "";
    if (!s.struct_name.empty()) // each enclosing struct, outermost first
      for (size_t dot = s.name.find('.'); dot != std::string::npos; dot = s.name.find('.', dot + 1))
        if (announced.insert(s.name.substr(0, dot)).second)
          out += "\t" + output + "unknown " + s.name.substr(0, dot) + "\n";
    out += "\t" + output + type_name(s.type) + " " + s.name + "\n";
  }
  return out;
}

std::string c_quote(const std::string& s) {
  std::string out = "\"";
  for (char c : s) {
    const char* e = nullptr;
    switch (c) {
    case '\\':
      e = "\\\\";
      break;
    case '"':
      e = "\\\"";
      break;
    case '\n':
      e = "\\n";
      break;
    case '\t':
      e = "\\t";
      break;
    case '\v':
      e = "\\v";
      break;
    case '\b':
      e = "\\b";
      break;
    case '\r':
      e = "\\r";
      break;
    case '\f':
      e = "\\f";
      break;
    case '\a':
      e = "\\a";
      break;
    default:
      break;
    }
    if (e)
      out += e;
    else
      out.push_back(c);
  }
  return out + "\"";
}

} // namespace lobe::ir
