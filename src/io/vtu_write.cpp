// VTK XML unstructured grids (.vtu), as ParaView and VTK read them: the writer. (The reader
// is vtu_read.cpp, with what every encoding means.)
// Written: raw appended binary (header_type UInt64), optionally zlib-compressed in blocks of
// 1 MiB (compressed on all host threads, blocks being independent), or ascii on request.
#include <zlib.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

#include "gpugeom/io.hpp"
#include "exec/scalar_table.hpp"
#include "io/io_util.hpp"

namespace gpugeom::io::detail {

namespace {

// Appends one array's bytes as an appended block: UInt64 length and the bytes, or zlib blocks
// of kBlock bytes with their header (blocks compressed in parallel).
constexpr std::size_t kBlock = std::size_t(1) << 20;
// zlib's fastest level: on a triangulation of 10^6 points 2.4 times faster than its default and
// 4 % larger (the coordinates hardly compress at any level; the index arrays compress well at
// every level).
constexpr int kLevel = 1;

void put_u64(std::string& out, std::uint64_t v) {
  char b[8];
  std::memcpy(b, &v, 8);  // (little-endian hosts only: the file says LittleEndian)
  out.append(b, 8);
}

void append_block(std::string& out, const void* data, std::size_t n, bool compress) {
  const char* p = static_cast<const char*>(data);
  if (!compress) {
    put_u64(out, n);
    out.append(p, n);
    return;
  }
  const std::size_t nb = (n + kBlock - 1) / kBlock;
  std::vector<std::string> blocks(nb);
  std::int64_t failed = 0;
#pragma omp parallel for schedule(dynamic, 1) reduction(+ : failed)
  for (std::int64_t i = 0; i < std::int64_t(nb); ++i) {
    const std::size_t len = std::min(kBlock, n - std::size_t(i) * kBlock);
    uLongf cap = compressBound(uLong(len));
    std::string& b = blocks[std::size_t(i)];
    b.resize(cap);
    if (compress2(reinterpret_cast<Bytef*>(&b[0]), &cap,
                  reinterpret_cast<const Bytef*>(p + std::size_t(i) * kBlock), uLong(len),
                  kLevel) != Z_OK)
      ++failed;
    b.resize(cap);
  }
  if (failed) throw Error(ErrorCode::Internal, "zlib failed to compress a VTU block");
  put_u64(out, nb);
  put_u64(out, kBlock);
  put_u64(out, nb ? n - (nb - 1) * kBlock : 0);
  for (const auto& b : blocks) put_u64(out, b.size());
  for (const auto& b : blocks) out += b;
}

// The four arrays of a mesh as VTU stores them (Points as 3 doubles, connectivity, offsets,
// types), each written in ranges of items so that a writer can stream it in small pieces.
class VtuArrays {
 public:
  explicit VtuArrays(const Mesh& m)
      : m_(m),
        nv_(m.num_vertices()),
        nc_(m.num_cells()),
        k_(std::size_t(m.cell_size)),
        wide_(nc_ * k_ > std::size_t(INT32_MAX)) {
    auto take = [&](const std::vector<DataArray>& v, std::size_t items, const char* what) {
      for (const DataArray& d : v) {
        if (d.components < 1 || d.count() != items * std::size_t(d.components) ||
            d.bytes.size() % scalar_size(d.type))
          throw Error(ErrorCode::InvalidArgument,
                      std::string(what) + " array '" + d.name + "' holds " +
                          std::to_string(d.count()) + " values; the mesh needs " +
                          std::to_string(items) + " x " + std::to_string(d.components));
        extra_.push_back(&d);
      }
    };
    take(m.point_data, nv_, "point data");
    num_point_data_ = extra_.size();
    take(m.cell_data, nc_, "cell data");
  }
  bool wide() const { return wide_; }  // offsets need 64 bits
  // Arrays: 0 Points, 1 connectivity, 2 offsets, 3 types, then point data, then cell data.
  int count() const { return 4 + int(extra_.size()); }
  const DataArray* extra(int a) const { return a < 4 ? nullptr : extra_[std::size_t(a - 4)]; }
  bool is_point_data(int a) const { return a >= 4 && std::size_t(a - 4) < num_point_data_; }
  std::size_t items(int a) const {
    return a == 0 ? nv_ : a == 1 ? nc_ * k_ : a < 4 ? nc_ : extra(a)->count();
  }
  std::size_t item_bytes(int a) const {
    return a == 0   ? 24
           : a == 1 ? 4
           : a == 2 ? (wide_ ? 8 : 4)
           : a == 3 ? 1
                    : scalar_size(extra(a)->type);
  }
  std::size_t bytes(int a) const { return items(a) * item_bytes(a); }
  // Items [first, first + count) of array a into d.
  void fill(int a, char* d, std::size_t first, std::size_t count) const {
    if (a >= 4) {
      const std::size_t w = item_bytes(a);
      std::memcpy(d, extra(a)->bytes.data() + first * w, count * w);
      return;
    }
    if (a == 0) {
      if (m_.dim == 3) {
        std::memcpy(d, m_.coords.data() + 3 * first, 24 * count);
        return;
      }
      for (std::size_t i = 0; i < count; ++i) {
        const std::size_t v = (first + i) * std::size_t(m_.dim);
        const double x[3] = {m_.coords[v], m_.dim > 1 ? m_.coords[v + 1] : 0.0, 0.0};
        std::memcpy(d + 24 * i, x, 24);
      }
    } else if (a == 1) {
      std::memcpy(d, m_.cells.data() + first, 4 * count);
    } else if (a == 2) {
      for (std::size_t c = 0; c < count; ++c) {
        const std::int64_t v = std::int64_t((first + c + 1) * k_);
        if (wide_) {
          std::memcpy(d + 8 * c, &v, 8);
        } else {
          const std::int32_t w = std::int32_t(v);
          std::memcpy(d + 4 * c, &w, 4);
        }
      }
    } else {
      std::memset(d, k_ == 3 ? 5 : 10, count);
    }
  }

 private:
  const Mesh& m_;
  std::size_t nv_, nc_, k_;
  bool wide_;
  std::vector<const DataArray*> extra_;
  std::size_t num_point_data_ = 0;
};

// The opening tag of a data array's DataArray element (no closing '>').
std::string data_array_tag(const DataArray& d) {
  return "<DataArray type=\"" + std::string(scalar_info(d.type).vtk_xml) + "\" Name=\"" + d.name +
         "\" NumberOfComponents=\"" + std::to_string(d.components) + "\"";
}

constexpr char kVtuTail[] = "\n</AppendedData>\n</VTKFile>\n";

// The DataArray elements of the appended arrays at byte offsets at[0..], up to the '_' that
// starts the appended data.
std::string appended_xml(const VtuArrays& A, const std::vector<std::size_t>& at) {
  std::string o;
  for (int sec = 0; sec < 2; ++sec) {  // PointData, CellData (before Points, as VTK has them)
    std::string arrays;
    for (int a = 4; a < A.count(); ++a)
      if (A.is_point_data(a) == (sec == 0))
        arrays += data_array_tag(*A.extra(a)) + " format=\"appended\" offset=\"" +
                  std::to_string(at[std::size_t(a)]) + "\"/>\n";
    if (!arrays.empty())
      o += (sec == 0 ? "<PointData>\n" : "<CellData>\n") + arrays +
           (sec == 0 ? "</PointData>\n" : "</CellData>\n");
  }
  o += "<Points>\n<DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"appended\" "
       "offset=\"" +
       std::to_string(at[0]) + "\"/>\n</Points>\n<Cells>\n";
  o += "<DataArray type=\"Int32\" Name=\"connectivity\" format=\"appended\" offset=\"" +
       std::to_string(at[1]) + "\"/>\n";
  o += std::string("<DataArray type=\"") + (A.wide() ? "Int64" : "Int32") +
       "\" Name=\"offsets\" format=\"appended\" offset=\"" + std::to_string(at[2]) + "\"/>\n";
  o += "<DataArray type=\"UInt8\" Name=\"types\" format=\"appended\" offset=\"" +
       std::to_string(at[3]) + "\"/>\n";
  o += "</Cells>\n</Piece>\n</UnstructuredGrid>\n<AppendedData encoding=\"raw\">\n_";
  return o;
}

std::string vtu_head(const Mesh& m, bool binary, bool compress) {
  std::string head =
      "<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" "
      "byte_order=\"LittleEndian\"";
  if (binary) head += " header_type=\"UInt64\"";
  if (binary && compress) head += " compressor=\"vtkZLibDataCompressor\"";
  head += ">\n<UnstructuredGrid>\n<Piece NumberOfPoints=\"" + std::to_string(m.num_vertices()) +
          "\" NumberOfCells=\"" + std::to_string(m.num_cells()) + "\">\n";
  return head;
}

}  // namespace

Text format_vtu(const Mesh& m, bool binary, bool compress);

// Raw appended binary, streamed to the file in pieces of at most 1 MiB: no copy of the mesh
// in memory, the arrays go from the caller's vectors to the file.
void write_vtu(const std::string& path, const Mesh& m, bool binary, bool compress) {
  if (!binary || compress) {
    write_file_atomic(path, format_vtu(m, binary, compress));
    return;
  }
  const VtuArrays arrays(m);
  std::vector<std::size_t> at(std::size_t(arrays.count()) + 1, 0);
  for (int i = 0; i < arrays.count(); ++i)
    at[std::size_t(i) + 1] = at[std::size_t(i)] + 8 + arrays.bytes(i);
  AtomicFile f(path);
  f.write(vtu_head(m, true, false) + appended_xml(arrays, at));
  // Pieces of 8 MiB, each filled on all host threads (padding 2D points, making offsets) and
  // then written: the write, the page cache's copy, is what remains serial.
  std::vector<char> buf(std::size_t(8) << 20);
  const std::int64_t nt = host_threads();
  for (int i = 0; i < arrays.count(); ++i) {
    const std::uint64_t n = arrays.bytes(i);
    f.write(&n, 8);  // (little-endian hosts only: the file says LittleEndian)
    const std::size_t w = arrays.item_bytes(i), per = buf.size() / w, items = arrays.items(i);
    for (std::size_t first = 0; first < items; first += per) {
      const std::size_t count = std::min(per, items - first);
#pragma omp parallel for schedule(static, 1) if (count > 65536)
      for (std::int64_t t = 0; t < nt; ++t) {
        const std::size_t lo = std::size_t(t) * count / std::size_t(nt),
                          hi = std::size_t(t + 1) * count / std::size_t(nt);
        if (hi > lo) arrays.fill(i, buf.data() + lo * w, first + lo, hi - lo);
      }
      f.write(buf.data(), count * w);
    }
  }
  f.write(kVtuTail, sizeof kVtuTail - 1);
  f.commit();
}

Text format_vtu(const Mesh& m, bool binary, bool compress) {
  const std::size_t nv = m.num_vertices(), nc = m.num_cells();
  const std::size_t k = std::size_t(m.cell_size), dim = std::size_t(m.dim);
  const std::string head = vtu_head(m, binary, compress);
  const bool wide = nc * k > std::size_t(INT32_MAX);  // offsets need 64 bits
  if (!binary) {                // (every section formatted on all host threads)
    const VtuArrays arrays(m);  // (checks the data arrays' lengths)
    Text o = head;
    for (int sec = 0; sec < 2; ++sec) {
      const auto& list = sec == 0 ? m.point_data : m.cell_data;
      if (list.empty()) continue;
      o += sec == 0 ? "<PointData>\n" : "<CellData>\n";
      for (const DataArray& d : list) {
        o += data_array_tag(d) + " format=\"ascii\">\n";
        const std::size_t per = std::size_t(d.components);
        o += format_lines(d.count() / per, per * 24, [&](std::size_t r, std::string& s) {
          for (std::size_t j = 0; j < per; ++j) {
            if (j) s += ' ';
            append_value(s, d, r * per + j);
          }
          s += '\n';
        });
        o += "</DataArray>\n";
      }
      o += sec == 0 ? "</PointData>\n" : "</CellData>\n";
    }
    o += "<Points>\n<DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">\n";
    o += format_lines(nv, 72, [&](std::size_t i, std::string& s) {
      for (std::size_t d = 0; d < 3; ++d) {
        if (d) s += ' ';
        append_double(s, d < dim ? m.coords[i * dim + d] : 0.0);
      }
      s += '\n';
    });
    o += "</DataArray>\n</Points>\n<Cells>\n<DataArray type=\"Int32\" Name=\"connectivity\" "
         "format=\"ascii\">\n";
    o += format_lines(nc, 12 * k, [&](std::size_t c, std::string& s) {
      for (std::size_t j = 0; j < k; ++j) {
        if (j) s += ' ';
        append_int(s, m.cells[c * k + j]);
      }
      s += '\n';
    });
    o += std::string("</DataArray>\n<DataArray type=\"") + (wide ? "Int64" : "Int32") +
         "\" Name=\"offsets\" format=\"ascii\">\n";
    o += format_lines(nc, 12, [&](std::size_t c, std::string& s) {
      append_int(s, std::int64_t((c + 1) * k));
      s += '\n';
    });
    o += "</DataArray>\n<DataArray type=\"UInt8\" Name=\"types\" format=\"ascii\">\n";
    const char* type = k == 3 ? "5\n" : "10\n";
    o += format_lines(nc, 3, [&](std::size_t, std::string& s) { s += type; });
    o += "</DataArray>\n</Cells>\n</Piece>\n</UnstructuredGrid>\n</VTKFile>\n";
    return o;
  }
  const VtuArrays arrays(m);
  std::vector<std::string> blocks(std::size_t(arrays.count()));  // (compressed only)
  std::vector<std::size_t> at(blocks.size() + 1, 0);
  for (std::size_t i = 0; i < blocks.size(); ++i) {
    std::string raw(arrays.bytes(int(i)), '\0');
    arrays.fill(int(i), &raw[0], 0, arrays.items(int(i)));
    append_block(blocks[i], raw.data(), raw.size(), compress);
    at[i + 1] = at[i] + blocks[i].size();
  }
  Text o = head + appended_xml(arrays, at);
  for (auto& b : blocks) o += std::move(b);
  o += kVtuTail;
  return o;
}
}  // namespace gpugeom::io::detail
