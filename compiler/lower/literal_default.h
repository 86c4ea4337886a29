// Which leaves of a shader parameter's default oslc writes into the .oso as literal values; it
// computes the others with init code (marked %initexpr), and OSL's query tools (oslinfo,
// OSLQuery) then report "Unknown default value". Lobe folds more than oslc (`float(3)`,
// `2 * 3.5`, `-color(1)`, struct constructors, array fields of structs): lowering marks such
// params ir::Symbol::folded so that `lobe info` reports what oslinfo reports.
//
// oslc 1.13's rules, as measured (docs/ir.md, "Lowering"):
//   - a literal is an int, float or string literal, `-x` or `+x` of a number literal, or a
//     binary operator on two literals of the same type, which oslc's parser folds (ints:
//     + - * / % << >> & | ^ and comparisons; floats: + - * / and comparisons);
//   - an int takes an int literal, a float an int or float literal, a string a string literal;
//   - a triple or matrix takes a number literal, or a constructor of its own type from 1 or
//     3 (16) number literals, without a space name;
//   - an array takes `{...}` of elements that each qualify;
//   - a struct takes `{...}` with one element per field: a struct field recurses, an array
//     field never qualifies, nor does any field of a struct constructor `S(...)`;
//   - a closure never does.
#pragma once

#include "ast/ast.h"

#include <vector>

namespace lobe::lower {

// One entry per leaf of `type`, in the order of Lowerer::leaves (depth first, field order):
// whether oslc writes that leaf's default `init` as literals.
std::vector<bool> literal_default_leaves(const ast::Expr* init, const ast::Type& type);

} // namespace lobe::lower
