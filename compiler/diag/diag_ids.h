// The one table of named diagnostics: every message Lobe's libraries report (front end,
// lowering, the driver that finds and loads shaders, and the runtime's group building, code
// generation and JIT).
//
// Each entry has an id (the enum), a default severity and a message template where %0, %1, ...
// are replaced by the arguments given when the diagnostic is reported. Naming the messages in
// one place keeps wording consistent and lets tests refer to a diagnostic by id. The runtime's
// rows are mostly "%0": their ids are the published contract, the message is worded where
// it is reported (docs/diagnostics.md).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace lobe::diag {

enum class Severity : uint8_t { Note, Warning, Error, Fatal };

enum class DiagId : uint16_t {
  // driver / files (compiler/driver)
  err_file_not_found,
  fatal_too_many_errors,
  err_file_unreadable,
  err_shader_not_found,
  err_ir_parse,
  err_ir_invalid,
  // lexer
  err_invalid_char,
  err_binary_input,
  err_unterminated_string,
  err_unterminated_comment,
  err_bad_number,
  err_int_too_large,
  // preprocessor
  err_include_not_found,
  err_include_depth,
  err_include_cycle,
  err_include_syntax,
  err_unknown_directive,
  warn_macro_redefined,
  note_previous_definition,
  err_macro_name_missing,
  err_macro_param_list,
  err_macro_arg_count,
  err_macro_unterminated_call,
  err_hash_not_param,
  err_paste_at_edge,
  err_macro_expansion_too_large,
  note_expanded_from,
  err_else_without_if,
  err_endif_without_if,
  err_elif_after_else,
  err_else_after_else,
  err_unterminated_conditional,
  err_pp_expr,
  err_pragma_error,
  warn_pragma_warning,
  warn_unknown_pragma,
  err_bad_line_directive,
  warn_extra_tokens,
  // parser
  err_expected,
  err_expected_found,
  err_expected_expression,
  err_expected_declaration,
  err_expected_type,
  err_nesting_too_deep,
  err_param_needs_default,
  note_to_match,
  err_unknown_type,
  err_array_size,
  // sema
  err_undeclared,
  err_redefinition,
  note_previous_decl,
  err_redeclares_global,
  err_unknown_function,
  err_no_matching_call,
  err_ambiguous_call,
  warn_ambiguous_call,
  note_candidate,
  note_chosen_candidate,
  note_other_candidate,
  warn_function_redefined,
  note_previous_builtin,
  err_bad_binary,
  err_bad_unary,
  err_cannot_assign,
  warn_lose_precision,
  err_not_assignable,
  warn_write_nonoutput_param,
  warn_write_nonoutput_param_arg,
  err_write_nonoutput_param,
  err_output_arg_not_lvalue,
  err_output_arg_type,
  err_missing_return,
  err_return_value_in_void,
  err_return_without_value,
  err_recursion,
  err_not_subscriptable,
  err_index_not_int,
  err_no_member,
  err_bad_condition,
  err_break_outside_loop,
  err_unknown_keyword,
  err_keyword_type,
  err_keyword_name,
  err_init_count,
  err_init_list_context,
  err_bad_cast,
  err_bad_constructor,
  err_metadata_not_const,
  err_void_variable,
  err_not_a_function,
  err_struct_ctor_args,
  err_array_assign_size,
  err_shader_redefinition,
  err_operator_not_struct,
  err_format_too_few_args,
  err_format_too_many_args,
  err_format_arg_type,
  err_format_conversion,
  err_format_struct_arg,
  warn_confusing_comma,
  warn_param_hides_function,
  warn_library_function_redefined,
  // lowering (compiler/lower): constructs the type checker accepts that have no IR form
  err_lower_no_shader,
  err_lower_unsized_struct_array,
  err_lower_metadata_not_const,
  err_lower_break_outside_loop,
  err_lower_no_body,
  err_lower_no_opcode,
  err_lower_internal,
  err_lower_invalid_ir,
  // the runtime (runtime/group): named as the runtime has always published them (no severity
  // prefix; lobe::Diagnostic::id), the message composed where it is reported
  group_syntax,
  group_no_shader,
  group_empty,
  nonexistent_param,
  param_type,
  builtin_option,
  closure_keyword,
  param_value,
  connect_layer,
  connect_order,
  connect_param,
  connect_type,
  storage_size,
  codegen,
  jit,
  kCount
};

struct DiagInfo {
  DiagId id;
  Severity severity;
  const char* format; // %0 %1 ... are arguments
};

const DiagInfo& diag_info(DiagId id);
const char* diag_name(DiagId id); // "err_undeclared", for tests and dumps

// Substitutes %0.. in `format` with `args` (missing args become "").
std::string format_message(const char* format, const std::vector<std::string>& args);

} // namespace lobe::diag
