// Implements describe(): the oslinfo -v style interface listing.
#include "ir/query.h"
#include "ir/printer.h"

namespace lobe::ir {

// Values as oslinfo prints them: scalars bare, strings quoted, several values in [ ... ].
static std::string info_values(const Type& t, const std::vector<ConstValue>& v) {
  std::string s = format_values(t, v);
  return v.size() > 1 ? "[ " + s + " ]" : s;
}

static std::string info_metadata(const Metadata& m, const char* indent) {
  return std::string(indent) + "metadata: " + to_string(m.type) + " " + m.name + " = " +
         info_values(m.type, m.value) + "\n";
}

std::string describe(const Shader& sh) {
  std::string out = std::string(to_string(sh.type)) + " " + quote(sh.name) + "\n";
  for (const Metadata& m : sh.metadata) out += info_metadata(m, "    ");
  std::string struct_base; // the struct parameter whose fields are being listed
  for (const Symbol& s : sh.symbols) {
    if (s.kind != SymKind::Param && s.kind != SymKind::OutputParam) continue;
    // A flattened struct parameter: a `"s" "struct S"` line before its first field.
    size_t dot = s.name.find('.');
    std::string base =
        s.struct_name.empty() || dot == std::string::npos ? "" : s.name.substr(0, dot);
    if (!base.empty() && base != struct_base) {
      std::string out_kw = s.kind == SymKind::OutputParam ? "output " : "";
      out += "    " + quote(base) + " " + quote(out_kw + "struct " + s.struct_name) + "\n";
    }
    struct_base = base;
    std::string type = to_string(s.type);
    if (s.kind == SymKind::OutputParam) type = "output " + type;
    out += "    " + quote(s.name) + " " + quote(type) + "\n";
    if (!s.init.empty())
      out += "\t\tDefault value: " + info_values(s.type, s.init) + "\n";
    else if (s.init_begin >= 0)
      out += "\t\tDefault value: (computed at run time)\n";
    else
      out += "\t\tDefault value: (none)\n";
    for (const Metadata& m : s.metadata) out += info_metadata(m, "\t\t");
  }
  return out;
}

} // namespace lobe::ir
