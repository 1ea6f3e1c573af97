// The element types of grids (gpugeom/scalar_type.hpp): in the core, which the grid
// capabilities need without the file readers.
#include "gpugeom/scalar_type.hpp"

#include "exec/scalar_table.hpp"
#include "gpugeom/common.hpp"

namespace gpugeom {

std::size_t scalar_size(ScalarType t) {
  return io::detail::visit_scalar(t, [](auto v) { return sizeof v; });
}
const char* scalar_name(ScalarType t) {
  return io::detail::scalar_info(t).numpy;
}
ScalarType parse_scalar(const std::string& s) {
  for (const io::detail::ScalarInfo& i : io::detail::kScalars)
    if (s == i.numpy) return i.type;
  throw Error(ErrorCode::InvalidArgument,
              "unknown element type '" + s +
                  "': expected bool, uint8, uint16, int32, int64, float32 or float64");
}

}  // namespace gpugeom
