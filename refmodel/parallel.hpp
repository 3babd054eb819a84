// Work split over the machine's cores for whole-image and whole-volume loops.
//
// Items are handed out one at a time from an atomic counter; each item writes
// only its own outputs, so the result is bit-identical for any thread count.
#pragma once

#include <algorithm>
#include <atomic>
#include <thread>
#include <vector>

namespace voxcast::ref {

// Number of worker threads: `requested` if > 0, else the hardware concurrency.
inline int worker_count(int requested = 0) {
  if (requested > 0) return requested;
  return std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
}

template <typename Fn>
void parallel_for(int count, Fn&& fn, int threads = 0) {
  const int n = std::min(worker_count(threads), std::max(count, 1));
  std::atomic<int> next{0};
  auto work = [&] {
    for (int i = next.fetch_add(1); i < count; i = next.fetch_add(1)) fn(i);
  };
  if (n == 1) {
    work();
    return;
  }
  std::vector<std::jthread> pool;
  pool.reserve(static_cast<std::size_t>(n - 1));
  for (int t = 1; t < n; ++t) pool.emplace_back(work);
  work();
}

}  // namespace voxcast::ref
