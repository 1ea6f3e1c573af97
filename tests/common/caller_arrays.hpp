// Helpers for the tests of device entry points and caller-provided output arrays (`into`).
#pragma once
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "gpugeom/common.hpp"

namespace gg_test {

// n elements of a host array (a device entry's result on the CPU executor, or a caller's array).
template <class T>
std::vector<T> host_prefix(const T* p, std::int64_t n) {
  return p ? std::vector<T>(p, p + n) : std::vector<T>();
}
template <class T>
std::vector<T> host_prefix(const std::shared_ptr<T>& p, std::int64_t n) {
  return host_prefix(p.get(), n);
}

// A caller's array of `size` elements, each `fill`, and its OutBuffer.
template <class T>
struct CallerArray {
  std::vector<T> v;
  CallerArray(std::int64_t size, T fill) : v(std::size_t(size), fill) {}
  gpugeom::OutBuffer<T> buf() { return {v.data(), std::int64_t(v.size())}; }
  bool untouched(T fill) const {
    for (const T& x : v)
      if (!(x == fill)) return false;
    return true;
  }
};

// f() must throw Error(InvalidArgument) whose message holds `fragment`.
template <class F>
void expect_refused(F f, const std::string& fragment) {
  try {
    f();
    ADD_FAILURE() << "accepted; expected a refusal mentioning '" << fragment << "'";
  } catch (const gpugeom::Error& e) {
    EXPECT_EQ(e.code(), gpugeom::ErrorCode::InvalidArgument) << e.what();
    EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
  }
}

}  // namespace gg_test
