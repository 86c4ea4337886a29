// Matching a call to the registry's closures: the one resolution shared by the compiler's type
// checker (compiler/sema/sema_call.cpp, a call in a shader) and `lobe brdf`'s closure
// expressions (runtime/closures/verify/closure_expr.cpp, a call with literal arguments).
//
// It decides which entry of that name a call binds to (the cheapest whose positional arguments
// all convert; the first among equals), where the positional arguments end, and which keyword
// parameter each `"name", value` pair after them sets. Converting and storing the values, and
// the wording of errors, stay with the caller: an AST expression and a literal convert
// differently, and each front end words its diagnostics its own way.
#pragma once

#include "closure_registry.h"

#include <functional>
#include <optional>
#include <span>
#include <string_view>
#include <vector>

namespace lobe::registry {

inline constexpr int kNoFit = -1; // CallArgs::cost of an argument that cannot take the type

// What the matcher asks of a call's arguments (the caller answers from its own representation).
struct CallArgs {
  size_t count = 0;
  // Cost of converting argument i to a parameter of type t (0: as it is; lower is better), or
  // kNoFit.
  std::function<int(size_t i, ArgType t)> cost;
  // Argument i is a string (a keyword's name must be).
  std::function<bool(size_t i)> is_string;
  // Argument i's text when it is a string literal (a keyword name is looked up by it).
  std::function<std::optional<std::string_view>(size_t i)> literal;
};

inline constexpr int kUnknownKeyword = -1; // KeywordArg::param: no keyword of that name
inline constexpr int kNameNotLiteral = -2; // KeywordArg::param: the name is not a literal

// One `"name", value` pair: arguments name_arg and name_arg + 1.
struct KeywordArg {
  size_t name_arg = 0;
  int param = kUnknownKeyword; // index into the entry's params, or one of the two above
};

// Why no entry of the name fits: the first problem, in argument order, of the entry that got
// furthest through the arguments.
enum class CallProblem {
  None,
  UnknownClosure,      // no entry has the name
  TooFewArguments,     // fewer arguments than positional parameters (arg: count)
  ArgumentType,        // argument `arg` cannot become positional parameter `arg`
  KeywordName,         // argument `arg`, after the positional ones, is not a string
  KeywordWithoutValue, // the last keyword name has no value (arg: count)
};

struct ClosureMatch {
  const ClosureEntry* entry = nullptr; // the chosen entry; null when none fits
  size_t positional = 0;               // arguments [0, positional) set params [0, positional)
  std::vector<KeywordArg> keywords;    // the pairs after them, in call order (a later pair for
                                       // the same parameter wins)
  std::vector<const ClosureEntry*> candidates; // every entry of the name, in table order
  CallProblem problem = CallProblem::None;     // when !entry
  size_t problem_arg = 0;                      // the argument the problem concerns
  const ClosureEntry* problem_entry = nullptr; // the entry it was found against
};

// The number of positional (non-keyword) parameters: they come first in `params`.
size_t positional_count(const ClosureEntry& e);

// Matches a call of `name` with `args` against `entries` (the registry's closures()).
ClosureMatch match_closure_call(std::span<const ClosureEntry> entries, std::string_view name,
                                const CallArgs& args);

} // namespace lobe::registry
