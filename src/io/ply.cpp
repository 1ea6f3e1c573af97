// PLY (Stanford polygon format): ascii, binary_little_endian and binary_big_endian bodies.
#include <cctype>
#include <cstring>

#include "io/io_util.hpp"

namespace gpugeom::io::detail {
namespace {

enum class T { I8, U8, I16, U16, I32, U32, F32, F64 };
bool type_of(std::string_view s, T& t) {
  static const struct {
    const char* a;
    const char* b;
    T t;
  } m[] = {{"char", "int8", T::I8},      {"uchar", "uint8", T::U8},    {"short", "int16", T::I16},
           {"ushort", "uint16", T::U16}, {"int", "int32", T::I32},     {"uint", "uint32", T::U32},
           {"float", "float32", T::F32}, {"double", "float64", T::F64}};
  for (auto& e : m)
    if (s == e.a || s == e.b) return t = e.t, true;
  return false;
}
// The C++ type of each PLY type, in T's order.
using PlyTypes = std::tuple<std::int8_t, std::uint8_t, std::int16_t, std::uint16_t, std::int32_t,
                            std::uint32_t, float, double>;
std::size_t size_of(T t) {
  return gpugeom::detail::visit_type<PlyTypes>(std::size_t(t), [](auto v) { return sizeof v; });
}

struct Prop {
  std::string name;
  bool list = false;
  T count_t = T::U8, t = T::F32;
};
struct Elem {
  std::string name;
  std::int64_t count = 0;
  std::vector<Prop> props;
};

// A little-endian value of type t at p, as a double.
double value_at(const unsigned char* p, T t) {
  return gpugeom::detail::visit_type<PlyTypes>(std::size_t(t), [p](auto v) {
    std::memcpy(&v, p, sizeof v);
    return double(v);
  });
}

// Reads values from the body, in whichever encoding the header declared.
class Body {
 public:
  Body(std::string_view b, int enc, const Lines& l) : b_(b), enc_(enc), lines_(l) {}
  double get(T t) {
    if (enc_ == 0) return ascii();
    const std::size_t n = size_of(t);
    if (pos_ + n > b_.size())
      lines_.fail("binary body is truncated (expected more vertex or face data)");
    unsigned char raw[8];
    std::memcpy(raw, b_.data() + pos_, n);
    pos_ += n;
    if (enc_ == 2)
      for (std::size_t k = 0; k < n / 2; ++k) std::swap(raw[k], raw[n - 1 - k]);
    return value_at(raw, t);
  }
  std::size_t remaining() const { return b_.size() - pos_; }
  // Binary bodies: the bytes from here on, and a skip over bytes a fast path read itself.
  const unsigned char* here() const {
    return reinterpret_cast<const unsigned char*>(b_.data()) + pos_;
  }
  void skip(std::size_t n) { pos_ += n; }
  // ASCII bodies: the text from here on, and a skip over text (and its lines) read elsewhere.
  std::string_view rest() const { return b_.substr(std::min(pos_, b_.size())); }
  void skip(std::size_t n, std::int64_t lines) { pos_ += n, line_ += lines; }
  int encoding() const { return enc_; }

 private:
  double ascii() {
    while (pos_ < b_.size() && std::isspace((unsigned char)b_[pos_])) {
      if (b_[pos_] == '\n') ++line_;
      ++pos_;
    }
    std::size_t e = pos_;
    while (e < b_.size() && !std::isspace((unsigned char)b_[e])) ++e;
    if (e == pos_)
      parse_fail(lines_.name(), lines_.line_no() + line_ + 1,
                 "ascii body ends early (expected more values)");
    double v;
    if (!to_double(b_.substr(pos_, e - pos_), v))
      parse_fail(lines_.name(), lines_.line_no() + line_ + 1,
                 "expected a number, found '" + std::string(b_.substr(pos_, e - pos_)) + "'");
    pos_ = e;
    return v;
  }
  std::string_view b_;
  int enc_;
  const Lines& lines_;
  std::size_t pos_ = 0;
  std::int64_t line_ = 0;
};

// Fast paths for little-endian binary bodies (what gpugeom and most tools write), on all host
// threads; each returns false, having read nothing, where the element is not of its simple
// shape (the general loop then reads it, with its messages).
// Vertices with scalar properties only: x, y (and z) picked from fixed-size records.
bool read_vertices_fast(Body& body, const Elem& e, int ix, int iy, int iz, PlyData& out,
                        const Lines& l) {
  if (body.encoding() != 1) return false;
  std::size_t stride = 0, off[3] = {0, 0, 0};
  T type[3] = {T::F64, T::F64, T::F64};
  const int want[3] = {ix, iy, iz};
  for (int k = 0; k < int(e.props.size()); ++k) {
    if (e.props[std::size_t(k)].list) return false;
    for (int a = 0; a < 3; ++a)
      if (want[a] == k) off[a] = stride, type[a] = e.props[std::size_t(k)].t;
    stride += size_of(e.props[std::size_t(k)].t);
  }
  const std::size_t n = std::size_t(e.count);
  if (stride == 0 || body.remaining() / stride < n)
    l.fail("binary body is truncated (expected more vertex or face data)");
  const int d = out.dim;
  const std::size_t base = out.coords.size();
  out.coords.resize(base + n * std::size_t(d));
  const unsigned char* p = body.here();
  double* c = out.coords.data() + base;
#pragma omp parallel for schedule(static) if (n > 65536)
  for (std::int64_t i = 0; i < std::int64_t(n); ++i)
    for (int a = 0; a < d; ++a)
      c[std::size_t(i) * std::size_t(d) + std::size_t(a)] =
          value_at(p + std::size_t(i) * stride + off[a], type[a]);
  body.skip(n * stride);
  return true;
}

// Cells whose only property is the index list, every list of the same length k (3 or 4, as the
// element wants) with a 1-byte count and 4-byte indices.
bool read_cells_fast(Body& body, const Elem& e, PlyData& out, const Lines& l) {
  if (body.encoding() != 1 || e.props.size() != 1 || !e.props[0].list) return false;
  const Prop& p = e.props[0];
  if ((p.count_t != T::U8 && p.count_t != T::I8) || (p.t != T::I32 && p.t != T::U32)) return false;
  const std::size_t n = std::size_t(e.count);
  if (n == 0 || body.remaining() < 1) return false;
  const int k = e.name == "tetra" ? 4 : 3;
  if (out.cell_size != 0 && out.cell_size != k) return false;
  const std::size_t stride = 1 + 4 * std::size_t(k);
  if (body.remaining() / stride < n) return false;  // (the general loop names the shortfall)
  const unsigned char* b = body.here();
  std::int64_t odd = std::int64_t(n), bad = std::int64_t(n);
#pragma omp parallel for schedule(static) reduction(min : odd, bad) if (n > 65536)
  for (std::int64_t i = 0; i < std::int64_t(n); ++i) {
    const unsigned char* q = b + std::size_t(i) * stride;
    if (*q != k) odd = std::min(odd, i);
    for (int j = 0; j < k; ++j) {
      const double v = value_at(q + 1 + 4 * j, p.t);
      if (v < 0 || v > 2147483647.0) bad = std::min(bad, i);
    }
  }
  if (odd < std::int64_t(n) && odd <= bad) return false;  // other lengths: the general loop
  if (bad < std::int64_t(n))
    l.fail(e.name + " " + std::to_string(bad) + " has an invalid vertex index");
  out.cell_size = k;
  const std::size_t base = out.cells.size();
  out.cells.resize(base + n * std::size_t(k));
  std::int32_t* c = out.cells.data() + base;
#pragma omp parallel for schedule(static) if (n > 65536)
  for (std::int64_t i = 0; i < std::int64_t(n); ++i)
    for (int j = 0; j < k; ++j)
      c[std::size_t(i) * std::size_t(k) + std::size_t(j)] =
          std::int32_t(value_at(b + std::size_t(i) * stride + 1 + 4 * std::size_t(j), p.t));
  body.skip(n * stride);
  return true;
}

// ASCII bodies with one item per line, as every writer puts them: the element's lines read in
// parallel parts (read_records). Returns false, having read nothing, where the text is not of
// that simple shape (a line with other than one item's tokens, a token that is not a number, a
// '#' anywhere after this point, an index out of range): the general token loop then reads it,
// with its own messages and line numbers, so the fast path never changes what is accepted.
bool read_ascii_fast(Body& body, const Elem& e, int ix, int iy, int iz, int il, bool vertex,
                     bool cells, PlyData& out, const std::string& name) {
  if (body.encoding() != 0 || e.count <= 0) return false;
  const std::string_view text = body.rest();
  if (text.find('#') != std::string_view::npos) return false;  // (lines the reader would skip)
  const std::size_t np = e.props.size();
  for (const Prop& p : e.props)
    if (p.list != (cells && &p == &e.props[0])) return false;
  if (cells && (np != 1 || il != 0)) return false;
  if (!vertex && !cells) return false;
  const int k = e.name == "tetra" ? 4 : 3;
  if (cells && out.cell_size != 0 && out.cell_size != k) return false;
  Lines l(text, name);
  try {
    if (vertex) {
      const int d = out.dim;
      std::vector<double> xyz;
      read_records(
          l, text, e.count, d, xyz,
          [&](const Lines& part, std::string_view line, std::int64_t, double* o) {
            Scan sc(line);
            std::size_t q = 0;
            for (double v; q < np && sc.next(v); ++q) {
              if (int(q) == ix) o[0] = v;
              if (int(q) == iy) o[1] = v;
              if (int(q) == iz) o[2] = v;
            }
            if (q == np && sc.done()) return;
            const auto t = split(line);
            if (t.size() != np) part.fail("");
            for (std::size_t q = 0; q < np; ++q) {
              double v;
              if (!to_double(t[q], v)) part.fail("");
              if (int(q) == ix) o[0] = v;
              if (int(q) == iy) o[1] = v;
              if (int(q) == iz) o[2] = v;
            }
          },
          [](std::int64_t) { return std::string(); });
      out.coords.insert(out.coords.end(), xyz.begin(), xyz.end());
    } else {
      std::vector<std::int32_t> idx;
      read_records(
          l, text, e.count, k, idx,
          [&](const Lines& part, std::string_view line, std::int64_t, std::int32_t* o) {
            const auto t = split(line);
            double c;
            if (t.size() != std::size_t(k) + 1 || !to_double(t[0], c) || c != k) part.fail("");
            for (int j = 0; j < k; ++j) {
              double v;
              if (!to_double(t[std::size_t(j) + 1], v) || v < 0 || v > 2147483647.0 ||
                  v != double(std::int64_t(v)))
                part.fail("");
              o[j] = std::int32_t(v);
            }
          },
          [](std::int64_t) { return std::string(); });
      out.cell_size = k;
      out.cells.insert(out.cells.end(), idx.begin(), idx.end());
    }
  } catch (const Error&) {
    return false;
  }
  body.skip(l.offset(), l.line_no());
  return true;
}

}  // namespace

PlyData parse_ply(std::string_view bytes, const std::string& name) {
  Lines l(bytes, name);
  std::string_view line;
  if (!l.next(line, false) || line != "ply") l.fail("not a PLY file: the first line must be 'ply'");
  int enc = -1;
  std::vector<Elem> elems;
  bool ended = false;
  while (l.next(line, false)) {
    auto tok = split(line);
    if (tok.empty()) continue;
    if (tok[0] == "comment" || tok[0] == "obj_info") continue;
    if (tok[0] == "end_header") {
      ended = true;
      break;
    }
    if (tok[0] == "format") {
      if (tok.size() < 2) l.fail("incomplete 'format' line");
      if (tok[1] == "ascii")
        enc = 0;
      else if (tok[1] == "binary_little_endian")
        enc = 1;
      else if (tok[1] == "binary_big_endian")
        enc = 2;
      else
        l.fail("unknown PLY format '" + std::string(tok[1]) + "'");
    } else if (tok[0] == "element") {
      if (tok.size() != 3) l.fail("expected 'element NAME COUNT'");
      Elem e;
      e.name = std::string(tok[1]);
      for (const Elem& f : elems)
        if (f.name == e.name) l.fail("element '" + e.name + "' is declared twice");
      e.count = need_int(l, tok[2], "the element count");
      if (e.count < 0) l.fail("negative element count");
      elems.push_back(e);
    } else if (tok[0] == "property") {
      if (elems.empty()) l.fail("'property' before any 'element'");
      Prop p;
      if (tok.size() == 5 && tok[1] == "list") {
        p.list = true;
        if (!type_of(tok[2], p.count_t) || !type_of(tok[3], p.t))
          l.fail("unknown property type in list");
        p.name = std::string(tok[4]);
      } else if (tok.size() == 3) {
        if (!type_of(tok[1], p.t)) l.fail("unknown property type '" + std::string(tok[1]) + "'");
        p.name = std::string(tok[2]);
      } else {
        l.fail("expected 'property TYPE NAME' or 'property list COUNT_TYPE TYPE NAME'");
      }
      for (const Prop& q : elems.back().props)
        if (q.name == p.name)
          l.fail("element '" + elems.back().name + "' declares property '" + p.name + "' twice");
      elems.back().props.push_back(p);
    } else {
      l.fail("unexpected header line '" + std::string(line) + "'");
    }
  }
  if (!ended) l.fail("the header has no 'end_header' line");
  if (enc < 0) l.fail("the header has no 'format' line");
  Body body(std::string_view(bytes).substr(l.offset() > bytes.size() ? bytes.size() : l.offset()),
            enc, l);
  PlyData out;
  for (const Elem& e : elems) {
    // Refuse counts the body cannot possibly hold, before allocating for them.
    if (!e.props.empty() && std::uint64_t(e.count) > body.remaining() + 1)
      l.fail("element '" + e.name + "' claims " + std::to_string(e.count) +
             " items but the body is only " + std::to_string(body.remaining()) + " bytes");
    const bool vertex = e.name == "vertex";
    const bool cells = e.name == "face" || e.name == "tetra";
    int ix = -1, iy = -1, iz = -1, il = -1;
    for (int k = 0; k < int(e.props.size()); ++k) {
      const auto& p = e.props[k];
      if (vertex && !p.list && p.name == "x") ix = k;
      if (vertex && !p.list && p.name == "y") iy = k;
      if (vertex && !p.list && p.name == "z") iz = k;
      if (cells && p.list && (p.name == "vertex_indices" || p.name == "vertex_index")) il = k;
    }
    if (vertex) {
      if (ix < 0 || iy < 0) l.fail("the vertex element needs properties x and y");
      out.dim = iz >= 0 ? 3 : 2;
      out.coords.reserve(std::size_t(e.count) * out.dim);
    }
    // An element without properties has nothing in the body, however many items it claims
    // (the count check above cannot bound it, and looping over them would hang).
    if (e.props.empty()) continue;
    if (vertex && read_vertices_fast(body, e, ix, iy, iz, out, l)) continue;  // (x, y, z order)
    if (cells && il == 0 && read_cells_fast(body, e, out, l)) continue;
    if (read_ascii_fast(body, e, ix, iy, iz, il, vertex, cells, out, name)) continue;
    for (std::int64_t i = 0; i < e.count; ++i) {
      for (int k = 0; k < int(e.props.size()); ++k) {
        const Prop& p = e.props[k];
        if (!p.list) {
          double v = body.get(p.t);
          if (k == ix) out.coords.push_back(v);
          if (k == iy) out.coords.push_back(v);
          if (k == iz) out.coords.push_back(v);
          continue;
        }
        double c = body.get(p.count_t);
        // (written so that NaN fails too: a float count type can hold one)
        if (!(c >= 0 && c <= 1e6)) l.fail("list length " + std::to_string(c) + " is out of range");
        const int n = int(c);
        if (k == il) {
          const int want = e.name == "tetra" ? 4 : 3;
          if (out.cell_size == 0) out.cell_size = want;
          if (n != out.cell_size)
            l.fail(e.name + " " + std::to_string(i) + " has " + std::to_string(n) +
                   " indices; only triangles (3) and tetrahedra (4) are supported");
        }
        for (int j = 0; j < n; ++j) {
          double v = body.get(p.t);
          if (k == il) {
            if (!(v >= 0 && v <= 2147483647.0) || v != double(std::int64_t(v)))
              l.fail(e.name + " " + std::to_string(i) + " has an invalid vertex index");
            out.cells.push_back(std::int32_t(v));
          }
        }
      }
    }
    // The reordering above pushes x,y,z in property order; put them back as x,y,z.
    if (vertex && !(ix < iy && (iz < 0 || iy < iz))) {
      const int d = out.dim;
      int order[3] = {ix, iy, iz};
      int rank[3];
      for (int a = 0; a < d; ++a) {
        rank[a] = 0;
        for (int b = 0; b < d; ++b) rank[a] += order[b] < order[a];
      }
      for (std::size_t v = 0; v < out.coords.size(); v += d) {
        double t[3];
        for (int a = 0; a < d; ++a) t[a] = out.coords[v + rank[a]];
        for (int a = 0; a < d; ++a) out.coords[v + a] = t[a];
      }
    }
  }
  const std::size_t nv = out.coords.size() / out.dim;
  for (auto c : out.cells)
    if (std::size_t(c) >= nv)
      parse_fail(name, 0,
                 "a cell refers to vertex " + std::to_string(c) + " but there are only " +
                     std::to_string(nv) + " vertices");
  return out;
}

Text format_ply(const double* coords, int dim, std::size_t nv, const std::int32_t* cells,
                int cell_size, std::size_t nc, bool binary) {
  std::string h = "ply\nformat ";
  h += binary ? "binary_little_endian 1.0\n" : "ascii 1.0\n";
  h += "comment written by gpugeom\n";
  h += "element vertex " + std::to_string(nv) + "\n";
  const char* axes[3] = {"x", "y", "z"};
  for (int d = 0; d < dim; ++d) h += std::string("property double ") + axes[d] + "\n";
  if (nc) {
    h +=
        std::string("element ") + (cell_size == 4 ? "tetra " : "face ") + std::to_string(nc) + "\n";
    h += "property list uchar int vertex_indices\n";
  }
  h += "end_header\n";
  Text out = h;
  if (binary) {
    out += std::string(reinterpret_cast<const char*>(coords), nv * dim * sizeof(double));
    // Each cell a count byte and its indices (little-endian, as this machine stores them).
    const std::size_t rec = 1 + 4 * std::size_t(cell_size);
    std::string b(nc * rec, '\0');
#pragma omp parallel for schedule(static) if (nc > 65536)
    for (std::int64_t c = 0; c < std::int64_t(nc); ++c) {
      char* o = b.data() + std::size_t(c) * rec;
      o[0] = char(cell_size);
      std::memcpy(o + 1, cells + std::size_t(c) * std::size_t(cell_size), rec - 1);
    }
    out += std::move(b);
  } else {
    const std::size_t dm = std::size_t(dim);
    out += format_lines(nv, dm * 24, [&](std::size_t v, std::string& o) {
      for (std::size_t d = 0; d < dm; ++d) {
        if (d) o += ' ';
        append_double(o, coords[v * dm + d]);
      }
      o += '\n';
    });
    out += format_cell_lines(cells, cell_size, nc, cell_size == 4 ? "4" : "3", false, 0);
  }
  return out;
}

}  // namespace gpugeom::io::detail
