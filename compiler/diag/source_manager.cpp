// SourceManager: buffers, the location space and the mapping back to file/line/column.
#include "diag/source_manager.h"

#include <algorithm>

namespace lobe::diag {

int SourceManager::add_buffer(std::unique_ptr<Buffer> b) {
  b->base = next_base_;
  // Cap the space: a pathological input can't overflow 32 bits (4 GB of source).
  uint64_t next = uint64_t(next_base_) + b->text.size() + 1;
  next_base_ = next > 0xF0000000u ? 0xF0000000u : uint32_t(next);
  b->line_starts.push_back(0);
  for (uint32_t i = 0; i < b->text.size(); ++i)
    if (b->text[i] == '\n') b->line_starts.push_back(i + 1);
  buffers_.push_back(std::move(b));
  return int(buffers_.size()) - 1;
}

int SourceManager::add_file(std::string name, std::string text, SourceLoc include_loc) {
  auto b = std::make_unique<Buffer>();
  b->name = std::move(name);
  b->text = std::move(text);
  b->include_loc = include_loc;
  return add_buffer(std::move(b));
}

int SourceManager::add_output(std::string text, std::vector<Segment> segments) {
  auto b = std::make_unique<Buffer>();
  b->name = "<preprocessed>";
  b->text = std::move(text);
  b->is_output = true;
  b->segments = std::move(segments);
  return add_buffer(std::move(b));
}

void SourceManager::add_line_directive(int id, uint32_t offset, int line, const std::string& file) {
  Buffer& b = *buffers_[size_t(id)];
  const char* name = nullptr;
  if (!file.empty()) {
    names_.push_back(file);
    name = names_.back().c_str();
  } else if (!b.directives.empty()) {
    name = b.directives.back().file;
  }
  b.directives.push_back({offset, line, name});
}

int SourceManager::buffer_of(SourceLoc loc) const {
  if (!loc.valid() || buffers_.empty()) return -1;
  auto it = std::upper_bound(buffers_.begin(), buffers_.end(), loc.offset,
                             [](uint32_t off, const auto& b) { return off < b->base; });
  if (it == buffers_.begin()) return -1;
  int id = int(it - buffers_.begin()) - 1;
  const Buffer& b = *buffers_[size_t(id)];
  return loc.offset <= b.base + b.text.size() ? id : -1;
}

SourceLoc SourceManager::file_loc(SourceLoc loc, const Segment** seg) const {
  if (seg) *seg = nullptr;
  int id = buffer_of(loc);
  if (id < 0) return {};
  const Buffer& b = *buffers_[size_t(id)];
  if (!b.is_output) return loc;
  uint32_t off = loc.offset - b.base;
  auto it = std::upper_bound(b.segments.begin(), b.segments.end(), off,
                             [](uint32_t o, const Segment& s) { return o < s.out_offset; });
  if (it == b.segments.begin()) return {};
  const Segment& s = *(it - 1);
  if (seg) *seg = &s;
  if (!s.linear) return s.loc;
  // Past the end of the piece's file (a newline the preprocessor added): the file's end.
  SourceLoc r = s.loc.advanced(off - s.out_offset);
  int src = buffer_of(s.loc);
  if (src >= 0) {
    const Buffer& f = *buffers_[size_t(src)];
    if (r.offset > f.base + f.text.size()) r = SourceLoc{uint32_t(f.base + f.text.size())};
  }
  return r;
}

int SourceManager::physical_line(const Buffer& b, uint32_t offset) {
  auto it = std::upper_bound(b.line_starts.begin(), b.line_starts.end(), offset);
  return int(it - b.line_starts.begin()) - 1;
}

PresumedLoc SourceManager::presumed(SourceLoc loc) const {
  SourceLoc f = file_loc(loc);
  int id = buffer_of(f);
  if (id < 0) return {};
  const Buffer& b = *buffers_[size_t(id)];
  uint32_t off = f.offset - b.base;
  int line = physical_line(b, off);
  PresumedLoc p;
  p.file = b.name.c_str();
  p.line = line + 1;
  p.column = int(off - b.line_starts[size_t(line)]) + 1;
  // The last #line directive before this offset renumbers lines from where it applies.
  for (auto d = b.directives.rbegin(); d != b.directives.rend(); ++d) {
    if (d->offset > off) continue;
    p.line = d->line + (line - physical_line(b, d->offset));
    p.renumbered = true;
    if (d->file) p.file = d->file;
    break;
  }
  return p;
}

std::string_view SourceManager::line_text(SourceLoc loc) const {
  SourceLoc f = file_loc(loc);
  int id = buffer_of(f);
  if (id < 0) return {};
  const Buffer& b = *buffers_[size_t(id)];
  uint32_t off = f.offset - b.base;
  uint32_t start = b.line_starts[size_t(physical_line(b, off))];
  size_t end = b.text.find('\n', start);
  if (end == std::string::npos) end = b.text.size();
  if (end > start && b.text[end - 1] == '\r') --end;
  return std::string_view(b.text).substr(start, end - start);
}

SourceLoc SourceManager::include_loc(SourceLoc loc) const {
  int id = buffer_of(file_loc(loc));
  return id < 0 ? SourceLoc{} : buffers_[size_t(id)]->include_loc;
}

} // namespace lobe::diag
