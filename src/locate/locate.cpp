// Exact point location by visibility walks (see include/gpugeom/locate.hpp; the walk itself in
// locate/walk.hpp), each host thread walking on from its previous answer.
#include "gpugeom/locate.hpp"

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <exception>
#include <string>
#include <vector>

#include "exec/deliver.hpp"
#include "locate/walk.hpp"

namespace gpugeom {

namespace {

using locate_detail::Mesh;
using locate_detail::walk;

template <int D>
HostVector<std::int32_t> locate(const Mesh<D>& m, const double* q, std::int64_t nq,
                                const LocateOptions& opt) {
  if (nq < 0) throw Error(ErrorCode::InvalidArgument, "find_simplex: negative query count");
  if (opt.backend == Backend::Cuda)
    throw Error(ErrorCode::Unsupported,
                "find_simplex runs on the host threads (there is no device point location): "
                "use Backend::Cpu or Backend::Auto");
  deliver::check(opt.into.simplices, nq, "simplices", true);
  for (std::int64_t i = 0; i < std::int64_t(D + 1) * m.ncell; ++i) {
    if (m.cells[i] < 0 || m.cells[i] >= m.n)
      throw Error(ErrorCode::InvalidInput, "find_simplex: simplex " + std::to_string(i / (D + 1)) +
                                               " has vertex " + std::to_string(m.cells[i]) +
                                               ", outside the " + std::to_string(m.n) + " points");
    if (m.nbr[i] < -1 || m.nbr[i] >= m.ncell)
      throw Error(ErrorCode::InvalidInput, "find_simplex: simplex " + std::to_string(i / (D + 1)) +
                                               " has neighbour " + std::to_string(m.nbr[i]) +
                                               ", outside the " + std::to_string(m.ncell) +
                                               " simplices");
  }
  for (std::int64_t i = 0; i < D * nq; ++i)
    if (!std::isfinite(q[i]))
      throw Error(ErrorCode::InvalidInput, "find_simplex: query point " + std::to_string(i / D) +
                                               " has a coordinate that is NaN or infinite");
  HostVector<std::int32_t> own;
  std::int32_t* out = opt.into.simplices.data;
  if (!out) {
    own = HostVector<std::int32_t>(std::size_t(nq));
    out = own.data();
  }
  if (m.ncell == 0) {  // (else every answer is written below)
    std::fill(out, out + nq, std::int32_t(-1));
    return own;
  }
  const int nt = opt.threads > 0 ? opt.threads : omp_get_max_threads();
#pragma omp parallel num_threads(nt)
  {
    std::vector<double> s(D == 2 ? pred::kOrient2dScratch : pred::kOrient3dScratch);
    std::int64_t c = 0;  // each thread walks on from its previous answer
#pragma omp for schedule(static)
    for (std::int64_t i = 0; i < nq; ++i) {
      const std::int32_t r = walk(m, c, q + D * i, s.data());
      out[i] = r;
      if (r >= 0) c = r;
    }
  }
  return own;
}

}  // namespace

// (The definitions name the arrays short: the header documents them.)
HostVector<std::int32_t> find_simplex2d(const double* xy, std::int64_t n, const std::int32_t* tri,
                                        const std::int32_t* nb, std::int64_t nt, const double* q,
                                        std::int64_t m, const LocateOptions& opt) {
  return locate(Mesh<2>{xy, n, tri, nb, nt}, q, m, opt);
}
HostVector<std::int32_t> find_simplex3d(const double* xyz, std::int64_t n, const std::int32_t* tet,
                                        const std::int32_t* nb, std::int64_t nt, const double* q,
                                        std::int64_t m, const LocateOptions& opt) {
  return locate(Mesh<3>{xyz, n, tet, nb, nt}, q, m, opt);
}

}  // namespace gpugeom
