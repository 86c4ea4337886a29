# Build-time helper: writes the built-in headers (INPUTS, a list of files) into OUTPUT as C++
# raw strings with a name -> text table, so the compiler carries them inside its binary. Run as
# `cmake -DINPUTS="a.h|b.h" -DOUTPUT=... -P embed.cmake`.
string(REPLACE "|" ";" INPUTS "${INPUTS}")
set(_table "")
set(_texts "")
set(_i 0)
foreach(_in IN LISTS INPUTS)
  file(READ "${_in}" _text)
  get_filename_component(_name "${_in}" NAME)
  string(APPEND _texts "static const char kText${_i}[] = R\"__lobe_hdr__(${_text})__lobe_hdr__\";\n")
  string(APPEND _table "    {\"${_name}\", {kText${_i}, sizeof(kText${_i}) - 1}},\n")
  math(EXPR _i "${_i} + 1")
endforeach()
file(WRITE "${OUTPUT}.tmp"
     "// Generated from compiler/stdlib/*.h by embed.cmake. Do not edit.\n"
     "#include \"stdlib/stdlib.h\"\n"
     "namespace lobe::stdlib {\n"
     "${_texts}"
     "static const Header kHeaders[] = {\n${_table}};\n"
     "std::span<const Header> headers() { return kHeaders; }\n"
     "} // namespace lobe::stdlib\n")
file(COPY_FILE "${OUTPUT}.tmp" "${OUTPUT}" ONLY_IF_DIFFERENT)
file(REMOVE "${OUTPUT}.tmp")
