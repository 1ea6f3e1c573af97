#include "verify_common.hpp"

#include <algorithm>

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
