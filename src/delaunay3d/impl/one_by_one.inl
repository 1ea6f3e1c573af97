// The CPU executor's schedule for 3D Delaunay (issue 53): the points inserted one by one, each by
// its cavity (Bowyer-Watson), the threads over chunks of the curve (mesh/cavity_schedule.hpp).
// Included inside gpugeom::del3d::{cpu,cuda}_impl after triangulator.inl; it runs on the CPU
// only (Triangulator::insert_by_cavities), over the same store, predicates and perturbation as
// the batches (geometry.inl). Phase 2 has nothing to do after it, and the flat tetrahedra and
// the output follow as after the batches.
//
// Why a second schedule: the batches' rounds suit thousands of GPU threads; on a few cores they
// pay for rounds over global lists, the points' relocation through the flip history, the votes,
// and phase 2's star splaying where flipping got stuck (docs/performance.md, issue 53). One point
// at a time, located by a walk from a tetrahedron made for the point before it on the curve,
// touches a few cache lines, and a cavity never gets stuck.
//
// Why the output is the same: the Delaunay tetrahedralisation of the perturbed points is unique
// (flat tetrahedra included), and both schedules build it with the same predicates (a
// tetrahedron conflicts with q where find_failed would call q inside its sphere: in_sphere_ext),
// so only the slots differ, and the output's order does not follow them (finish.inl).
//
// The threads: each holds the tetrahedra it reads for a cavity by a lock word per slot (a
// compare-and-swap from 0 to its number plus one; never waited for). A thread locks the tetrahedron
// its walk ended on, then every neighbour it tests while growing the cavity (the cavity's and those
// beyond its boundary, whose neighbour words it rewrites), and reads each record after locking
// it, so the tests read settled records: a record is written only by the thread that holds it
// or, in a new slot of its range, before any record names it (new slots are written first), and
// every new tetrahedron has a boundary tetrahedron as a neighbour, held until all are written, so
// no other cavity can take one in before. Where a lock is held by another thread, it lets go of all
// it holds, changes nothing, and the point waits. Walks read without locks: a torn or stale record
// can only mislead a walk, whose end is tested again on the locked record. Each thread's slots come
// from its cavities and its own range (its freed slots wait for one thread alone: another may still
// hold one), so a slot is written by one thread at a time. Conflicts come only where two threads
// work on the same tetrahedra at the same time, not wherever a cavity has another chunk's vertex
// (the first version's rule, under which a third of the points waited at 16 threads). The points
// that wait go in by further rounds of threads over slabs (Hooks::split), then on one thread.

constexpr int kWalkSteps3 = 1 << 16;  // a walk this long gives up (threads only)

// One thread's insertions (the sample's and the waiting points' run as chunk 0 of 1).
struct TetInserter {
  TetInserter(Tet* t, const Geo& geo, const std::int32_t* f) : tet(t), g(geo) {
    std::copy(f, f + 4, first);
  }
  Tet* tet;  // by slot number
  Geo g;
  std::int32_t first[4];   // the first tetrahedron's vertices
  std::int64_t chunk = 0;  // points per chunk; 0: one thread alone, nothing is anyone else's
  std::int32_t own = 0;    // this thread's chunk
  std::int64_t next = 0, end = 0;   // the slots it may still take: [next, end)
  std::int64_t own_first = 0;       // threads: where its range begins
  std::int64_t before_ranges = 0;   // threads: where this stage's first range begins
  std::vector<std::int32_t> freed;  // and the slots its cavities freed
  bool broken = false;              // a cavity's boundary was no sphere (a bug guard)
  bool full = false;                // an insertion needed more slots than it may take
  std::uint32_t rng = 2463534242u;
  std::int32_t last = -1;        // a slot made by the last insertion: the next walk starts there
  std::int32_t* lock = nullptr;  // per slot: 1 + the part that holds it, 0: none (threads only)
  std::vector<std::int32_t> cav;
  std::vector<Tet> held;  // the cavity's tetrahedra as read (their records are settled)
  // The slots this insertion has read, each with what it was found to be: open addressing
  // (a per-slot array of marks cost a cache miss a neighbour). A tetrahedron beyond the cavity
  // is often next to two or three of its tetrahedra: found outside once, it is not tested (nor
  // locked, nor read) again. With threads every slot in it is one this thread holds.
  static constexpr std::int32_t kUnseen = -1, kOutside = 0, kInCavity = 1;
  struct SlotMap {
    struct Entry {
      std::int32_t slot, what;
    };
    std::vector<Entry> at = std::vector<Entry>(64, Entry{-1, kUnseen});
    std::vector<std::size_t> filled;  // (so that a reset clears only those)
    void reset() {
      for (const std::size_t h : filled) at[h].slot = -1;
      filled.clear();
    }
    static std::size_t hash(std::int32_t s) { return std::size_t(std::uint32_t(s) * 2654435761u); }
    std::int32_t what(std::int32_t s) const {
      const std::size_t mask = at.size() - 1;
      for (std::size_t h = hash(s) & mask;; h = (h + 1) & mask) {
        if (at[h].slot == s) return at[h].what;
        if (at[h].slot < 0) return kUnseen;
      }
    }
    void place(Entry e) {
      const std::size_t mask = at.size() - 1;
      std::size_t h = hash(e.slot) & mask;
      while (at[h].slot >= 0) h = (h + 1) & mask;
      at[h] = e;
      filled.push_back(h);
    }
    void put(std::int32_t s, std::int32_t w) {  // (s unseen; at most a quarter full)
      if (4 * (filled.size() + 1) > at.size()) {
        std::vector<Entry> old;
        for (const std::size_t h : filled) old.push_back(at[h]);
        at.assign(2 * at.size(), Entry{-1, kUnseen});
        filled.clear();
        for (const Entry& e : old) place(e);
      }
      place(Entry{s, w});
    }
  } seen;
  std::vector<std::int32_t> holding;  // threads: the slots this thread holds
  bool hold(std::int32_t s) {         // a tetrahedron not yet seen locked; false: another's
    cuda::atomic_ref<std::int32_t, cuda::thread_scope_system> r(lock[s]);
    std::int32_t free = 0;
    if (!r.compare_exchange_strong(free, own + 1, cuda::memory_order_acquire,
                                   cuda::memory_order_relaxed))
      return false;
    holding.push_back(s);
    return true;
  }
  void let_go() {  // (after every write, so a thread that locks a slot next reads them)
    for (const std::int32_t s : holding) mesh::cavities::store_word(lock + s, 0);
    holding.clear();
  }
  struct Face {
    std::int32_t at;  // the cavity tetrahedron it bounds (held[at]; its new one takes its vertices)
    int k;            // the face is that tetrahedron's face k; q takes vertex k's place
    std::int32_t out;  // the neighbour beyond it (encoded)
  };
  std::vector<Face> bnd;
  std::vector<std::int32_t> made;  // per boundary face: its new tetrahedron's slot
  struct Edge {
    std::uint64_t key;    // the edge's two vertices (the lesser high)
    std::int32_t at;      // enc(boundary face, local face) of the first new one seen with it
    std::uint32_t stamp;  // the insertion that filled it; another's: empty (no clearing)
  };
  std::vector<Edge> edges;    // open addressing: the new tetrahedra's faces through q, paired
  std::size_t edge_mask = 0;  // this insertion's part of edges: [0, edge_mask]
  std::uint32_t stamp = 0;
  std::int64_t pairs = 0;  // edges paired (-1: one was in three faces)

  Tet read(std::int32_t s) const {
    const std::int32_t* w = tet[s].v;
    Tet T;
    for (int k = 0; k < 8; ++k) (k < 4 ? T.v[k] : T.n[k - 4]) = mesh::cavities::load_word(w + k);
    return T;
  }
  void write(std::int32_t s, const Tet& T) {
    std::int32_t* w = tet[s].v;
    for (int k = 0; k < 8; ++k) mesh::cavities::store_word(w + k, k < 4 ? T.v[k] : T.n[k - 4]);
  }
  void prefetch_slot(std::int32_t t) const {  // its record, and its lock word to be written
    prefetch_on_host(tet + t);
    if (lock) prefetch_on_host<true>(lock + t);
  }
  bool is_first(std::int32_t q) const {
    return q == first[0] || q == first[1] || q == first[2] || q == first[3];
  }
  // Whose a vertex is: its chunk of the curve, or in the later rounds its slab across an axis
  // (axis >= 0: how many cuts lie at or below its coordinate).
  int axis = -1;
  std::vector<double> cuts;
  std::int64_t owner(std::int32_t v) const {
    if (axis < 0) return v / chunk;
    const double x = g.at(v)[axis];
    std::int64_t k = 0;
    while (k < std::int64_t(cuts.size()) && cuts[std::size_t(k)] <= x) ++k;
    return k;
  }
  static bool torn(const Tet& T) {
    if (T.v[0] < 0) return true;
    for (int a = 0; a < 4; ++a)
      for (int b = a + 1; b < 4; ++b)
        if (T.v[a] == T.v[b]) return true;
    return false;
  }
  // The tetrahedron (of the extended tetrahedralisation: infinite ones are cones from the
  // kernel point) that holds q, by the stochastic visibility walk from slot t; -1 where it gives
  // up or ends on a record it cannot trust (threads).
  std::int32_t walk(std::int32_t t, std::int32_t q) {
    Tet T;
    return mesh::cavities::visibility_walk<4, TetAdjacency>(
        t, rng, chunk ? kWalkSteps3 : -1, chunk != 0, T, [&](std::int32_t s) { return read(s); },
        [&](const Tet& R) { return !chunk || !torn(R); },
        [&](const Tet& R, int k) { return orient_with(g, R.v, k, q) < 0; },
        [](std::int32_t, const Tet&) {});
  }
  // A slot for the i-th new tetrahedron: the cavity's own, then freed ones, then new ones.
  std::int32_t slot(std::size_t i) const {
    if (i < cav.size()) return cav[i];
    i -= cav.size();
    if (i < usable_freed()) return freed[freed.size() - 1 - i];
    return std::int32_t(next + std::int64_t(i - usable_freed()));
  }
  std::size_t usable_freed() const { return lock ? 0 : freed.size(); }
  void pair_edge(std::int32_t a, std::int32_t b, std::int32_t at) {
    if (a > b) std::swap(a, b);
    const std::uint64_t key = (std::uint64_t(std::uint32_t(a)) << 32) | std::uint32_t(b);
    const std::size_t mask = edge_mask;
    std::size_t h = std::size_t((key * 0x9E3779B97F4A7C15ull) >> 32) & mask;
    for (;; h = (h + 1) & mask) {
      Edge& E = edges[h];
      if (E.stamp != stamp) {
        E.key = key, E.at = at, E.stamp = stamp;
        return;
      }
      if (E.key == key) {  // (the other new tetrahedron through q and this edge)
        if (E.at < 0) {    // (a third: no sphere)
          pairs = -1;
          return;
        }
        made_n(at) = E.at;
        made_n(E.at) = at;
        E.at = -1;
        if (pairs >= 0) ++pairs;
        return;
      }
    }
  }
  std::vector<Tet> fresh;  // the new tetrahedra, by boundary face, before they are written
  std::int32_t& made_n(std::int32_t at) { return fresh[std::size_t(simplex_of(at))].n[loc_of(at)]; }

  // Inserts q, or returns false having changed nothing (its walk or cavity reaches another
  // thread's tetrahedra, or it needs more slots than it may take: full).
  bool insert(std::int32_t q) {
    const bool ok = cavity_and_refill(q);
    if (lock) let_go();
    return ok;
  }
  // Where a walk may start: t, or where it has been removed since it was made (by another
  // thread, or on one thread by the threads before), the nearest live slot below it. On one
  // thread any slot below `next` will do (each was written whole or marked dead). With threads,
  // a slot of another thread's range may hold a record being written for the first time, so
  // only this thread's own range, then the slots below every range of this stage (written
  // before it, or since by a thread that held them: every word a valid one). -1: none.
  std::int32_t live_from(std::int32_t t) const {
    auto live_in = [&](std::int64_t hi, std::int64_t lo) {  // [lo, hi], from the top
      for (std::int64_t s = hi; s >= lo; --s)
        if (mesh::cavities::load_word(tet[s].v) >= 0) return std::int32_t(s);
      return std::int32_t(-1);
    };
    if (mesh::cavities::load_word(tet[t].v) >= 0) return t;
    if (!lock) return live_in(t, 0);
    const std::int32_t s = live_in(next - 1, own_first);
    return s >= 0 ? s : live_in(std::min<std::int64_t>(t, before_ranges - 1), 0);
  }
  // Is q in the tetrahedron T (as the walk ends: no face with q beyond it)?
  bool holds(const Tet& T, std::int32_t q) const {
    for (int k = 0; k < 4; ++k)
      if (orient_with(g, T.v, k, q) < 0) return false;
    return true;
  }
  bool cavity_and_refill(std::int32_t q) {
    const std::int32_t from = live_from(last >= 0 ? last : 0);
    if (from < 0) return false;
    const std::int32_t t0 = walk(from, q);
    if (t0 < 0) return false;
    if (lock && !hold(t0)) return false;
    const Tet T0 = read(t0);
    if (lock && (T0.v[0] < 0 || !holds(T0, q))) return false;  // (the walk read a stale record)
    // The cavity: the tetrahedra whose spheres (half-spaces, for infinite ones) hold q, found
    // from the one that holds it; its boundary, the faces to the others.
    cav.clear(), bnd.clear(), held.clear();
    seen.reset();
    cav.push_back(t0), held.push_back(T0);
    seen.put(t0, kInCavity);
    for (std::size_t i = 0; i < cav.size(); ++i) {
      const Tet C = held[i];
      // (the neighbours' records, then their points, asked for before any is tested: the
      // misses overlap, where one at a time they were half of an insertion's time)
      std::int32_t was[4];
      for (int k = 0; k < 4; ++k) {
        was[k] = seen.what(simplex_of(C.n[k]));
        if (was[k] == kUnseen) prefetch_slot(simplex_of(C.n[k]));
      }
      Tet N4[4];
      for (int k = 0; k < 4; ++k) {
        if (was[k] != kUnseen) continue;
        const std::int32_t nb = simplex_of(C.n[k]);
        if (lock && !hold(nb)) return false;
        N4[k] = read(nb);
        for (int j = 0; j < 4; ++j) prefetch_on_host(g.at(N4[k].v[j]));
      }
      for (int k = 0; k < 4; ++k) {
        if (was[k] == kInCavity) continue;
        const std::int32_t nb = simplex_of(C.n[k]);
        const Tet& N = N4[k];
        if (was[k] == kUnseen && in_sphere_ext(g, N.v, q)) {
          cav.push_back(nb), held.push_back(N);
          seen.put(nb, kInCavity);
          // (its neighbours asked for now, while the tetrahedra before it in the queue are
          // tested: they are read when its turn comes)
          for (int j = 0; j < 4; ++j) prefetch_slot(simplex_of(N.n[j]));
        } else {
          if (was[k] == kUnseen) seen.put(nb, kOutside);
          bnd.push_back({std::int32_t(i), k, C.n[k]});
        }
      }
    }
    // Refilled by the tetrahedra (q, face) over the boundary's faces: a sphere of f triangles
    // has f / 2 + 2 vertices; the cavity's c tetrahedra, freed slots, then new ones.
    const std::size_t f = bnd.size();
    if (f < 4 || f % 2) {  // (a bug guard: the boundary of a cavity is a sphere)
      broken = true;       // (no throw: a thread of a team must not; put() throws)
      return false;
    }
    if (f > cav.size() &&
        std::int64_t(f - cav.size()) > std::int64_t(usable_freed()) + end - next) {
      full = true;
      return false;
    }
    fresh.resize(f);
    std::size_t size = 16;
    while (size < 3 * f) size *= 2;             // (3f/2 edges, at most half full)
    if (++stamp == 0 || edges.size() < size) {  // (else the stamps tell the entries apart)
      edges.assign(std::max(size, edges.size()), Edge{0, 0, 0});
      stamp = 1;
    }
    edge_mask = size - 1;
    pairs = 0;
    for (std::size_t i = 0; i < f; ++i) {
      const Face& F = bnd[i];
      Tet& N = fresh[i];
      N = held[F.at];  // (the cavity's tetrahedron: its record is settled)
      N.v[F.k] = q;
      N.n[F.k] = F.out;
      // Its faces through q: the one opposite vertex o[j] holds the edge of the other two.
      int o[3], no = 0;
      for (int l = 0; l < 4; ++l)
        if (l != F.k) o[no++] = l;
      const std::int32_t at = std::int32_t(i);
      pair_edge(N.v[o[1]], N.v[o[2]], enc(at, o[0]));
      pair_edge(N.v[o[0]], N.v[o[2]], enc(at, o[1]));
      pair_edge(N.v[o[0]], N.v[o[1]], enc(at, o[2]));
    }
    if (pairs !=
        std::int64_t(3 * f / 2)) {  // (a bug guard: every edge in two faces of the boundary)
      broken = true;
      return false;
    }
    // Slots: the cavity's first; those left over are freed (dead), or new ones taken.
    made.resize(f);
    for (std::size_t i = 0; i < f; ++i) made[i] = slot(i);
    // (the slots past the cavity's first, from the last down: a new slot is named only by the
    // new tetrahedra and the boundary, so none is reachable before it is written whole; a walk
    // reaching a slot that held another thread's unwritten bytes could end there and lock it)
    for (std::size_t i = f; i-- > 0;) {
      Tet N = fresh[i];
      for (int j = 0; j < 4; ++j)
        if (j != bnd[i].k) N.n[j] = enc(made[std::size_t(simplex_of(N.n[j]))], loc_of(N.n[j]));
      write(made[i], N);
    }
    for (std::size_t i = 0; i < f; ++i) {  // the outer neighbours, after the tetrahedra they name
      const std::int32_t out = bnd[i].out;
      mesh::cavities::store_word(tet[simplex_of(out)].n + loc_of(out), enc(made[i], bnd[i].k));
    }
    if (f < cav.size()) {
      for (std::size_t i = f; i < cav.size(); ++i) {
        mesh::cavities::store_word(tet[cav[i]].v, -1);
        freed.push_back(cav[i]);
      }
    } else {
      const std::size_t extra = f - cav.size();
      const std::size_t from_freed = std::min(extra, usable_freed());
      freed.resize(freed.size() - from_freed);
      next += std::int64_t(extra - from_freed);
    }
    last = made[0];
    return true;
  }
};

template <class E>
void Triangulator::insert_by_cavities(E& ex) {
  if constexpr (E::backend != Backend::Cpu) {
    throw Error(ErrorCode::Internal, "the cavities' schedule is the CPU executor's");
  } else {
    const std::int32_t m = m_;
    first_five(tet_.data());  // (start()'s, without the points' location: the walks find them)
    TetInserter one(tet_.data(), g_, first_.v);
    one.next = 5, one.end = cap_;
    struct Hooks {
      Hooks(Triangulator& t, TetInserter& o, std::int32_t n) : T(t), one(o), m(n) {}
      Triangulator& T;
      TetInserter& one;
      std::int32_t m;
      std::int64_t nc = 1, chunk = 0;
      std::vector<std::int32_t> start;      // per chunk: where its thread's walks begin
      std::vector<std::int64_t> next, end;  // per chunk: its range of slots
      std::vector<std::vector<std::int32_t>> freed;
      Clock::time_point t0 = Clock::now();
      // Per slot, while threads run (TetInserter::hold), 0 where free: fresh zeroed pages, faulted
      // in by the threads that lock them. (Filled with -1 by one thread, as they were, they took
      // 20 ms of a 10^6-point run on 16 threads, and 200 ms at 10^7.)
      std::unique_ptr<std::int32_t, void (*)(void*)> locks{nullptr, std::free};
      std::size_t lock_slots = 0;
      bool skip(std::int32_t q) const { return one.is_first(q); }
      void chunks(std::int64_t n, std::int64_t c) {
        nc = n, chunk = c;
        start.assign(std::size_t(n), -1);
      }
      // One thread alone: the slots past every chunk's range, the store grown where they end.
      void put(TetInserter& I, std::int64_t c, std::int32_t q) {
        for (;;) {
          if (I.insert(q)) break;
          if (!I.full)
            throw Error(ErrorCode::Internal, std::string(I.broken ? "a cavity that is no ball"
                                                                  : "a cavity insertion failed") +
                                                 "; please report this input");
          I.full = false;
          T.reserve(T.cap_ + T.cap_ / 8 + 1024);
          I.tet = T.tet_.data(), I.end = T.cap_;
        }
        start[std::size_t(c)] = I.last;
        if (++done % 4096 == 0) report();
      }
      // Progress (and a place for the callback to cancel: never inside the threads): every 4096
      // points one thread inserts, and as each stage ends; "batch" counts the reports.
      std::int64_t done = 4, reports = 0;
      void report() {
        if (T.progress_) T.progress_(Delaunay3dProgress{"insert_flip", done, m, ++reports});
      }
      // A tetrahedron with a vertex in chunk c: near c's points (another thread may remove it;
      // a walk that meets a removed one gives up, and the point waits).
      bool holds_chunk(const TetInserter& I, std::int32_t s, std::int64_t c) const {
        const Tet& X = T.tet_.data()[s];
        if (X.v[0] < 0) return false;
        for (int k = 0; k < 4; ++k)
          if (X.v[k] != m && I.owner(X.v[k]) == c) return true;
        return false;
      }
      // The threads: chunk c's range of slots is sized from its points (a tetrahedralisation holds
      // about 6.7 a point; 8, and a chunk that runs out leaves its points to wait); each thread's
      // walks begin at a tetrahedron with a vertex of its part (the last insertion's for its
      // chunk, else the first such slot).
      // The later rounds' parts: slabs across an axis. The waiting points lie along the curve's
      // chunks' borders, often planes (the chunks of 2^k points are cut at dyadic planes), and
      // slabs cut where those are dense would leave them waiting again. So of the axes but the
      // last round's, each cut is placed at one of the waiting points' quantiles (c + d) / parts,
      // d in [-1/4, 1/4] (the slabs share them out to within a half), the one with the fewest
      // waiting points near it (within two of the points' mean spacings), the nearest to c /
      // parts where they tie; the axis whose cuts have the fewest near them in all. (A first
      // version also tried all the points' quantiles offset by half a slab: at two parts that
      // is a quarter, and one thread inserted nearly all of the round's points.)
      int last_axis = -1;
      bool split(int, std::int64_t parts, TetInserter& I,
                 const std::vector<std::vector<std::int32_t>>& waiting) {
        std::int64_t best = -1;
        const std::int64_t step = std::max<std::int64_t>(1, m / (4096 * parts));
        constexpr int kTries = 8;  // quantiles tried each side of c / parts
        for (int axis = 0; axis < 3; ++axis) {
          if (axis == last_axis) continue;
          std::vector<double> x, all;
          for (const auto& w : waiting)
            for (const std::int32_t q : w) x.push_back(T.g_.at(q)[axis]);
          for (std::int64_t v = 0; v < m; v += step) all.push_back(T.g_.at(std::int32_t(v))[axis]);
          if (x.empty()) continue;
          std::sort(x.begin(), x.end());
          std::sort(all.begin(), all.end());
          const double near = 2 * (all.back() - all.front()) / std::cbrt(double(m));
          const auto crowd_at = [&](double at) {
            return std::upper_bound(x.begin(), x.end(), at + near) -
                   std::lower_bound(x.begin(), x.end(), at - near);
          };
          const std::int64_t nx = std::int64_t(x.size());
          std::vector<double> cuts;
          std::int64_t crowd = 0;
          for (std::int64_t c = 1; c < parts; ++c) {
            double at = 0;
            std::int64_t least = -1;
            for (int d = 0; d <= 2 * kTries; ++d) {  // 0, +1, -1, +2, ...: nearest first
              const std::int64_t off = (d + 1) / 2 * (d % 2 ? 1 : -1);
              const std::int64_t i = (nx * (4 * kTries * c + off)) / (4 * kTries * parts);
              const double y = x[std::size_t(std::clamp<std::int64_t>(i, 0, nx - 1))];
              const std::int64_t n = crowd_at(y);
              if (least < 0 || n < least) least = n, at = y;
            }
            cuts.push_back(at);
            crowd += least;
          }
          if (best < 0 || crowd < best) best = crowd, I.axis = axis, I.cuts = cuts;
        }
        if (best < 0) return false;
        I.chunk = chunk;
        last_axis = I.axis;
        return true;
      }
      // The parts split off (PartPoints) take their ranges from one room after the parts' (a
      // quarter of a slot a point, while it lasts: 3D on 2 and 4 threads, 10^6 points, the splits
      // took 0.1-0.37 of a slot a point, and fewer splits do almost as well).
      std::size_t parts_now = 0;
      std::vector<std::int32_t> start_now;  // start as the stage began (a split part's walks)
      std::atomic<std::int64_t> split_next{0};
      std::int64_t split_end = 0;
      void threads_begin(const std::vector<std::int64_t>& points, const TetInserter& probe,
                         std::int64_t most) {
        const std::size_t parts = points.size();  // (nc, or fewer in the later rounds)
        const std::size_t cap = std::size_t(most);
        parts_now = parts;
        next.resize(parts), end.resize(parts), freed.assign(cap, {});
        std::int64_t at = one.next, all = 0;
        for (std::size_t c = 0; c < parts; ++c)
          next[c] = at, at += 8 * points[c] + 1024, end[c] = at, all += points[c];
        split_next = at;
        const std::int64_t room = T.ex_.tuning().del3d.split_room;
        at += room >= 0 ? room : all / 4 + 1024 * std::int64_t(cap - parts);
        split_end = at;
        for (std::int64_t c = 0; c < std::int64_t(parts); ++c) {
          std::int32_t& s = start[std::size_t(c)];
          if (s >= 0 && holds_chunk(probe, s, c)) continue;
          s = -1;
          for (std::int64_t t = 0; t < one.next && s < 0; ++t)
            if (holds_chunk(probe, std::int32_t(t), c)) s = std::int32_t(t);
        }
        start_now.assign(start.begin(), start.begin() + std::ptrdiff_t(parts));
        T.reserve(at + 1024);
        if (lock_slots < std::size_t(T.cap_)) {  // (every lock is free between the stages)
          locks.reset();
          lock_slots = std::size_t(T.cap_);
          locks.reset(static_cast<std::int32_t*>(std::calloc(lock_slots, sizeof(std::int32_t))));
          if (!locks)
            throw Error(ErrorCode::OutOfMemory, "host allocation of " +
                                                    std::to_string(lock_slots * 4) +
                                                    " bytes for the threads' locks failed");
        }
        one.tet = T.tet_.data();
        one.next = at, one.end = T.cap_;
      }
      // Slots [a, b) marked dead (a part's range or the room's ends, not taken).
      void mark_dead(std::int64_t a, std::int64_t b) {
        for (std::int64_t s = a; s < b; ++s) T.tet_.data()[s].v[0] = -1;
      }
      // A part's thread begins on slots [a, b), its walks from slot `from`.
      void begin_range(TetInserter& I, std::int64_t a, std::int64_t b, std::int32_t from) {
        I.tet = T.tet_.data();
        I.lock = locks.get();
        I.next = a, I.end = b, I.own_first = a;
        I.before_ranges = next.front();
        I.freed.clear();
        I.last = from;
      }
      void enter(TetInserter& I, std::int64_t c) {
        begin_range(I, next[std::size_t(c)], end[std::size_t(c)], start[std::size_t(c)]);
      }
      // Part id, split off part root's points: a range from the room for n points, its walks
      // from where root's began (or a live slot near it: live_from).
      bool enter_split(TetInserter& I, std::int64_t, std::int64_t root, std::int64_t n) {
        const std::int64_t size = 8 * n + 1024;
        const std::int64_t a = split_next.fetch_add(size, std::memory_order_relaxed);
        if (a + size > split_end) {  // (the room's end: what this thread was given of it is dead)
          mark_dead(a, split_end);
          return false;
        }
        begin_range(I, a, a + size, start_now[std::size_t(root)]);
        return true;
      }
      void leave(TetInserter& I, std::int64_t c) {
        // (the range's slots it did not take are dead; its walks go on from where it ended)
        mark_dead(I.next, I.end);
        freed[std::size_t(c)] = std::move(I.freed);
        if (std::size_t(c) < parts_now) start[std::size_t(c)] = I.last;
      }
      void threads_done(std::int64_t inserted) {  // (their freed slots to the one thread)
        // (the room's slots no part took are dead)
        mark_dead(std::min(split_next.load(), split_end), split_end);
        for (auto& f : freed) one.freed.insert(one.freed.end(), f.begin(), f.end());
        done += inserted;
      }
      void mark(const char* what) {
        T.st_.phase_ms.push_back({std::string("insert_flip.") + what, ms_since(t0)});
        if (std::string(what) == "deferred") done = m;
        report();
        t0 = Clock::now();
      }
    };
    Hooks h(*this, one, m);
    deferred_ = mesh::cavities::insert_by_chunks(
        ex, m, loc_.data(), one, h, mesh::cavities::locking_schedule(m, ex.team_size()));
    cavity_insertions_ = m - 4;
    Counters c = counters();
    c.used = one.next;
    ex_.from_host(&c, 1, ctr_.data());
  }
}
