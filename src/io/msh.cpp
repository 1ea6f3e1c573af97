// Gmsh's MSH 2.2 ASCII format, written (the oldest version every Gmsh and meshio reads): the
// vertices as nodes (2D points with z = 0), the cells as triangles (element type 2) or
// tetrahedra (type 4), numbered from 1. Each element's two tags (physical group, elementary
// entity) are its region: a one-component cell array named "attribute" whose values are all
// integers (refine2d's regions, for instance), else 1 for every cell.
#include <cmath>
#include <string>

#include "gpugeom/io.hpp"
#include "io/io_util.hpp"

namespace gpugeom::io::detail {

Text format_msh(const Mesh& m) {
  const std::size_t nv = m.num_vertices(), nc = m.num_cells(), dm = std::size_t(m.dim);
  const std::size_t k = std::size_t(m.cell_size);
  // The region tags, when the attribute array holds integers that fit a tag.
  const double* attr = nullptr;
  for (const DataArray& d : m.cell_data)
    if (d.name == "attribute" && d.type == ScalarType::F64 && d.components == 1 && d.count() == nc)
      attr = reinterpret_cast<const double*>(d.bytes.data());
  for (std::size_t c = 0; attr && c < nc; ++c)
    if (!(std::floor(attr[c]) == attr[c] && std::fabs(attr[c]) < 2147483647.0)) attr = nullptr;
  Text out = "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n" + std::to_string(nv) + "\n";
  out += format_lines(nv, 80, [&](std::size_t i, std::string& o) {
    append_int(o, std::int64_t(i) + 1);
    for (std::size_t d = 0; d < 3; ++d) {
      o += ' ';
      append_double(o, d < dm ? m.coords[i * dm + d] : 0.0);
    }
    o += '\n';
  });
  out += "$EndNodes\n$Elements\n" + std::to_string(nc) + "\n";
  const char* type = k == 3 ? " 2 2 " : " 4 2 ";
  out += format_lines(nc, 12 * k + 40, [&](std::size_t c, std::string& o) {
    append_int(o, std::int64_t(c) + 1);
    o += type;
    const std::int64_t tag = attr ? std::int64_t(attr[c]) : 1;
    append_int(o, tag);
    o += ' ';
    append_int(o, tag);
    for (std::size_t j = 0; j < k; ++j) {
      o += ' ';
      append_int(o, std::int64_t(m.cells[c * k + j]) + 1);
    }
    o += '\n';
  });
  out += "$EndElements\n";
  return out;
}

}  // namespace gpugeom::io::detail
