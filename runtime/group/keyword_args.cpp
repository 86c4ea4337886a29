// Dropping the keyword arguments a call does not take (see keyword_args.h).
#include "keyword_args.h"

#include "closure_registry.h"
#include "group_build.h"
#include "ir/opcodes.h"
#include "public_diag.h"

#include <algorithm>
#include <cstdint>
#include <string>

namespace lobe::group {
namespace {

Diagnostic dropped(const std::string& msg, diag::DiagId id) {
  return runtime_diag(id, msg, diag::Severity::Warning);
}

// "(x.osl:3)", the op's place as OSL's messages give it.
std::string place(const ir::Op& op) {
  return "(" + op.loc.file + ":" + std::to_string(op.loc.line) + ")";
}

// The keyword of operand `a` (a constant string), or "" when it is not one.
std::string keyword(const ir::Shader& sh, const ir::Op& op, size_t a) {
  const std::string* kw = ir::string_value(sh.symbols[size_t(op.args[a])]);
  return kw ? *kw : std::string();
}

// The `"keyword", value` operands [i, i + 1] taken out of `op` (the written bits above them move
// down with them).
void erase_pair(ir::Op& op, size_t i) {
  op.args.erase(op.args.begin() + std::ptrdiff_t(i), op.args.begin() + std::ptrdiff_t(i) + 2);
  uint32_t low = i >= 32 ? op.written_mask : op.written_mask & ((1u << i) - 1);
  uint32_t high = i + 2 >= 32 ? 0 : op.written_mask >> (i + 2);
  op.written_mask = low | (i >= 32 ? 0 : high << i);
}

// Whether a value of type `t` converts to a closure parameter of type `a` (OSL's assignment:
// a float takes an int, a triple any triple or a number).
bool fits_closure_param(registry::ArgType a, const ir::Type& t) {
  using B = ir::BaseType;
  if (t.is_array()) return false;
  bool number = t.base == B::Int || t.base == B::Float;
  switch (a) {
  case registry::ArgType::Int:
    return t.base == B::Int;
  case registry::ArgType::Float:
    return number;
  case registry::ArgType::Color:
  case registry::ArgType::Vector:
    return number || t.is_triple();
  case registry::ArgType::String:
    return t.base == B::String;
  case registry::ArgType::Closure:
    return t.base == B::Closure;
  }
  return false;
}

void drop_texture_options(ir::Shader& sh, ir::Op& op, DiagnosticList& diags) {
  for (size_t i = ir::first_texture_option(sh, op); i + 1 < op.args.size();) {
    std::string kw = keyword(sh, op, i);
    const ir::Type& t = sh.symbols[size_t(op.args[i + 1])].type;
    const ir::KeywordOption* o = ir::texture_option(kw);
    if (o && ir::option_fits(*o, t, i + 1 < 32 && op.writes(int(i + 1)))) {
      i += 2;
      continue;
    }
    diags.push_back(dropped(
        std::string("Unknown ") + (op.opcode == ir::Opcode::Texture3d ? "texture3d" : "texture") +
            " optional argument: \"" + kw + "\", <" + osl_type_name(t) + "> " + place(op),
        diag::DiagId::builtin_option));
    erase_pair(op, i);
  }
}

// Where the `"keyword", value` options of a noise op by name (noise("gabor", P, ...)) begin: the
// first string operand after the name and coordinates; op.args.size() for none (or no name).
size_t noise_options(const ir::Shader& sh, const ir::Op& op) {
  bool noise = op.opcode == ir::Opcode::Noise || op.opcode == ir::Opcode::PNoise ||
               op.opcode == ir::Opcode::SNoise || op.opcode == ir::Opcode::PSNoise;
  auto is_string = [&](size_t a) {
    return sh.symbols[size_t(op.args[a])].type.base == ir::BaseType::String;
  };
  if (!noise || op.args.size() < 3 || !is_string(1)) return op.args.size();
  size_t i = 2;
  while (i < op.args.size() && !is_string(i)) ++i;
  return i;
}

// The options from operand `first` on (noise_options).
void drop_noise_options(ir::Shader& sh, ir::Op& op, size_t first, DiagnosticList& diags) {
  // A constant name other than "gabor" takes no options: OSL ignores them without a word.
  const std::string* kind = ir::string_value(sh.symbols[size_t(op.args[1])]);
  for (size_t i = first; i + 1 < op.args.size();) {
    std::string kw = keyword(sh, op, i);
    const ir::Type& t = sh.symbols[size_t(op.args[i + 1])].type;
    const ir::KeywordOption* o = ir::gabor_option(kw);
    if (o && ir::option_fits(*o, t, false)) {
      i += 2;
      continue;
    }
    if (!kind || *kind == "gabor")
      diags.push_back(dropped("Unknown " + std::string(ir::info(op.opcode).name) +
                                  " optional argument: \"" + kw + "\", <" + osl_type_name(t) +
                                  "> " + place(op),
                              diag::DiagId::builtin_option));
    erase_pair(op, i);
  }
}

void drop_closure_keywords(ir::Shader& sh, ir::Op& op, DiagnosticList& diags) {
  const std::string* key = ir::string_value(sh.symbols[size_t(op.args[1])]);
  const registry::ClosureEntry* entry = key ? registry::find_by_key(*key) : nullptr;
  if (!entry) return;
  size_t i = 2; // after the result and the key: the positional arguments, then the pairs
  for (const registry::ClosureParam& p : entry->params) i += p.keyword ? 0 : 1;
  while (i + 1 < op.args.size()) {
    std::string kw = keyword(sh, op, i);
    const ir::Type& t = sh.symbols[size_t(op.args[i + 1])].type;
    auto p =
        std::find_if(entry->params.begin(), entry->params.end(),
                     [&](const registry::ClosureParam& q) { return q.keyword && kw == q.name; });
    if (p != entry->params.end() && fits_closure_param(p->type, t)) {
      i += 2;
      continue;
    }
    diags.push_back(dropped("Unsupported closure keyword arg \"" + kw + "\" for " +
                                std::string(entry->name) + " " + place(op),
                            diag::DiagId::closure_keyword));
    erase_pair(op, i);
  }
}

} // namespace

void drop_misfit_keywords(ir::Shader& sh, DiagnosticList& diags) {
  for (ir::Op& op : sh.ops) {
    if (op.opcode == ir::Opcode::Texture || op.opcode == ir::Opcode::Texture3d ||
        op.opcode == ir::Opcode::Environment)
      drop_texture_options(sh, op, diags);
    else if (size_t first = noise_options(sh, op); first < op.args.size())
      drop_noise_options(sh, op, first, diags);
    else if (op.opcode == ir::Opcode::Closure && op.args.size() > 1)
      drop_closure_keywords(sh, op, diags);
  }
}

} // namespace lobe::group
