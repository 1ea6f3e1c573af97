// Triangle's .poly files: a planar straight-line graph (points, segments, holes, regional
// attributes). Read serially, line by line; the points may instead come from the .node file of
// the same name (a vertex count of 0). And segments alone as an int (m, 2) .npy.
#include <string>

#include "gpugeom/io.hpp"
#include "io/io_util.hpp"

namespace gpugeom::io {
namespace detail {
PointSet parse_node_file(std::string_view b, const std::string& name, int* base);
}
using namespace detail;

namespace {
std::vector<std::string_view> fields(const Lines& l, std::string_view line, std::size_t least,
                                     const char* expect) {
  const auto t = split(line);
  if (t.size() < least) l.fail(std::string("expected '") + expect + "'");
  return {t.begin(), t.end()};
}
// A section's count from the line `line` (laid out as `header`; `what`: "the hole count"), at
// least 0 and at most the text's size (a section cannot have more lines than bytes).
std::int64_t section_count(const Lines& l, std::string_view line, const char* header,
                           const std::string& what, std::size_t text_size) {
  const std::int64_t c = need_int(l, fields(l, line, 1, header)[0], what.c_str());
  if (c < 0 || std::uint64_t(c) > text_size) l.fail(what + " is out of range");
  return c;
}
// The section's `count` lines (`what`: "holes"), each of at least `least` fields laid out as
// `layout`: row(i, fields) for each.
template <class Row>
void section_rows(Lines& l, std::string_view& line, std::int64_t count, const char* what,
                  std::size_t least, const char* layout, Row row) {
  for (std::int64_t i = 0; i < count; ++i) {
    if (!l.next(line))
      l.fail("the file ends after " + std::to_string(i) + " of " + std::to_string(count) + " " +
             what);
    row(i, fields(l, line, least, layout));
  }
}
}  // namespace

Pslg read_poly(const std::string& path) {
  FileView file(path);
  return parse_poly(file.view(), path);
}

Pslg parse_poly(std::string_view text, const std::string& path) {
  Lines l(text, path);
  std::string_view line;
  Pslg g;
  if (!l.next(line))
    l.fail("empty file: expected '<#vertices> <dimension> <#attributes> <#markers>'");
  auto h = fields(l, line, 2, "<#vertices> <dimension> <#attributes> <#markers>");
  const std::int64_t nv = need_int(l, h[0], "the vertex count");
  if (need_int(l, h[1], "the dimension") != 2) l.fail("the dimension must be 2");
  if (nv < 0 || std::uint64_t(nv) > text.size()) l.fail("the vertex count is out of range");
  int base = 0;
  g.points.dim = 2;
  if (nv == 0) {  // the points are in the .node file beside it
    const std::string node = sibling(path, ".node");
    g.points = detail::parse_node_file(FileView(node).view(), node, &base);
    if (g.points.dim != 2) parse_fail(node, 1, "the points must be 2D for a .poly file");
  } else {
    g.points.coords.resize(2 * std::size_t(nv));
    section_rows(l, line, nv, "vertices", 3, "<index> x y", [&](std::int64_t i, const auto& v) {
      const std::int64_t idx = need_int(l, v[0], "the vertex index");
      if (i == 0) {
        if (idx != 0 && idx != 1) l.fail("the first vertex index must be 0 or 1");
        base = int(idx);
      }
      g.points.coords[2 * std::size_t(i)] = need_double(l, v[1], "a coordinate");
      g.points.coords[2 * std::size_t(i) + 1] = need_double(l, v[2], "a coordinate");
    });
  }
  const std::int64_t n = std::int64_t(g.points.size());
  if (!l.next(line)) l.fail("the file ends before the segment count");
  const std::int64_t ns =
      section_count(l, line, "<#segments> <#markers>", "the segment count", text.size());
  g.segments.resize(2 * std::size_t(ns));
  section_rows(l, line, ns, "segments", 3, "<index> <endpoint> <endpoint>",
               [&](std::int64_t i, const auto& v) {
                 for (int k = 0; k < 2; ++k) {
                   const std::int64_t e = need_int(l, v[1 + k], "an endpoint") - base;
                   if (e < 0 || e >= n)
                     l.fail("segment endpoint " + std::string(v[1 + k]) + " names no vertex (" +
                            std::to_string(base) + ".." + std::to_string(n - 1 + base) + ")");
                   g.segments[2 * std::size_t(i) + k] = std::int32_t(e);
                 }
               });
  if (!l.next(line)) l.fail("the file ends before the hole count");
  const std::int64_t nh = section_count(l, line, "<#holes>", "the hole count", text.size());
  section_rows(l, line, nh, "holes", 3, "<index> x y", [&](std::int64_t, const auto& v) {
    g.holes.push_back(need_double(l, v[1], "a coordinate"));
    g.holes.push_back(need_double(l, v[2], "a coordinate"));
  });
  if (!l.next(line)) return g;  // (regional attributes are optional)
  const std::int64_t nr = section_count(l, line, "<#regions>", "the region count", text.size());
  section_rows(l, line, nr, "regions", 4, "<index> x y <attribute> [<maximum area>]",
               [&](std::int64_t, const auto& v) {
                 for (int k = 1; k <= 3; ++k)
                   g.regions.push_back(need_double(l, v[std::size_t(k)], "a number"));
                 g.region_areas.push_back(v.size() > 4 ? need_double(l, v[4], "an area") : 0.0);
               });
  return g;
}

void write_poly(const std::string& path, const Pslg& g, const std::int32_t* markers) {
  const std::size_t n = g.points.size(), m = g.segments.size() / 2;
  if (g.points.dim != 2) throw Error(ErrorCode::InvalidArgument, "a .poly file holds 2D points");
  std::string out = "# written by gpugeom; indices from 0\n";
  out += std::to_string(n) + " 2 0 0\n";
  for (std::size_t i = 0; i < n; ++i) {
    append_int(out, std::int64_t(i));
    for (int d = 0; d < 2; ++d) {
      out += ' ';
      append_double(out, g.points.coords[2 * i + std::size_t(d)]);
    }
    out += '\n';
  }
  out += std::to_string(m) + (markers ? " 1\n" : " 0\n");
  for (std::size_t i = 0; i < m; ++i) {
    out += std::to_string(i) + " " + std::to_string(g.segments[2 * i]) + " " +
           std::to_string(g.segments[2 * i + 1]);
    if (markers) out += " " + std::to_string(markers[i]);
    out += '\n';
  }
  out += std::to_string(g.holes.size() / 2) + "\n";
  for (std::size_t i = 0; i + 1 < g.holes.size(); i += 2) {
    out += std::to_string(i / 2) + " ";
    append_double(out, g.holes[i]);
    out += ' ';
    append_double(out, g.holes[i + 1]);
    out += '\n';
  }
  if (!g.regions.empty()) {
    out += std::to_string(g.regions.size() / 3) + "\n";
    for (std::size_t i = 0; i + 2 < g.regions.size(); i += 3) {
      out += std::to_string(i / 3);
      for (int k = 0; k < 3; ++k) {
        out += ' ';
        append_double(out, g.regions[i + std::size_t(k)]);
      }
      out += " -1\n";
    }
  }
  write_text(path, out);
}

std::vector<std::int32_t> read_segments(const std::string& path) {
  if (path.size() < 4 || path.substr(path.size() - 4) != ".npy")
    throw Error(ErrorCode::InvalidInput,
                "cannot read segments from '" + path + "': expected an int (m, 2) .npy");
  FileView file(path);
  const NpyArray a = parse_npy(file.view(), path);
  if (a.shape.size() != 2 || a.shape[1] != 2 || (a.descr[1] != 'i' && a.descr[1] != 'u'))
    parse_fail(path, 0, "expected an integer array of point index pairs, shape (m, 2)");
  std::vector<std::int32_t> s(std::size_t(a.shape[0] * 2));
  for (std::size_t i = 0; i < s.size(); ++i) {
    const std::int64_t v = npy_integer(a, std::int64_t(i), path);
    if (v < 0 || v > 2147483647) parse_fail(path, 0, "a point index is out of range");
    s[i] = std::int32_t(v);
  }
  return s;
}

}  // namespace gpugeom::io
