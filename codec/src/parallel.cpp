// A minimal deterministic parallel loop: indices are handed out one by one; every result is
// written by index, so the outcome is the same for any thread count.
#include "parallel.h"

#include <algorithm>
#include <atomic>
#include <exception>
#include <mutex>
#include <system_error>
#include <thread>
#include <vector>

namespace ellicast::detail {

void parallel_for(size_t n, unsigned threads, const std::function<void(size_t)>& body) {
    threads = std::max(1u, std::min<unsigned>(threads, unsigned(std::min<size_t>(n, 64))));
    if (threads <= 1) {
        for (size_t i = 0; i < n; ++i) body(i);
        return;
    }
    // An exception thrown by body (on any thread) stops the handing out and is thrown again here,
    // as the loop on one thread would throw it, once every thread has stopped.
    std::atomic<size_t> next{0};
    std::exception_ptr failure;
    std::mutex failure_lock;
    auto worker = [&] {
        try {
            for (size_t i; (i = next.fetch_add(1)) < n;) body(i);
        } catch (...) {
            next.store(n);
            const std::lock_guard<std::mutex> hold(failure_lock);
            if (!failure) failure = std::current_exception();
        }
    };
    std::vector<std::thread> pool;
    try {
        for (unsigned t = 1; t < threads; ++t) pool.emplace_back(worker);
    } catch (const std::system_error&) {
        // No more threads to be had: the ones started and this one share the loop.
    }
    worker();
    for (auto& t : pool) t.join();
    if (failure) std::rethrow_exception(failure);
}

}  // namespace ellicast::detail
