// OSL's printf/format: C printf conversions applied to shader values. A triple or matrix
// argument prints each component with the same conversion, separated by spaces; an array
// prints each element likewise; `%s` of a closure prints its tree (RuntimeEnv::closure_printer).
//
// Arguments arrive as a type-code string (one code per argument: i int, f float, t triple,
// m matrix, s string, c closure; an array adds its length in braces, "f{3}") and an array of
// pointers to the values.
#pragma once

#include "env.h"

#include <string>
#include <string_view>

namespace lobe::shadeops {

// Whose conversions: OSL's printf (C's, but a string left-aligned in its width); its format()
// as run while shading (a string right-aligned as in C, a float's exact tie at the precision
// rounded away from zero and the # flag ignored: OSL 1.13.12 prints format("%.1f %.0f %#.0f",
// x, y, z) of varying 0.25, 2.5 and 1.5 as "0.3 3 2", testshade -g 1 1); or its format() folded
// by its optimizer, all arguments constant (C's, a string right-aligned: "0.2 2 2.").
enum class FormatRule { Printf, Format, FormatFolded };
// format()'s type codes start with one of these, naming the rule (codegen's op_printf).
inline constexpr char kFormatRuntimeCode = 'R', kFormatFoldedCode = 'F';

std::string format_values(const RuntimeEnv& env, std::string_view fmt, std::string_view codes,
                          const void* const* args, FormatRule rule = FormatRule::Printf);
// The same text, appended to `out` (which a caller may reuse to keep its capacity).
void append_formatted(std::string& out, const RuntimeEnv& env, std::string_view fmt,
                      std::string_view codes, const void* const* args,
                      FormatRule rule = FormatRule::Printf);

// The same text interned in env.strings (format(); `codes` may start with a rule's code). Formats
// of up to kMemoInts int arguments
// ("tile_%d_%d") are remembered per thread, one per slot of a table indexed by the format's
// address and the values, checked against the format's text, the values and the table
// (StringTable::serial), so that asking again returns the interned string without formatting.
inline constexpr int kMemoInts = 4;
const char* format_interned(RuntimeEnv& env, const char* fmt, const char* codes,
                            const void* const* args);

} // namespace lobe::shadeops
