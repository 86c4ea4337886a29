// Sema: calls. Resolution order: a struct name makes a constructor; otherwise user functions
// (including the standard header's) and builtins of that name compete by conversion cost, then
// by the expected return type; if none of them exists or fits, the closure registry is tried.
#include "sema/sema_impl.h"

#include "closure_registry.h"

#include <algorithm>
#include <cstring>
#include <map>

namespace lobe::sema {

using ast::Type;

namespace {

std::string tname(const Type& t) { return ast::to_string(t); }

Type type_of(registry::ArgType a) {
  switch (a) {
  case registry::ArgType::Int:
    return t_int();
  case registry::ArgType::Float:
    return t_float();
  case registry::ArgType::Color:
    return t_color();
  case registry::ArgType::Vector:
    return t_vector();
  case registry::ArgType::String:
    return t_string();
  case registry::ArgType::Closure:
    return t_closure();
  }
  return t_error();
}

std::string closure_signature(const registry::ClosureEntry& c) {
  std::string s = std::string("closure color ") + c.name + "(";
  bool first = true;
  for (const auto& p : c.params) {
    if (p.keyword) continue;
    s += (first ? "" : ", ") + tname(type_of(p.type)) + " " + p.name;
    first = false;
  }
  return s + ")";
}

constexpr size_t kMaxCandidateNotes = 12;

// Preference among candidates that tie on argument cost and on the expected return type:
// float, int, then any triple (equal: point, vector and normal, like colour, are not ordered
// against each other, so the table order or an ambiguity decides), matrix, string, the rest.
int return_rank(const Type& t) {
  if (t.is_array()) return 5;
  switch (t.base) {
  case ast::BaseType::Float:
    return 0;
  case ast::BaseType::Int:
    return 1;
  case ast::BaseType::Color:
  case ast::BaseType::Point:
  case ast::BaseType::Vector:
  case ast::BaseType::Normal:
    return 2;
  case ast::BaseType::Matrix:
    return 3;
  case ast::BaseType::String:
    return 4;
  default:
    return 5;
  }
}

} // namespace

std::string Sema::Candidate::signature() const {
  if (builtin) return builtin->signature();
  std::string s = tname(fn->return_type) + " " + fn->name + "(";
  for (size_t i = 0; i < fn->params.size(); ++i) {
    if (i) s += ", ";
    if (fn->params[i]->is_output) s += "output ";
    s += tname(fn->params[i]->type);
  }
  return s + ")";
}

std::string Sema::arg_types(const std::vector<ExprPtr>& args) const {
  std::string s;
  for (size_t i = 0; i < args.size(); ++i) {
    if (i) s += ", ";
    s += args[i]->kind == ast::ExprKind::InitList ? "{...}" : tname(args[i]->type);
  }
  return s;
}

void Sema::call(ast::CallExpr* e, const Type* expected) {
  for (auto& a : e->args)
    if (a->kind != ast::ExprKind::InitList) expr(a);
  e->type = t_error();
  e->num_positional = int(e->args.size());
  std::vector<ast::FunctionDecl*> user = lookup_functions(e->name);
  if (user.empty())
    if (const ast::StructDecl* s = find_struct(e->name)) return struct_constructor(e, s);
  auto sigs = builtins().lookup(e->name);
  bool is_closure = std::any_of(opts_.closures.begin(), opts_.closures.end(),
                                [&](const registry::ClosureEntry& c) { return e->name == c.name; });
  // A [[ builtin = 1 ]] prototype of something the registry or the builtin table provides
  // (old-style headers declare closures that way) defers to the real definition.
  std::erase_if(
      user, [&](ast::FunctionDecl* f) { return f->is_builtin && (is_closure || !sigs.empty()); });
  std::vector<Candidate> all;
  for (auto* f : user) all.push_back({f, nullptr, 0});
  for (const auto& s : sigs) all.push_back({nullptr, &s, 0});
  if (all.empty()) {
    if (is_closure) {
      closure_call(e);
    } else {
      error(lookup_var(e->name) ? DiagId::err_not_a_function : DiagId::err_unknown_function,
            e->name_range, {e->name});
    }
    return;
  }
  for (auto& a : e->args)
    if (a->type.is_error() && a->kind != ast::ExprKind::InitList) return; // already reported
  std::vector<Candidate> viable;
  for (auto& c : all) {
    c.cost = candidate_cost(c, e->args);
    if (c.cost >= 0) viable.push_back(c);
  }
  if (viable.empty()) {
    if (is_closure && closure_call(e)) return;
    report_no_match(e, all, false);
    return;
  }
  int best = std::min_element(viable.begin(), viable.end(), [](auto& a, auto& b) {
               return a.cost < b.cost;
             })->cost;
  std::erase_if(viable, [&](const Candidate& c) { return c.cost != best; });
  // Ties: the return type the context expects decides (`color c = noise(P)`).
  if (viable.size() > 1 && expected) {
    std::vector<Candidate> exact, fits;
    for (auto& c : viable) {
      if (c.ret() == *expected)
        exact.push_back(c);
      else if (assignable(*expected, c.ret()))
        fits.push_back(c);
    }
    if (!exact.empty())
      viable = exact;
    else if (!fits.empty())
      viable = fits;
  }
  // A user function ties with a builtin of the same signature: the user's wins (it overrides).
  if (viable.size() > 1 && std::any_of(viable.begin(), viable.end(), [](auto& c) { return c.fn; }))
    std::erase_if(viable, [](const Candidate& c) { return c.builtin != nullptr; });
  // Still tied (no expected type, or it did not decide): prefer float, then int, then the
  // triples, as OSL does; the builtin table lists float results first for the same reason.
  if (viable.size() > 1) {
    auto rank = [](const Candidate& c) { return return_rank(c.ret()); };
    int best_rank = rank(*std::min_element(viable.begin(), viable.end(),
                                           [&](auto& a, auto& b) { return rank(a) < rank(b); }));
    std::erase_if(viable, [&](const Candidate& c) { return rank(c) != best_rank; });
  }
  bool all_builtin = std::all_of(viable.begin(), viable.end(), [](auto& c) { return c.builtin; });
  if (viable.size() > 1 && !all_builtin) {
    report_no_match(e, viable, true);
    return;
  }
  apply_candidate(e, viable.front()); // builtins: the table's preference order
}

// Total conversion cost of calling `c` with `args`, or -1 if it does not apply.
int Sema::candidate_cost(const Candidate& c, const std::vector<ExprPtr>& args) const {
  std::vector<std::pair<Type, bool>> params; // type, output
  if (c.fn) {
    for (auto& p : c.fn->params) params.push_back({p->type, p->is_output});
  } else {
    for (auto& p : c.builtin->params) params.push_back({p.type, p.output});
    if (c.builtin->any_param) return args.size() == 1 ? 0 : -1;
    if (c.builtin->array_param) return args.size() == 1 && args[0]->type.is_array() ? 0 : -1;
  }
  size_t n = params.size();
  using Extra = BuiltinSig::Extra;
  // A closure the shader declares itself ([[ int builtin = 1 ]]) takes keyword arguments of
  // any name and type after its positional ones, as OSL's renderers register them.
  Extra extra = c.builtin                   ? c.builtin->extra
                : is_declared_closure(c.fn) ? Extra::Keywords
                                            : Extra::None;
  if (args.size() < n || (extra == Extra::None && args.size() != n)) return -1;
  if (extra == Extra::Keywords || extra == Extra::Pairs) {
    if ((args.size() - n) % 2) return -1;
    for (size_t i = n; i < args.size(); i += 2)
      if (args[i]->kind != ast::ExprKind::StringLit) return -1;
  }
  if (extra != Extra::None)
    for (size_t i = n; i < args.size(); ++i)
      if (args[i]->kind == ast::ExprKind::InitList) return -1;
  int cost = 0;
  for (size_t i = 0; i < n; ++i) {
    const ast::Expr* a = args[i].get();
    const auto& [pt, output] = params[i];
    if (a->kind == ast::ExprKind::InitList) {
      if (!init_list_fits(a, pt) || output) return -1;
      continue;
    }
    int k = conversion_cost(a->type, pt, is_zero_literal(a));
    if (k == kNoConversion || (output && k != 0)) return -1;
    cost += k;
  }
  return cost;
}

void Sema::apply_candidate(ast::CallExpr* e, const Candidate& c) {
  size_t n = c.fn ? c.fn->params.size() : c.builtin->params.size();
  for (size_t i = 0; i < n && i < e->args.size(); ++i) {
    bool output = c.fn ? c.fn->params[i]->is_output : c.builtin->params[i].output;
    Type pt = c.fn ? c.fn->params[i]->type : c.builtin->params[i].type;
    if (c.builtin && (c.builtin->any_param || c.builtin->array_param)) break;
    ExprPtr& a = e->args[i];
    if (a->kind == ast::ExprKind::InitList) {
      init_list(a, pt);
    } else if (output) {
      if (!a->lvalue) {
        error(DiagId::err_output_arg_not_lvalue, a->range, {std::to_string(i + 1), e->name});
      } else {
        // A non-output parameter as a builtin's output argument: silent, as in oslc; as a
        // user function's, oslc's warning naming the function.
        check_writable(a.get(), a->range, true);
        ast::VarDecl* v = root_var(a.get());
        if (c.fn && v && v->storage == ast::Storage::FuncParam && !v->is_output &&
            !(v->type.is_array() && a->kind == ast::ExprKind::Index))
          error(DiagId::warn_write_nonoutput_param_arg, a->range,
                {v->name, e->name, std::to_string(i + 1), c.fn->params[i]->name});
      }
    } else {
      coerce(a, pt);
    }
  }
  if (c.fn) {
    e->callee.kind = ast::CalleeKind::User;
    e->callee.function = c.fn;
    e->type = c.fn->return_type;
    if (is_declared_closure(c.fn)) {
      e->num_positional = int(n);
      for (size_t i = n; i + 1 < e->args.size(); i += 2)
        add_keyword(e, static_cast<ast::StringLit*>(e->args[i].get())->value, -1,
                    e->args[i + 1].get());
    }
    user_calls_.push_back(e);
    if (!functions_.empty()) edges_.push_back({functions_.back(), c.fn, e->name_range});
    return;
  }
  e->callee.kind = ast::CalleeKind::Builtin;
  e->callee.builtin = c.builtin;
  e->type = c.builtin->ret;
  check_format_args(e);
  if (c.builtin->extra == BuiltinSig::Extra::Keywords) {
    e->num_positional = int(n);
    for (size_t i = n; i + 1 < e->args.size(); i += 2) {
      auto* name = static_cast<ast::StringLit*>(e->args[i].get());
      check_builtin_keyword(e, name, e->args[i + 1]);
      add_keyword(e, name->value, -1, e->args[i + 1].get());
    }
  }
  if (c.builtin->extra == BuiltinSig::Extra::Pairs) { // any names and types, in order
    e->num_positional = int(n);
    for (size_t i = n; i + 1 < e->args.size(); i += 2) {
      ExprPtr& value = e->args[i + 1];
      if (c.builtin->pairs_written && !value->lvalue)
        error(DiagId::err_output_arg_not_lvalue, value->range, {std::to_string(i + 2), e->name});
      else if (c.builtin->pairs_written)
        check_writable(value.get(), value->range, true);
      e->keywords.push_back(
          {static_cast<ast::StringLit*>(e->args[i].get())->value, -1, value.get()});
    }
  }
}

bool Sema::is_declared_closure(const ast::FunctionDecl* f) {
  return f && f->is_builtin && !f->body && f->return_type.is_closure();
}

// Records a keyword argument; given several times, the last one wins.
void Sema::add_keyword(ast::CallExpr* e, const std::string& name, int param_index,
                       ast::Expr* value) {
  auto it = std::find_if(e->keywords.begin(), e->keywords.end(),
                         [&](const ast::KeywordArg& k) { return k.name == name; });
  if (it != e->keywords.end())
    it->value = value;
  else
    e->keywords.push_back({name, param_index, value});
}

namespace {
// The optional arguments OSL's texture functions and trace() take, with their types. `Float`
// takes an int too; `Output` ones are written (an lvalue of that type).
struct BuiltinKeyword {
  const char* function; // "texture" also covers texture3d and environment
  const char* name;
  ast::BaseType type;
  bool output = false;
  bool or_string = false; // subimage: an index or a name
};
const BuiltinKeyword kBuiltinKeywords[] = {
    {"texture", "blur", ast::BaseType::Float},
    {"texture", "sblur", ast::BaseType::Float},
    {"texture", "tblur", ast::BaseType::Float},
    {"texture", "rblur", ast::BaseType::Float},
    {"texture", "width", ast::BaseType::Float},
    {"texture", "swidth", ast::BaseType::Float},
    {"texture", "twidth", ast::BaseType::Float},
    {"texture", "rwidth", ast::BaseType::Float},
    {"texture", "wrap", ast::BaseType::String},
    {"texture", "swrap", ast::BaseType::String},
    {"texture", "twrap", ast::BaseType::String},
    {"texture", "rwrap", ast::BaseType::String},
    {"texture", "fill", ast::BaseType::Float},
    {"texture", "firstchannel", ast::BaseType::Int},
    {"texture", "subimage", ast::BaseType::Int, false, true},
    {"texture", "interp", ast::BaseType::String},
    {"texture", "missingcolor", ast::BaseType::Color},
    {"texture", "missingalpha", ast::BaseType::Float},
    {"texture", "time", ast::BaseType::Float},
    {"texture", "alpha", ast::BaseType::Float, true},
    {"texture", "errormessage", ast::BaseType::String, true},
    {"trace", "mindist", ast::BaseType::Float},
    {"trace", "maxdist", ast::BaseType::Float},
    {"trace", "shade", ast::BaseType::Int},
    {"trace", "traceset", ast::BaseType::String},
};
} // namespace

// A builtin's `"keyword", value` pair: a keyword it takes, with a value of the right type
// (converted to it), as OSL requires; codegen then reads each value as its type.
void Sema::check_builtin_keyword(ast::CallExpr* e, const ast::StringLit* name, ExprPtr& value) {
  std::string fn = e->name == "trace" ? "trace" : "texture";
  const BuiltinKeyword* k = nullptr;
  for (const BuiltinKeyword& b : kBuiltinKeywords)
    if (fn == b.function && name->value == b.name) k = &b;
  if (!k) {
    error(DiagId::err_unknown_keyword, name->range, {name->value, e->name});
    return;
  }
  Type want{k->type, 0};
  if (k->or_string && value->type == Type{ast::BaseType::String, 0}) return;
  if (k->output) {
    if (!(value->type == want)) {
      error(DiagId::err_keyword_type, value->range,
            {name->value, e->name, tname(want), tname(value->type)});
      return;
    }
    if (!value->lvalue)
      error(DiagId::err_not_assignable, value->range);
    else
      check_writable(value.get(), value->range, true);
    return;
  }
  if (!assignable(want, value->type) || value->type.is_array()) {
    error(DiagId::err_keyword_type, value->range,
          {name->value, e->name, tname(want), tname(value->type)});
    return;
  }
  coerce(value, want);
}

// printf, format, error, warning, fprintf with a literal format string: the arguments must
// match its conversions in number, and in kind as OSL's type checker requires (%d %i %o %x %X
// an int; %f %g %e (and F G E a A) a float, triple or matrix, or an array of them; a string or
// closure only %s; %s prints anything). `%%` is a literal percent sign.
void Sema::check_format_args(ast::CallExpr* e) {
  static const char* const kPrinters[] = {"printf", "format", "error", "warning", "fprintf"};
  if (std::find_if(std::begin(kPrinters), std::end(kPrinters),
                   [&](const char* n) { return e->name == n; }) == std::end(kPrinters))
    return;
  size_t fmt_i = e->name == "fprintf" ? 1 : 0;
  if (e->args.size() <= fmt_i) return;
  auto* lit = ast::as<ast::StringLit>(e->args[fmt_i].get());
  if (!lit) return;
  const std::string& f = lit->value;
  size_t arg = fmt_i + 1, needed = 0;
  bool reported = false;
  for (size_t i = 0; i < f.size(); ++i) {
    if (f[i] != '%') continue;
    if (i + 1 < f.size() && f[i + 1] == '%') {
      ++i;
      continue;
    }
    size_t start = i++;
    while (i < f.size() && std::strchr("0123456789.#-+ lh", f[i])) ++i;
    if (i >= f.size()) break; // a lone '%' at the end prints as itself
    char conv = f[i];
    ++needed;
    if (arg >= e->args.size() || reported) {
      ++arg;
      continue;
    }
    const ast::Expr* a = e->args[arg].get();
    const Type& t = a->type;
    std::string spec = f.substr(start, i + 1 - start);
    // oslc's rules: ints print with %d %i %o %x %X, floats, triples and matrices with %f %g %e,
    // strings and closures with %s; nothing else (no %u, %c, %E, %s of a number).
    bool int_conv = std::strchr("dioxX", conv), float_conv = std::strchr("fge", conv),
         str_conv = conv == 's';
    std::string argno = std::to_string(arg + 1);
    if (t.base == BaseType::Struct) {
      error(DiagId::err_format_struct_arg, a->range, {argno, e->name, tname(t)});
      reported = true;
    } else if (!int_conv && !float_conv && !str_conv) {
      error(DiagId::err_format_conversion, a->range, {spec, e->name});
      reported = true;
    } else if (t.base == BaseType::Int                                     ? !int_conv
               : t.base == BaseType::String || t.base == BaseType::Closure ? !str_conv
                                                                           : !float_conv) {
      const char* need = int_conv     ? "an int"
                         : float_conv ? "a float, triple or matrix"
                                      : "a string or closure";
      error(DiagId::err_format_arg_type, a->range, {spec, need, argno, e->name, tname(t)});
      reported = true;
    }
    ++arg;
  }
  if (reported) return;
  size_t given = e->args.size() - fmt_i - 1;
  if (needed != given)
    error(needed > given ? DiagId::err_format_too_few_args : DiagId::err_format_too_many_args,
          e->range, {e->name, std::to_string(needed), std::to_string(given)});
}

void Sema::report_no_match(ast::CallExpr* e, const std::vector<Candidate>& cands, bool ambiguous) {
  error(ambiguous ? DiagId::err_ambiguous_call : DiagId::err_no_matching_call, e->name_range,
        {e->name, arg_types(e->args)});
  for (size_t i = 0; i < cands.size() && i < kMaxCandidateNotes; ++i) {
    SourceRange where = cands[i].fn ? cands[i].fn->name_range : e->name_range;
    error(DiagId::note_candidate, where, {cands[i].signature()});
  }
  if (cands.size() > kMaxCandidateNotes)
    error(DiagId::note_candidate, e->name_range,
          {"... and " + std::to_string(cands.size() - kMaxCandidateNotes) + " more"});
}

void Sema::struct_constructor(ast::CallExpr* e, const ast::StructDecl* s) {
  e->callee.kind = ast::CalleeKind::StructCtor;
  e->callee.strct = s;
  e->type = Type(ast::BaseType::Struct, 0, s);
  if (e->args.size() != s->fields.size()) {
    error(DiagId::err_struct_ctor_args, e->range,
          {s->name, std::to_string(s->fields.size()), std::to_string(e->args.size())});
    return;
  }
  for (size_t i = 0; i < e->args.size(); ++i) {
    const Type& ft = s->fields[i]->type;
    if (e->args[i]->kind == ast::ExprKind::InitList)
      init_list(e->args[i], ft);
    else
      convert(e->args[i], ft);
  }
}

// A closure call: positional arguments by the registry entry's parameter types (the cheapest
// overload wins), then `"keyword", value` pairs; an unknown keyword is an error and the last
// of duplicated keywords wins.
bool Sema::closure_call(ast::CallExpr* e) {
  const registry::ClosureEntry* best = nullptr;
  int best_cost = 1 << 30;
  std::vector<const registry::ClosureEntry*> entries;
  for (const auto& c : opts_.closures) {
    if (e->name != c.name) continue;
    entries.push_back(&c);
    size_t npos =
        size_t(std::count_if(c.params.begin(), c.params.end(), [](auto& p) { return !p.keyword; }));
    if (e->args.size() < npos || (e->args.size() - npos) % 2) continue;
    int cost = 0;
    for (size_t i = 0; i < npos && cost >= 0; ++i) {
      int k = conversion_cost(e->args[i]->type, type_of(c.params[i].type),
                              is_zero_literal(e->args[i].get()));
      cost = k == kNoConversion ? -1 : cost + k;
    }
    for (size_t i = npos; i < e->args.size() && cost >= 0; i += 2)
      if (!e->args[i]->type.is_string()) cost = -1;
    if (cost >= 0 && cost < best_cost) {
      best = &c;
      best_cost = cost;
    }
  }
  if (!best) {
    error(DiagId::err_no_matching_call, e->name_range, {e->name, arg_types(e->args)});
    for (auto* c : entries) error(DiagId::note_candidate, e->name_range, {closure_signature(*c)});
    return false;
  }
  e->callee.kind = ast::CalleeKind::Closure;
  e->callee.closure = best;
  e->type = t_closure();
  size_t npos = size_t(
      std::count_if(best->params.begin(), best->params.end(), [](auto& p) { return !p.keyword; }));
  e->num_positional = int(npos);
  for (size_t i = 0; i < npos; ++i) coerce(e->args[i], type_of(best->params[i].type));
  for (size_t i = npos; i + 1 < e->args.size(); i += 2) {
    auto* name = ast::as<ast::StringLit>(e->args[i].get());
    if (!name) {
      error(DiagId::err_keyword_name, e->args[i]->range, {e->name});
      continue;
    }
    int index = -1;
    for (size_t p = 0; p < best->params.size(); ++p)
      if (best->params[p].keyword && name->value == best->params[p].name) index = int(p);
    if (index < 0) {
      error(DiagId::err_unknown_keyword, name->range, {name->value, e->name});
      continue;
    }
    ExprPtr& value = e->args[i + 1];
    Type pt = type_of(best->params[size_t(index)].type);
    if (!assignable(pt, value->type)) {
      error(DiagId::err_keyword_type, value->range,
            {name->value, e->name, tname(pt), tname(value->type)});
      continue;
    }
    coerce(value, pt);
    auto it = std::find_if(e->keywords.begin(), e->keywords.end(),
                           [&](const ast::KeywordArg& k) { return k.param_index == index; });
    if (it != e->keywords.end())
      it->value = value.get(); // the last one wins
    else
      e->keywords.push_back({name->value, index, value.get()});
  }
  return true;
}

} // namespace lobe::sema
