// Prints the IR text form. Layout (docs/ir.md):
//   lobe-ir 1
//   surface name [[ metadata ]]
//   struct S { float a, color[2] c }  (the struct types of struct parameters, if any)
//   symbols
//     kind type name [= values] [folded] [derivs] [init=B:E] [len=N] [struct=S] [[ metadata ]]
//     [@loc]
//   init                          (only when there are parameter-initialisation ops)
//     opcode args... [-> Ltarget...] [wmask=N] [%infn] [@loc]
//   main
//   L12:                          (a label before each jump target)
//     ...
//   end
#include "ir/printer.h"
#include "ir/opcodes.h"

#include <charconv>
#include <cstdio>
#include <set>

namespace lobe::ir {

std::string format_float(float f) {
  char buf[64];
  auto res = std::to_chars(buf, buf + sizeof buf, f);
  return std::string(buf, res.ptr);
}

std::string quote(const std::string& s) {
  std::string out = "\"";
  for (unsigned char c : s) {
    switch (c) {
    case '"':
      out += "\\\"";
      break;
    case '\\':
      out += "\\\\";
      break;
    case '\n':
      out += "\\n";
      break;
    case '\t':
      out += "\\t";
      break;
    default:
      if (c < 0x20 || c == 0x7f) {
        char buf[8];
        std::snprintf(buf, sizeof buf, "\\x%02x", c);
        out += buf;
      } else {
        out.push_back(char(c));
      }
    }
  }
  out.push_back('"');
  return out;
}

static bool plain_name_char(char c, bool first) {
  bool alpha = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || c == '_' || c == '$';
  if (first) return alpha;
  return alpha || (c >= '0' && c <= '9') || c == '.' || c == '~';
}

std::string format_name(const std::string& s) {
  bool plain = !s.empty();
  for (size_t i = 0; i < s.size() && plain; ++i) plain = plain_name_char(s[i], i == 0);
  return plain ? s : quote(s);
}

std::string format_values(const Type& t, const std::vector<ConstValue>& v) {
  std::string out;
  for (size_t i = 0; i < v.size(); ++i) {
    if (i) out.push_back(' ');
    if (t.base == BaseType::Int)
      out += std::to_string(v[i].i);
    else if (t.base == BaseType::String)
      out += quote(v[i].s);
    else
      out += format_float(v[i].f);
  }
  return out;
}

std::string format_metadata(const std::vector<Metadata>& md) {
  if (md.empty()) return "";
  std::string out = "[[ ";
  for (size_t i = 0; i < md.size(); ++i) {
    if (i) out += ", ";
    out += to_string(md[i].type) + " " + format_name(md[i].name) + " = " +
           format_values(md[i].type, md[i].value);
  }
  return out + " ]]";
}

std::string format_loc(const SourceLoc& loc) {
  if (loc.file.empty() && loc.line == 0 && loc.column == 0) return "";
  std::string file = loc.file;
  // Plain only if the tokenizer reads it back as one word: printable, no quote, backslash or
  // comma (a comma is a token of its own).
  bool plain = true;
  for (unsigned char c : file)
    plain = plain && c > ' ' && c < 0x7f && c != '"' && c != '\\' && c != ',';
  return "@" + (plain ? file : quote(file)) + ":" + std::to_string(loc.line) + ":" +
         std::to_string(loc.column);
}

// Appends " piece" when piece is not empty.
static void append(std::string& line, const std::string& piece) {
  if (piece.empty()) return;
  line.push_back(' ');
  line += piece;
}

static std::string print_symbol(const Symbol& s) {
  std::string line =
      std::string("  ") + to_string(s.kind) + " " + to_string(s.type) + " " + format_name(s.name);
  if (!s.init.empty()) line += " = " + format_values(s.type, s.init);
  if (s.folded) line += " folded";
  if (s.derivs) line += " derivs";
  if (s.init_begin >= 0)
    line += " init=" + std::to_string(s.init_begin) + ":" + std::to_string(s.init_end);
  if (s.default_len > 0) line += " len=" + std::to_string(s.default_len);
  if (!s.struct_name.empty()) { // a quoted name is its own token: `struct= "a b"`
    std::string n = format_name(s.struct_name);
    line += " struct=" + (n[0] == '"' ? " " + n : n);
  }
  append(line, format_metadata(s.metadata));
  append(line, format_loc(s.loc));
  return line;
}

// `struct T { S s, int[2] k }`: a struct-typed field prints its struct's name as its type.
static std::string print_struct(const StructType& st) {
  std::string line = "struct " + format_name(st.name) + " {";
  for (size_t i = 0; i < st.fields.size(); ++i) {
    const StructField& f = st.fields[i];
    std::string type = f.struct_name.empty() ? to_string(f.type)
                                             : format_name(f.struct_name) + array_suffix(f.type);
    line += (i ? ", " : " ") + type + " " + format_name(f.name);
  }
  return line + " }";
}

static std::string sym_name(const Shader& sh, int i) {
  if (i < 0 || i >= int(sh.symbols.size())) return "?" + std::to_string(i);
  return format_name(sh.symbols[i].name);
}

static std::string print_op(const Shader& sh, const Op& op) {
  std::string line = "  " + std::string(to_string(op.opcode));
  for (int a : op.args) line += " " + sym_name(sh, a);
  if (!op.jumps.empty()) {
    line += " ->";
    for (int j : op.jumps) line += " L" + std::to_string(j);
  }
  if (info(op.opcode).written != op.written_mask)
    line += " wmask=" + std::to_string(op.written_mask);
  if (op.in_function) line += " %infn";
  append(line, format_loc(op.loc));
  return line;
}

std::string print(const Shader& sh) {
  std::string out = "lobe-ir 1\n";
  out += std::string(to_string(sh.type)) + " " + format_name(sh.name);
  append(out, format_metadata(sh.metadata));
  out += "\n";
  for (const StructType& st : sh.structs) out += print_struct(st) + "\n";
  out += "symbols\n";
  for (const Symbol& s : sh.symbols) out += print_symbol(s) + "\n";
  std::set<int> targets;
  for (const Op& op : sh.ops) targets.insert(op.jumps.begin(), op.jumps.end());
  int n = int(sh.ops.size());
  for (int i = 0; i <= n; ++i) {
    if (i == 0 && sh.main_begin > 0) out += "init\n";
    if (i == sh.main_begin) out += "main\n";
    if (targets.count(i)) out += "L" + std::to_string(i) + ":\n";
    if (i < n) out += print_op(sh, sh.ops[i]) + "\n";
  }
  if (sh.main_begin > n) out += "main\n";
  return out + "end\n";
}

} // namespace lobe::ir
