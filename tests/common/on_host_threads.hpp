// Runs f(k) for k < n on n host threads at once and returns the results in k's order: the
// tests' way to show that calls from several threads do not disturb each other.
#pragma once
#include <cstddef>
#include <thread>
#include <vector>

namespace gg_test {
template <class F>
auto on_host_threads(int n, F f) {
  std::vector<decltype(f(0))> out(static_cast<std::size_t>(n));
  std::vector<std::thread> th;
  for (int k = 0; k < n; ++k) th.emplace_back([&, k] { out[std::size_t(k)] = f(k); });
  for (auto& t : th) t.join();
  return out;
}
}  // namespace gg_test
