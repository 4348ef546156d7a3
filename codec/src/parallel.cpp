// A minimal deterministic parallel loop: indices are handed out one by one; every result is
// written by index, so the outcome is the same for any thread count.
#include "parallel.h"

#include <vector>

#include <algorithm>
#include <atomic>
#include <thread>

namespace ellicast::detail {

void parallel_for(size_t n, unsigned threads, const std::function<void(size_t)>& body) {
    threads = std::max(1u, std::min<unsigned>(threads, unsigned(std::min<size_t>(n, 64))));
    if (threads <= 1) {
        for (size_t i = 0; i < n; ++i) body(i);
        return;
    }
    std::atomic<size_t> next{0};
    auto worker = [&] {
        for (size_t i; (i = next.fetch_add(1)) < n;) body(i);
    };
    std::vector<std::thread> pool;
    for (unsigned t = 1; t < threads; ++t) pool.emplace_back(worker);
    worker();
    for (auto& t : pool) t.join();
}

}  // namespace ellicast::detail
