// A type chosen at run time, once: visit_type<Types>(i, f) calls f(T{}) with T the i-th type of
// the tuple Types (the last one where i is out of range), through a table of one function per
// type rather than a switch written out per caller. Every f(T{}) must return the same type.
// The element loops of the file formats (io/) run inside f, so the type is decided once per
// array, not per element.
#pragma once
#include <cstddef>
#include <tuple>
#include <utility>

namespace gpugeom::detail {

template <class Types, class R, class F, std::size_t... I>
R visit_type_at(std::size_t i, F& f, std::index_sequence<I...>) {
  using Arm = R (*)(F&);
  static constexpr Arm arms[] = {[](F& g) -> R { return g(std::tuple_element_t<I, Types>{}); }...};
  return arms[i < sizeof...(I) ? i : sizeof...(I) - 1](f);
}

template <class Types, class F>
decltype(auto) visit_type(std::size_t i, F&& f) {
  using R = decltype(f(std::tuple_element_t<0, Types>{}));
  return visit_type_at<Types, R>(i, f, std::make_index_sequence<std::tuple_size_v<Types>>{});
}

}  // namespace gpugeom::detail
