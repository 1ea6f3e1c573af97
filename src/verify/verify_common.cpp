#include "verify_common.hpp"

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
