// Test sizes under compute-sanitizer, shared by the GPU tests: the variable `env` (e.g.
// GG_DEL3D_MAX_N, set by scripts/gpu_session.sh) caps them, since the large cases take too long
// there. Where the cap leaves none of a test's sizes, the cap itself: every test still runs and
// takes its paths, and no caller reads an empty list.
#pragma once
#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <utility>
#include <vector>

namespace gg_test {

inline std::vector<std::int64_t> capped_sizes(const char* env, std::vector<std::int64_t> s) {
  if (const char* e = std::getenv(env)) {
    const std::int64_t cap = std::atoll(e);
    s.erase(std::remove_if(s.begin(), s.end(), [&](std::int64_t n) { return n > cap; }), s.end());
    if (s.empty()) s.push_back(cap);
  }
  return s;
}

}  // namespace gg_test
