// Source locations: one 32-bit offset into a single location space shared by every buffer the
// SourceManager holds (each file, and the preprocessor's output text), in the manner of Clang.
//
// Why one number: every AST node and token carries two of them, so they must be small; the
// SourceManager turns a location back into file, line and column (through #include and macro
// expansion: a location in the preprocessed text maps to the original file and line).
#pragma once

#include <cstdint>

namespace lobe::diag {

struct SourceLoc {
  uint32_t offset = 0; // 0: invalid / unknown

  bool valid() const { return offset != 0; }
  SourceLoc advanced(uint32_t n) const { return SourceLoc{offset + n}; }
  friend bool operator==(const SourceLoc&, const SourceLoc&) = default;
};

// A half-open range [begin, end) of characters; end == begin for an empty or point range.
struct SourceRange {
  SourceLoc begin, end;

  SourceRange() = default;
  SourceRange(SourceLoc b, SourceLoc e) : begin(b), end(e) {}
  explicit SourceRange(SourceLoc b) : begin(b), end(b) {}
  bool valid() const { return begin.valid(); }
  friend bool operator==(const SourceRange&, const SourceRange&) = default;
};

// What a location means to a person: file, 1-based line and column.
struct PresumedLoc {
  const char* file = ""; // owned by the SourceManager
  int line = 0;
  int column = 0;
  bool renumbered = false; // a #line directive gave the line (and maybe the file)
  bool valid() const { return line > 0; }
};

} // namespace lobe::diag
