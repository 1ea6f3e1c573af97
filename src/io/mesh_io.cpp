// Triangle and tetrahedron meshes: .ply .off .obj .ele/.node .vtu .vtk .npy.
#include <algorithm>
#include <iterator>

#include "gpugeom/io.hpp"
#include "io/io_util.hpp"

namespace gpugeom::io {

std::size_t DataArray::count() const {
  return bytes.size() / scalar_size(type);
}

DataArray make_data_array(const std::string& name, ScalarType type, int components,
                          const void* data, std::size_t values) {
  DataArray a;
  a.name = name;
  a.type = type;
  a.components = components;
  const auto* p = static_cast<const unsigned char*>(data);
  a.bytes.assign(p, p + values * scalar_size(type));
  return a;
}
namespace detail {
PointSet parse_off_mesh(std::string_view b, const std::string& name, Mesh* m);
PointSet parse_obj_mesh(std::string_view b, const std::string& name, Mesh* m);
PointSet parse_node_file(std::string_view b, const std::string& name, int* base);
Mesh parse_vtu(std::string_view bytes, const std::string& name);  // (vtu.cpp)
Text format_vtu(const Mesh& m, bool binary, bool compress);
void write_vtu(const std::string& path, const Mesh& m, bool binary, bool compress);
Mesh parse_vtk(std::string_view bytes, const std::string& name);  // (vtk.cpp)
Text format_vtk(const Mesh& m, bool binary);
}  // namespace detail
using namespace detail;

namespace {

Mesh parse_ele(std::string_view b, const std::string& name, int base, std::int64_t nv) {
  Lines l(b, name);
  std::string_view line;
  if (!l.next(line)) l.fail("empty file: expected '<#cells> <nodes per cell> <#attributes>'");
  auto t = split(line);
  if (t.size() < 2) l.fail("expected '<#cells> <nodes per cell> <#attributes>'");
  std::int64_t nc = need_int(l, t[0], "the cell count"),
               k = need_int(l, t[1], "the nodes per cell");
  if (k != 3 && k != 4) l.fail("only triangles (3) and tetrahedra (4) are supported");
  if (nc < 0 || std::uint64_t(nc) > b.size()) l.fail("the cell count is out of range");
  Mesh m;
  m.cell_size = int(k);
  read_records(
      l, b, nc, m.cell_size, m.cells,
      [&](const Lines& part, std::string_view line, std::int64_t, std::int32_t* out) {
        Scan sc(line);
        std::int64_t idx, x[4];
        int j = 0;
        if (sc.next(idx))
          while (j < k && sc.next(x[j])) x[j] -= base, ++j;
        if (j == k && in_range(x, j, 0, nv < 0 ? INT32_MAX + std::int64_t(1) : nv)) {
          for (int q = 0; q < j; ++q) out[q] = std::int32_t(x[q]);
          return;
        }
        auto v = split(line);
        if (std::int64_t(v.size()) < 1 + k)
          part.fail("expected '<index>' and " + std::to_string(k) + " vertex indices");
        for (int j = 1; j <= k; ++j) {
          std::int64_t x = need_int(part, v[j], "a vertex index") - base;
          if (x < 0 || x > INT32_MAX || (nv >= 0 && x >= nv))
            part.fail("vertex index " + std::string(v[j]) + " is out of range");
          out[j - 1] = std::int32_t(x);
        }
      },
      [&](std::int64_t c) {
        return "file ends after " + std::to_string(c) + " of " + std::to_string(nc) + " cells";
      });
  return m;
}

Mesh parse_npy_cells(std::string_view b, const std::string& name) {
  NpyArray a = parse_npy(b, name);
  if (a.shape.size() != 2 || (a.shape[1] != 3 && a.shape[1] != 4) ||
      (a.descr[1] != 'i' && a.descr[1] != 'u'))
    parse_fail(name, 0, "expected an integer cell array of shape (N, 3) or (N, 4)");
  Mesh m;
  m.cell_size = int(a.shape[1]);
  const std::int64_t n = a.shape[0] * a.shape[1];
  m.cells.resize(std::size_t(n));
  for (std::int64_t i = 0; i < n; ++i) {
    double v = npy_value(a, i, name);
    if (v < 0 || v > 2147483647.0) parse_fail(name, 0, "cell index out of range");
    m.cells[i] = std::int32_t(v);
  }
  return m;
}

}  // namespace

Mesh parse_mesh(std::string_view b, const std::string& ext, const std::string& name) {
  Mesh m;
  if (ext == ".ply") {
    PlyData d = parse_ply(b, name);
    m.dim = d.dim;
    m.coords = std::move(d.coords);
    m.cell_size = d.cell_size ? d.cell_size : 3;
    m.cells = std::move(d.cells);
  } else if (ext == ".off" || ext == ".obj") {
    PointSet p = ext == ".off" ? parse_off_mesh(b, name, &m) : parse_obj_mesh(b, name, &m);
    m.dim = 3;
    m.coords = std::move(p.coords);
  } else if (ext == ".vtu") {
    m = parse_vtu(b, name);
  } else if (ext == ".vtk") {
    m = parse_vtk(b, name);
  } else if (ext == ".npy") {
    m = parse_npy_cells(b, name);
  } else if (ext == ".ele") {
    m = parse_ele(b, name, 0, -1);
  } else {
    throw Error(ErrorCode::InvalidArgument,
                name + ": unknown mesh format '" + ext +
                    "': expected .ply .off .obj .ele .vtu .vtk or .npy");
  }
  return m;
}

Mesh read_mesh(const std::string& path) {
  const std::string ext = extension(path);
  if (ext == ".ele") {
    int base = 0;
    const std::string node = sibling(path, ".node");
    PointSet p = parse_node_file(FileView(node).view(), node, &base);
    Mesh m = parse_ele(FileView(path).view(), path, base, std::int64_t(p.size()));
    m.dim = p.dim;
    m.coords = std::move(p.coords);
    return m;
  }
  static const char* const known[] = {".ply", ".off", ".obj", ".vtu", ".vtk", ".npy"};
  return parse_file(path, ext, known, &parse_mesh);
}

void write_mesh(const std::string& path, const Mesh& m, const WriteOptions& o) {
  const std::string ext = extension(path);
  if (m.cell_size != 3 && m.cell_size != 4)
    throw Error(ErrorCode::InvalidArgument, "cells must be triangles or tetrahedra");
  const std::size_t nv = m.num_vertices(), nc = m.num_cells();
  for (auto c : m.cells)
    if (c < 0 || (nv && std::size_t(c) >= nv))
      throw Error(ErrorCode::InvalidArgument, "a cell refers to a vertex that does not exist");
  Text out;
  if (ext == ".ply") {
    out = format_ply(m.coords.data(), m.dim, nv, m.cells.data(), m.cell_size, nc, o.binary);
  } else if (ext == ".off" || ext == ".obj") {
    if (m.cell_size != 3)
      throw Error(ErrorCode::InvalidArgument,
                  ext + " holds surfaces only: write tetrahedra as .vtu, .ele or .ply");
    const bool obj = ext == ".obj";
    if (!obj) out = "OFF\n" + std::to_string(nv) + " " + std::to_string(nc) + " 0\n";
    out += format_vertex_lines(m.coords.data(), m.dim, nv, obj ? "v " : "");
    out += format_cell_lines(m.cells.data(), 3, nc, obj ? "f" : "3", false, obj ? 1 : 0);
  } else if (ext == ".ele") {
    PointSet p;
    p.dim = m.dim;
    p.coords = m.coords;
    write_points(sibling(path, ".node"), p);
    out = std::to_string(nc) + " " + std::to_string(m.cell_size) + " 0\n";
    out += format_cell_lines(m.cells.data(), m.cell_size, nc, "", true, 0);
  } else if (ext == ".vtu") {
    write_vtu(path, m, o.binary, o.compress);  // (streamed to the file)
    return;
  } else if (ext == ".vtk") {
    out = format_vtk(m, o.binary);
  } else if (ext == ".msh") {
    out = format_msh(m);
  } else if (ext == ".npy") {
    out = format_npy("<i4", {std::int64_t(nc), m.cell_size}, m.cells.data(), m.cells.size() * 4);
  } else {
    throw Error(ErrorCode::InvalidArgument,
                path + ": unknown mesh format '" + ext +
                    "': expected .ply .off .obj .ele .vtu .vtk .msh (written only) or .npy");
  }
  write_file_atomic(path, out);
}

}  // namespace gpugeom::io
