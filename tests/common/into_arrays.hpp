// A result's arrays in the caller's memory (a capability's `into`), for the tests that check it:
// one caller array per output, sized from a reference result, filled with a value no result
// holds, compared with the reference's arrays afterwards. Outputs are described by member
// pointers (the OutBuffer in the buffers type, the HostVector in the host result), so one
// harness serves every capability whose host result and buffers share their array names.
#pragma once
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "caller_arrays.hpp"
#include "gpugeom/common.hpp"
#include "gpugeom/host_vector.hpp"

namespace gg_test {

// One output: where `into` takes it and where the host result holds it.
template <class Buffers, class Result, class T>
struct Output {
  gpugeom::OutBuffer<T> Buffers::*into;
  gpugeom::HostVector<T> Result::*host;
  const char* name;
};
template <class Buffers, class Result, class T>
Output<Buffers, Result, T> output(gpugeom::OutBuffer<T> Buffers::*into,
                                  gpugeom::HostVector<T> Result::*host, const char* name) {
  return {into, host, name};
}

// The caller's arrays for every output of `outs`, each as long as ref's (the one named `short`
// one element shorter), filled with -7.
template <class Buffers, class Result, class... T>
class IntoArrays {
 public:
  IntoArrays(const Result& ref, std::tuple<Output<Buffers, Result, T>...> outs,
             const std::string& shorter = "")
      : outs_(outs) {
    each([&](auto& o, auto& a) { a = make(ref, o, shorter); });
  }
  Buffers buffers() {
    Buffers b;
    each([&](auto& o, auto& a) { b.*(o.into) = a.buf(); });
    return b;
  }
  bool untouched() const {
    bool all = true;
    each([&](auto&, auto& a) { all = all && a.untouched(-7); });
    return all;
  }
  // The arrays hold ref's.
  void expect_equal(const Result& ref) const {
    each([&](auto& o, auto& a) {
      const auto& h = ref.*(o.host);
      EXPECT_TRUE(std::equal(a.v.begin(), a.v.end(), h.begin(), h.end())) << o.name;
    });
  }
  // A host result written into them holds none of the arrays itself.
  void expect_none(const Result& r) const {
    each([&](auto& o, auto&) { EXPECT_TRUE((r.*(o.host)).empty()) << o.name; });
  }

 private:
  template <class U>
  static CallerArray<U> make(const Result& ref, const Output<Buffers, Result, U>& o,
                             const std::string& shorter) {
    const std::int64_t len = std::int64_t((ref.*(o.host)).size());
    return CallerArray<U>(shorter == o.name ? len - 1 : len, U(-7));
  }
  // f(output, array) for each output, on a const or a mutable IntoArrays alike.
  template <class F>
  void each(F f) const {
    each_in(*this, f, std::index_sequence_for<T...>{});
  }
  template <class F>
  void each(F f) {
    each_in(*this, f, std::index_sequence_for<T...>{});
  }
  template <class Self, class F, std::size_t... I>
  static void each_in(Self& self, F f, std::index_sequence<I...>) {
    (f(std::get<I>(self.outs_), std::get<I>(self.arrays_)), ...);
  }

  std::tuple<Output<Buffers, Result, T>...> outs_;
  std::tuple<CallerArray<T>...> arrays_{CallerArray<T>(0, T(0))...};
};

}  // namespace gg_test
