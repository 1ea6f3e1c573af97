/// @file
/// Reading and writing the files users already have. Formats are chosen by extension.
///
/// Points in:  .xyz .txt .csv (2 or 3 numeric columns), .ply (ascii / binary little / big
///             endian), .off, .obj (v lines), .node (Triangle/TetGen), .npy (float32/float64,
///             N x 2 or N x 3).
/// Meshes out: .ply, .off, .obj, .ele (+ .node beside it), .vtk (legacy VTK 4.2, binary or
///             ascii; read: ascii and binary, 4.x and 5.1 cell layouts), .vtu (VTK XML, ParaView:
///             raw appended binary, optionally zlib-compressed, or ascii), .npy (the cell array
///             only, int32 N x 3 or N x 4), .msh (Gmsh 2.2 ascii, written only: region tags from
///             an integer cell array "attribute"). The others read back; .vtu in every encoding
///             VTK writes (ascii, inline base64, appended raw or base64; zlib or not; 32- or
///             64-bit headers; either byte order), with the point and cell data arrays a
///             mesh carries (Mesh::point_data, cell_data; the delaunay commands attach the
///             duplicate map).
/// Grids:      .pgm/.pbm (P1/P2/P4/P5, 8/16-bit), .png (8/16-bit grey; colour is converted to
///             luminance), .npy (2D/3D, bool/uint8/uint16/int32/int64/float32/float64), raw
///             (shape and type given by the caller).
///
/// Every parse error is an Error(Parse) naming the file, the line (text formats) and what was
/// expected. Writers go to a temporary file in the same folder, renamed over the target only
/// once complete, so a failure never leaves a half-written file.
#pragma once
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "gpugeom/common.hpp"
#include "gpugeom/grid_view.hpp"
#include "gpugeom/scalar_type.hpp"
#include "gpugeom/host_vector.hpp"

namespace gpugeom::io {

/// Coordinates and cells come in HostVectors (host_vector.hpp), as the library's results do: a
/// reader sizes them without a fill and its threads write (and so fault in) their own parts.
struct PointSet {
  int dim = 3;                ///< 2 or 3
  HostVector<double> coords;  ///< dim values per point
  /// The number of points.
  std::size_t size() const { return dim ? coords.size() / dim : 0; }
};

/// Values attached to a mesh's vertices (point data) or cells (cell data), as VTK files carry
/// them: `components` values per vertex or cell, of `type`, native byte order. .vtu writes and
/// reads them in every encoding (ParaView shows them by name); the other formats have no place
/// for them and leave them out. Read back, an array keeps its VTK type where a ScalarType has it
/// (Int8/Int16/UInt32 widen to int32/int64; UInt64 is read as int64).
struct DataArray {
  std::string name;
  ScalarType type = ScalarType::F64;
  int components = 1;
  std::vector<unsigned char> bytes;
  std::size_t count() const;  ///< values: bytes / scalar_size(type)
};
/// A data array holding `values` elements of `type` copied from `data`.
DataArray make_data_array(const std::string& name, ScalarType type, int components,
                          const void* data, std::size_t values);

/// A mesh read from or written to a file: vertex coordinates, cells of one size, optional point and
/// cell data.
struct Mesh {
  int dim = 3;                ///< coordinates per vertex (2 or 3)
  HostVector<double> coords;  ///< dim per vertex; may be empty for a cells-only .npy
  int cell_size = 3;          ///< 3: triangles, 4: tetrahedra
  HostVector<std::int32_t> cells;
  /// Optional arrays (.vtu): point_data of num_vertices() x components values each, cell_data of
  /// num_cells() x components; other lengths are refused when written (Error(InvalidArgument)).
  std::vector<DataArray> point_data, cell_data;
  /// The number of vertices.
  std::size_t num_vertices() const { return dim ? coords.size() / dim : 0; }
  /// The number of cells.
  std::size_t num_cells() const { return cell_size ? cells.size() / cell_size : 0; }
};

/// A grid read from or written to a file (.npy, .png, .pgm, raw): its shape, element type and
/// bytes.
struct Grid {
  std::vector<std::int64_t> shape;  ///< C order: (rows, cols) or (slices, rows, cols)
  ScalarType type = ScalarType::U8;
  std::vector<unsigned char> data;  ///< native byte order
  /// The number of elements.
  std::int64_t count() const;
  double value(std::int64_t i) const;  ///< element i as a double
};

/// How a file is written: binary or text, compressed or not.
struct WriteOptions {
  bool binary = true;     ///< PLY: binary little endian, or ascii; VTU: raw appended, or ascii
  bool compress = false;  ///< VTU: zlib-compressed blocks (binary only)
};

/// Reads a point file; the format from the extension (.xyz .txt .csv .ply .off .obj .node .npy).
PointSet read_points(const std::string& path);
/// Writes points; the format from the extension; atomically (a temporary file renamed).
void write_points(const std::string& path, const PointSet& pts, const WriteOptions& o = {});

/// Reads a mesh file (.ply .off .obj .ele .vtk .vtu .npy).
Mesh read_mesh(const std::string& path);
/// Writes a mesh; the format from the extension (.ply .off .obj .ele .vtk .vtu .msh .npy);
/// atomically.
void write_mesh(const std::string& path, const Mesh& mesh, const WriteOptions& o = {});

/// A planar straight-line graph as Triangle's .poly file holds it (2D): the points (from the
/// .node file of the same name where the .poly lists none), segments as pairs of point indices
/// counted from 0 whatever the file's first index, hole points (x, y) and regional attributes
/// (x, y, attribute) with each region's maximum area in region_areas (0 where the file gives
/// none). Boundary markers and point attributes are read and ignored.
struct Pslg {
  PointSet points;
  std::vector<std::int32_t> segments;
  std::vector<double> holes, regions;
  std::vector<double> region_areas;  ///< one per region (refine2d's per-region bound)
};
/// Reads Triangle's .poly file (and its .node where the .poly lists no points).
Pslg read_poly(const std::string& path);
/// Writes g as a .poly file (points inline, indices from 0); markers, when given, one boundary
/// marker per segment.
void write_poly(const std::string& path, const Pslg& g, const std::int32_t* markers = nullptr);
/// Segments as an int (m, 2) .npy of point indices (from 0).
std::vector<std::int32_t> read_segments(const std::string& path);

/// Reads a grid (.npy, .png, .pgm/.pbm).
Grid read_grid(const std::string& path);
/// Raw files carry no header: the caller says the shape and the element type.
Grid read_raw_grid(const std::string& path, const std::vector<std::int64_t>& shape,
                   ScalarType type);
/// Writes a grid (.npy, .png, .pgm); atomically.
void write_grid(const std::string& path, const Grid& grid);
/// An 8-bit RGB PNG (rgb: rows * cols * 3 bytes), for previews a person looks at.
void write_png_rgb(const std::string& path, std::int64_t rows, std::int64_t cols,
                   const std::vector<unsigned char>& rgb);

/// Any text (an SVG drawing, a report), written atomically like every other output.
void write_text(const std::string& path, const std::string& text);

/// Parsers over memory, for fuzzing and tests: name is used in messages, ext picks the format.
PointSet parse_points(std::string_view bytes, const std::string& ext, const std::string& name);
/// A mesh file's bytes (as read_mesh reads the file).
Mesh parse_mesh(std::string_view bytes, const std::string& ext, const std::string& name);
/// A grid file's bytes (as read_grid reads the file).
Grid parse_grid(const std::string& bytes, const std::string& ext, const std::string& name);
/// A .poly file's text; name is its path (a .node beside it is read where it lists no points).
Pslg parse_poly(std::string_view text, const std::string& name);

/// A view of a grid read from a file (no copy), for the grid capabilities. Throws
/// Error(InvalidArgument) when its data does not hold the bytes its shape and type need.
GridView view_of(const Grid& g);

/// Lower-case extension with the dot, e.g. ".ply".
std::string extension(const std::string& path);

}  // namespace gpugeom::io
