#include "verify_common.hpp"

#include <algorithm>
#include <unordered_map>

#include "verify.hpp"

namespace gpugeom::verify::detail {

std::string cell_name(int k, std::int64_t c, const std::int32_t* cells) {
  std::string s = (k == 3 ? "triangle " : "tetrahedron ") + std::to_string(c) + " (";
  for (int j = 0; j < k; ++j) s += (j ? " " : "") + std::to_string(cells[c * k + j]);
  return s + ")";
}

bool check_cells(Report& r, std::int64_t n, const std::int32_t* cells, std::int64_t ncell, int k,
                 const std::int32_t* dup_of, const double* pts, int dim) {
  std::vector<char> used(n, 0);
  for (std::int64_t c = 0; c < ncell; ++c)
    for (int j = 0; j < k; ++j) {
      std::int32_t v = cells[c * k + j];
      if (v < 0 || v >= n)
        return r.fail(cell_name(k, c, cells) + " refers to vertex " + std::to_string(v) +
                      ", outside 0.." + std::to_string(n - 1));
      for (int i = 0; i < j; ++i)
        if (cells[c * k + i] == v) return r.fail(cell_name(k, c, cells) + " repeats a vertex");
      if (dup_of && dup_of[v] >= 0)
        return r.fail(cell_name(k, c, cells) + " uses vertex " + std::to_string(v) +
                      ", which is reported as a duplicate");
      used[v] = 1;
    }
  for (std::int64_t i = 0; i < n; ++i) {
    if (dup_of && dup_of[i] >= 0) {
      const std::int64_t j = dup_of[i];
      if (j >= n || (dup_of[j] >= 0))
        return r.fail("point " + std::to_string(i) + " is mapped to " + std::to_string(j) +
                      ", which is not a kept point");
      for (int d = 0; d < dim; ++d)
        if (pts[i * dim + d] != pts[j * dim + d])
          return r.fail("point " + std::to_string(i) + " is reported a duplicate of " +
                        std::to_string(j) + " but their coordinates differ");
      continue;
    }
    if (!used[i])
      return r.fail("input point " + std::to_string(i) + " is not a vertex of the triangulation");
  }
  return true;
}

std::uint64_t directed(std::uint32_t u, std::uint32_t v) {
  return (std::uint64_t(u) << 32) | v;
}
std::uint64_t undirected(std::uint32_t u, std::uint32_t v) {
  return u < v ? directed(u, v) : directed(v, u);
}

// Every interior edge of a valid triangulation locally Delaunay (exact in-circle; cocircular
// allowed), except the edges in `exempt` (undirected keys).
bool locally_delaunay(Report& r, const double* p, const std::int32_t* t, std::int64_t nt,
                      const std::unordered_set<std::uint64_t>& exempt) {
  std::unordered_map<std::uint64_t, std::int64_t> dir;
  dir.reserve(std::size_t(nt) * 6);
  for (std::int64_t c = 0; c < nt; ++c)
    for (int j = 0; j < 3; ++j) dir.emplace(directed(t[3 * c + j], t[3 * c + (j + 1) % 3]), c);
  for (std::int64_t c = 0; c < nt; ++c)
    for (int j = 0; j < 3; ++j) {
      std::uint32_t u = t[3 * c + j], v = t[3 * c + (j + 1) % 3];
      auto it = dir.find(directed(v, u));
      if (it == dir.end() || exempt.count(undirected(u, v))) continue;
      std::int64_t o = it->second;
      std::int64_t far = std::int64_t(t[3 * o]) + t[3 * o + 1] + t[3 * o + 2] - u - v;
      const std::int32_t* a = t + 3 * c;
      if (pred::incircle(at<2>(p, a[0]), at<2>(p, a[1]), at<2>(p, a[2]), at<2>(p, far), scratch()) >
          0)
        return r.fail("edge " + std::to_string(u) + "-" + std::to_string(v) +
                      (exempt.empty() ? "" : " (on no segment)") +
                      " is not locally Delaunay: vertex " + std::to_string(far) +
                      " lies inside the circumcircle of " + cell_name(3, c, t));
    }
  return true;
}

}  // namespace gpugeom::verify::detail

namespace gpugeom::verify {

std::vector<std::array<std::int32_t, 3>> canonical_triangles(const std::int32_t* tris,
                                                             std::int64_t nt) {
  std::vector<std::array<std::int32_t, 3>> s(static_cast<std::size_t>(nt));
  for (std::size_t c = 0; c < s.size(); ++c) {
    const std::int32_t* v = tris + 3 * c;
    const int k = v[0] < v[1] ? (v[0] < v[2] ? 0 : 2) : (v[1] < v[2] ? 1 : 2);
    s[c] = {v[k], v[(k + 1) % 3], v[(k + 2) % 3]};
  }
  std::sort(s.begin(), s.end());
  return s;
}

}  // namespace gpugeom::verify
