// The lowering entry: the shader declaration, its parameters (constant defaults into `init`,
// computed ones into init op ranges), metadata, the body, then the derivative analysis.
#include "lower/literal_default.h"
#include "lower/lowerer.h"

#include "ir/verifier.h"
#include "passes/derivs.h"
#include "passes/optimize.h"

#include <algorithm>
#include <optional>

namespace lobe::lower {

static size_t leaf_count(const ast::Type& t) {
  if (t.base != ast::BaseType::Struct) return 1;
  size_t n = 0;
  for (const auto& f : t.strct->fields) n += leaf_count(f->type);
  return n;
}

// Appends the constant default of each leaf of a (struct) parameter, nullopt for a leaf whose
// part of the default is not constant. `e` null: no leaf is constant.
void Lowerer::const_flat(const ast::Expr* e, const ast::Type& t, std::vector<ConstLeaf>& out) {
  if (t.base != ast::BaseType::Struct) {
    std::vector<ir::ConstValue> v;
    if (e && const_values(e, irtype(t, e), v))
      out.push_back(std::move(v));
    else
      out.push_back(std::nullopt);
    return;
  }
  std::vector<const ast::Expr*> parts;
  if (e && e->kind == ast::ExprKind::InitList)
    for (const auto& x : static_cast<const ast::InitListExpr*>(e)->elems) parts.push_back(x.get());
  else if (e && e->kind == ast::ExprKind::Call &&
           static_cast<const ast::CallExpr*>(e)->callee.kind == ast::CalleeKind::StructCtor)
    for (const auto& x : static_cast<const ast::CallExpr*>(e)->args) parts.push_back(x.get());
  if (t.is_array()) {
    // An array of structs: each leaf holds the elements' fields one after the other.
    bool whole = e && e->kind == ast::ExprKind::InitList && parts.size() == size_t(t.arraylen);
    std::vector<ConstLeaf> flat(leaf_count(t),
                                whole ? ConstLeaf(std::vector<ir::ConstValue>{}) : ConstLeaf());
    for (size_t k = 0; whole && k < parts.size(); ++k) {
      std::vector<ConstLeaf> elem;
      const_flat(parts[k], t.element(), elem);
      for (size_t i = 0; i < elem.size(); ++i)
        if (!elem[i])
          flat[i] = std::nullopt;
        else if (flat[i])
          flat[i]->insert(flat[i]->end(), elem[i]->begin(), elem[i]->end());
    }
    out.insert(out.end(), flat.begin(), flat.end());
    return;
  }
  const auto& fields = t.strct->fields;
  // A shorter list leaves its last fields zero (oslc's defaults: `S s = {1}` is 1 and 0); a
  // constructor call must name them all.
  bool shorter = e && e->kind == ast::ExprKind::InitList && parts.size() < fields.size();
  if (parts.size() != fields.size() && !shorter) parts.assign(fields.size(), nullptr);
  for (size_t i = 0; i < fields.size(); ++i) {
    if (i < parts.size())
      const_flat(parts[i], fields[i]->type, out);
    else
      zero_flat(fields[i]->type, out);
  }
}

// Appends a zero default for each leaf of `t` (a field a shorter list leaves out); an array of
// structs has no such default here (its leaves stay unknown).
void Lowerer::zero_flat(const ast::Type& t, std::vector<ConstLeaf>& out) {
  if (t.base == ast::BaseType::Struct) {
    if (t.is_array()) {
      out.insert(out.end(), leaf_count(t), ConstLeaf());
      return;
    }
    for (const auto& f : t.strct->fields) zero_flat(f->type, out);
    return;
  }
  ir::Type it = irtype(t, nullptr);
  out.push_back(std::vector<ir::ConstValue>(size_t(it.components() * std::max(1, it.arraylen))));
}

// Adds struct `s` (after the structs its fields use) to the shader's struct table.
void Lowerer::record_struct(const ast::StructDecl* s) {
  if (sh_.find_struct(s->name)) return;
  ir::StructType st{s->name, {}};
  for (const auto& f : s->fields) {
    ir::StructField field{f->name, {}, ""};
    if (f->type.base == ast::BaseType::Struct) {
      record_struct(f->type.strct);
      field.struct_name = f->type.strct->name;
      field.type.arraylen = f->type.arraylen;
    } else {
      field.type = irtype(f->type, f.get());
    }
    st.fields.push_back(std::move(field));
  }
  sh_.structs.push_back(std::move(st));
}

static ir::ShaderType shader_type(ast::ShaderType t) {
  switch (t) {
  case ast::ShaderType::Surface:
    return ir::ShaderType::Surface;
  case ast::ShaderType::Displacement:
    return ir::ShaderType::Displacement;
  case ast::ShaderType::Volume:
    return ir::ShaderType::Volume;
  case ast::ShaderType::Shader:
    return ir::ShaderType::Shader;
  }
  return ir::ShaderType::Shader;
}

// The shader's constants and parameter defaults with -0 read as +0, as OSL's do: oslc writes
// them to its .oso, and a constant or default of -0 comes back from it as 0 (`printf("%g",
// -0.0)` prints 0 in OSL 1.13.12). A -0 computed while shading, or folded by the runtime's
// optimiser, stays -0.
static void positive_zeros(ir::Shader& sh) {
  for (ir::Symbol& s : sh.symbols) {
    bool constant = s.kind == ir::SymKind::Const || s.kind == ir::SymKind::Param ||
                    s.kind == ir::SymKind::OutputParam;
    bool floats = s.type.base == ir::BaseType::Float || s.type.is_triple() ||
                  s.type.base == ir::BaseType::Matrix;
    if (!constant || !floats) continue;
    for (ir::ConstValue& c : s.init)
      if (c.f == 0.0f) c.f = 0.0f;
  }
}

LowerResult Lowerer::run() {
  LowerResult res;
  const ast::ShaderDecl* sd = tu_.shader();
  if (!sd) {
    error(nullptr, diag::DiagId::err_lower_no_shader);
    return res;
  }
  sh_.type = shader_type(sd->shader_type);
  sh_.useparams = true; // emit() announces the reads of params
  sh_.name = sd->name;
  auto metadata = [&](const ast::Metadata& md) {
    std::vector<ir::Metadata> out;
    for (const ast::MetadataItem& m : md) {
      ir::Metadata x{irtype(m.type, nullptr), m.name, {}};
      if (!m.value || !const_values(m.value.get(), x.type, x.value))
        error(m.value.get(), diag::DiagId::err_lower_metadata_not_const, {m.name});
      out.push_back(std::move(x));
    }
    return out;
  };
  sh_.metadata = metadata(sd->metadata);
  for (const auto& p : sd->params) {
    std::vector<int> syms =
        declare(p.get(), p->is_output ? ir::SymKind::OutputParam : ir::SymKind::Param);
    std::vector<ir::Metadata> md = metadata(p->metadata);
    for (int s : syms) sh_.symbols[size_t(s)].metadata = md;
    if (p->type.base == ast::BaseType::Struct) record_struct(p->type.strct);
    if (!p->init) continue;
    // The leaves with a constant default get it; `folded` where oslc would compute it.
    std::vector<ConstLeaf> values;
    const_flat(p->init.get(), p->type, values);
    std::vector<bool> literal = literal_default_leaves(p->init.get(), p->type);
    bool all_const = values.size() == syms.size();
    for (size_t i = 0; i < syms.size() && i < values.size(); ++i) {
      ir::Symbol& sym = sh_.symbols[size_t(syms[i])];
      all_const &= values[i].has_value();
      if (!values[i]) continue;
      sym.init = *values[i];
      sym.folded = i >= literal.size() || !literal[i];
    }
    if (all_const) continue;
    // Each other symbol gets an init range of its own (the fields of a struct parameter may
    // get values independently): the default is evaluated once per field, the other fields'
    // parts going to temporaries.
    for (size_t i = 0; i < syms.size(); ++i) {
      if (!sh_.symbols[size_t(syms[i])].init.empty()) continue;
      int begin = here();
      std::vector<LRef> dst;
      for (size_t j = 0; j < syms.size(); ++j)
        dst.push_back(LRef{j == i ? syms[j] : temp(sh_.symbols[size_t(syms[j])].type)});
      store_init(dst, p->type, p->init.get());
      sh_.symbols[size_t(syms[i])].init_begin = begin;
      sh_.symbols[size_t(syms[i])].init_end = here();
    }
    // An unsized array keeps `T[]`; the length of its computed default goes beside it.
    if (p->type.is_unsized_array() && p->type.base != ast::BaseType::Struct && syms.size() == 1)
      sh_.symbols[size_t(syms[0])].default_len = std::max(0, p->init->type.arraylen);
  }
  sh_.main_begin = here();
  stmt(sd->body.get());
  if (errors_ > 0) return res;
  if (opt_.optimize) passes::optimize(sh_, {.math = {opt_.fast_math}});
  positive_zeros(sh_);
  passes::analyze_derivatives(sh_);
  for (const std::string& e : ir::verify(sh_)) {
    where_ = nullptr;
    error(nullptr, diag::DiagId::err_lower_invalid_ir, {e});
  }
  if (errors_ == 0) res.shader = std::move(sh_);
  return res;
}

LowerResult lower(const ast::TranslationUnit& tu, diag::DiagnosticEngine& diags,
                  const LowerOptions& options) {
  return Lowerer(tu, diags, options).run();
}

} // namespace lobe::lower
