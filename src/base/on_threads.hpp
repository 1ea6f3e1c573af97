// f(i) for each i in [0, k), each on a host thread of its own (the several-devices entries: a
// thread per device); the first exception, by index, is rethrown once all have ended.
#pragma once
#include <cstddef>
#include <exception>
#include <thread>
#include <vector>

namespace gpugeom::detail {

template <class F>
void on_threads(std::size_t k, F&& f) {
  std::vector<std::exception_ptr> err(k);
  std::vector<std::thread> ts;
  ts.reserve(k);
  for (std::size_t i = 0; i < k; ++i)
    ts.emplace_back([&, i] {
      try {
        f(i);
      } catch (...) {
        err[i] = std::current_exception();
      }
    });
  for (auto& t : ts) t.join();
  for (auto& e : err)
    if (e) std::rethrow_exception(e);
}

}  // namespace gpugeom::detail
