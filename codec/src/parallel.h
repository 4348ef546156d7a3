// A minimal deterministic parallel loop, shared by the encoder and the decoder (codec only).
#pragma once

#include <cstddef>
#include <functional>

namespace ellicast::detail {

// Runs body(i) for i in [0, n) on `threads` threads; each index is processed exactly once and
// results must be written per index, so the outcome does not depend on the thread count.
void parallel_for(size_t n, unsigned threads, const std::function<void(size_t)>& body);

}  // namespace ellicast::detail
