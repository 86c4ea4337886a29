// An included file's __LINE__ is its line (tests/shade/line_macro.osl).
int line_in_header() { return __LINE__; }
