// The diagnostic table. Columns: id, name (for tests), severity, message template.
// Entries are in enum order; diag_test checks that every id maps to its own row.
#include "diag/diag_ids.h"

namespace lobe::diag {
namespace {

struct Row {
  DiagId id;
  const char* name;
  DiagInfo info;
};
#define ROW(ID, SEV, FMT)                                                                          \
  {                                                                                                \
    DiagId::ID, #ID, { DiagId::ID, Severity::SEV, FMT }                                            \
  }

const Row kTable[] = {
    ROW(err_file_not_found, Error, "cannot open file '%0'"),
    ROW(fatal_too_many_errors, Fatal, "too many errors emitted, stopping now"),
    ROW(err_file_unreadable, Error, "cannot read '%0'"),
    ROW(err_shader_not_found, Error, "shader '%0' not found"),
    ROW(err_ir_parse, Error, "%0"),
    ROW(err_ir_invalid, Error, "invalid IR: %0"),
    // lexer
    ROW(err_invalid_char, Error, "invalid character '%0' in source"),
    ROW(err_binary_input, Error, "source contains a NUL byte (binary input?)"),
    ROW(err_unterminated_string, Error, "missing terminating '\"' character"),
    ROW(err_unterminated_comment, Error, "unterminated /* comment"),
    ROW(err_bad_number, Error, "invalid numeric literal '%0'"),
    ROW(err_int_too_large, Error, "integer literal '%0' is too large for int"),
    // preprocessor
    ROW(err_include_not_found, Error, "'%0' file not found"),
    ROW(err_include_depth, Error, "#include nested too deeply (limit %0)"),
    ROW(err_include_cycle, Error, "#include cycle: '%0' is already being included"),
    ROW(err_include_syntax, Error, "#include expects \"FILENAME\" or <FILENAME>"),
    ROW(err_unknown_directive, Error, "invalid preprocessing directive '#%0'"),
    ROW(warn_macro_redefined, Warning, "'%0' macro redefined"),
    ROW(note_previous_definition, Note, "previous definition is here"),
    ROW(err_macro_name_missing, Error, "macro name missing"),
    ROW(err_macro_param_list, Error, "invalid macro parameter list: %0"),
    ROW(err_macro_arg_count, Error, "macro '%0' requires %1 arguments, but %2 given"),
    ROW(err_macro_unterminated_call, Error, "unterminated argument list invoking macro '%0'"),
    ROW(err_hash_not_param, Error, "'#' is not followed by a macro parameter"),
    ROW(err_paste_at_edge, Error, "'##' cannot appear at either end of a macro expansion"),
    ROW(err_macro_expansion_too_large, Error, "macro expansion of '%0' is too deep or too large"),
    ROW(note_expanded_from, Note, "expanded from macro '%0'"),
    ROW(err_else_without_if, Error, "#%0 without #if"),
    ROW(err_endif_without_if, Error, "#endif without #if"),
    ROW(err_elif_after_else, Error, "#elif after #else"),
    ROW(err_else_after_else, Error, "#else after #else"),
    ROW(err_unterminated_conditional, Error, "unterminated conditional directive"),
    ROW(err_pp_expr, Error, "invalid #if expression: %0"),
    ROW(err_pragma_error, Error, "%0"),
    ROW(warn_pragma_warning, Warning, "%0"),
    ROW(warn_unknown_pragma, Warning, "Unknown pragma '%0'"),
    ROW(err_bad_line_directive, Error, "#line directive requires a positive line number"),
    ROW(warn_extra_tokens, Warning, "extra tokens at end of #%0 directive"),
    // parser
    ROW(err_expected, Error, "expected %0"),
    ROW(err_expected_found, Error, "expected %0, found '%1'"),
    ROW(err_expected_expression, Error, "expected expression, found '%0'"),
    ROW(err_expected_declaration, Error,
        "expected a shader, function or struct declaration, found '%0'"),
    ROW(err_expected_type, Error, "expected a type name, found '%0'"),
    ROW(err_nesting_too_deep, Error, "nesting too deep (limit %0)"),
    ROW(err_param_needs_default, Error, "shader parameter '%0' needs a default value"),
    ROW(note_to_match, Note, "to match this '%0'"),
    ROW(err_unknown_type, Error, "unknown type name '%0'"),
    ROW(err_array_size, Error, "array size must be a positive integer literal"),
    // sema
    ROW(err_undeclared, Error, "use of undeclared identifier '%0'"),
    ROW(err_redefinition, Error, "redefinition of '%0'"),
    ROW(note_previous_decl, Note, "previous definition is here"),
    ROW(err_redeclares_global, Error,
        "'%0' already declared in this scope (a shader global; a shader's parameters and the "
        "outermost block of its body share a scope with them)"),
    ROW(err_unknown_function, Error, "use of undeclared function '%0'"),
    ROW(err_no_matching_call, Error, "no matching function for call to '%0(%1)'"),
    ROW(err_ambiguous_call, Error, "call to '%0(%1)' is ambiguous"),
    ROW(warn_ambiguous_call, Warning, "call to '%0(%1)' is ambiguous"),
    ROW(note_candidate, Note, "candidate: %0"),
    ROW(note_chosen_candidate, Note, "chosen: %0"),
    ROW(note_other_candidate, Note, "other candidate: %0"),
    ROW(warn_function_redefined, Warning, "Function '%0' redefined in the same scope"),
    ROW(note_previous_builtin, Note, "previous definition is built-in: %0"),
    ROW(err_bad_binary, Error, "invalid operands to binary '%0' ('%1' and '%2')"),
    ROW(err_bad_unary, Error, "invalid operand to unary '%0' ('%1')"),
    ROW(err_cannot_assign, Error, "cannot assign '%0' to '%1'"),
    // oslc's words: a float assigned to an int variable truncates (calls, returns and
    // initialiser-list elements stay errors, as in oslc).
    ROW(warn_lose_precision, Warning, "Assignment may lose precision: %0 %1 = %2"),
    ROW(err_not_assignable, Error, "expression is not assignable"),
    ROW(warn_write_nonoutput_param, Warning, "cannot write to non-output parameter \"%0\""),
    ROW(warn_write_nonoutput_param_arg, Warning,
        "cannot write to non-output parameter \"%0\", as passed to function %1() as arg %2 "
        "(output parameter \"%3\")"),
    ROW(err_write_nonoutput_param, Error, "cannot write to non-output parameter \"%0\""),
    ROW(err_output_arg_not_lvalue, Error,
        "argument %0 of '%1' is an output parameter and needs a writable variable"),
    ROW(err_output_arg_type, Error,
        "cannot pass '%0' as argument %1 of '%2': it is an output parameter of type '%3'"),
    ROW(err_missing_return, Error, "non-void function '%0' does not return a value"),
    ROW(err_return_value_in_void, Error, "void function '%0' should not return a value"),
    ROW(err_return_without_value, Error, "non-void function '%0' should return a value"),
    ROW(err_recursion, Error, "recursive call to '%0': recursion is not allowed"),
    ROW(err_not_subscriptable, Error,
        "subscripted value of type '%0' is not an array, triple or matrix"),
    ROW(err_index_not_int, Error, "index must be an int, not '%0'"),
    ROW(err_no_member, Error, "no member named '%1' in '%0'"),
    ROW(err_bad_condition, Error, "a value of type '%0' cannot be used as a condition"),
    ROW(err_break_outside_loop, Error, "'%0' statement not in a loop"),
    ROW(err_unknown_keyword, Error, "unknown keyword argument '%0' for '%1'"),
    ROW(err_keyword_type, Error, "keyword argument '%0' of '%1' needs '%2', not '%3'"),
    ROW(err_keyword_name, Error, "expected a keyword name string in the arguments of '%0'"),
    ROW(err_init_count, Error, "too many initializers for '%0'"),
    ROW(err_init_list_context, Error, "cannot infer the type of '{...}' here"),
    ROW(err_bad_cast, Error, "cannot convert '%0' to '%1'"),
    ROW(err_bad_constructor, Error, "no constructor '%0(%1)'"),
    ROW(err_metadata_not_const, Error, "metadata '%0' needs a constant value"),
    ROW(err_void_variable, Error, "variable '%0' declared void"),
    ROW(err_not_a_function, Error, "'%0' is not a function"),
    ROW(err_struct_ctor_args, Error, "constructor of struct '%0' needs %1 arguments, %2 given"),
    ROW(err_array_assign_size, Error, "cannot assign '%0' to '%1': array lengths differ"),
    ROW(err_shader_redefinition, Error,
        "a file may declare only one shader ('%0' already declared)"),
    ROW(err_operator_not_struct, Error, "operator function '%0' needs a struct parameter"),
    ROW(err_format_too_few_args, Error,
        "too few arguments for the format string of '%0' (%1 needed, %2 given)"),
    ROW(err_format_too_many_args, Error,
        "too many arguments for the format string of '%0' (%1 needed, %2 given)"),
    ROW(err_format_arg_type, Error, "format '%0' needs %1, but argument %2 of '%3' is '%4'"),
    ROW(err_format_conversion, Error,
        "format '%0' of '%1' is not an OSL conversion (%d %i %o %x %X, %f %g %e, %s)"),
    ROW(err_format_struct_arg, Error,
        "argument %0 of '%1' is a struct ('%2'), which cannot be printed"),
    ROW(warn_confusing_comma, Warning,
        "Comma operator inside parenthesis is probably an error -- it is not a vector/color."),
    ROW(warn_param_hides_function, Warning, "\"%0\" already declared in this scope"),
    ROW(warn_library_function_redefined, Warning,
        "'%0' redefines the standard library's '%1', which this definition replaces"),
    // lowering
    ROW(err_lower_no_shader, Error, "no shader declared"),
    ROW(err_lower_unsized_struct_array, Error,
        "unsized arrays of structs with array fields are not supported"),
    ROW(err_lower_metadata_not_const, Error, "metadata '%0' is not a constant"),
    ROW(err_lower_break_outside_loop, Error, "break or continue outside a loop"),
    // oslc 1.13 for `float f(float x);` called as f(1): `p.osl:3: error: non-void function "f"
    // had no 'return' statement.` (a void one it accepts: the call does nothing).
    ROW(err_lower_no_body, Error, "non-void function '%0' had no 'return' statement"),
    ROW(err_lower_no_opcode, Error, "no IR opcode for the builtin '%0'"),
    ROW(err_lower_internal, Error, "internal: %0"),
    ROW(err_lower_invalid_ir, Error, "internal error: invalid IR: %0"),
    // the runtime (runtime/group; docs/diagnostics.md, "The runtime's ids")
    ROW(group_syntax, Error, "%0"),
    ROW(group_no_shader, Error, "the group has no `shader`"),
    ROW(group_empty, Error, "the group has no layers"),
    ROW(nonexistent_param, Warning, "%0"),
    ROW(param_type, Warning, "%0"),
    ROW(builtin_option, Warning, "%0"),
    ROW(closure_keyword, Warning, "%0"),
    ROW(param_value, Error, "%0"),
    ROW(connect_layer, Error, "%0"),
    ROW(connect_order, Error, "%0"),
    ROW(connect_param, Error, "%0"),
    ROW(connect_type, Error, "%0"),
    ROW(storage_size, Error, "%0"),
    ROW(codegen, Error, "%0"),
    ROW(jit, Error, "%0"),
};
#undef ROW
static_assert(sizeof(kTable) / sizeof(kTable[0]) == size_t(DiagId::kCount),
              "one row per diagnostic id");

} // namespace

const DiagInfo& diag_info(DiagId id) { return kTable[size_t(id)].info; }
const char* diag_name(DiagId id) { return kTable[size_t(id)].name; }

std::string format_message(const char* format, const std::vector<std::string>& args) {
  std::string out;
  for (const char* p = format; *p; ++p) {
    if (p[0] == '%' && p[1] >= '0' && p[1] <= '9') {
      size_t i = size_t(p[1] - '0');
      if (i < args.size()) out += args[i];
      ++p;
    } else {
      out += *p;
    }
  }
  return out;
}

} // namespace lobe::diag
