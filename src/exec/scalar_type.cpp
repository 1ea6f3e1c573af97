// The element types of grids (gpugeom/scalar_type.hpp): in the core, which the grid
// capabilities need without the file readers.
#include "gpugeom/scalar_type.hpp"

#include "gpugeom/common.hpp"

namespace gpugeom {

std::size_t scalar_size(ScalarType t) {
  switch (t) {
    case ScalarType::Bool:
    case ScalarType::U8:
      return 1;
    case ScalarType::U16:
      return 2;
    case ScalarType::I32:
    case ScalarType::F32:
      return 4;
    default:
      return 8;
  }
}
const char* scalar_name(ScalarType t) {
  switch (t) {
    case ScalarType::Bool:
      return "bool";
    case ScalarType::U8:
      return "uint8";
    case ScalarType::U16:
      return "uint16";
    case ScalarType::I32:
      return "int32";
    case ScalarType::I64:
      return "int64";
    case ScalarType::F32:
      return "float32";
    default:
      return "float64";
  }
}
ScalarType parse_scalar(const std::string& s) {
  for (ScalarType t : {ScalarType::Bool, ScalarType::U8, ScalarType::U16, ScalarType::I32,
                       ScalarType::I64, ScalarType::F32, ScalarType::F64})
    if (s == scalar_name(t)) return t;
  throw Error(ErrorCode::InvalidArgument,
              "unknown element type '" + s +
                  "': expected bool, uint8, uint16, int32, int64, float32 or float64");
}

}  // namespace gpugeom
