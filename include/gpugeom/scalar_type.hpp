/// @file
/// Element types of grids (GridView, io::Grid) and data arrays: part of the core, so that the
/// grid capabilities need nothing of the file readers (gpugeom_io).
#pragma once
#include <cstddef>
#include <string>

namespace gpugeom {

/// Element types of grids and data arrays, as NumPy names them: bool, uint8, uint16, int32,
/// int64, float32, float64.
enum class ScalarType { Bool, U8, U16, I32, I64, F32, F64 };
/// Bytes per element of the type.
std::size_t scalar_size(ScalarType t);
/// NumPy's name of the type: "bool", "uint8", ..., "float64".
const char* scalar_name(ScalarType t);
/// The type of a NumPy name ("uint8", "float32", ...); throws Error(InvalidArgument) otherwise.
ScalarType parse_scalar(const std::string& name);

namespace io {
// The names files and grids have used since the types lived in io.hpp.
using gpugeom::parse_scalar;
using gpugeom::scalar_name;
using gpugeom::scalar_size;
using gpugeom::ScalarType;
}  // namespace io

}  // namespace gpugeom
