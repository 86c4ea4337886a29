// Thread counts past the machine's cores, for `--threads N` and `-t N`.
#pragma once

#include <tbb/global_control.h>

#include <algorithm>
#include <cstddef>
#include <optional>

namespace lobe::render {

// oneTBB runs at most as many threads as the machine has cores: an arena asking for more gets
// fewer, and oneTBB prints a warning on stderr. Lifts that limit to `threads` while the
// returned object lives (none needed at or below it).
inline std::optional<tbb::global_control> allow_threads(int threads) {
  using G = tbb::global_control;
  size_t now = G::active_value(G::max_allowed_parallelism);
  if (threads <= 0 || size_t(threads) <= now) return std::nullopt;
  return std::optional<G>(std::in_place, G::max_allowed_parallelism, size_t(threads));
}

} // namespace lobe::render
