// VTK legacy files (.vtk), unstructured grids of triangles or tetrahedra, as VTK, ParaView,
// meshio and most FEM codes write them.
//
// Written: version 4.2 (read by every VTK since 2000): BINARY (big-endian, as the format
// prescribes) by default, ASCII on request; POINTS as doubles, CELLS as counts and indices,
// CELL_TYPES, and the mesh's point and cell data as SCALARS (one array each, any number of
// components; names with blanks get '_').
// Read: ASCII and BINARY; the CELLS layout of versions up to 4.2 (a count before each cell) and
// of 5.1 (OFFSETS and CONNECTIVITY arrays); POINT_DATA / CELL_DATA SCALARS, VECTORS, NORMALS and
// FIELD arrays (kept as Mesh::point_data / cell_data with their types); METADATA blocks skipped.
// Every count read from the file is checked against the bytes that are left before anything is
// allocated for it, so a malformed file is a Parse error naming its line.
#include <algorithm>
#include <cstring>
#include <string>
#include <vector>

#include "gpugeom/io.hpp"
#include "exec/scalar_table.hpp"
#include "io/io_util.hpp"

namespace gpugeom::io::detail {

namespace {

struct VtkType {
  ScalarType as;  // how Mesh keeps it
  int bytes;
  char kind;  // 'i' signed, 'u' unsigned, 'f' float
  NumType num() const { return {bytes, kind}; }
};

bool vtk_type(std::string_view s, VtkType& t) {
  static const struct {
    const char* n;
    VtkType t;
  } m[] = {{"unsigned_char", {ScalarType::U8, 1, 'u'}},
           {"char", {ScalarType::I32, 1, 'i'}},
           {"unsigned_short", {ScalarType::U16, 2, 'u'}},
           {"short", {ScalarType::I32, 2, 'i'}},
           {"unsigned_int", {ScalarType::I64, 4, 'u'}},
           {"int", {ScalarType::I32, 4, 'i'}},
           {"unsigned_long", {ScalarType::I64, 8, 'u'}},
           {"long", {ScalarType::I64, 8, 'i'}},
           {"vtktypeuint64", {ScalarType::I64, 8, 'u'}},
           {"vtktypeint64", {ScalarType::I64, 8, 'i'}},
           {"vtkIdType", {ScalarType::I64, 8, 'i'}},
           {"float", {ScalarType::F32, 4, 'f'}},
           {"double", {ScalarType::F64, 8, 'f'}},
           // VTK 9's fixed-width names (meshio writes them too)
           {"vtktypeint8", {ScalarType::I32, 1, 'i'}},
           {"vtktypeuint8", {ScalarType::U8, 1, 'u'}},
           {"vtktypeint16", {ScalarType::I32, 2, 'i'}},
           {"vtktypeuint16", {ScalarType::U16, 2, 'u'}},
           {"vtktypeint32", {ScalarType::I32, 4, 'i'}},
           {"vtktypeuint32", {ScalarType::I64, 4, 'u'}},
           {"vtktypefloat32", {ScalarType::F32, 4, 'f'}},
           {"vtktypefloat64", {ScalarType::F64, 8, 'f'}}};
  for (const auto& e : m)
    if (s == e.n) return t = e.t, true;
  return false;
}

// A cursor over the file: header lines (blank lines skipped, line numbers kept), ASCII values
// as whitespace-separated tokens, BINARY values as big-endian blocks.
class Cursor {
 public:
  Cursor(std::string_view b, const std::string& name) : b_(b), name_(&name) {}
  [[noreturn]] void fail(const std::string& what) const { parse_fail(*name_, line_, what); }
  // The next non-blank line's tokens; false at the end of the file.
  bool line(Tokens& tok) {
    while (pos_ < b_.size()) {
      std::size_t e = b_.find('\n', pos_);
      if (e == std::string_view::npos) e = b_.size();
      const std::string_view l = b_.substr(pos_, e - pos_);
      pos_ = std::min(b_.size(), e + 1);
      ++line_;
      tok = split(l);
      if (!tok.empty()) return true;
    }
    return false;
  }
  std::string_view raw_line() {  // the next line as it is (the title); empty at the end
    if (pos_ >= b_.size()) return {};
    std::size_t e = b_.find('\n', pos_);
    if (e == std::string_view::npos) e = b_.size();
    const std::string_view l = b_.substr(pos_, e - pos_);
    pos_ = std::min(b_.size(), e + 1);
    ++line_;
    return l;
  }
  // n values of type t as doubles (exact for integers below 2^53 and every float).
  std::vector<double> values(std::uint64_t n, const VtkType& t, bool binary) {
    const std::size_t left = b_.size() - std::min(pos_, b_.size());
    if (n > (binary ? left / std::size_t(t.bytes) : left / 2 + 1))
      fail("the file ends before the " + std::to_string(n) + " values this section declares");
    std::vector<double> v(static_cast<std::size_t>(n));
    if (binary) {
      const auto* p = reinterpret_cast<const unsigned char*>(b_.data()) + pos_;
      visit_num(t.num(), [&](auto zero) {  // (BINARY legacy files are big-endian)
        using T = decltype(zero);
#pragma omp parallel for schedule(static) if (n > 65536)
        for (std::int64_t i = 0; i < std::int64_t(n); ++i)
          v[std::size_t(i)] = double(num_at<T>(p, std::size_t(i), true));
      });
      pos_ += std::size_t(n) * std::size_t(t.bytes);
      return v;
    }
    for (std::size_t i = 0; i < v.size(); ++i) {
      while (pos_ < b_.size() &&
             (b_[pos_] == ' ' || b_[pos_] == '\t' || b_[pos_] == '\r' || b_[pos_] == '\n')) {
        if (b_[pos_] == '\n') ++line_;
        ++pos_;
      }
      std::size_t e = pos_;
      while (e < b_.size() && !(b_[e] == ' ' || b_[e] == '\t' || b_[e] == '\r' || b_[e] == '\n'))
        ++e;
      if (e == pos_) fail("the file ends before the " + std::to_string(n) + " values declared");
      if (!to_double(b_.substr(pos_, e - pos_), v[i]))
        fail("expected a number, found '" + std::string(b_.substr(pos_, e - pos_)) + "'");
      pos_ = e;
    }
    // (the rest of the last value's line belongs to it)
    const std::size_t e = b_.find('\n', pos_);
    if (e != std::string_view::npos &&
        b_.substr(pos_, e - pos_).find_first_not_of(" \t\r") == std::string_view::npos)
      pos_ = e + 1, ++line_;
    return v;
  }

 private:
  std::string_view b_;
  const std::string* name_;
  std::size_t pos_ = 0;
  std::int64_t line_ = 0;
};

std::uint64_t count_of(Cursor& c, std::string_view s, const char* what) {
  std::int64_t v = 0;
  if (!to_int64(s, v) || v < 0)
    c.fail(std::string("expected ") + what + ", found '" + std::string(s) + "'");
  return std::uint64_t(v);
}

VtkType type_of(Cursor& c, std::string_view s) {
  VtkType t;
  if (!vtk_type(s, t)) c.fail("unsupported data type '" + std::string(s) + "'");
  return t;
}

DataArray as_array(Cursor& c, std::string name, const VtkType& t, int comps,
                   const std::vector<double>& v) {
  std::replace(name.begin(), name.end(), ' ', '_');
  DataArray a;
  if (!data_array_from(name, t.as, comps, v, a))
    c.fail("array '" + name + "' holds a value outside the range of its type");
  return a;
}

}  // namespace

Mesh parse_vtk(std::string_view bytes, const std::string& name) {
  Cursor c(bytes, name);
  Tokens t;
  if (!c.line(t) || t.size() < 4 || t[0] != "#" || t[1] != "vtk" || t[2] != "DataFile")
    c.fail("not a VTK legacy file: the first line must be '# vtk DataFile Version x.y'");
  (void)c.raw_line();  // the title
  if (!c.line(t) || (t[0] != "ASCII" && t[0] != "BINARY")) c.fail("expected ASCII or BINARY");
  const bool binary = t[0] == "BINARY";
  if (!c.line(t) || t.size() != 2 || t[0] != "DATASET")
    c.fail("expected 'DATASET UNSTRUCTURED_GRID'");
  if (t[1] != "UNSTRUCTURED_GRID")
    c.fail("only UNSTRUCTURED_GRID datasets hold meshes gpugeom reads (found " + std::string(t[1]) +
           ")");
  std::vector<double> xyz, conn, types;
  std::vector<std::int64_t> starts;  // first index of each cell in conn, plus the end
  bool have_points = false, have_cells = false;
  std::vector<DataArray> point_data, cell_data;
  std::vector<DataArray>* target = nullptr;
  std::uint64_t target_items = 0;
  while (c.line(t)) {
    const std::string_view k = t[0];
    if (k == "POINTS") {
      if (t.size() != 3) c.fail("expected 'POINTS n type'");
      const std::uint64_t n = count_of(c, t[1], "the point count");
      if (n > std::uint64_t(1) << 40) c.fail("the point count is out of range");
      xyz = c.values(3 * n, type_of(c, t[2]), binary);
      have_points = true;
    } else if (k == "CELLS") {
      if (t.size() != 3) c.fail("expected 'CELLS n size'");
      const std::uint64_t n = count_of(c, t[1], "the cell count"),
                          size = count_of(c, t[2], "the cell list size");
      Tokens u;
      // Version 5.1: OFFSETS (n values, the first 0) and CONNECTIVITY (size values) follow.
      Cursor probe = c;
      if (probe.line(u) && u[0] == "OFFSETS") {
        c = probe;
        if (u.size() != 2) c.fail("expected 'OFFSETS type'");
        const std::vector<double> off = c.values(n, type_of(c, u[1]), binary);
        if (!c.line(u) || u.size() != 2 || u[0] != "CONNECTIVITY")
          c.fail("expected 'CONNECTIVITY type' after the offsets");
        conn = c.values(size, type_of(c, u[1]), binary);
        starts.assign(off.size(), 0);
        for (std::size_t i = 0; i < off.size(); ++i) {
          if (!(off[i] >= 0 && off[i] <= double(size) && (i == 0 || off[i] >= off[i - 1])))
            c.fail("the cell offsets are not increasing within the connectivity");
          starts[i] = std::int64_t(off[i]);
        }
        if (starts.empty() || starts[0] != 0 || starts.back() != std::int64_t(size))
          c.fail("the cell offsets must run from 0 to the connectivity size");
      } else {  // up to 4.2: each cell is its count and its indices
        VtkType i32;
        vtk_type("int", i32);
        const std::vector<double> list = c.values(size, i32, binary);
        conn.clear();
        starts.assign(1, 0);
        std::size_t at = 0;
        for (std::uint64_t i = 0; i < n; ++i) {
          if (at >= list.size())
            c.fail("the cell list ends before its " + std::to_string(n) + " cells");
          const double cnt = list[at];
          if (!(cnt >= 1 && cnt <= 64) || at + 1 + std::size_t(cnt) > list.size())
            c.fail("cell " + std::to_string(i) + " has a bad vertex count");
          conn.insert(conn.end(), list.begin() + std::ptrdiff_t(at + 1),
                      list.begin() + std::ptrdiff_t(at + 1 + std::size_t(cnt)));
          at += 1 + std::size_t(cnt);
          starts.push_back(std::int64_t(conn.size()));
        }
        if (at != list.size()) c.fail("the cell list is longer than its cells");
      }
      have_cells = true;
    } else if (k == "CELL_TYPES") {
      if (t.size() != 2) c.fail("expected 'CELL_TYPES n'");
      VtkType i32;
      vtk_type("int", i32);
      types = c.values(count_of(c, t[1], "the cell count"), i32, binary);
    } else if (k == "POINT_DATA" || k == "CELL_DATA") {
      if (t.size() != 2) c.fail("expected '" + std::string(k) + " n'");
      target = k == "POINT_DATA" ? &point_data : &cell_data;
      target_items = count_of(c, t[1], "the item count");
      const std::uint64_t want = k == "POINT_DATA" ? xyz.size() / 3 : types.size();
      if (target_items != want)
        c.fail(std::string(k) + " counts " + std::to_string(target_items) +
               " items; the mesh has " + std::to_string(want));
    } else if (k == "SCALARS" || k == "VECTORS" || k == "NORMALS") {
      if (!target) c.fail(std::string(k) + " outside POINT_DATA or CELL_DATA");
      if (t.size() < 3) c.fail("expected '" + std::string(k) + " name type'");
      int comps = k == "SCALARS" ? 1 : 3;
      if (k == "SCALARS" && t.size() > 3) {
        const std::uint64_t nc = count_of(c, t[3], "the component count");
        if (nc < 1 || nc > 4) c.fail("SCALARS have 1 to 4 components");
        comps = int(nc);
      }
      const VtkType ty = type_of(c, t[2]);
      if (k == "SCALARS") {  // a LOOKUP_TABLE line may follow
        Cursor probe = c;
        Tokens u;
        if (probe.line(u) && u[0] == "LOOKUP_TABLE") c = probe;
      }
      target->push_back(as_array(c, std::string(t[1]), ty, comps,
                                 c.values(target_items * std::uint64_t(comps), ty, binary)));
    } else if (k == "FIELD") {
      if (!target) c.fail("FIELD outside POINT_DATA or CELL_DATA");
      if (t.size() != 3) c.fail("expected 'FIELD name n'");
      const std::uint64_t arrays = count_of(c, t[2], "the array count");
      for (std::uint64_t a = 0; a < arrays; ++a) {
        Tokens u;
        if (!c.line(u) || u.size() != 4) c.fail("expected 'name components tuples type'");
        const std::uint64_t comps = count_of(c, u[1], "the component count"),
                            tuples = count_of(c, u[2], "the tuple count");
        if (comps < 1 || comps > 1024 || tuples != target_items)
          c.fail("field array '" + std::string(u[0]) + "' does not match its " +
                 std::to_string(target_items) + " items");
        const VtkType ty = type_of(c, u[3]);
        target->push_back(
            as_array(c, std::string(u[0]), ty, int(comps), c.values(comps * tuples, ty, binary)));
      }
    } else if (k == "METADATA") {  // (VTK 9: information keys, up to a blank line)
      std::string_view l;
      do l = c.raw_line();
      while (!l.empty() && l.find_first_not_of(" \t\r") != std::string_view::npos);
    } else {
      c.fail("unsupported section '" + std::string(k) + "'");
    }
  }
  if (!have_points) c.fail("no POINTS section");
  if (!have_cells) c.fail("no CELLS section");
  const std::size_t nc = starts.size() - 1, nv = xyz.size() / 3;
  if (types.size() != nc) c.fail("CELL_TYPES and CELLS differ in length");
  Mesh m;
  m.cell_size = nc && types[0] == 10 ? 4 : 3;
  for (std::size_t i = 0; i < nc; ++i) {
    if (types[i] != (m.cell_size == 3 ? 5 : 10))
      c.fail("mixed or unsupported VTK cell types (expected all 5 or all 10)");
    if (starts[i + 1] - starts[i] != m.cell_size)
      c.fail("cell " + std::to_string(i) + " does not have " + std::to_string(m.cell_size) +
             " vertices");
  }
  m.cells.resize(conn.size());
  for (std::size_t i = 0; i < conn.size(); ++i) {
    if (!(conn[i] >= 0 && conn[i] < double(nv)) || conn[i] != double(std::int64_t(conn[i])))
      c.fail("a cell refers to a missing point");
    m.cells[i] = std::int32_t(conn[i]);
  }
  bool flat = m.cell_size == 3;
  for (std::size_t i = 0; flat && i < nv; ++i) flat = xyz[3 * i + 2] == 0.0;
  m.dim = flat ? 2 : 3;
  m.coords.resize(nv * std::size_t(m.dim));
  for (std::size_t i = 0; i < nv; ++i)
    for (int d = 0; d < m.dim; ++d)
      m.coords[i * std::size_t(m.dim) + std::size_t(d)] = xyz[3 * i + std::size_t(d)];
  m.point_data = std::move(point_data);
  m.cell_data = std::move(cell_data);
  return m;
}

namespace {

// n little-endian values of w bytes each, as big-endian bytes (BINARY legacy files).
void put_big_endian(Text& out, const void* data, std::size_t n, std::size_t w) {
  std::string b(n * w, '\0');
  const auto* p = static_cast<const unsigned char*>(data);
  char* o = b.data();
#pragma omp parallel for schedule(static) if (n > 65536)
  for (std::int64_t i = 0; i < std::int64_t(n); ++i)
    for (std::size_t k = 0; k < w; ++k)
      o[std::size_t(i) * w + k] = char(p[std::size_t(i) * w + w - 1 - k]);
  out += std::move(b);
  out += '\n';
}

// The values of a data array as text, `per` to a line.
void put_text(Text& out, const DataArray& d, std::size_t per) {
  const std::size_t n = d.count();
  out += format_lines((n + per - 1) / per, per * 24, [&](std::size_t line, std::string& o) {
    for (std::size_t i = line * per; i < std::min(n, (line + 1) * per); ++i) {
      if (i > line * per) o += ' ';
      append_value(o, d, i);
    }
    o += '\n';
  });
}

}  // namespace

Text format_vtk(const Mesh& m, bool binary) {
  const std::size_t nv = m.num_vertices(), nc = m.num_cells(), k = std::size_t(m.cell_size);
  auto check = [&](const std::vector<DataArray>& v, std::size_t items, const char* what) {
    for (const DataArray& d : v)
      if (d.components < 1 || d.components > 4 || d.count() != items * std::size_t(d.components))
        throw Error(ErrorCode::InvalidArgument,
                    std::string(what) + " array '" + d.name + "' holds " +
                        std::to_string(d.count()) + " values; the mesh needs " +
                        std::to_string(items) + " x " + std::to_string(d.components) +
                        " (1 to 4 components in a .vtk file)");
  };
  check(m.point_data, nv, "point data");
  check(m.cell_data, nc, "cell data");
  Text o = "# vtk DataFile Version 4.2\ngpugeom\n";
  o += binary ? "BINARY\n" : "ASCII\n";
  o += "DATASET UNSTRUCTURED_GRID\nPOINTS " + std::to_string(nv) + " double\n";
  std::vector<double> xyz(3 * nv, 0.0);
  for (std::size_t i = 0; i < nv; ++i)
    for (int d = 0; d < m.dim && d < 3; ++d)
      xyz[3 * i + std::size_t(d)] = m.coords[i * std::size_t(m.dim) + std::size_t(d)];
  std::vector<std::int32_t> list(nc * (k + 1));
  for (std::size_t c = 0; c < nc; ++c) {
    list[c * (k + 1)] = std::int32_t(k);
    for (std::size_t j = 0; j < k; ++j) list[c * (k + 1) + 1 + j] = m.cells[c * k + j];
  }
  const std::vector<std::int32_t> types(nc, k == 3 ? 5 : 10);
  if (binary) {
    put_big_endian(o, xyz.data(), xyz.size(), 8);
    o += "CELLS " + std::to_string(nc) + " " + std::to_string(list.size()) + "\n";
    put_big_endian(o, list.data(), list.size(), 4);
    o += "CELL_TYPES " + std::to_string(nc) + "\n";
    put_big_endian(o, types.data(), types.size(), 4);
  } else {
    o += format_vertex_lines(xyz.data(), 3, nv, "");
    o += "CELLS " + std::to_string(nc) + " " + std::to_string(list.size()) + "\n";
    o += format_cell_lines(m.cells.data(), m.cell_size, nc, k == 3 ? "3" : "4", false, 0);
    o += "CELL_TYPES " + std::to_string(nc) + "\n";
    o += format_lines(nc, 3, [&](std::size_t, std::string& s) { s += k == 3 ? "5\n" : "10\n"; });
  }
  for (int sec = 0; sec < 2; ++sec) {
    const auto& arrays = sec == 0 ? m.point_data : m.cell_data;
    if (arrays.empty()) continue;
    o += (sec == 0 ? "POINT_DATA " + std::to_string(nv) : "CELL_DATA " + std::to_string(nc)) + "\n";
    for (const DataArray& d : arrays) {
      std::string nm = d.name.empty() ? "data" : d.name;
      std::replace(nm.begin(), nm.end(), ' ', '_');
      o += "SCALARS " + nm + " " + scalar_info(d.type).vtk_legacy + " " +
           std::to_string(d.components) + "\nLOOKUP_TABLE default\n";
      if (binary)
        put_big_endian(o, d.bytes.data(), d.count(), scalar_size(d.type));
      else
        put_text(o, d, std::size_t(d.components));
    }
  }
  return o;
}

}  // namespace gpugeom::io::detail
