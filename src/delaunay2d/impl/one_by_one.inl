// The CPU executor's schedule for 2D Delaunay (issue 53): the points inserted one by one in
// curve order, each by its cavity (Bowyer-Watson), the threads over chunks of the curve.
// Included inside gpugeom::del2d::{cpu,cuda}_impl after triangulator.inl; it runs on the CPU
// only (Triangulator::insert_one_by_one), over the same store, predicates and perturbation
// as the batches (store.inl, geometry.inl), and the peel and the output follow as after them.
//
// Why a second schedule: the batches' rounds suit thousands of GPU threads, and on a few cores
// they pay for rounds over global lists, the points' relocation through the flip history and
// the votes (docs/performance.md, issue 53). One point at a time, located by a walk from the
// triangle made for the point before it on the curve, touches a few cache lines.
//
// Why the output is the same: the Delaunay triangulation of the perturbed points is unique,
// and both schedules build it with the same predicates (a triangle conflicts with q where the
// flips would call its edge to q illegal: illegal_fast / illegal_exact), so only the slots
// differ, and the output's order does not follow the slots (finish.inl).
//
// The order and the chunks' schedule are shared with 3D (mesh/cavity_schedule.hpp): levels of a
// biased randomised order (order_by_level), each in curve order. The threads: the sample (the top
// levels, a 32nd of the points) goes in first, on one thread. Then thread p inserts the rest of its
// chunk of the curve, and may change only triangles whose finite vertices all lie in its chunk
// ("its own"); the infinity vertex lies in every chunk. Where a point's walk or cavity reaches
// another's triangle, the point waits (deferred), and the deferred points go in last, on one
// thread. This is safe without locks:
// - a triangle of thread p's stays p's (a cavity of p's triangles is refilled by triangles of
//   its boundary's vertices and the point, all in p's chunk), and no other thread changes it;
// - a triangle with vertices in two chunks ("shared") is in no cavity while the threads run, so
//   its vertices never change; an edge's two finite vertices lie in one chunk for at most one
//   thread, and only that thread rewrites a shared triangle's neighbour across such an edge.
// A thread reads others' triangles only while walking (a torn or stale record can only mislead
// the walk, which then ends on a triangle that is not the thread's own, and the point waits);
// every word of the store is read and written atomically (acquire / release: a neighbour
// pointer is published after the triangle it names). Which points wait depends on timing, the
// triangulation does not.

constexpr int kWalkSteps = 1 << 8;  // a walk this long gives up (threads only)
using mesh::cavities::load_word;
using mesh::cavities::store_word;

// One thread's insertions (the sample's and the deferred points' run as chunk 0 of 1).
struct CavityInserter {
  CavityInserter(Tri* t, std::int64_t slots, const Geo& geo, std::int32_t b, const std::int32_t* f)
      : tri(t), most(std::size_t(slots)), g(geo), base(b) {
    std::copy(f, f + 3, first);
    std::sort(first, first + 3);
  }
  Tri* tri;          // by slot number
  std::size_t most;  // slots in all: no cavity holds more
  Geo g;
  std::int32_t base;       // the first slot's number
  std::int32_t first[3];   // the first triangle's vertices, sorted
  std::int64_t chunk = 0;  // points per chunk; 0: one thread alone, nothing is anyone else's
  std::int32_t own = 0;    // this thread's chunk
  std::int32_t next = 0;   // the next free slot of the chunk it inserts for
  bool broken = false;     // a cavity was no disk (a bug guard)
  std::uint32_t rng = 2463534242u;
  std::int32_t last = -1;     // a slot made by the last insertion: the next walk starts there
  std::int32_t reached = -1;  // the last slot the last walk read
  std::vector<std::int32_t> cav;
  struct Edge {
    std::int32_t a, b, out;  // counter-clockwise seen from the cavity; the outer neighbour
  };
  std::vector<Edge> bnd;  // in order round the cavity
  // The cavity's search: a triangle's slot and its edges left to cross. (Each built field by
  // field where it is kept, as the edges are: a record assembled on the stack from narrower
  // stores and copied by wider loads stalls on store forwarding, which cost a tenth of the
  // insertion's time on the 2-core machine.)
  struct Frame {
    std::int32_t s;
    std::int8_t k, left;  // the next edge, and how many
  };
  std::vector<Frame> dfs;
  void push_frame(std::int32_t s, int k, int left) {
    Frame& F = dfs.emplace_back();
    F.s = s, F.k = std::int8_t(k), F.left = std::int8_t(left);
  }
  std::vector<double> scratch = std::vector<double>(std::size_t(kIncircleScratch));

  Tri read(std::int32_t s) const {
    const std::int32_t* w = tri[s].v;
    Tri T;
    for (int k = 0; k < 3; ++k) T.v[k] = load_word(w + k), T.n[k] = load_word(w + 3 + k);
    return T;
  }
  // Where the slots of a chunk's points begin: each point adds two, after the first triangle's
  // four, and a chunk takes them in the order it inserts (so that the triangles of points
  // inserted one after the other lie together), with no counter shared by the threads.
  std::int32_t first_slot(std::int32_t lo) const {
    return base + 4 + 2 * (lo - (lo > first[0]) - (lo > first[1]) - (lo > first[2]));
  }
  bool is_first(std::int32_t q) const { return q == first[0] || q == first[1] || q == first[2]; }
  std::int64_t owner(std::int32_t v) const { return v / chunk; }  // (the chunks of the curve)
  bool mine(const std::int32_t* v) const {  // (by the chunk's range: no division)
    if (!chunk) return true;
    const std::int64_t lo = own * chunk;
    for (int k = 0; k < 3; ++k)
      if (v[k] != g.m && std::uint64_t(v[k] - lo) >= std::uint64_t(chunk)) return false;
    return true;
  }
  bool conflict(const std::int32_t* v, std::int32_t q) {
    int r = illegal_fast(g, v, q);
    if (!r) r = illegal_exact(g, v, q, scratch.data());
    return r > 0;
  }
  // (records are read after their neighbours' pointers, each a likely cache miss: the loads are
  // started while the tests on the triangle that names them run)
  void prefetch_neighbours(const Tri& T) const {
    for (int k = 0; k < 3; ++k) prefetch_on_host(tri + simplex_of(T.n[k]));
  }
  // The triangle (of the extended triangulation: infinite ones are cones from the kernel
  // point) that holds q, by the stochastic visibility walk from slot t (its record in T); -1
  // where it gives up (threads: after kWalkSteps, or on a torn record).
  std::int32_t walk(std::int32_t t, std::int32_t q, Tri& T) {
    return mesh::cavities::visibility_walk<3, Adj>(
        t, rng, chunk ? kWalkSteps : -1, chunk != 0, T, [&](std::int32_t s) { return read(s); },
        [](const Tri& R) { return R.v[0] != R.v[1] && R.v[1] != R.v[2] && R.v[2] != R.v[0]; },
        [&](const Tri& R, int k) {
          return orient_ext(g, R.v[(k + 1) % 3], R.v[(k + 2) % 3], q) < 0;
        },
        [&](std::int32_t s, const Tri& R) {
          reached = s;
          prefetch_neighbours(R);  // (the next step's, or the cavity search's first reads)
        });
  }
  // Inserts q, or returns false having changed nothing (its cavity reaches another thread's
  // triangles).
  bool insert(std::int32_t q) {
    // (where q must wait, the next walk starts where this one got to: from the last insertion's
    // triangle, each walk of a run of waiting points went further, and on points whose
    // triangles span the chunks, e.g. two segments, every point came to wait, at the cost of a
    // walk of up to kWalkSteps)
    auto wait_from = [&](std::int32_t t) {
      last = t;
      return false;
    };
    Tri T0;
    const std::int32_t t0 = walk(last >= 0 ? last : base, q, T0);
    if (t0 < 0) return wait_from(reached);
    if (!mine(T0.v)) return wait_from(t0);
    // The cavity: the triangles whose circles (half-planes, for infinite ones) hold q, found
    // from the one that holds it by a depth-first search that turns counter-clockwise, so that
    // its boundary edges (counter-clockwise seen from inside) come out in order around it.
    // Every vertex of a cavity lies on its boundary (each becomes q's neighbour), so its
    // triangles, joined across their shared edges, form a tree: the search reaches each once
    // from the edge it came by, with no marks (a mark array cost a cache line more a neighbour,
    // and linking the boundary edges into a cycle afterwards a search or a sort).
    cav.clear(), bnd.clear(), dfs.clear();
    cav.push_back(t0);
    push_frame(t0, 0, 3);
    while (!dfs.empty()) {
      Frame& F = dfs.back();
      if (!F.left) {
        dfs.pop_back();
        continue;
      }
      const int k = F.k;
      F.k = k == 2 ? 0 : k + 1, --F.left;
      const std::int32_t* w = tri[F.s].v;  // (this thread's own triangle: no one changes it)
      const std::int32_t across = load_word(w + 3 + k);
      const std::int32_t nb = simplex_of(across);
      const Tri N = read(nb);
      if (conflict(N.v, q)) {
        if (!mine(N.v)) return wait_from(t0);
        // (a bug guard: a cavity with a vertex inside would lead the search round it forever)
        if (cav.size() >= most) return broken = true, false;
        cav.push_back(nb);
        prefetch_neighbours(N);
        const int in = loc_of(across);  // (N's edge back to C; its next two edges in turn)
        push_frame(nb, in == 2 ? 0 : in + 1, 2);
      } else {
        Edge& E = bnd.emplace_back();
        E.a = load_word(w + (k == 2 ? 0 : k + 1)), E.b = load_word(w + (k == 0 ? 2 : k - 1));
        E.out = across;
      }
    }
    // Refilled by the triangles (q, a, b) over the boundary edges, in the cavity's slots and
    // q's two new ones (a star of e edges has e triangles; the cavity had e - 2).
    const std::size_t e = bnd.size();
    if (e != cav.size() + 2) {  // (a bug guard: the cavity of a triangulation is a disk)
      broken = true;            // (no throw: a thread of a team must not; put() throws)
      return false;
    }
    auto slot = [&](std::size_t i) {
      return i < cav.size() ? cav[i] : next + std::int32_t(i - cav.size());
    };
    // (the two new slots first, from the last down: the cavity's slots name them, and a walk of
    // another thread reading one could otherwise reach a new slot before it is written)
    for (std::size_t i = e; i-- > 0;) {
      const Edge& E = bnd[i];
      // (q, b, c) across edge q-b, opposite c; (q, z, a) across edge a-q, opposite z
      const std::int32_t nb_after = slot(i + 1 == e ? 0 : i + 1);  // (the boundary's cycle)
      const std::int32_t nb_before = slot(i == 0 ? e - 1 : i - 1);
      std::int32_t* w = tri[slot(i)].v;
      const std::int32_t rec[6] = {q, E.a, E.b, E.out, enc(nb_after, 2), enc(nb_before, 1)};
      for (int k = 0; k < 6; ++k) store_word(w + k, rec[k]);
      tri[slot(i)].stamp = -1, tri[slot(i)].pair = 0;
    }
    for (std::size_t i = 0; i < e; ++i)  // the outer neighbours, after the triangles they name
      store_word(tri[simplex_of(bnd[i].out)].n + loc_of(bnd[i].out), enc(slot(i), 0));
    last = slot(0);
    next += 2;
    return true;
  }
};

template <class E>
bool Triangulator::insert_one_by_one(E& ex) {
  if constexpr (E::backend != Backend::Cpu) {
    return false;
  } else {
    const detail::Tuning::Del2d& knobs = ex.tuning().del2d;
    if (knobs.batches || knobs.batch_points || knobs.log_records || knobs.exact_entries ||
        knobs.team_list)
      return false;  // (the batches' knobs ask for the batches)
    write_first();
    const std::int32_t m = m_;
    CavityInserter one(tri(), tmax_, g_, std::int32_t(base_), P_.first);
    cavity_insertions_ = m - 3;
    ntri_ = tmax_;
    // Each chunk's next free slot (a chunk's points take theirs in the order it inserts).
    struct Hooks : mesh::cavities::OwnChunkHooks<CavityInserter> {
      Triangulator& T;
      const CavityInserter& one;
      std::int32_t m;
      std::vector<std::int32_t> next, starts, ends;
      bool skip(std::int32_t q) const { return one.is_first(q); }
      void chunks(std::int64_t nc, std::int64_t chunk) {
        for (std::int64_t c = 0; c <= nc; ++c)
          next.push_back(one.first_slot(std::int32_t(std::min<std::int64_t>(m, c * chunk))));
        starts = next;
        ends.assign(next.begin() + 1, next.end());
      }
      void put(CavityInserter& I, std::int64_t c, std::int32_t q) {  // (always goes in)
        I.next = next[std::size_t(c)];
        if (!I.insert(q))
          throw Error(ErrorCode::Internal, std::string(I.broken ? "a cavity that is no disk"
                                                                : "a cavity insertion failed") +
                                               "; please report this input");
        next[std::size_t(c)] = I.next;
      }
      void enter(CavityInserter& I, std::int64_t c) {
        I.next = next[std::size_t(c)];
        // (the walks start from the chunk's last sample triangle, where it has one)
        I.last = I.next > starts[std::size_t(c)] ? I.next - 2 : -1;
      }
      void leave(const CavityInserter& I, std::int64_t c) { next[std::size_t(c)] = I.next; }
      void mark(const char* what) { T.mark((std::string("one by one: ") + what).c_str()); }
    };
    Hooks h{{}, *this, one, m, {}, {}, {}};
    // The sample's top levels on one thread, the rest of it by the threads (as the hull's; on one
    // thread the sample held the other threads idle), then the chunks.
    mesh::cavities::Schedule how;
    how.level_bits = 3, how.sample_level = 2;
    how.alone_level = mesh::cavities::alone_sample_level(m, ex.team_size(), how.level_bits);
    deferred_ = mesh::cavities::insert_by_chunks(ex, m, loc_.data(), one, h, how);
    for (std::size_t c = 0; c < h.ends.size(); ++c)  // (a bug guard: every slot in use)
      if (h.next[c] != h.ends[c])
        throw Error(ErrorCode::Internal, "the triangulation's slots are not all in use");
    return true;
  }
}
