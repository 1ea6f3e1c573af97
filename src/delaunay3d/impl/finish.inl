// The end of phase 1 (triangulator.inl): the faces it left not locally Delaunay (phase 2's
// work), the finite tetrahedra in input indices, and its statistics.

// The store as the output step reads it: finite tetrahedra, in input indices, in one order
// (mesh/compact.hpp), whatever the schedule and the slots it left.
struct FiniteTets {
  const Tet* tet;
  const std::int32_t* orig;
  std::int32_t m;
  GG_HD bool live(std::int64_t t) const {
    const std::int32_t* v = tet[t].v;
    return v[0] >= 0 && v[0] != m && v[1] != m && v[2] != m && v[3] != m;
  }
  GG_HD void prefetch(std::int64_t t) const { prefetch_on_host(tet + t); }
  GG_HD void order_names(std::int64_t t, std::int32_t* w) const {  // (curve positions)
    for (int k = 0; k < 4; ++k) w[k] = tet[t].v[k];
  }
  GG_HD mesh::SimplexRecord<4> get(std::int64_t t) const {
    const Tet T = tet[t];
    mesh::SimplexRecord<4> r;
    for (int k = 0; k < 4; ++k) r.v[k] = orig[T.v[k]], r.n[k] = simplex_of(T.n[k]);
    return r;
  }
};

// Every face of the tetrahedralisation tested; the vertices of faces that are not locally
// Delaunay are marked (failed: m + 1 entries). Counts the flat finite tetrahedra (flat_ext)
// in flat. Returns the number of failed faces. only (per slot, or null: all): the faces of
// these slots alone (the others' faces are known to be locally Delaunay: DynamicDelaunay3d's
// slots that no flip or split rewrote).
inline std::int64_t Triangulator::find_failed(typename Exec::template Buffer<std::int8_t>& failed,
                                              std::int64_t& flat, const std::int8_t* only) {
  const Geo g = g_;
  const Mesh M = M_;
  std::int8_t* f = failed.data();
  ex_.fill(f, std::int64_t(m_) + 1, std::int8_t(0));
  Counters* ctr = ctr_.data();
  const Counters c = counters();
  ex_.for_each_index(
      c.used, GG_LAMBDA(std::int64_t t) {
        const Tet T = M.tet[t];
        if (T.v[0] < 0 || (only && !only[t])) return;
        for (int k = 0; k < 4; ++k) {
          const std::int32_t nb = simplex_of(T.n[k]);
          if (nb < t && (!only || only[nb])) continue;  // (each face once, from its higher slot)
          const std::int32_t d = M.tet[nb].v[loc_of(T.n[k])];
          if (!in_sphere_ext(g, T.v, d)) continue;
          atomic_add(&ctr->failed_faces, std::int64_t(1));
          std::int32_t x[3];
          face_of(T.v, k, x);
          for (int j = 0; j < 3; ++j) f[x[j]] = 1;
        }
        if (flat_ext(g, T.v)) atomic_add(&ctr->flat, std::int64_t(1));
      });
  const Counters after = counters();
  flat = after.flat;
  return after.failed_faces;
}

template <class Into>
Triangulator::Finished Triangulator::finish(const std::int32_t* orig, Into into) {
  const Counters c = counters();
  return mesh::compact_live_sorted<4>(ex_, c.used, FiniteTets{tet_.data(), orig, m_}, m_, into,
                                      /*with_last=*/true);
}

inline void Triangulator::report() {
  const Counters c = counters();
  st_.device_bytes_phase1 = peak_bytes_;
  st_.slots_used = c.used;
  st_.slots_capacity = cap_;
  st_.batches = batches_;
  st_.max_list = c.max_len;
  st_.max_epoch_records = c.max_log;
  st_.max_free_slots = c.max_free;
  st_.max_splits = max_nins_;
  st_.halts = c.halts;
  st_.carried_batches = c.carries;
  st_.log_capacity = log_cap_;
  st_.list_capacity = list_cap_;
  st_.ring_capacity = ring_cap_;
  st_.flip_rounds = c.rounds;
  st_.flips23 = c.flips23;
  st_.flips32 = c.flips32;
  st_.unflippable_tests = c.unflippable;
  // Where phase 1's time goes (host clock; each part ends with a read of the counters):
  // choosing and splitting, rounds as kernels, rounds in a team.
  st_.us_choose_split = std::int64_t(1000 * ms_choose_);
  st_.us_rounds_wide = std::int64_t(1000 * sched_.wide_ms);
  st_.us_rounds_team = std::int64_t(1000 * sched_.team_ms);
  st_.round_chunks = sched_.chunks;
  st_.team_launches = sched_.team_calls;
  st_.failed_faces = c.failed_faces;
  st_.cavity_insertions = cavity_insertions_;
  st_.deferred_points = deferred_;
}
