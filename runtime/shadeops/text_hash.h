// A transparent hash of text for unordered containers keyed by std::string: finds a
// std::string_view (or a const char*) without making a std::string.
#pragma once

#include <cstddef>
#include <functional>
#include <string_view>

namespace lobe::shadeops {

struct TextHash {
  using is_transparent = void;
  size_t operator()(std::string_view s) const noexcept { return std::hash<std::string_view>{}(s); }
};

} // namespace lobe::shadeops
