// Every name of an element type, in one table (internal): NumPy's name and .npy descriptor,
// the legacy VTK and the VTK XML type names; and its C++ type (visit_scalar, below), whose size
// is the element's. The public scalar_size/scalar_name and the file formats read these instead
// of switching over the type each on its own.
#pragma once
#include <cstddef>
#include <cstdint>
#include <tuple>
#include <utility>

#include "base/type_visit.hpp"
#include "gpugeom/scalar_type.hpp"

namespace gpugeom::io::detail {

struct ScalarInfo {
  ScalarType type;
  const char* numpy;       // NumPy's dtype name
  const char* npy_descr;   // the .npy header's descr (little-endian)
  const char* vtk_legacy;  // legacy .vtk (bool as bytes)
  const char* vtk_xml;     // VTK XML DataArray type (bool as bytes)
};

// In the enum's order (checked below).
inline constexpr ScalarInfo kScalars[] = {
    {ScalarType::Bool, "bool", "|b1", "unsigned_char", "UInt8"},
    {ScalarType::U8, "uint8", "|u1", "unsigned_char", "UInt8"},
    {ScalarType::U16, "uint16", "<u2", "unsigned_short", "UInt16"},
    {ScalarType::I32, "int32", "<i4", "int", "Int32"},
    {ScalarType::I64, "int64", "<i8", "vtktypeint64", "Int64"},
    {ScalarType::F32, "float32", "<f4", "float", "Float32"},
    {ScalarType::F64, "float64", "<f8", "double", "Float64"},
};

constexpr bool scalars_in_enum_order() {
  int i = 0;
  for (const ScalarInfo& s : kScalars)
    if (int(s.type) != i++) return false;
  return true;
}
static_assert(scalars_in_enum_order(), "kScalars must list the types in ScalarType's order");

// An out-of-range value (a cast the library never makes) reads as float64, as the switches did.
inline const ScalarInfo& scalar_info(ScalarType t) {
  const int i = int(t);
  constexpr int n = int(sizeof kScalars / sizeof kScalars[0]);
  return kScalars[i >= 0 && i < n ? i : n - 1];
}

// The C++ type of each element type, in the enum's order (bool as its byte).
using ScalarCppTypes = std::tuple<std::uint8_t, std::uint8_t, std::uint16_t, std::int32_t,
                                  std::int64_t, float, double>;

static_assert(std::tuple_size_v<ScalarCppTypes> == sizeof kScalars / sizeof kScalars[0],
              "one C++ type per entry of kScalars");

// f(T{}) with T the C++ type of t (double for a value out of range, as scalar_info): the type
// decided once, not per element. Every arm must return the same type.
template <class F>
decltype(auto) visit_scalar(ScalarType t, F&& f) {
  return gpugeom::detail::visit_type<ScalarCppTypes>(std::size_t(t), std::forward<F>(f));
}

}  // namespace gpugeom::io::detail
