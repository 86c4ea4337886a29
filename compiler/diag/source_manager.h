// SourceManager: owns every buffer the front end reads (source files, included files, the
// embedded standard header) and the preprocessor's output, and maps any SourceLoc back to a
// file, line and column a person can use.
//
// Location space: buffer k occupies offsets [base_k, base_k + size_k] (one past the end is a
// valid location: end of file). Locations in the preprocessed output are mapped back through
// segments the preprocessor records: text copied from a file maps character by character; text
// produced by a macro expansion maps to the macro's invocation (and remembers the macro, for an
// "expanded from macro" note). `#line` directives adjust the reported line and file name.
#pragma once

#include "diag/source_location.h"

#include <deque>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

namespace lobe::diag {

class SourceManager {
public:
  // A piece of preprocessor output: output bytes from `out_offset` up to the next segment come
  // from `loc` (a file location). `linear`: byte i of the piece is loc + i; otherwise (macro
  // expansion text) every byte maps to `loc`, the invocation, and `macro` names the macro.
  struct Segment {
    uint32_t out_offset = 0;
    SourceLoc loc;
    bool linear = true;
    std::string macro;   // macro expansions only
    SourceLoc macro_def; // where that macro was defined
  };

  // Adds a file buffer; `include_loc` is the #include that brought it in (invalid for the main
  // file). Returns the buffer's id.
  int add_file(std::string name, std::string text, SourceLoc include_loc = {});
  // Adds the preprocessor output with its segments (sorted by out_offset).
  int add_output(std::string text, std::vector<Segment> segments);
  // `#line N "file"` seen in file buffer `id` at byte `offset` (the start of the next line).
  void add_line_directive(int id, uint32_t offset, int line, const std::string& file);

  SourceLoc buffer_start(int id) const { return SourceLoc{buffers_[size_t(id)]->base}; }
  const std::string& buffer_text(int id) const { return buffers_[size_t(id)]->text; }
  const std::string& buffer_name(int id) const { return buffers_[size_t(id)]->name; }
  int buffer_count() const { return int(buffers_.size()); }
  int buffer_of(SourceLoc loc) const; // -1 if invalid

  // Maps a location in the preprocessor output to the file location it came from (identity
  // for a file location). If `seg` is given it receives the output segment used (or null).
  SourceLoc file_loc(SourceLoc loc, const Segment** seg = nullptr) const;
  PresumedLoc presumed(SourceLoc loc) const;
  // The physical line of a file location, without its newline.
  std::string_view line_text(SourceLoc loc) const;
  // Where the file containing `loc` was #included from (invalid for the main file).
  SourceLoc include_loc(SourceLoc loc) const;

private:
  struct LineDirective {
    uint32_t offset; // applies from this byte
    int line;
    const char* file;
  };
  struct Buffer {
    std::string name, text;
    uint32_t base = 0;
    bool is_output = false;
    SourceLoc include_loc;
    std::vector<uint32_t> line_starts;
    std::vector<LineDirective> directives;
    std::vector<Segment> segments;
  };
  int add_buffer(std::unique_ptr<Buffer> b);
  static int physical_line(const Buffer& b, uint32_t offset); // 0-based

  std::vector<std::unique_ptr<Buffer>> buffers_;
  std::deque<std::string> names_; // storage for #line file names
  uint32_t next_base_ = 1;
};

} // namespace lobe::diag
