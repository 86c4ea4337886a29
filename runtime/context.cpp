// ShadingContext: the per-thread arena closures are built in, and the sink for messages from
// shader code (printf, run-time errors). Rewinding the arena is O(1), so the renderer can
// reset it at every shading point.
#include "lobe/context.h"

#include "lobe/detail/messages.h"
#include "lobe/renderer_services.h"

namespace lobe {

ShadingContext::ShadingContext(size_t arena_bytes)
    : arena_(new unsigned char[arena_bytes]), capacity_(arena_bytes) {}
ShadingContext::~ShadingContext() = default;
ShadingContext::ShadingContext(ShadingContext&&) noexcept = default;
ShadingContext& ShadingContext::operator=(ShadingContext&&) noexcept = default;

detail::MessageStore& ShadingContext::messages() {
  if (!messages_) messages_ = std::make_unique<detail::MessageStore>();
  return *messages_;
}

std::string DataType::str() const {
  static const char* const kNames[] = {"int",    "float",  "color",  "point",
                                       "vector", "normal", "matrix", "string"};
  std::string s = kNames[size_t(base)];
  if (arraylen > 0) { // appended piecewise: "[" + to_string(n) trips GCC 12's -Wrestrict
    s += "[";
    s += std::to_string(arraylen);
    s += "]";
  }
  return s;
}

void* ShadingContext::allocate(size_t bytes) {
  size_t start = (used_ + 7) & ~size_t(7);
  if (start > capacity_ || bytes > capacity_ - start) return nullptr;
  used_ = start + bytes;
  return arena_.get() + start;
}

void ShadingContext::message(const std::string& text) {
  if (print)
    print(text);
  else
    output += text;
}

} // namespace lobe
