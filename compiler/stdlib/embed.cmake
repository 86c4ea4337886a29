# Build-time helper: writes INPUT (the standard header) into OUTPUT as a C++ raw string, so the
# compiler carries stdosl.h inside its binary. Run as `cmake -DINPUT=... -DOUTPUT=... -P`.
file(READ "${INPUT}" _text)
file(WRITE "${OUTPUT}" "// Generated from compiler/stdlib/stdosl.h by embed.cmake. Do not edit.\n"
     "#include \"stdlib/stdlib.h\"\n"
     "namespace lobe::stdlib {\n"
     "static const char kStdosl[] = R\"__lobe_stdosl__(${_text})__lobe_stdosl__\";\n"
     "std::string_view stdosl_source() { return {kStdosl, sizeof(kStdosl) - 1}; }\n"
     "} // namespace lobe::stdlib\n")
