// Phase 2 of the 3D Delaunay tetrahedralisation: adaptive star splaying (thesis 5.3.2;
// Shewchuk's star splaying), on host threads.
//
// The star of a vertex v is its link: triangles (a, b, c) such that (v, a, b, c) is a
// positively oriented tetrahedron, a triangulated sphere around v (the infinity point is a
// vertex of the links of hull vertices). Lifted to 4D, a star is convex when every link edge
// is: for link triangles (a, b, c) and (b, a, d), d lies outside the sphere of (v, a, b, c).
// A vertex whose faces are all locally Delaunay has a convex star in phase 1's result, so
// only the stars of the failed vertices are rebuilt:
//  1. each failed vertex's star is taken from the tetrahedralisation and made convex by
//     Flip-Flop on the lifted star (thesis 5.2.2 one dimension up): a reflex link edge is
//     flipped where the two new link triangles stay positively oriented around v; where it
//     cannot be, the corner that lies inside the cone of the other three is not extreme: its
//     link edges are flipped until it has three, and its three triangles become one.
//  2. splaying: every tetrahedron of a changed star must be in the stars of its other finite
//     vertices. Where star(w) lacks it, its vertices are inserted into star(w) (a convex star
//     takes a vertex by removing the triangles whose spheres contain it and joining it to the
//     boundary of that region, as Bowyer-Watson does); where star(w) still lacks it, star(w)
//     has a vertex inside the tetrahedron's sphere, which is inserted into star(v). Stars only
//     take vertices, each at most once, so this ends; when every star is consistent, the
//     stars are those of the Delaunay tetrahedralisation (Shewchuk).
//  3. the tetrahedra of the old stars that the new ones lack are removed, the new ones added,
//     and the faces between them and the rest linked.
// Stars not read from the tetrahedralisation are never built. Every step runs on host threads:
// 1 and 3 a star to a thread, 2 in rounds (see splay()).
#include <algorithm>
#include <array>
#include <cstring>
#include <exception>
#include <string>
#include <unordered_map>
#include <unordered_set>
#include <vector>

#include "base/clock.hpp"
#include "delaunay3d/tet.hpp"
#include "exec/scratch_lease.hpp"
#include "gpugeom/common.hpp"
#include "mesh/adjacency.hpp"
#include "predicates/predicates.hpp"

#include <omp.h>

namespace gpugeom::del3d {
namespace host_impl {
#include "delaunay3d/impl/geometry.inl"
#include "delaunay3d/impl/link.inl"
}  // namespace host_impl

namespace {
using host_impl::face_vertex;
using host_impl::Geo;
using host_impl::in_sphere_ext;
using host_impl::link_find;
using host_impl::link_find_edge;
using host_impl::link_third;
using host_impl::LinkTri;
using host_impl::orient_ext;
using mesh::enc;
using mesh::loc_of;
using mesh::simplex_of;

[[noreturn]] void internal(const std::string& what) {
  throw Error(ErrorCode::Internal,
              "internal error in star splaying: " + what + "; please report this input");
}

using Key4 = std::array<std::int32_t, 4>;
using Key3 = std::array<std::int32_t, 3>;
Key4 key4(std::int32_t a, std::int32_t b, std::int32_t c, std::int32_t d) {
  Key4 k{a, b, c, d};
  std::sort(k.begin(), k.end());
  return k;
}
Key3 key3(std::int32_t a, std::int32_t b, std::int32_t c) {
  Key3 k{a, b, c};
  std::sort(k.begin(), k.end());
  return k;
}
struct Hash4 {
  std::size_t operator()(const Key4& k) const {
    std::uint64_t h = 0x9e3779b97f4a7c15ull;
    for (std::int32_t x : k) h = (h ^ std::uint32_t(x)) * 0xbf58476d1ce4e5b9ull, h ^= h >> 29;
    return std::size_t(h);
  }
};
struct Hash3 {
  std::size_t operator()(const Key3& k) const { return Hash4{}(Key4{k[0], k[1], k[2], -7}); }
};

// Replaces the tetrahedra in slots `removed` by `added`, which fill the same region: the new
// ones take the freed slots (then new slots at the end), and their faces are linked among
// themselves and, across the removed region's outer faces, with the tetrahedra that stay.
void replace_tets(HostMesh& H, std::vector<std::int32_t> removed, const std::vector<Tet>& added,
                  const char* step) {
  std::sort(removed.begin(), removed.end());
  removed.erase(std::unique(removed.begin(), removed.end()), removed.end());
  std::vector<Tet> old;
  for (std::int32_t t : removed) old.push_back(H.get(t));
  {  // the tetrahedra across the region's outer faces, in one copy rather than one each
    std::vector<std::int32_t> outer;
    for (const Tet& D : old)
      for (int k = 0; k < 4; ++k) outer.push_back(simplex_of(D.n[k]));
    H.load_slots(outer);
  }
  std::vector<std::int32_t> slots;
  std::size_t r = 0;
  for (const Tet& T : added) {
    std::int32_t slot;
    if (r < removed.size()) {
      slot = removed[r++];
      H.set(slot) = T;
    } else {
      slot = H.append(T);
    }
    slots.push_back(slot);
    H.written.push_back(slot);
  }
  for (; r < removed.size(); ++r) {
    Tet dead;
    for (int k = 0; k < 4; ++k) dead.v[k] = dead.n[k] = -1;
    H.set(removed[r]) = dead;
    H.written.push_back(removed[r]);
  }
  // The faces to pair up by their vertices: each new tetrahedron's four, and the removed
  // region's outer faces (with the pointer of the tetrahedron that stays). Sorted, equal keys
  // come in pairs: a new face with a new one, or with an outer one, which sorts after it. (A
  // hash map of faces cost about a microsecond a face on large peels.)
  struct Side {
    Key3 key;
    std::int32_t e;      // new: enc(slot, local); outer: the staying tetrahedron's face
    std::int32_t outer;  // 0 new, 1 outer
    std::int32_t from;   // outer: the removed tetrahedron (index in old), for the message
  };
  auto face_key = [](const Tet& T, int k) {
    return key3(T.v[face_vertex(k, 0)], T.v[face_vertex(k, 1)], T.v[face_vertex(k, 2)]);
  };
  std::vector<Side> sides;
  sides.reserve(4 * (slots.size() + old.size()));
  for (std::int32_t y : slots)
    for (int l = 0; l < 4; ++l) sides.push_back({face_key(H.get(y), l), enc(y, l), 0, -1});
  for (std::size_t j = 0; j < old.size(); ++j)
    for (int k = 0; k < 4; ++k) {
      const std::int32_t nb = simplex_of(old[j].n[k]);
      if (std::binary_search(removed.begin(), removed.end(), nb)) continue;  // inside
      sides.push_back({face_key(old[j], k), old[j].n[k], 1, std::int32_t(j)});
    }
  std::sort(sides.begin(), sides.end(), [](const Side& x, const Side& y) {
    return x.key != y.key ? x.key < y.key : x.outer < y.outer;
  });
  for (std::size_t i = 0; i < sides.size(); i += 2) {
    const bool pair = i + 1 < sides.size() && sides[i + 1].key == sides[i].key &&
                      !(i + 2 < sides.size() && sides[i + 2].key == sides[i].key);
    if (!pair || sides[i].outer) {
      const Side& x = sides[i].outer || !pair || !sides[i + 1].outer ? sides[i] : sides[i + 1];
      if (!x.outer)
        internal(std::string(step) + ": face " + std::to_string(x.key[0]) + " " +
                 std::to_string(x.key[1]) + " " + std::to_string(x.key[2]) +
                 " of the new tetrahedra is left unmatched");
      const Tet& D = old[std::size_t(x.from)];
      internal(std::string(step) + ": surviving face " + std::to_string(x.key[0]) + " " +
               std::to_string(x.key[1]) + " " + std::to_string(x.key[2]) + " (of " +
               std::to_string(D.v[0]) + " " + std::to_string(D.v[1]) + " " +
               std::to_string(D.v[2]) + " " + std::to_string(D.v[3]) + ", neighbour slot " +
               std::to_string(simplex_of(x.e)) + ") has no new tetrahedron");
    }
    const Side& a = sides[i];
    const Side& b = sides[i + 1];
    H.set(simplex_of(a.e)).n[loc_of(a.e)] = b.e;
    H.set(simplex_of(b.e)).n[loc_of(b.e)] = a.e;
    if (b.outer) H.written.push_back(simplex_of(b.e));
  }
}

// Four finite points exactly on one plane (see peel_flat). scratch: kOrient3dScratch doubles.
bool flat_tet(const HostMesh& H, const Tet& T, double* scratch) {
  if (T.v[0] < 0) return false;
  for (int k = 0; k < 4; ++k)
    if (T.v[k] == H.m) return false;
  auto at = [&](std::int32_t i) { return H.pts + 3 * std::int64_t(i); };
  const double *a = at(T.v[0]), *b = at(T.v[1]), *c = at(T.v[2]), *d = at(T.v[3]);
  return pred::orient3d_fast(a, b, c, d) == 0 && pred::orient3d(a, b, c, d, scratch) == 0;
}

// The written live slots' neighbours share their faces and point back (a guard on the host
// paths, local: the rest of the store is as phase 1 left it).
void check_adjacency(HostMesh& H, const char* step) {
  // (a slot is listed once per write; each is checked once)
  std::vector<std::int32_t> slots(H.written);
  std::sort(slots.begin(), slots.end());
  slots.erase(std::unique(slots.begin(), slots.end()), slots.end());
  {  // (neighbours not read yet come in one copy)
    std::vector<std::int32_t> nb;
    for (const std::int32_t t : slots)
      for (int k = 0; k < 4; ++k) nb.push_back(simplex_of(H.get(t).n[k]));
    H.load_slots(nb);
  }
  // Face k of slot t: 0 fine, 1 no neighbour, 2 a wrong one. (Read-only: every slot needed
  // is loaded, so all threads check; the first bad slot in slot order is reported.)
  auto face_state = [&H](std::int32_t t, const Tet& T, int k) {
    const std::int32_t e = T.n[k], o = simplex_of(e);
    const Tet* O = e < 0 || o >= H.used ? nullptr : H.peek(o);
    if (!O) return 1;
    const bool ok =
        O->v[0] >= 0 && O->n[loc_of(e)] == enc(t, k) &&
        host_impl::opposite_of_face(O->v, T.v[face_vertex(k, 0)], T.v[face_vertex(k, 1)],
                                    T.v[face_vertex(k, 2)]) == loc_of(e);
    return ok ? 0 : 2;
  };
  std::int64_t bad = std::int64_t(slots.size());
#pragma omp parallel for schedule(static, 1024) reduction(min : bad)
  for (std::int64_t i = 0; i < std::int64_t(slots.size()); ++i) {
    const Tet* T = H.peek(slots[std::size_t(i)]);
    if (!T || T->v[0] < 0) continue;
    for (int k = 0; k < 4 && i < bad; ++k)
      if (face_state(slots[std::size_t(i)], *T, k)) bad = i;
  }
  if (bad == std::int64_t(slots.size())) return;
  const std::int32_t t = slots[std::size_t(bad)];
  const Tet& T = *H.peek(t);
  for (int k = 0; k < 4; ++k)
    if (const int st = face_state(t, T, k))
      internal(std::string(step) + ": slot " + std::to_string(t) + " face " + std::to_string(k) +
               (st == 1 ? " has no neighbour" : " has a wrong neighbour"));
}

using Tri = LinkTri;  // (delaunay3d/impl/link.inl)

struct Edge {
  std::int32_t a, b;
};

struct Star {
  std::vector<Tri> tris;
  // Every vertex this star has been given, sorted (a few dozen; thousands on the hull planes
  // of integer grids, where a linear search made entering stars quadratic).
  std::vector<std::int32_t> offered;
  bool was_offered(std::int32_t x) const {
    return std::binary_search(offered.begin(), offered.end(), x);
  }
  void offer_all(const std::vector<Tri>& ts) {
    for (const Tri& t : ts) offered.insert(offered.end(), {t.a, t.b, t.c});
    std::sort(offered.begin(), offered.end());
    offered.erase(std::unique(offered.begin(), offered.end()), offered.end());
  }
  bool offer(std::int32_t x) {  // false if x was given before
    const auto it = std::lower_bound(offered.begin(), offered.end(), x);
    if (it != offered.end() && *it == x) return false;
    offered.insert(it, x);
    return true;
  }
  bool changed = false;
  bool rebuilt = false;
};

class Splayer {
 public:
  // A tetrahedron to check, positively oriented, from the star of t[owner]: if that star has
  // it, the stars of its other vertices must have it too.
  struct Item {
    std::array<std::int32_t, 4> t;
    int owner;
  };
  Splayer(HostMesh& H) : H_(H) {
    g_.p = H.pts;
    for (int k = 0; k < 3; ++k) g_.s[k] = H.s[k];
    g_.m = H.m;
    scratch_.assign(std::size_t(std::max(pred::kInsphereScratch, pred::kOrient3dScratch)), 0.0);
    g_.lease = ScratchLease{scratch_.data(), &busy_, 1, pred::kInsphereScratch};
    if (H.vt.size() != std::size_t(H.m) + 1) internal("no vertex map");
  }

  // faces: the failed faces (three vertices each), or empty with every vertex of a failed face
  // marked in `failed` when the list did not fit.
  SplayStats run(const std::vector<std::int8_t>& failed, const std::vector<std::int32_t>& faces,
                 int threads) {
    // The link edges each failed vertex must test first: a star read from the mesh is convex
    // at every edge but those of its failed faces (the edge (a, b) of star(v) is reflex iff
    // the face (v, a, b) is not locally Delaunay).
    auto t0 = Clock::now();
    std::unordered_map<std::int32_t, std::vector<Edge>> seeds;
    for (std::size_t f = 0; f + 2 < faces.size(); f += 3)
      for (int i = 0; i < 3; ++i) {
        const std::int32_t v = faces[f + i], a = faces[f + (i + 1) % 3], b = faces[f + (i + 2) % 3];
        if (v != H_.m) seeds[v].push_back({a, b});
      }
    std::vector<std::int32_t> fv;
    if (faces.empty()) {
      for (std::int32_t v = 0; v < H_.m; ++v)
        if (failed[std::size_t(v)]) fv.push_back(v);
    } else {
      for (auto& kv : seeds) fv.push_back(kv.first);
      std::sort(fv.begin(), fv.end());
    }
    // Each failed star read and made convex on its own (in parallel: they share nothing but
    // the mesh, which they only read), then entered in order.
    const int nt = threads > 0 ? threads : omp_get_max_threads();
    load_stars(fv);
    std::vector<Star> built(fv.size());
    std::vector<std::vector<Tri>> before(fv.size());
    parallel_for(std::int64_t(fv.size()), nt, [&](std::int64_t i, const Geo& g) {
      const std::int32_t v = fv[std::size_t(i)];
      Star& st = built[std::size_t(i)];
      mesh_star(v, &st.tris, nullptr);
      before[std::size_t(i)] = st.tris;
      std::vector<Edge> work;
      if (faces.empty())
        all_edges(st, work);
      else
        work = seeds.at(v);
      convexify(g, v, st, work);
    });
    {  // the stars splaying will read first: those of the failed vertices' neighbours
      std::vector<std::int32_t> near;
      for (const auto& b : before)
        for (const Tri& t : b) near.insert(near.end(), {t.a, t.b, t.c});
      load_stars(near);
    }
    for (std::size_t i = 0; i < fv.size(); ++i) {
      const std::int32_t v = fv[i];
      ++st_.failed_vertices;
      Star& s = stars_[v];
      s = std::move(built[i]);
      s.offer_all(s.tris);
      s.offer_all(before[i]);
      s.rebuilt = s.changed = true;
      ++st_.stars_rebuilt;
      changed(v, before[i], s.tris);
    }
    st_.us_stars = std::int64_t(1000 * ms_since(t0));
    t0 = Clock::now();
    splay(nt);
    st_.us_queue = std::int64_t(1000 * ms_since(t0));
    t0 = Clock::now();
    patch(nt);
    check_adjacency(H_, "after splaying");
    st_.us_patch = std::int64_t(1000 * ms_since(t0));
    return st_;
  }

  // ---- stars ----
  // The star of v as the tetrahedralisation has it (slots too, for the patch).
  void mesh_star(std::int32_t v, std::vector<Tri>* tris, std::vector<std::int32_t>* slots) {
    const std::int32_t t0 = H_.vt[std::size_t(v)];
    if (t0 < 0) internal("vertex " + std::to_string(v) + " is in no tetrahedron");
    std::vector<std::int32_t> stack{t0};
    std::unordered_set<std::int32_t> seen{t0};
    while (!stack.empty()) {
      const std::int32_t t = stack.back();
      stack.pop_back();
      const Tet* P = H_.peek(t);
      if (!P) internal("a star read before it was loaded");
      const Tet& T = *P;
      int k = 0;
      while (k < 4 && T.v[k] != v) ++k;
      if (k == 4) internal("vertex map out of date");
      if (tris)
        tris->push_back({T.v[face_vertex(k, 0)], T.v[face_vertex(k, 1)], T.v[face_vertex(k, 2)]});
      if (slots) slots->push_back(t);
      for (int j = 0; j < 4; ++j) {
        if (j == k) continue;
        const std::int32_t nb = simplex_of(T.n[j]);
        if (seen.insert(nb).second) stack.push_back(nb);
      }
    }
  }
  // The star of v, built (read-only: parallel rounds look stars up, build_stars makes them).
  const Star& star(std::int32_t v) const {
    const auto it = stars_.find(v);
    if (it == stars_.end()) internal("a star used before it was built");
    return it->second;
  }
  Star& star_to_change(std::int32_t v) {  // (find only: safe beside other threads' finds)
    const auto it = stars_.find(v);
    if (it == stars_.end()) internal("a star changed before it was built");
    return it->second;
  }
  // The stars of the items' vertices that are not built yet, from the tetrahedralisation
  // (loaded in one copy, walked on all threads).
  void build_stars(const std::vector<Item>& items, int threads) {
    std::vector<std::int32_t> want;
    for (const Item& it : items)
      for (std::int32_t w : it.t)
        if (w != H_.m && !stars_.count(w)) want.push_back(w);
    std::sort(want.begin(), want.end());
    want.erase(std::unique(want.begin(), want.end()), want.end());
    if (want.empty()) return;
    load_stars(want);
    std::vector<std::vector<Tri>> tris(want.size());
    parallel_for(std::int64_t(want.size()), threads, [&](std::int64_t i, const Geo&) {
      mesh_star(want[std::size_t(i)], &tris[std::size_t(i)], nullptr);
    });
    for (std::size_t i = 0; i < want.size(); ++i) {
      Star& s = stars_[want[i]];
      s.tris = std::move(tris[i]);
      s.offer_all(s.tris);
    }
  }
  // Stars from the executor (timed: the copies and the walks there).
  void load_stars(const std::vector<std::int32_t>& verts) {
    const auto t0 = Clock::now();
    H_.load_stars(verts);
    st_.us_load += std::int64_t(1000 * ms_since(t0));
  }
  // f(i, geo) for i in [0, n) on host threads, each with its own exact scratch; the first
  // exception (in index order of the threads that threw, any one of them) is rethrown.
  template <class F>
  void parallel_for(std::int64_t n, int threads, F&& f) {
    std::exception_ptr err;
#pragma omp parallel num_threads(threads)
    {
      std::vector<double> scratch(scratch_.size());
      std::int32_t busy = 0;
      Geo g = g_;
      g.lease = ScratchLease{scratch.data(), &busy, 1, pred::kInsphereScratch};
#pragma omp for schedule(dynamic, 16)
      for (std::int64_t i = 0; i < n; ++i) {
        try {
          f(i, g);
        } catch (...) {
#pragma omp critical
          if (!err) err = std::current_exception();
        }
      }
    }
    if (err) std::rethrow_exception(err);
  }

  // (The link operations are delaunay3d/impl/link.inl's, shared with the digital method.)
  static int find_edge(const Star& s, std::int32_t a, std::int32_t b) {  // directed a -> b
    return link_find_edge(s.tris.data(), int(s.tris.size()), a, b);
  }
  static std::int32_t third(const Tri& t, std::int32_t a, std::int32_t b) {
    return link_third(t, a, b);
  }
  static bool contains(const Star& s, std::int32_t a, std::int32_t b, std::int32_t c) {
    return link_find(s.tris.data(), int(s.tris.size()), a, b, c) >= 0;
  }
  static bool reflex(const Geo& g, std::int32_t v, const Tri& t, std::int32_t d) {
    return host_impl::link_reflex(g, v, t, d);
  }

  // Link edge a -> b of triangles (a, b, c) and (b, a, d) replaced by (c, d): triangles
  // (a, d, c) and (d, b, c), when both stay positively oriented around v. cd, if given, gets
  // the new edge.
  static bool try_flip(const Geo& g, std::int32_t v, Star& s, std::int32_t a, std::int32_t b,
                       Edge* cd = nullptr) {
    const int i1 = find_edge(s, a, b), i2 = find_edge(s, b, a);
    if (i1 < 0 || i2 < 0) internal("link edge without two triangles");
    const std::int32_t c = third(s.tris[std::size_t(i1)], a, b);
    const std::int32_t d = third(s.tris[std::size_t(i2)], a, b);
    if (c == d) return false;
    if (orient_ext(g, v, a, d, c) <= 0 || orient_ext(g, v, d, b, c) <= 0) return false;
    s.tris[std::size_t(i1)] = {a, d, c};
    s.tris[std::size_t(i2)] = {d, b, c};
    if (cd) *cd = {c, d};
    return true;
  }

  // Removes x (not extreme in v's star) from the star: flips of its link edges until it has
  // three neighbours, then its three triangles become one. Every edge of a triangle it makes
  // goes to work (only those can have become reflex).
  static void remove_vertex(const Geo& g, std::int32_t v, Star& s, std::int32_t x,
                            std::vector<Edge>& work) {
    for (int guard = 0;; ++guard) {
      if (guard > 100000) internal("a vertex could not be removed from a star");
      std::vector<std::int32_t> nbrs;
      for (const Tri& t : s.tris) {
        if (t.a == x) nbrs.push_back(t.b);
        if (t.b == x) nbrs.push_back(t.c);
        if (t.c == x) nbrs.push_back(t.a);
      }
      if (nbrs.empty()) return;
      if (nbrs.size() == 3) {
        // the triangles (x, y0, y1), (x, y1, y2), (x, y2, y0) -> (y0, y1, y2)
        const std::int32_t y0 = nbrs[0];
        const int i0 = find_edge(s, x, y0);
        const std::int32_t y1 = third(s.tris[std::size_t(i0)], x, y0);
        const int i1 = find_edge(s, x, y1);
        const std::int32_t y2 = third(s.tris[std::size_t(i1)], x, y1);
        if (orient_ext(g, v, y0, y1, y2) <= 0) internal("a removed vertex left a folded star");
        std::vector<Tri> keep;
        for (const Tri& t : s.tris)
          if (!t.has(x)) keep.push_back(t);
        keep.push_back({y0, y1, y2});
        s.tris.swap(keep);
        work.insert(work.end(), {Edge{y0, y1}, Edge{y1, y2}, Edge{y2, y0}});
        return;
      }
      bool flipped = false;
      for (std::int32_t y : nbrs) {
        Edge n;
        if (try_flip(g, v, s, x, y, &n)) {  // (x, y) -> (c, d): the two new triangles' edges
          const std::int32_t c = n.a, d = n.b;
          work.insert(work.end(), {Edge{x, d}, Edge{d, y}, Edge{y, c}, Edge{c, x}, Edge{c, d}});
          flipped = true;
          break;
        }
      }
      if (!flipped) internal("no flip reduces a non-extreme vertex of a star");
    }
  }

  // Every link edge of s once.
  static void all_edges(const Star& s, std::vector<Edge>& work) {
    for (const Tri& t : s.tris) {
      const std::int32_t e[3][2] = {{t.a, t.b}, {t.b, t.c}, {t.c, t.a}};
      for (auto& x : e)
        if (x[0] < x[1]) work.push_back({x[0], x[1]});
    }
  }

  // Flip-Flop on the lifted star of v (see the top of the file), from the link edges in work:
  // a flipped edge's four neighbours are tested next, and a vertex taken out lists the edges
  // of every triangle it made. (It once listed every edge of the star again, which on the
  // large stars over integer grids' hull planes took up to a second.)
  static void convexify(const Geo& g, std::int32_t v, Star& s, std::vector<Edge>& work) {
    for (std::int64_t guard = 0; !work.empty(); ++guard) {
      if (guard > 10000000) internal("Flip-Flop on a star did not converge");
      Edge ed = work.back();
      work.pop_back();
      int i1 = find_edge(s, ed.a, ed.b);
      if (i1 < 0) {
        std::swap(ed.a, ed.b);
        i1 = find_edge(s, ed.a, ed.b);
        if (i1 < 0) continue;  // flipped away since it was listed
      }
      const std::int32_t a = ed.a, b = ed.b;
      const int j = find_edge(s, b, a);
      if (j < 0) internal("open star");
      const std::int32_t c = third(s.tris[std::size_t(i1)], a, b);
      const std::int32_t d = third(s.tris[std::size_t(j)], a, b);
      if (!reflex(g, v, Tri{a, b, c}, d)) continue;
      if (try_flip(g, v, s, a, b)) {
        work.push_back({a, d});
        work.push_back({d, b});
        work.push_back({b, c});
        work.push_back({c, a});
        continue;
      }
      // Not flippable: the corner inside the cone of the other three is not extreme.
      const std::int32_t x = orient_ext(g, v, a, d, c) < 0 ? a : b;
      remove_vertex(g, v, s, x, work);
    }
  }

  // Bowyer-Watson in a convex star: x enters when some triangle's sphere contains it. The
  // items to check afterwards go to out. (Touches only s: stars take vertices in parallel.)
  static bool insert(const Geo& g, std::int32_t v, Star& s, std::int32_t x,
                     std::vector<Item>& out) {
    if (x == v || !s.offer(x)) return false;
    // (A disk of c triangles has at most c + 2 boundary edges: room for 2 n + 2 suffices.)
    const int n = int(s.tris.size());
    s.tris.resize(std::size_t(2 * n + 8));
    int removed = 0;
    const int r = host_impl::link_insert(g, v, s.tris.data(), n, int(s.tris.size()), x,
                                         [&](const Tri& t) { gone(v, t, out), ++removed; });
    if (r < 0) {
      s.tris.resize(std::size_t(n));
      internal(r == host_impl::kLinkBroken ? "a star insertion made a negative triangle"
                                           : "a star insertion without room");
    }
    s.tris.resize(std::size_t(r));
    if (removed == 0) return false;
    // The new triangles are the last ones: those with x.
    for (int i = r - 1; i >= 0 && s.tris[std::size_t(i)].has(x); --i) {
      const Tri& t = s.tris[std::size_t(i)];
      out.push_back({{v, t.a, t.b, t.c}, 0});
    }
    s.changed = true;
    return true;
  }

  // ---- splaying ----
  // Triangle (a, b, c) left the star of v: the stars of a, b and c may still have (v, a, b, c).
  static void gone(std::int32_t v, const Tri& t, std::vector<Item>& out) {
    for (int o = 1; o < 4; ++o) out.push_back({{v, t.a, t.b, t.c}, o});
  }
  // The star of v went from `before` to `after`: check what left it and what came.
  void changed(std::int32_t v, const std::vector<Tri>& before, const std::vector<Tri>& after) {
    std::unordered_set<Key3, Hash3> now, was;
    for (const Tri& t : after) now.insert(key3(t.a, t.b, t.c));
    for (const Tri& t : before) {
      was.insert(key3(t.a, t.b, t.c));
      if (!now.count(key3(t.a, t.b, t.c))) gone(v, t, queue_);
    }
    for (const Tri& t : after)
      if (!was.count(key3(t.a, t.b, t.c))) queue_.push_back({{v, t.a, t.b, t.c}, 0});
  }
  static void others(const std::array<std::int32_t, 4>& t, int i, std::int32_t* o) {
    int n = 0;
    for (int j = 0; j < 4; ++j)
      if (j != i) o[n++] = t[std::size_t(j)];
  }

  // A vertex that a star must take (a request of one round's check).
  struct Take {
    std::int32_t star, vertex;
    bool operator<(const Take& o) const {
      return star != o.star ? star < o.star : vertex < o.vertex;
    }
    bool operator==(const Take& o) const { return star == o.star && vertex == o.vertex; }
  };
  // One item against the stars as they are (read-only): what they must take, and whether
  // the item must be checked again after that.
  bool check(const Geo& g, const Item& it, std::vector<Take>& take) const {
    const std::array<std::int32_t, 4>& q = it.t;
    const std::int32_t x = q[std::size_t(it.owner)];
    if (x == H_.m) return false;
    std::int32_t ox[3];
    others(q, it.owner, ox);
    const Star& sx = star(x);
    if (!contains(sx, ox[0], ox[1], ox[2])) return false;  // not (or no longer) in star(x)
    bool again = false;
    for (int i = 0; i < 4; ++i) {
      const std::int32_t w = q[std::size_t(i)];
      if (i == it.owner || w == H_.m) continue;
      std::int32_t o[3];
      others(q, i, o);
      const Star& sw = star(w);
      if (contains(sw, o[0], o[1], o[2])) continue;
      again = true;
      bool fresh = false;  // star(w) takes the vertices of the tetrahedron it lacks
      for (int j = 0; j < 3; ++j)
        if (!sw.was_offered(o[j])) take.push_back({w, o[j]}), fresh = true;
      if (fresh) continue;
      // It took them and still lacks it: star(w) keeps a vertex inside the sphere of q, which
      // star(x) takes (it was never offered to x: x's star would not hold the face of q).
      std::vector<std::int32_t> cand;
      for (const Tri& t : sw.tris)
        for (std::int32_t y : {t.a, t.b, t.c})
          if (y != q[0] && y != q[1] && y != q[2] && y != q[3]) cand.push_back(y);
      std::sort(cand.begin(), cand.end());
      cand.erase(std::unique(cand.begin(), cand.end()), cand.end());
      bool moved = false;
      for (std::int32_t y : cand)
        if (in_sphere_ext(g, q.data(), y)) take.push_back({x, y}), moved = true;
      if (!moved) internal("inconsistent stars that no insertion separates");
    }
    return again;
  }

  // Splaying in rounds: every queued item is checked against the stars as they are (in
  // parallel, read-only), then each star takes the vertices asked of it (in parallel, a star
  // to a thread, in vertex order), which queues the next round's items. A star is the convex
  // star of the vertices it was offered, whatever their order, and stars only take vertices,
  // so this ends, in the same stars as one queue would (Shewchuk), on any number of threads.
  void splay(int threads) {
    std::vector<Item> items;
    while (!queue_.empty()) {
      items.swap(queue_);
      queue_.clear();
      ++st_.rounds;
      build_stars(items, threads);
      std::vector<std::vector<Take>> takes(static_cast<std::size_t>(threads));
      std::vector<std::vector<Item>> again(static_cast<std::size_t>(threads));
      parallel_for(std::int64_t(items.size()), threads, [&](std::int64_t i, const Geo& g) {
        const int me = omp_get_thread_num();
        if (check(g, items[std::size_t(i)], takes[std::size_t(me)]))
          again[std::size_t(me)].push_back(items[std::size_t(i)]);
      });
      std::vector<Take> all;
      for (int t = 0; t < threads; ++t) {
        all.insert(all.end(), takes[std::size_t(t)].begin(), takes[std::size_t(t)].end());
        queue_.insert(queue_.end(), again[std::size_t(t)].begin(), again[std::size_t(t)].end());
      }
      std::sort(all.begin(), all.end());
      all.erase(std::unique(all.begin(), all.end()), all.end());
      std::vector<std::size_t> first;  // where each star's requests begin
      for (std::size_t k = 0; k < all.size(); ++k)
        if (k == 0 || all[k].star != all[k - 1].star) first.push_back(k);
      first.push_back(all.size());
      const std::size_t groups = first.size() - 1;
      std::vector<std::vector<Item>> made(groups);
      std::vector<std::int64_t> taken(groups, 0);
      parallel_for(std::int64_t(groups), threads, [&](std::int64_t k, const Geo& g) {
        const std::size_t b = first[std::size_t(k)], e = first[std::size_t(k) + 1];
        Star& s = star_to_change(all[b].star);
        for (std::size_t r = b; r < e; ++r)
          taken[std::size_t(k)] += insert(g, all[b].star, s, all[r].vertex, made[std::size_t(k)]);
      });
      for (std::size_t k = 0; k < groups; ++k) {
        st_.insertions += taken[k];
        queue_.insert(queue_.end(), made[k].begin(), made[k].end());
      }
    }
  }

  // ---- patch ----
  // Each changed star on its own (in parallel): the old tetrahedra of v the new star lacks go,
  // the new ones of v the old star lacks come. A tetrahedron of the mesh is in the old star of
  // each of its vertices, so one missing from the old star of v is new to the mesh; the same
  // new tetrahedron comes from up to four stars and is added once, as the lowest vertex's star
  // gives it (a positive order of its vertices, the same on every run).
  void patch(int threads) {
    std::vector<std::pair<std::int32_t, const Star*>> work;
    for (auto& [v, s] : stars_)
      if (s.changed) work.push_back({v, &s});
    st_.stars_touched = std::int64_t(work.size());
    struct New {
      Key4 key;
      std::int32_t v;
      Tet tet;
    };
    std::vector<std::vector<std::int32_t>> gone(work.size());
    std::vector<std::vector<New>> made(work.size());
    parallel_for(std::int64_t(work.size()), threads, [&](std::int64_t i, const Geo&) {
      const std::int32_t v = work[std::size_t(i)].first;
      const Star& s = *work[std::size_t(i)].second;
      std::vector<Tri> ot;
      std::vector<std::int32_t> os;
      mesh_star(v, &ot, &os);
      std::vector<Key3> now, was;
      for (const Tri& t : s.tris) now.push_back(key3(t.a, t.b, t.c));
      for (const Tri& t : ot) was.push_back(key3(t.a, t.b, t.c));
      std::sort(now.begin(), now.end());
      std::sort(was.begin(), was.end());
      for (std::size_t j = 0; j < ot.size(); ++j)
        if (!std::binary_search(now.begin(), now.end(), key3(ot[j].a, ot[j].b, ot[j].c)))
          gone[std::size_t(i)].push_back(os[j]);
      for (const Tri& t : s.tris)
        if (!std::binary_search(was.begin(), was.end(), key3(t.a, t.b, t.c))) {
          // (the link triangle turned to start at its lowest vertex, an even permutation: how
          // a star was loaded or rebuilt must not show in the output's vertex order)
          std::int32_t x[3] = {t.a, t.b, t.c};
          const int lo = x[1] < x[0] && x[1] < x[2] ? 1 : x[2] < x[0] && x[2] < x[1] ? 2 : 0;
          const Tet T{{v, x[lo], x[(lo + 1) % 3], x[(lo + 2) % 3]}, {-1, -1, -1, -1}};
          made[std::size_t(i)].push_back({key4(v, t.a, t.b, t.c), v, T});
        }
    });
    std::vector<std::int32_t> removed;
    std::vector<New> all;
    for (std::size_t i = 0; i < work.size(); ++i) {
      removed.insert(removed.end(), gone[i].begin(), gone[i].end());
      all.insert(all.end(), made[i].begin(), made[i].end());
    }
    std::sort(all.begin(), all.end(), [](const New& x, const New& y) {
      return x.key != y.key ? x.key < y.key : x.v < y.v;
    });
    std::vector<Tet> tets;
    for (std::size_t i = 0; i < all.size(); ++i) {
      if (i > 0 && all[i].key == all[i - 1].key) continue;
      tets.push_back(all[i].tet);
      if (flat_tet(H_, all[i].tet, scratch_.data())) ++st_.flat_added;
    }
    std::sort(removed.begin(), removed.end());
    removed.erase(std::unique(removed.begin(), removed.end()), removed.end());
    st_.removed = std::int64_t(removed.size());
    st_.added = std::int64_t(tets.size());
    replace_tets(H_, removed, tets, "patch");
  }

  HostMesh& H_;
  Geo g_;
  std::vector<double> scratch_;
  std::int32_t busy_ = 0;
  std::unordered_map<std::int32_t, Star> stars_;  // (references stay valid as it grows)
  std::vector<Item> queue_;
  SplayStats st_;
};

// Flat tetrahedra on the hull (see tet.hpp), all at once. A flat tetrahedron's four points lie
// in one plane, and it can be Delaunay under the perturbation only where that plane supports
// the hull (anywhere else its sphere, nearly that plane, holds the points on one side), so the
// flat tetrahedra are thin layers over hull facets' planes. The tetrahedra with positive
// volume tile the hull by themselves; the boundary of their union is the hull's surface, made
// of the hull facets of positive tetrahedra that stay, and of the faces between positive and
// flat tetrahedra. So every flat tetrahedron goes, with the infinite tetrahedra over its faces,
// and each face between a positive and a flat tetrahedron gets an infinite tetrahedron:
// replace_tets links them along the hull's edges. The other tetrahedra stay as they were, so
// the result is still Delaunay. (Peeling one flat tetrahedron at a time, as this once did,
// could stall: over a plane with many points the layers overlap, and no single peel kept the
// hull a surface.)
std::int64_t peel(HostMesh& H, std::vector<std::int32_t> cand, bool all_slots) {
  if (all_slots) {
    H.load_all();
    cand.resize(std::size_t(H.used));
    for (std::int32_t t = 0; t < std::int32_t(H.used); ++t) cand[std::size_t(t)] = t;
  } else {  // phase 1's flat slots and what phase 2 wrote, with their neighbours, in one copy
    cand.insert(cand.end(), H.written.begin(), H.written.end());
    std::sort(cand.begin(), cand.end());
    cand.erase(std::unique(cand.begin(), cand.end()), cand.end());
    H.load_slots(cand);
    std::vector<std::int32_t> nb;
    for (const std::int32_t t : cand)
      for (int k = 0; k < 4; ++k)
        if (H.peek(t)->v[0] >= 0) nb.push_back(simplex_of(H.peek(t)->n[k]));
    H.load_slots(nb);
  }
  auto infinite = [&](const Tet& T) {
    return T.v[0] == H.m || T.v[1] == H.m || T.v[2] == H.m || T.v[3] == H.m;
  };
  std::vector<std::int8_t> is_flat(cand.size(), 0);
#pragma omp parallel
  {
    std::vector<double> scratch(std::size_t(pred::kOrient3dScratch));
#pragma omp for schedule(static, 4096)
    for (std::int64_t i = 0; i < std::int64_t(cand.size()); ++i)
      is_flat[std::size_t(i)] = flat_tet(H, *H.peek(cand[std::size_t(i)]), scratch.data());
  }
  std::vector<double> scratch(std::size_t(pred::kOrient3dScratch));
  std::vector<std::uint8_t> seen(std::size_t(H.used), 0);  // (a byte per slot: cheaper than a set)
  std::vector<std::int32_t> removed, stack;
  std::vector<Tet> added;
  std::int64_t peeled = 0;
  for (std::size_t i = 0; i < cand.size(); ++i) {
    if (!is_flat[i] || seen[std::size_t(cand[i])]) continue;
    // One connected layer: it must reach the outside (else it would lie inside the hull).
    bool outside = false;
    stack.assign(1, cand[i]);
    seen[std::size_t(cand[i])] = 1;
    while (!stack.empty()) {
      const std::int32_t t = stack.back();
      stack.pop_back();
      removed.push_back(t);
      ++peeled;
      const Tet T = H.get(t);
      for (int k = 0; k < 4; ++k) {
        const std::int32_t nb = simplex_of(T.n[k]);
        const Tet& N = H.get(nb);
        if (infinite(N)) {
          removed.push_back(nb);
          outside = true;
        } else if (flat_tet(H, N, scratch.data())) {
          if (!seen[std::size_t(nb)]) seen[std::size_t(nb)] = 1, stack.push_back(nb);
        } else {  // T's face k, oriented outward from the neighbour, with the infinity point
          added.push_back(
              Tet{{T.v[face_vertex(k, 0)], T.v[face_vertex(k, 2)], T.v[face_vertex(k, 1)], H.m},
                  {-1, -1, -1, -1}});
        }
      }
    }
    if (!outside)
      internal("flat tetrahedra inside the hull, around slot " + std::to_string(cand[i]));
  }
  if (peeled > 0) replace_tets(H, removed, added, "peel");
  check_adjacency(H, "after peeling");
  return peeled;
}
}  // namespace

SplayStats splay(HostMesh& mesh, const std::vector<std::int8_t>& failed,
                 const std::vector<std::int32_t>& faces, int threads) {
  Splayer s(mesh);
  return s.run(failed, faces, threads);
}

std::int64_t peel_flat(HostMesh& mesh, const std::vector<std::int32_t>& flats, bool all_slots) {
  return peel(mesh, flats, all_slots);
}

}  // namespace gpugeom::del3d
