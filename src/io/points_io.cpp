// Point-cloud readers and writers.
#include <algorithm>
#include <cctype>
#include <cstring>
#include <exception>
#include <new>
#include <string_view>
#include <vector>
#ifdef _OPENMP
#include <omp.h>
#endif

#include "gpugeom/io.hpp"
#include "io/io_util.hpp"

namespace gpugeom::io {
using namespace detail;

std::string extension(const std::string& path) {
  std::size_t slash = path.find_last_of('/');
  std::size_t dot = path.find_last_of('.');
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return "";
  std::string e = path.substr(dot);
  std::transform(e.begin(), e.end(), e.begin(), [](unsigned char c) { return std::tolower(c); });
  return e;
}

namespace {

// Text tables: the first line (a header row, or the first point, which fixes the dimension)
// serially, the rest in parallel parts (read_records).
PointSet parse_table(std::string_view b, const std::string& name, bool csv) {
  Lines l(b, name);
  std::string_view line;
  PointSet p;
  p.dim = 0;
  bool first = true;
  while (l.next(line)) {
    auto tok = split(line, csv || line.find(',') != std::string_view::npos);
    double v;
    if (first && !tok.empty() && !to_double(tok[0], v)) {  // a header row of column names
      first = false;
      continue;
    }
    if (tok.size() != 2 && tok.size() != 3)
      l.fail("expected 2 or 3 coordinates per line, found " + std::to_string(tok.size()));
    p.dim = int(tok.size());
    for (auto t : tok) p.coords.push_back(need_double(l, t, "a coordinate"));
    break;
  }
  if (p.dim == 0) parse_fail(name, 0, "no points found");
  read_records(
      l, b, -1, p.dim, p.coords,
      [&](const Lines& part, std::string_view line, std::int64_t, double* out) {
        // (commas as separators are the same as split's choice below: with no comma on the
        // line they change nothing)
        Scan sc(line, true);
        int d = 0;
        while (d < p.dim && sc.next(out[d])) ++d;
        if (d == p.dim && sc.done()) return;
        auto tok = split(line, csv || line.find(',') != std::string_view::npos);
        if (int(tok.size()) != p.dim)
          part.fail("expected " + std::to_string(p.dim) +
                    " coordinates (as on the first line), found " + std::to_string(tok.size()));
        for (int d = 0; d < p.dim; ++d)
          out[d] = need_double(part, tok[std::size_t(d)], "a coordinate");
      },
      [](std::int64_t) { return std::string(); });
  return p;
}

// A point table as text, one line per point (formatted on all host threads).
Text format_table(const PointSet& p, char sep) {
  const std::size_t dim = std::size_t(p.dim);
  return format_lines(p.size(), dim * 24, [&](std::size_t i, std::string& o) {
    for (std::size_t d = 0; d < dim; ++d) {
      if (d) o += sep;
      append_double(o, p.coords[i * dim + d]);
    }
    o += '\n';
  });
}

PointSet parse_off_points(std::string_view b, const std::string& name, Mesh* mesh) {
  Lines l(b, name);
  std::string_view line;
  if (!l.next(line)) l.fail("empty file: expected 'OFF'");
  auto tok = split(line);
  if (tok.empty() || tok[0] != "OFF") l.fail("not an OFF file: the first line must be 'OFF'");
  tok.drop_front();
  if (tok.empty()) {
    if (!l.next(line)) l.fail("expected the counts 'vertices faces edges'");
    tok = split(line);
  }
  if (tok.size() < 2) l.fail("expected the counts 'vertices faces edges'");
  std::int64_t nv = need_int(l, tok[0], "the vertex count"),
               nf = need_int(l, tok[1], "the face count");
  if (nv < 0 || nf < 0 || std::uint64_t(nv) > b.size() || std::uint64_t(nf) > b.size())
    l.fail("vertex/face counts are out of range for this file");
  PointSet p;
  p.dim = 3;
  read_records(
      l, b, nv, 3, p.coords,
      [&](const Lines& part, std::string_view line, std::int64_t i, double* out) {
        Scan sc(line);
        if (sc.next(out[0]) && sc.next(out[1]) && sc.next(out[2])) return;
        auto t = split(line);
        if (t.size() < 3) part.fail("expected 'x y z' for vertex " + std::to_string(i));
        for (int k = 0; k < 3; ++k) out[k] = need_double(part, t[k], "a coordinate");
      },
      [&](std::int64_t i) {
        return "file ends after " + std::to_string(i) + " of " + std::to_string(nv) + " vertices";
      });
  if (mesh) {
    mesh->cell_size = 3;
    read_records(
        l, b, nf, 3, mesh->cells,
        [&](const Lines& part, std::string_view line, std::int64_t f, std::int32_t* out) {
          Scan sc(line);
          std::int64_t c = 0, v[3];
          if (sc.next(c) && c == 3 && sc.next(v[0]) && sc.next(v[1]) && sc.next(v[2]) &&
              in_range(v, 3, 0, nv)) {
            for (int k = 0; k < 3; ++k) out[k] = std::int32_t(v[k]);
            return;
          }
          auto t = split(line);
          if (t.empty() || need_int(part, t[0], "the face size") != 3 || t.size() < 4)
            part.fail("face " + std::to_string(f) + " is not a triangle ('3 a b c')");
          for (int k = 1; k <= 3; ++k) {
            std::int64_t v = need_int(part, t[k], "a vertex index");
            if (v < 0 || v >= nv)
              part.fail("vertex index " + std::to_string(v) + " is out of range");
            out[k - 1] = std::int32_t(v);
          }
        },
        [&](std::int64_t f) {
          return "file ends after " + std::to_string(f) + " of " + std::to_string(nf) + " faces";
        });
  }
  return p;
}

// True when a line (as Lines::next gives it: no leading blanks) starts with the one-letter
// keyword c as its own token.
bool obj_keyword(std::string_view line, char c) {
  return line[0] == c && (line.size() == 1 || line[1] == ' ' || line[1] == '\t' ||
                          line[1] == '\r' || line[1] == '\n');
}

// OBJ: 'v' and 'f' lines among anything else. Read in parallel parts: each part's line ends
// and 'v' / 'f' lines are counted first (so each knows its first line number, first vertex and
// first face: a face's relative indices count back from the vertices defined before it), then
// the parts are parsed on their own threads into their slices. The first error in file order
// is the one reported, as a serial loop would.
PointSet parse_obj(std::string_view b, const std::string& name, Mesh* mesh) {
  const std::string_view text(b);
  const std::vector<std::size_t> start = line_parts(text);
  const std::size_t nparts = start.size() - 1;
  auto part = [&](std::size_t k) { return text.substr(start[k], start[k + 1] - start[k]); };
  std::vector<std::int64_t> lines(nparts + 1, 0), verts(nparts + 1, 0), faces(nparts + 1, 0);
#pragma omp parallel for schedule(static, 1)
  for (std::int64_t k = 0; k < std::int64_t(nparts); ++k) {
    const std::size_t i = std::size_t(k);
    const std::string_view t = part(i);
    lines[i + 1] = std::int64_t(std::count(t.begin(), t.end(), '\n'));
    Lines l(t, name);
    std::string_view line;
    while (l.next(line)) {
      verts[i + 1] += obj_keyword(line, 'v');
      faces[i + 1] += mesh && obj_keyword(line, 'f');
    }
  }
  for (std::size_t k = 0; k < nparts; ++k)
    lines[k + 1] += lines[k], verts[k + 1] += verts[k], faces[k + 1] += faces[k];
  PointSet p;
  p.dim = 3;
  p.coords.resize(std::size_t(3 * verts[nparts]));
  if (mesh) mesh->cells.resize(std::size_t(3 * faces[nparts]));
  std::vector<std::exception_ptr> error(nparts);
#pragma omp parallel for schedule(static, 1)
  for (std::int64_t k = 0; k < std::int64_t(nparts); ++k) {
    const std::size_t i = std::size_t(k);
    try {
      Lines l(part(i), name, lines[i]);
      std::string_view line;
      std::int64_t nv = verts[i], nf = faces[i];
      while (l.next(line)) {
        if (obj_keyword(line, 'v')) {
          Scan sc(line.substr(1));
          double* o = p.coords.data() + 3 * nv;
          if (sc.next(o[0]) && sc.next(o[1]) && sc.next(o[2])) {
            ++nv;
            continue;
          }
          auto t = split(line);
          if (t.size() < 4) l.fail("expected 'v x y z'");
          for (int c = 1; c <= 3; ++c)
            p.coords[std::size_t(3 * nv + c - 1)] = need_double(l, t[c], "a coordinate");
          ++nv;
        } else if (mesh && obj_keyword(line, 'f')) {
          auto t = split(line);
          if (t.size() != 4) l.fail("only triangular faces ('f a b c') are supported");
          for (int c = 1; c <= 3; ++c) {
            std::string_view s = t[c].substr(0, t[c].find('/'));
            std::int64_t v = need_int(l, s, "a vertex index");
            v = v < 0 ? nv + v : v - 1;  // OBJ is 1-based; negative counts back from the end
            if (v < 0 || v >= nv)
              l.fail("face refers to vertex " + std::string(s) + " which is not defined yet");
            mesh->cells[std::size_t(3 * nf + c - 1)] = std::int32_t(v);
          }
          ++nf;
        }
      }
    } catch (...) {
      error[i] = std::current_exception();
    }
  }
  for (const auto& e : error)
    if (e) std::rethrow_exception(e);
  if (p.coords.empty()) parse_fail(name, 0, "no 'v' lines found");
  if (mesh) mesh->cell_size = 3;
  return p;
}

// Triangle/TetGen .node; base receives the first index (0 or 1) for a matching .ele.
PointSet parse_node(std::string_view b, const std::string& name, int* base) {
  Lines l(b, name);
  std::string_view line;
  if (!l.next(line))
    l.fail("empty file: expected '<#points> <dimension> <#attributes> <#markers>'");
  auto t = split(line);
  if (t.size() < 2) l.fail("expected '<#points> <dimension> <#attributes> <#markers>'");
  std::int64_t n = need_int(l, t[0], "the point count"), dim = need_int(l, t[1], "the dimension");
  std::int64_t nattr = t.size() > 2 ? need_int(l, t[2], "the attribute count") : 0;
  std::int64_t nmark = t.size() > 3 ? need_int(l, t[3], "the marker count") : 0;
  if (dim != 2 && dim != 3) l.fail("dimension must be 2 or 3");
  if (n < 0 || std::uint64_t(n) > b.size() || nattr < 0 || nmark < 0 || nmark > 1 || nattr > 1000)
    l.fail("header counts are out of range");
  PointSet p;
  p.dim = int(dim);
  read_records(
      l, b, n, p.dim, p.coords,
      [&](const Lines& part, std::string_view line, std::int64_t i, double* out) {
        if (i > 0) {  // (the first point's index is checked below)
          Scan sc(line);
          std::int64_t idx;
          int k = 0;
          if (sc.next(idx))
            while (k < dim && sc.next(out[k])) ++k;
          if (k == dim) return;
        }
        auto v = split(line);
        if (std::int64_t(v.size()) < 1 + dim)
          part.fail("expected '<index> x y" + std::string(dim == 3 ? " z'" : "'"));
        std::int64_t idx = need_int(part, v[0], "the point index");
        if (i == 0) {
          if (idx != 0 && idx != 1) part.fail("the first point index must be 0 or 1");
          if (base) *base = int(idx);
        }
        for (int k = 1; k <= dim; ++k) out[k - 1] = need_double(part, v[k], "a coordinate");
      },
      [&](std::int64_t i) {
        return "file ends after " + std::to_string(i) + " of " + std::to_string(n) + " points";
      });
  return p;
}

PointSet parse_npy_points(std::string_view b, const std::string& name) {
  NpyArray a = parse_npy(b, name);
  if (a.shape.size() != 2 || (a.shape[1] != 2 && a.shape[1] != 3))
    parse_fail(name, 0, "expected a point array of shape (N, 2) or (N, 3)");
  if (a.descr[1] != 'f')
    parse_fail(name, 0, "expected float32 or float64 points, found dtype '" + a.descr + "'");
  PointSet p;
  p.dim = int(a.shape[1]);
  const std::int64_t n = a.shape[0] * a.shape[1];
  if (a.descr == "<f8" && n > 0 && a.payload.size() >= std::size_t(n) * 8) {  // a copy
    p.coords.resize(std::size_t(n));
    std::memcpy(p.coords.data(), a.payload.data(), std::size_t(n) * 8);
    return p;
  }
  p.coords.resize(std::size_t(n));
  for (std::int64_t i = 0; i < n; ++i) p.coords[i] = npy_value(a, i, name);
  return p;
}

}  // namespace

PointSet parse_points(std::string_view b, const std::string& ext, const std::string& name) {
  if (ext == ".xyz" || ext == ".txt") return parse_table(b, name, false);
  if (ext == ".csv") return parse_table(b, name, true);
  if (ext == ".off") return parse_off_points(b, name, nullptr);
  if (ext == ".obj") return parse_obj(b, name, nullptr);
  if (ext == ".node") return parse_node(b, name, nullptr);
  if (ext == ".npy") return parse_npy_points(b, name);
  if (ext == ".ply") {
    PlyData d = parse_ply(b, name);
    PointSet p;
    p.dim = d.dim;
    p.coords = std::move(d.coords);
    return p;
  }
  throw Error(ErrorCode::InvalidArgument,
              name + ": unknown point format '" + ext +
                  "': expected .xyz .txt .csv .ply .off .obj .node or .npy");
}

PointSet read_points(const std::string& path) {
  const std::string ext = extension(path);
  static const char* const known[] = {".xyz", ".txt",  ".csv", ".off",
                                      ".obj", ".node", ".npy", ".ply"};
  return parse_file(path, ext, known, &parse_points);
}

void write_points(const std::string& path, const PointSet& p, const WriteOptions& o) {
  const std::string ext = extension(path);
  const std::size_t n = p.size();
  Text out;
  if (p.dim != 2 && p.dim != 3) throw Error(ErrorCode::InvalidArgument, "points must be 2D or 3D");
  if (ext == ".xyz" || ext == ".txt" || ext == ".csv") {
    out = format_table(p, ext == ".csv" ? ',' : ' ');
  } else if (ext == ".ply") {
    out = format_ply(p.coords.data(), p.dim, n, nullptr, 3, 0, o.binary);
  } else if (ext == ".off" || ext == ".obj") {
    if (ext == ".off") out = "OFF\n" + std::to_string(n) + " 0 0\n";
    out += format_vertex_lines(p.coords.data(), p.dim, n, ext == ".obj" ? "v " : "");
  } else if (ext == ".node") {
    out = std::to_string(n) + " " + std::to_string(p.dim) + " 0 0\n";
    out += format_lines(n, std::size_t(p.dim) * 24 + 8, [&](std::size_t i, std::string& o) {
      append_int(o, std::int64_t(i));
      for (int d = 0; d < p.dim; ++d) {
        o += ' ';
        append_double(o, p.coords[i * std::size_t(p.dim) + std::size_t(d)]);
      }
      o += '\n';
    });
  } else if (ext == ".npy") {
    out = format_npy("<f8", {std::int64_t(n), p.dim}, p.coords.data(), p.coords.size() * 8);
  } else {
    throw Error(ErrorCode::InvalidArgument,
                path + ": unknown point format '" + ext +
                    "': expected .xyz .txt .csv .ply .off .obj .node or .npy");
  }
  write_file_atomic(path, out);
}

// Mesh helpers that share the point parsers live here too.
namespace detail {
PointSet parse_off_mesh(std::string_view b, const std::string& name, Mesh* m) {
  return parse_off_points(b, name, m);
}
PointSet parse_obj_mesh(std::string_view b, const std::string& name, Mesh* m) {
  return parse_obj(b, name, m);
}
PointSet parse_node_file(std::string_view b, const std::string& name, int* base) {
  return parse_node(b, name, base);
}
}  // namespace detail

}  // namespace gpugeom::io
