// Sema: calls. Resolution order: a struct name makes a constructor; otherwise the user functions
// (including the standard header's) and builtins of that name in sight compete as oslc ranks
// them (overload.h); if none of them exists or fits, the closure registry is tried.
#include "sema/sema_impl.h"

#include "closure_call.h"
#include "closure_registry.h"
#include "ir/ir.h"

#include <algorithm>
#include <cstring>
#include <map>
#include <optional>

namespace lobe::sema {

using ast::Type;

namespace {

// The builtins that take a format string and its arguments.
bool is_printer(const std::string& name) {
  return name == "printf" || name == "format" || name == "error" || name == "warning" ||
         name == "fprintf";
}

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

// A builtin's wildcard parameters (printf's `...`, texture's keyword pairs, isconnected's
// any-type argument) match anything, each argument scoring less than any real conversion
// (oslc's exact weights are not observable; they only rank a user function that shadows a
// varargs builtin, and any value below 23 ranks it the same).
constexpr int kWildcardScore = 1;

bool is_literal(const ast::Expr* e) {
  return e->kind == ast::ExprKind::IntLit || e->kind == ast::ExprKind::FloatLit ||
         e->kind == ast::ExprKind::StringLit;
}

// An `output` argument is written back as it is: it must hold the parameter's kind of value
// (any triple for a triple, as oslc allows), not one a conversion would reach (int -> float).
bool same_representation(const Type& formal, const Type& actual) {
  if (formal.is_array() != actual.is_array()) return false;
  auto triple = [](ast::BaseType b) {
    return b == ast::BaseType::Color || b == ast::BaseType::Point || b == ast::BaseType::Vector ||
           b == ast::BaseType::Normal;
  };
  if (triple(formal.base) && triple(actual.base)) return true;
  return formal.base == actual.base && formal.strct == actual.strct;
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

SourceRange Sema::Candidate::where() const {
  return fn ? fn->name_range : SourceRange(); // builtins print without a location
}

std::string Sema::arg_types(const std::vector<ExprPtr>& args) const {
  std::string s;
  for (size_t i = 0; i < args.size(); ++i) {
    if (i) s += ", ";
    s += args[i]->kind == ast::ExprKind::InitList ? "{...}" : tname(args[i]->type);
  }
  return s;
}

// The overloads of `name` a call here can see, newest declaration first (oslc's order): the
// user functions (lookup_functions; the standard header's are the oldest globals), then, unless
// a nested declaration hides them, the builtin table's, in table order, less those a user
// function redefines. A [[ builtin = 1 ]] prototype of something the table or the registry
// provides defers to it.
std::vector<Sema::Candidate> Sema::overloads(const std::string& name, bool is_closure) {
  bool nested = false;
  std::vector<ast::FunctionDecl*> user = lookup_functions(name, &nested);
  auto sigs = nested ? std::span<const BuiltinSig>() : builtins().lookup(name);
  std::erase_if(
      user, [&](ast::FunctionDecl* f) { return f->is_builtin && (is_closure || !sigs.empty()); });
  std::vector<Candidate> chain;
  for (auto* f : user) chain.push_back({f, nullptr, 0});
  for (const auto& b : sigs)
    if (std::none_of(user.begin(), user.end(), [&](auto* f) { return redefines(f, b); }))
      chain.push_back({nullptr, &b, 0});
  return chain;
}

void Sema::call(ast::CallExpr* e, const Type* expected) {
  e->type = t_error();
  e->num_positional = int(e->args.size());
  if (lookup_functions(e->name).empty())
    if (const ast::StructDecl* s = find_struct(e->name)) return struct_constructor(e, s);
  // oslc types every argument with the call's own expected type, not the parameter's: it
  // decides ties inside (`color c = g(noise(P))` takes the color noise).
  // oslc checks argument i of a call i + 1 times, printing a warning inside it as often
  // (counted for `lobe shade`'s oslc-style output; nested calls multiply).
  int repeat = diags_.oslc_repeat();
  for (size_t i = 0; i < e->args.size(); ++i) {
    diags_.set_oslc_repeat(repeat * int(i + 1));
    if (e->args[i]->kind != ast::ExprKind::InitList) expr(e->args[i], expected);
  }
  diags_.set_oslc_repeat(repeat);
  bool is_closure = std::any_of(opts_.closures.begin(), opts_.closures.end(),
                                [&](const registry::ClosureEntry& c) { return e->name == c.name; });
  std::vector<Candidate> chain = overloads(e->name, is_closure);
  if (chain.empty()) {
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
  resolve(e, chain, expected, is_closure);
}

// Scores the candidates and binds the one oslc would choose (overload.h), with its warning
// or error when the choice was a tie.
void Sema::resolve(ast::CallExpr* e, std::vector<Candidate>& chain, const Type* expected,
                   bool is_closure) {
  std::vector<int> scores;
  std::vector<Type> returns;
  for (auto& c : chain) {
    c.score = candidate_score(c, e->args);
    scores.push_back(c.score);
    returns.push_back(c.ret());
  }
  OverloadChoice choice = choose_overload(scores, returns, expected);
  using Kind = OverloadChoice::Kind;
  if (choice.kind == Kind::NoMatch) {
    if (is_closure && closure_call(e)) return;
    report_no_match(e, chain);
    return;
  }
  if (choice.kind == Kind::ByRank || choice.kind == Kind::StructTie)
    report_ambiguous(e, chain, choice);
  if (choice.kind != Kind::StructTie) apply_candidate(e, chain[choice.chosen]);
}

// The sum of the argument scores of calling `c` with `args` (match_score), or kNotViable.
int Sema::candidate_score(const Candidate& c, const std::vector<ExprPtr>& args) const {
  std::vector<std::pair<Type, bool>> params; // type, output
  if (c.fn) {
    for (auto& p : c.fn->params) params.push_back({p->type, p->is_output});
  } else {
    for (auto& p : c.builtin->params) params.push_back({p.type, p.output});
    if (c.builtin->any_param) return args.size() == 1 ? kWildcardScore : kNotViable;
    if (c.builtin->array_param)
      return args.size() == 1 && args[0]->type.is_array() ? kWildcardScore : kNotViable;
  }
  size_t n = params.size();
  using Extra = BuiltinSig::Extra;
  // A closure the shader declares itself ([[ int builtin = 1 ]]) takes keyword arguments of
  // any name and type after its positional ones, as OSL's renderers register them.
  Extra extra = c.builtin                   ? c.builtin->extra
                : is_declared_closure(c.fn) ? Extra::Keywords
                                            : Extra::None;
  if (args.size() < n || (extra == Extra::None && args.size() != n)) return kNotViable;
  if (extra == Extra::Keywords || extra == Extra::Pairs) {
    if ((args.size() - n) % 2) return kNotViable;
    for (size_t i = n; i < args.size(); i += 2)
      if (args[i]->kind != ast::ExprKind::StringLit) return kNotViable;
  }
  for (size_t i = n; i < args.size(); ++i)
    if (args[i]->kind == ast::ExprKind::InitList) return kNotViable;
  int score = int(args.size() - n) * kWildcardScore;
  for (size_t i = 0; i < n; ++i) {
    const ast::Expr* a = args[i].get();
    const auto& [pt, output] = params[i];
    // A `{...}` argument takes the parameter's type when it fits (an array or a struct), and
    // is no place for an output.
    bool fits = a->kind == ast::ExprKind::InitList && !output && init_list_fits(a, pt);
    int s =
        a->kind == ast::ExprKind::InitList ? (fits ? kExactMatch : 0) : match_score(pt, a->type);
    if (s == 0) return kNotViable;
    score += s;
  }
  return score;
}

// Binds the chosen candidate: converts the arguments to the parameter types and checks the
// `output` ones, which are scored like the others and only then must be values of the
// parameter's kind (as in oslc: `int x` for `output float` is an error, not a reason to pick
// another overload).
void Sema::apply_candidate(ast::CallExpr* e, const Candidate& c) {
  size_t n = c.fn ? c.fn->params.size() : c.builtin->params.size();
  for (size_t i = 0; i < n && i < e->args.size(); ++i) {
    bool output = c.fn ? c.fn->params[i]->is_output : c.builtin->params[i].output;
    Type pt = c.fn ? c.fn->params[i]->type : c.builtin->params[i].type;
    if (c.builtin && (c.builtin->any_param || c.builtin->array_param)) break;
    ExprPtr& a = e->args[i];
    if (a->kind == ast::ExprKind::InitList)
      init_list(a, pt);
    else if (output)
      check_output_arg(e, i, pt, c.fn);
    else
      coerce(a, pt);
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

// Argument i of `e` for an `output` parameter of type `pt`. A value that is not a variable
// (`x + 1`) is accepted, as oslc accepts it (the function writes a temporary); a literal is not.
// A function's non-output parameter as a builtin's output argument is silent, as in oslc; as a
// user function's (`fn`), it is oslc's warning naming the function. A shader's input parameter
// there is oslc's error (check_writable), for builtins too (`sincos(0.5, p, c)`).
void Sema::check_output_arg(ast::CallExpr* e, size_t i, const Type& pt,
                            const ast::FunctionDecl* fn) {
  ExprPtr& a = e->args[i];
  std::string argno = std::to_string(i + 1);
  if (is_literal(a.get())) {
    error(DiagId::err_output_arg_not_lvalue, a->range, {argno, e->name});
  } else if (!same_representation(pt, a->type)) {
    error(DiagId::err_output_arg_type, a->range, {tname(a->type), argno, e->name, tname(pt)});
  } else if (a->lvalue) {
    check_writable(a.get(), a->range, /*output_arg=*/true);
    ast::VarDecl* v = root_var(a.get());
    auto* ix = ast::as<ast::IndexExpr>(a.get());
    bool element = ix && ix->base->type.is_array();
    bool readonly = v && ((v->storage == ast::Storage::FuncParam && !v->is_output) ||
                          (v->storage == ast::Storage::Global && !v->writable));
    if (fn && readonly && !element)
      error(DiagId::warn_write_nonoutput_param_arg, a->range,
            {v->name, e->name, argno, fn->params[i]->name});
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
// The optional arguments trace() takes, with their types (`Float` takes an int too); texture's
// and gabor noise's are the IR's (ir::texture_option, ir::gabor_option).
struct TraceKeyword {
  const char* name;
  ast::BaseType type;
};
const TraceKeyword kTraceKeywords[] = {
    {"mindist", ast::BaseType::Float},
    {"maxdist", ast::BaseType::Float},
    {"shade", ast::BaseType::Int},
    {"traceset", ast::BaseType::String},
};

// The base types the AST and the IR share.
constexpr std::pair<ast::BaseType, ir::BaseType> kBases[] = {
    {ast::BaseType::Int, ir::BaseType::Int},         {ast::BaseType::Float, ir::BaseType::Float},
    {ast::BaseType::Color, ir::BaseType::Color},     {ast::BaseType::Point, ir::BaseType::Point},
    {ast::BaseType::Vector, ir::BaseType::Vector},   {ast::BaseType::Normal, ir::BaseType::Normal},
    {ast::BaseType::Matrix, ir::BaseType::Matrix},   {ast::BaseType::String, ir::BaseType::String},
    {ast::BaseType::Closure, ir::BaseType::Closure},
};

// A value's type as the IR's, for ir::option_fits; none for a struct, void or an error.
std::optional<ir::Type> ir_type(const Type& t) {
  for (const auto& [a, i] : kBases)
    if (t.base == a) return ir::Type{i, t.arraylen};
  return std::nullopt;
}

ast::BaseType ast_base(ir::BaseType b) {
  for (const auto& [a, i] : kBases)
    if (b == i) return a;
  return ast::BaseType::Error;
}
} // namespace

// A builtin's `"keyword", value` pair. trace() takes its keywords, each with a value of its
// type (converted to it), as OSL requires. texture(), texture3d(), environment() and noise()
// take any pair of a value, as oslc does: one that fits its option is converted to the option's
// type, and one that does not (an unknown name, another type) is kept as written for the group
// builder, which drops it with OSL's message when the shader is set up (ir::option_fits).
void Sema::check_builtin_keyword(ast::CallExpr* e, const ast::StringLit* name, ExprPtr& value) {
  if (e->name != "trace") {
    std::optional<ir::Type> t = ir_type(value->type);
    if (!t) { // no value to pass (void), or a struct: not even oslc keeps it
      if (!value->type.is_error())
        error(DiagId::err_keyword_type, value->range,
              {name->value, e->name, "a value", tname(value->type)});
      return;
    }
    bool noise = e->name == "noise" || e->name == "pnoise";
    const ir::KeywordOption* o =
        noise ? ir::gabor_option(name->value) : ir::texture_option(name->value);
    if (o && o->output && !value->lvalue && !t->is_array() &&
        ast_base(o->type) == value->type.base) {
      error(DiagId::err_not_assignable, value->range); // written: as oslc, not a constant
      return;
    }
    if (!o || !ir::option_fits(*o, *t, value->lvalue)) return;
    if (o->output)
      check_writable(value.get(), value->range, /*output_arg=*/true);
    else if (!(o->or_string && value->type.base == ast::BaseType::String))
      coerce(value, Type{ast_base(o->type), 0});
    return;
  }
  const TraceKeyword* k = nullptr;
  for (const TraceKeyword& b : kTraceKeywords)
    if (name->value == b.name) k = &b;
  if (!k) {
    error(DiagId::err_unknown_keyword, name->range, {name->value, e->name});
    return;
  }
  Type want{k->type, 0};
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
  if (!is_printer(e->name)) return;
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
    while (i < f.size() && std::strchr("0123456789.#-+ lhLjztq", f[i])) ++i;
    if (i >= f.size()) { // a spec the string ends in ("100%") still wants its argument (oslc)
      ++needed;
      break;
    }
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

// No candidate applies: every overload in sight, newest first.
void Sema::report_no_match(ast::CallExpr* e, const std::vector<Candidate>& chain) {
  error(DiagId::err_no_matching_call, e->name_range, {e->name, arg_types(e->args)});
  std::vector<size_t> all(chain.size());
  for (size_t i = 0; i < all.size(); ++i) all[i] = i;
  note_candidates(e, chain, all, DiagId::note_candidate);
}

// A tie the return ranks decided (a warning: the chosen one, then the others), or one they
// cannot decide because several candidates return structs (an error listing them all).
void Sema::report_ambiguous(ast::CallExpr* e, const std::vector<Candidate>& chain,
                            const OverloadChoice& choice) {
  bool structs = choice.kind == OverloadChoice::Kind::StructTie;
  // oslc resolves a call again each time it checks it (see call()) only when a built-in is
  // among the candidates; a choice among user functions alone it keeps, and warns once
  // (OSL 1.13.12: printf("%g %g\n", 1.0, r(0)) with two user r(float) warns once, with a user
  // noise(float) beside the built-ins three times).
  bool builtin = std::any_of(chain.begin(), chain.end(), [](const Candidate& c) {
    return c.builtin || (c.fn && c.fn->from_stdlib);
  });
  int repeat = diags_.oslc_repeat();
  if (!builtin) diags_.set_oslc_repeat(1);
  error(structs ? DiagId::err_ambiguous_call : DiagId::warn_ambiguous_call, e->name_range,
        {e->name, arg_types(e->args)});
  if (!structs) {
    const Candidate& c = chain[choice.chosen];
    error(DiagId::note_chosen_candidate, c.where(), {c.signature()});
  }
  note_candidates(e, chain, choice.others,
                  structs ? DiagId::note_candidate : DiagId::note_other_candidate);
  diags_.set_oslc_repeat(repeat);
}

// Notes for the candidates `which` (indices into `chain`), at most kMaxCandidateNotes.
void Sema::note_candidates(ast::CallExpr* e, const std::vector<Candidate>& chain,
                           const std::vector<size_t>& which, DiagId note) {
  for (size_t k = 0; k < which.size() && k < kMaxCandidateNotes; ++k)
    error(note, chain[which[k]].where(), {chain[which[k]].signature()});
  if (which.size() > kMaxCandidateNotes)
    error(note, e->name_range,
          {"... and " + std::to_string(which.size() - kMaxCandidateNotes) + " more"});
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
  // Each argument is typed expecting its field's type (as oslc does: `S(f(), f())` takes the
  // overloads of f returning the two fields' types).
  for (size_t i = 0; i < e->args.size(); ++i) {
    const Type& ft = s->fields[i]->type;
    if (e->args[i]->kind == ast::ExprKind::InitList) {
      init_list(e->args[i], ft);
    } else {
      expr(e->args[i], &ft);
      convert(e->args[i], ft);
    }
  }
}

// A closure call: the registry's entry of that name it binds to (registry/closure_call.h: the
// cheapest whose positional arguments convert), its positional arguments converted to the
// parameter types, then `"keyword", value` pairs; the last of duplicated keywords wins, and an
// unknown keyword or a value of another type is kept for the group builder (parameter index -1),
// which drops it with OSL's warning.
bool Sema::closure_call(ast::CallExpr* e) {
  registry::CallArgs args;
  args.count = e->args.size();
  args.cost = [&](size_t i, registry::ArgType t) {
    int k = conversion_cost(e->args[i]->type, type_of(t), is_zero_literal(e->args[i].get()));
    return k == kNoConversion ? registry::kNoFit : k;
  };
  args.is_string = [&](size_t i) { return e->args[i]->type.is_string(); };
  args.literal = [&](size_t i) -> std::optional<std::string_view> {
    if (auto* s = ast::as<ast::StringLit>(e->args[i].get())) return s->value;
    return std::nullopt;
  };
  registry::ClosureMatch m = registry::match_closure_call(opts_.closures, e->name, args);
  if (!m.entry) {
    error(DiagId::err_no_matching_call, e->name_range, {e->name, arg_types(e->args)});
    for (auto* c : m.candidates)
      error(DiagId::note_candidate, e->name_range, {closure_signature(*c)});
    return false;
  }
  const registry::ClosureEntry* best = m.entry;
  e->callee.kind = ast::CalleeKind::Closure;
  e->callee.closure = best;
  e->type = t_closure();
  e->num_positional = int(m.positional);
  for (size_t i = 0; i < m.positional; ++i) coerce(e->args[i], type_of(best->params[i].type));
  for (const registry::KeywordArg& kw : m.keywords) {
    if (kw.param == registry::kNameNotLiteral) {
      error(DiagId::err_keyword_name, e->args[kw.name_arg]->range, {e->name});
      continue;
    }
    auto* name = static_cast<ast::StringLit*>(e->args[kw.name_arg].get());
    ExprPtr& value = e->args[kw.name_arg + 1];
    // A keyword the closure does not take, or a value of another type: kept as written, as oslc
    // keeps it; the group builder drops it with OSL's warning when the shader is set up.
    if (!ir_type(value->type)) { // no value to pass (void), or a struct
      if (!value->type.is_error())
        error(DiagId::err_keyword_type, value->range,
              {name->value, e->name, "a value", tname(value->type)});
      continue;
    }
    if (kw.param == registry::kUnknownKeyword ||
        !assignable(type_of(best->params[size_t(kw.param)].type), value->type)) {
      e->keywords.push_back({name->value, -1, value.get()});
      continue;
    }
    Type pt = type_of(best->params[size_t(kw.param)].type);
    coerce(value, pt);
    auto it = std::find_if(e->keywords.begin(), e->keywords.end(),
                           [&](const ast::KeywordArg& k) { return k.param_index == kw.param; });
    if (it != e->keywords.end())
      it->value = value.get(); // the last one wins
    else
      e->keywords.push_back({name->value, kw.param, value.get()});
  }
  return true;
}

} // namespace lobe::sema
