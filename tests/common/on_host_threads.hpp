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

// solve(threads) runs one call with that many CPU threads. Four host threads call it at once
// (1 or 2 CPU threads each); every result must be what a lone one-thread call gives, as judged
// by same(reference, result).
template <class Solve, class Same>
void expect_concurrent_calls_agree(Solve solve, Same same) {
  const auto ref = solve(1);
  for (const auto& got : on_host_threads(4, [&](int k) { return solve(1 + k % 2); }))
    same(ref, got);
}
}  // namespace gg_test
