// The CPU executor's schedule for the 3D hull (issue 53): the points put in one by one, each
// located by a walk over the facets' cones from the kernel point, dropped for good where it lies
// inside the hull so far, else inserted by its cavity (the facets it sees, refilled by the fan
// from it over their boundary). Included inside gpugeom::hull3d::{cpu,cuda}_impl after
// flipflop.inl; it runs on the CPU only (one_pass), over the same facet encoding (surface.inl)
// and the same orientation predicates with the same perturbation (geometry.inl: the kernel
// point is point n) as the rounds, and the extreme test, the second pass and the output follow
// as after them.
//
// Why a second schedule: the rounds (a star-shaped surface by splits, then Flip-Flop's flips)
// suit thousands of GPU threads, and on a few cores they pay for rounds over global lists:
// 10^6 points on a sphere took 6.2 s on the 2-core machine, 4.7 s of it in the flips. One point
// at a time, located from the facet made for the point before it on the curve, touches a few
// cache lines: on a sphere the hull is a triangulation of the points as a 2D Delaunay one is.
//
// Why the output is the same: with simulation of simplicity the hull of the perturbed points is
// unique, and a facet is in q's cavity exactly when q lies above it by the rounds' own test
// (orient3d with the perturbation), so both schedules build the same facets; only the slots
// differ, and the output's order does not follow the slots (hull.inl: compact). Every test here
// is exact with the perturbation, the cones' too (the kernel point perturbed as point n): in the
// perturbed world no point lies on a cone's plane or a facet's, so a walk's end and a drop are
// decided without ties.
//
// The schedule is 2D Delaunay's (mesh/cavity_schedule.hpp, non-locking): the sample (a 32nd of
// the points, in levels of a biased randomised order) on one thread, then each thread inserts its
// chunk of the curve and may change only facets whose three vertices lie in its chunk ("its
// own"); a point whose cavity reaches another facet waits, and the waiting points go in last on
// one thread. The 2D note's argument holds word for word: a cavity of a thread's own facets is
// refilled by facets of its boundary's vertices and the point, all in its chunk; a facet with
// vertices in two chunks is in no cavity while the threads run, so its vertices never change,
// and an edge's two vertices lie in one chunk, so only that chunk's thread rewrites the
// neighbour across it. Two things are the hull's own:
// - a point inside the hull is dropped where its walk ends, on any facet, the thread's or not:
//   the walk's last record (perhaps stale or torn, read while another thread rewrote it) names
//   three inserted points a, b, c, and where s lies below (a, b, c) and q inside the cone from s
//   over it and below it too, q lies in the tetrahedron (s, a, b, c), inside the hull of the
//   points so far, whatever that record was; so a ball's interior points, most of its points,
//   never wait;
// - a cavity may swallow vertices (every facet around them seen): its fan then has fewer facets
//   than it took, 2 fewer a vertex, and the slots left over are marked removed.
// Each point has two slots in its chunk's range (a chunk takes them in the order it inserts);
// those of dropped points and the left-over ones stay removed (tv = -1), as the rounds' dead
// slots, and the output skips them.

constexpr int kHullWalkSteps = 1 << 16;  // a walk this long gives up (then: a scan, or a wait)
using mesh::cavities::load_word;
using mesh::cavities::store_word;

// One thread's insertions (the sample's and the waiting points' run as chunk 0 of 1).
struct HullInserter {
  HullInserter(std::int32_t* tv_, std::int32_t* to_, std::int32_t* mk, std::int32_t* bp,
               const Geo& geo, const std::int32_t* first4, std::int64_t slots)
      : tv(tv_), to(to_), mark(mk), bpos(bp), g(geo), used(slots) {
    std::copy(first4, first4 + 4, first);
    std::sort(first, first + 4);
  }
  std::int32_t* tv;  // the facets (surface.inl's encoding)
  std::int32_t* to;
  std::int32_t* mark;  // per slot: the last point whose cavity took it (q + 1; 0: none)
  std::int32_t* bpos;  // per point: its place on the cavity's boundary (its chunk's thread's)
  Geo g;
  std::int64_t used;       // slots in all
  std::int32_t first[4];   // the first tetrahedron's vertices, sorted
  std::int64_t chunk = 0;  // points per chunk; 0: one thread alone, nothing is anyone else's
  std::int32_t own = 0;    // this thread's chunk
  std::int32_t next = 0;   // the next free slot of the chunk it inserts for
  std::int32_t from = 0;   // the first slot of that chunk (a live facet is looked for there)
  bool broken = false;     // a cavity was no disk (a bug guard)
  std::uint32_t rng = 2463534242u;
  std::int32_t last = -1;  // where the next walk starts: the last point's facet
  std::int32_t home = -1;  // a facet of the last insertion (its own: live while it runs)
  std::int64_t inserted = 0, dropped = 0, exact = 0;
  struct Rec {
    std::int32_t v[3], n[3];
  };
  struct Edge {
    std::int32_t a, b, out;  // counter-clockwise seen from outside; the outer neighbour
  };
  std::vector<std::int32_t> cav;
  std::vector<Edge> bnd;
  std::vector<std::int32_t> before;
  std::vector<double> scratch = std::vector<double>(std::size_t(kScratch));

  Rec read(std::int32_t f) const {
    Rec R;
    for (int k = 0; k < 3; ++k)
      R.v[k] = load_word(tv + 3 * f + k), R.n[k] = load_word(to + 3 * f + k);
    return R;
  }
  // Where the slots of a chunk's points begin: two a point, after the first tetrahedron's four.
  std::int32_t first_slot(std::int32_t lo) const {
    std::int32_t below = 0;
    for (const std::int32_t f : first) below += lo > f;
    return 4 + 2 * (lo - below);
  }
  bool is_first(std::int32_t q) const {
    return q == first[0] || q == first[1] || q == first[2] || q == first[3];
  }
  std::int64_t owner(std::int32_t v) const { return v / chunk; }  // (the chunks of the curve)
  bool mine(const std::int32_t* v) const {
    if (!chunk) return true;
    for (int k = 0; k < 3; ++k)
      if (owner(v[k]) != own) return false;
    return true;
  }
  int orient(std::int32_t i, std::int32_t j, std::int32_t k, std::int32_t l) {
    const int r = FastOrient{g}(i, j, k, l);
    if (r) return r;
    ++exact;
    return ExactOrient{g, scratch.data()}(i, j, k, l);
  }
  // q against the plane through s and facet R's edge k (opposite vertex k): < 0 where q lies
  // beyond it, outside R's cone.
  int side(const Rec& R, int k, std::int32_t q) {
    return orient(g.n, R.v[(k + 1) % 3], R.v[(k + 2) % 3], q);
  }
  bool in_cone(const Rec& R, std::int32_t q) {
    return side(R, 0, q) > 0 && side(R, 1, q) > 0 && side(R, 2, q) > 0;
  }
  static bool sane(const Rec& R) {  // (a removed slot, or a record torn by another thread)
    return R.v[0] >= 0 && R.v[1] >= 0 && R.v[2] >= 0 && R.v[0] != R.v[1] && R.v[1] != R.v[2] &&
           R.v[2] != R.v[0];
  }
  // The facet whose cone from s holds q, by the stochastic visibility walk from slot f (its
  // record in R); -1 where it gives up (a removed or torn record, or too long a walk).
  std::int32_t walk(std::int32_t f, std::int32_t q, Rec& R) {
    return mesh::cavities::visibility_walk<3, mesh::Adjacency>(
        f, rng, kHullWalkSteps, chunk != 0, R, [&](std::int32_t s) { return read(s); },
        [](const Rec& T) { return sane(T); },
        [&](const Rec& T, int k) { return side(T, k, q) < 0; }, [](std::int32_t, const Rec&) {});
  }
  // A live facet at or after slot `at` (the walks' start where none is known), or -1.
  std::int32_t live_from(std::int32_t at) const {
    for (std::int64_t f = at; f < used; ++f)
      if (load_word(tv + 3 * f) >= 0) return std::int32_t(f);
    for (std::int64_t f = 0; f < at; ++f)
      if (load_word(tv + 3 * f) >= 0) return std::int32_t(f);
    return -1;
  }
  // The facet whose cone holds q when no walk found it (one thread alone: every facet tried).
  std::int32_t scan(std::int32_t q, Rec& R) {
    for (std::int64_t f = 0; f < used; ++f) {
      R = read(std::int32_t(f));
      if (sane(R) && in_cone(R, q)) return std::int32_t(f);
    }
    return -1;
  }
  std::int32_t locate(std::int32_t q, Rec& R) {
    const std::int32_t start = last >= 0 ? last : home >= 0 ? home : live_from(from);
    if (start < 0) return -1;
    std::int32_t f = walk(start, q, R);
    if (f < 0 && home >= 0 && start != home) f = walk(home, q, R);  // (last was removed)
    if (f < 0) {  // (home too, or none yet: from any live facet, the chunk's own slots first)
      const std::int32_t l = live_from(from);
      if (l >= 0 && l != start) f = walk(l, q, R);
    }
    if (f < 0 && !chunk) f = scan(q, R);
    return f;
  }
  // An abandoned cavity's marks taken back (they are the thread's own facets), so that a later
  // attempt at the same point, whatever its stamp, finds none: false.
  bool unmark() {
    for (const std::int32_t f : cav) store_word(mark + f, 0);
    return false;
  }
  // Puts q in (inserted, or dropped inside the hull), or returns false having changed nothing
  // (its walk failed, or its cavity reaches another thread's facets).
  bool insert(std::int32_t q) {
    Rec R;
    const std::int32_t f0 = locate(q, R);
    if (f0 < 0) {
      last = -1;
      if (!chunk) broken = true;  // (cannot happen: the cones cover space)
      return false;
    }
    if (orient(R.v[0], R.v[1], R.v[2], q) < 0) {
      // q lies below the facet whose cone holds it: inside the tetrahedron (s, facet), hence
      // inside the hull. A record read while another thread rewrote it may be no facet: then
      // the tetrahedron is checked to be one with s below (a, b, c) and q inside the cone (the
      // walk's end tested two or three of its sides).
      if (chunk) {
        if (orient(R.v[0], R.v[1], R.v[2], g.n) > 0 || !in_cone(R, q)) return last = -1, false;
      }
      last = f0;
      ++dropped;
      return true;
    }
    if (!mine(R.v)) return false;
    // The cavity: the facets q lies above, found from f0; its boundary, edges counter-clockwise
    // seen from outside with the facet across each.
    cav.clear(), bnd.clear();
    cav.push_back(f0);
    const std::int32_t stamp = q + 1;
    store_word(mark + f0, stamp);
    for (std::size_t i = 0; i < cav.size(); ++i) {
      const Rec C = read(cav[i]);
      for (int k = 0; k < 3; ++k) {
        const std::int32_t nb = simplex_of(C.n[k]);
        if (load_word(mark + nb) == stamp) continue;
        const Rec N = read(nb);
        if (orient(N.v[0], N.v[1], N.v[2], q) > 0) {
          if (!mine(N.v)) return unmark();
          store_word(mark + nb, stamp);
          cav.push_back(nb);
        } else {
          bnd.push_back({C.v[(k + 1) % 3], C.v[(k + 2) % 3], C.n[k]});
        }
      }
    }
    // Refilled by the facets (q, a, b) over the boundary's edges. The cavity is a disk: a
    // boundary of e edges around i swallowed vertices closes e + 2i - 2 facets, and the fan has e.
    const std::size_t e = bnd.size(), c = cav.size();
    if (e < 3 || e > c + 2 || (c + 2 - e) % 2) {  // (a bug guard)
      broken = true;                              // (no throw: a thread of a team must not)
      return false;
    }
    for (std::size_t i = 0; i < e; ++i) bpos[bnd[i].a] = std::int32_t(i);
    before.assign(e, -1);
    for (std::size_t i = 0; i < e; ++i) {
      const std::int32_t j = bpos[bnd[i].b];
      if (j < 0 || std::size_t(j) >= e || bnd[std::size_t(j)].a != bnd[i].b ||
          before[std::size_t(j)] >= 0) {
        broken = true;  // (the boundary is one cycle through each of its vertices once)
        return unmark();
      }
      before[std::size_t(j)] = std::int32_t(i);
    }
    auto slot = [&](std::size_t i) { return i < c ? cav[i] : next + std::int32_t(i - c); };
    // (the new slots first, from the last down: the cavity's slots name them, and a walk of
    // another thread reading one could otherwise reach a new slot before it is written)
    for (std::size_t i = e; i-- > 0;) {
      const Edge& E = bnd[i];
      const std::int32_t after = slot(std::size_t(bpos[E.b]));  // (q, b, x): edge q-b opposite x
      const std::int32_t prev = slot(std::size_t(before[i]));   // (q, z, a): edge a-q opposite z
      const std::int32_t f = slot(i);
      const std::int32_t vs[3] = {q, E.a, E.b}, ns[3] = {E.out, enc(after, 2), enc(prev, 1)};
      for (int k = 0; k < 3; ++k) store_word(to + 3 * f + k, ns[k]);
      for (int k = 0; k < 3; ++k) store_word(tv + 3 * f + k, vs[k]);
    }
    for (std::size_t i = 0; i < e; ++i) {  // the outer neighbours, after the facets they name
      const std::int32_t out = bnd[i].out;
      store_word(to + 3 * simplex_of(out) + loc_of(out), enc(slot(i), 0));
    }
    for (std::size_t i = e; i < c; ++i)  // (the slots of swallowed vertices' facets: removed)
      for (int k = 0; k < 3; ++k) store_word(tv + 3 * cav[i] + k, -1);
    last = home = slot(0);
    next += 2;  // (a point's two slots, used or not)
    ++inserted;
    return true;
  }
};

// The first pass's facets by the points one by one (the CPU executor; -1 on the GPU's, which
// has no such schedule): 2n - 4 slots, written into tv / to, the kernel point t.s. Returns the
// slots (each live or removed).
template <class E>
std::int64_t insert_one_by_one(E& ex, const double* pts, std::int64_t n, const Tetra& t,
                               typename E::template Buffer<std::int32_t>& tvb,
                               typename E::template Buffer<std::int32_t>& tob, Hull3dStats& st) {
  if constexpr (E::backend != Backend::Cpu) {
    return -1;
  } else {
    const std::int64_t used = 2 * n - 4;  // (4 + 2 for each of the n - 4 other points)
    tvb = ex.template alloc<std::int32_t>(std::size_t(3 * used));
    tob = ex.template alloc<std::int32_t>(std::size_t(3 * used));
    auto markb = ex.template alloc<std::int32_t>(std::size_t(used));
    auto bposb = ex.template alloc<std::int32_t>(std::size_t(n));
    auto order = ex.template alloc<std::int32_t>(std::size_t(n));
    std::int32_t *tv = tvb.data(), *to = tob.data(), *mk = markb.data();
    ex.fill(tv, 3 * used, std::int32_t(-1));
    ex.fill(mk, used, std::int32_t(0));
    ex.fill(bposb.data(), n, std::int32_t(-1));
    first_facets(t, tv, to);  // (slots 0-3, as the rounds start)
    const Geo geo{pts, t.s, std::int32_t(n)};
    HullInserter one(tv, to, mk, bposb.data(), geo, t.v, used);
    one.last = 0;
    // Each chunk's next free slot, its last sample facet (where its thread's walks start), and
    // what its thread counted (the sample's and the waiting points' are `one`'s own).
    struct Hooks : mesh::cavities::OwnChunkHooks<HullInserter> {
      const HullInserter& one;
      std::int64_t n;
      std::vector<std::int32_t> next, starts, lastf;
      std::vector<std::array<std::int64_t, 3>> counts;  // inserted, dropped, exact
      bool skip(std::int32_t q) const { return one.is_first(q); }
      void chunks(std::int64_t nc, std::int64_t chunk) {
        for (std::int64_t c = 0; c <= nc; ++c)
          next.push_back(one.first_slot(std::int32_t(std::min<std::int64_t>(n, c * chunk))));
        starts = next;
        lastf.assign(std::size_t(nc), -1);
        counts.assign(std::size_t(nc), {0, 0, 0});
      }
      void put(HullInserter& I, std::int64_t c, std::int32_t q) {  // (always goes in)
        I.next = next[std::size_t(c)];
        I.from = starts[std::size_t(c)];
        const std::int64_t before = I.inserted;
        if (!I.insert(q))
          throw Error(ErrorCode::Internal,
                      std::string(I.broken ? "convex hull: a cavity that is no disk"
                                           : "convex hull: a point insertion failed") +
                          "; please report this input");
        next[std::size_t(c)] = I.next;
        if (I.inserted > before) lastf[std::size_t(c)] = I.home;
      }
      void enter(HullInserter& I, std::int64_t c) {
        I.next = next[std::size_t(c)];
        I.from = starts[std::size_t(c)];
        // (the walks start from the chunk's last sample facet, where it has one; it may be gone)
        if (lastf[std::size_t(c)] >= 0) I.last = lastf[std::size_t(c)];
        I.home = -1;
        I.inserted = I.dropped = I.exact = 0;
      }
      void leave(const HullInserter& I, std::int64_t c) {
        next[std::size_t(c)] = I.next;
        auto& k = counts[std::size_t(c)];
        k[0] += I.inserted, k[1] += I.dropped, k[2] += I.exact;
        if (I.home >= 0) lastf[std::size_t(c)] = I.home;  // (where the next stage's walks start)
      }
      void mark(const char*) {}
    };
    Hooks h{{}, one, n, {}, {}, {}, {}};
    // The sample's top levels on one thread, the rest of it by the threads (a ball's sample is
    // mostly dropped, and drops never wait; 16 threads: 10^6 ball 56-61 ms against 64-82, sphere
    // 332-359 against 337-384, 10^7 sphere 2.69-2.87 s against 2.89-3.03), then the chunks.
    mesh::cavities::Schedule how;
    how.alone_level = mesh::cavities::alone_sample_level(n, ex.team_size());
    st.deferred_points +=
        mesh::cavities::insert_by_chunks(ex, std::int32_t(n), order.data(), one, h, how);
    std::array<std::int64_t, 3> all{one.inserted, one.dropped, one.exact};
    for (const auto& k : h.counts)
      for (int i = 0; i < 3; ++i) all[std::size_t(i)] += k[std::size_t(i)];
    st.cavity_insertions += all[0];
    st.exact_predicates += all[2];
    if (all[0] + all[1] != n - 4)  // (a bug guard: every point in or dropped)
      throw Error(ErrorCode::Internal, "convex hull: a point was neither inserted nor dropped");
    return used;
  }
}
