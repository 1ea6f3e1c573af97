// 3D: a valid tetrahedralisation of the convex hull of the input, and the Delaunay property.
//
// Checks: every tetrahedron positively oriented (exact); every triangle shared by at most two
// tetrahedra, with opposite orientations; the boundary triangles form a closed, connected
// 2-manifold of Euler characteristic 2 whose every edge is convex; the covering degree is
// exactly 1 at sample points (counted with simulation of simplicity, so a point on a face is
// counted once); every input point is a vertex or a reported duplicate. A locally injective
// oriented map whose boundary is a convex sphere and whose degree is 1 tiles the hull once.
#include <algorithm>
#include <array>
#include <map>
#include <unordered_map>

#include "verify_common.hpp"

namespace gpugeom::verify {
using namespace detail;

namespace {

struct FaceKey {
  std::array<std::int32_t, 3> v;  // sorted
  bool operator==(const FaceKey& o) const { return v == o.v; }
};
struct FaceHash {
  std::size_t operator()(const FaceKey& k) const {
    std::uint64_t h = std::uint64_t(std::uint32_t(k.v[0])) * 0x9e3779b97f4a7c15ull;
    h ^= (std::uint64_t(std::uint32_t(k.v[1])) + 0x7f4a7c15ull) * 0xbf58476d1ce4e5b9ull;
    h ^= (std::uint64_t(std::uint32_t(k.v[2])) + 0x94d049bbull) * 0x94d049bb133111ebull;
    return std::size_t(h ^ (h >> 31));
  }
};
// Sorted vertices and the parity of the sort, so an oriented face and its reverse share a key.
FaceKey face_key(std::int32_t a, std::int32_t b, std::int32_t c, int& parity) {
  std::array<std::int32_t, 3> v{a, b, c};
  parity = 0;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j + 1 < 3 - i; ++j)
      if (v[j] > v[j + 1]) std::swap(v[j], v[j + 1]), parity ^= 1;
  return {v};
}
// Faces of tetrahedron (a,b,c,d) oriented so that the tet lies on their positive side's
// opposite: face opposite vertex k, listed with outward orientation.
const int kFace[4][3] = {{1, 2, 3}, {0, 3, 2}, {0, 1, 3}, {0, 2, 1}};

struct Faces {
  std::unordered_map<FaceKey, std::array<std::int64_t, 2>, FaceHash> map;  // [parity] -> tet*4+k
};

}  // namespace

static Report triangulation3d(const double* p, std::int64_t n, const std::int32_t* t,
                              std::int64_t nt, const std::int32_t* dup_of, Faces& faces) {
  Report r;
  if (nt == 0) return r.fail("the tetrahedralisation has no tetrahedra"), r;
  if (!check_cells(r, n, t, nt, 4, dup_of, p, 3)) return r;
  for (std::int64_t c = 0; c < nt; ++c) {
    const std::int32_t* v = t + 4 * c;
    int o =
        pred::orient3d(at<3>(p, v[0]), at<3>(p, v[1]), at<3>(p, v[2]), at<3>(p, v[3]), scratch());
    if (o <= 0)
      return r.fail(cell_name(4, c, t) +
                    (o == 0 ? " is flat (coplanar)" : " is negatively oriented")),
             r;
  }
  faces.map.reserve(std::size_t(nt) * 3);
  for (std::int64_t c = 0; c < nt; ++c)
    for (int k = 0; k < 4; ++k) {
      const std::int32_t* v = t + 4 * c;
      int par;
      FaceKey fk = face_key(v[kFace[k][0]], v[kFace[k][1]], v[kFace[k][2]], par);
      auto& slot = faces.map.try_emplace(fk, std::array<std::int64_t, 2>{-1, -1}).first->second;
      if (slot[par] >= 0)
        return r.fail("triangle " + std::to_string(fk.v[0]) + " " + std::to_string(fk.v[1]) + " " +
                      std::to_string(fk.v[2]) + " is used twice with the same orientation " +
                      "(overlapping tetrahedra), by " + cell_name(4, c, t)),
               r;
      slot[par] = c * 4 + k;
    }
  // Boundary surface: outward faces present on one side only.
  std::vector<std::array<std::int32_t, 3>> bnd;
  for (auto& f : faces.map) {
    if (f.second[0] >= 0 && f.second[1] >= 0) continue;
    std::int64_t tk = f.second[0] >= 0 ? f.second[0] : f.second[1];
    const std::int32_t* v = t + 4 * (tk / 4);
    const int k = int(tk % 4);
    bnd.push_back({v[kFace[k][0]], v[kFace[k][1]], v[kFace[k][2]]});
  }
  std::unordered_map<std::uint64_t, std::pair<std::int64_t, int>> edge;  // directed -> face, apex
  auto key = [](std::uint32_t u, std::uint32_t v) { return (std::uint64_t(u) << 32) | v; };
  for (std::size_t f = 0; f < bnd.size(); ++f)
    for (int j = 0; j < 3; ++j)
      if (!edge.emplace(key(bnd[f][j], bnd[f][(j + 1) % 3]),
                        std::make_pair(std::int64_t(f), bnd[f][(j + 2) % 3]))
               .second)
        return r.fail("boundary edge " + std::to_string(bnd[f][j]) + "-" +
                      std::to_string(bnd[f][(j + 1) % 3]) +
                      " is shared by more than two boundary triangles"),
               r;
  std::map<std::int32_t, int> bverts;
  for (auto& e : edge) {
    std::uint32_t u = std::uint32_t(e.first >> 32), v = std::uint32_t(e.first);
    auto it = edge.find(key(v, u));
    if (it == edge.end())
      return r.fail("the boundary surface is not closed at edge " + std::to_string(u) + "-" +
                    std::to_string(v)),
             r;
    const auto& f = bnd[e.second.first];
    int far = it->second.second;
    if (pred::orient3d(at<3>(p, f[0]), at<3>(p, f[1]), at<3>(p, f[2]), at<3>(p, far), scratch()) >
        0)
      return r.fail("the boundary is reflex at edge " + std::to_string(u) + "-" +
                    std::to_string(v) + ": the region is not convex"),
             r;
    bverts[std::int32_t(u)] = 1;
  }
  const std::int64_t V = std::int64_t(bverts.size()), E = std::int64_t(edge.size() / 2),
                     F = std::int64_t(bnd.size());
  if (V - E + F != 2)
    return r.fail("the boundary surface has Euler characteristic " + std::to_string(V - E + F) +
                  " (a convex boundary has 2)"),
           r;
  // Covering degree at a few interior points, counted with SoS (index n): each the rounded
  // centroid of a tetrahedron that holds it strictly (tested exactly), so the point is inside
  // the hull and a tiling covers it exactly once. (The rounded centroid of a needle along a
  // hull edge can fall outside the hull, where no tetrahedron covers it: such tetrahedra are
  // passed over for the next one.)
  auto holds = [&](std::int64_t c, const double q[3]) {
    for (int k = 0; k < 4; ++k) {
      const double* w[4];
      for (int j = 0; j < 4; ++j) w[j] = at<3>(p, t[4 * c + j]);
      w[k] = q;
      if (pred::orient3d(w[0], w[1], w[2], w[3], scratch()) <= 0) return false;
    }
    return true;
  };
  for (std::int64_t s = 0; s < std::min<std::int64_t>(nt, 3); ++s) {
    double q[3] = {0, 0, 0};
    std::int64_t c = (s * (nt - 1)) / 2, tried = 0;
    for (; tried < nt; ++tried, c = (c + 1) % nt) {
      q[0] = q[1] = q[2] = 0;
      for (int k = 0; k < 4; ++k)
        for (int d = 0; d < 3; ++d) q[d] += 0.25 * p[3 * t[4 * c + k] + d];
      if (holds(c, q)) break;
    }
    if (tried == nt) break;  // no tetrahedron holds its rounded centroid: nothing to sample
    std::int64_t inside = 0;
    const int qi = int(n);
#pragma omp parallel for reduction(+ : inside)
    for (std::int64_t o = 0; o < nt; ++o) {
      const std::int32_t* v = t + 4 * o;
      bool in = true;
      for (int k = 0; k < 4 && in; ++k) {
        const double* w[4];
        int wi[4];
        for (int j = 0; j < 4; ++j) w[j] = at<3>(p, v[j]), wi[j] = v[j];
        w[k] = q, wi[k] = qi;
        in = pred::orient3d_sos(w[0], wi[0], w[1], wi[1], w[2], wi[2], w[3], wi[3], scratch()) > 0;
      }
      inside += in;
    }
    if (inside != 1)
      return r.fail("the tetrahedra cover the point near " + cell_name(4, c, t) + " " +
                    std::to_string(inside) + " times (must be once)"),
             r;
  }
  r.notes.push_back(std::to_string(nt) + " tetrahedra, " + std::to_string(F) +
                    " boundary triangles: valid tetrahedralisation of the convex hull");
  return r;
}

Report check_triangulation3d(const double* p, std::int64_t n, const std::int32_t* t,
                             std::int64_t nt, const std::int32_t* dup_of) {
  Faces f;
  return triangulation3d(p, n, t, nt, dup_of, f);
}

Report check_delaunay3d(const double* p, std::int64_t n, const std::int32_t* t, std::int64_t nt,
                        const std::int32_t* dup_of) {
  Faces faces;
  Report r = triangulation3d(p, n, t, nt, dup_of, faces);
  if (!r.ok) return r;
  for (auto& f : faces.map) {
    if (f.second[0] < 0 || f.second[1] < 0) continue;
    const std::int64_t c = f.second[0] / 4, o = f.second[1] / 4;
    const int ko = int(f.second[1] % 4);
    const std::int32_t* v = t + 4 * c;
    const std::int32_t far = t[4 * o + ko];
    if (pred::insphere(at<3>(p, v[0]), at<3>(p, v[1]), at<3>(p, v[2]), at<3>(p, v[3]),
                       at<3>(p, far), scratch()) > 0)
      return r.fail("triangle " + std::to_string(f.first.v[0]) + " " +
                    std::to_string(f.first.v[1]) + " " + std::to_string(f.first.v[2]) +
                    " is not locally Delaunay: vertex " + std::to_string(far) +
                    " lies inside the circumsphere of " + cell_name(4, c, t)),
             r;
  }
  r.notes.push_back("every interior triangle is locally Delaunay (exact in-sphere)");
  return r;
}

}  // namespace gpugeom::verify
