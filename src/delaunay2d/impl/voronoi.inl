// The Voronoi diagram of a triangulation in the executor's memory, computed there (the device
// entry, voronoi2d_device): the same arrays, in the same order, as voronoi2d's loop makes on
// the host, from the same per-element pieces (voronoi_core.hpp). Included inside
// gpugeom::del2d::{cpu,cuda}_impl.

// Whether the walk from corner c (a start corner) goes round an unbounded cell.
GG_HD inline bool vor_open(const std::int32_t* nb, std::int64_t c) {
  return nb[3 * (c / 3) + (c % 3 + 2) % 3] < 0;
}

// The Voronoi vertices of a triangulation: one per circle. Triangles across an edge whose four
// points lie on one circle exactly (the exact in-circle test, no perturbation) have the same
// circumcentre, so the diagram gives them one vertex: the classes of triangles joined through such
// edges (mesh/vertex_classes.hpp). Without the merge a 3x3 grid has 8 vertices where it has 4,
// and zero-length ridges between them (issue 49).
inline mesh::Classes<Exec> vor_vertices(Exec& ex, const double* xy, const std::int32_t* tri,
                                        const std::int32_t* nb, std::int64_t nt) {
  using I32 = std::int32_t;
  using I64 = std::int64_t;
  auto d_parent = ex.template alloc<I32>(std::size_t(nt));
  I32* parent = d_parent.data();
  ex.for_each_index(
      nt, GG_LAMBDA(I64 t) { parent[t] = I32(t); });
  LeasePool<Exec> pool(ex, std::clamp<std::int64_t>(ex.concurrency(), 64, 1024),
                       pred::kIncircleScratch);
  const ScratchLease lease = pool.view;
  auto d_joined = ex.template alloc<I64>(1);
  I64* joined = d_joined.data();
  ex.fill(joined, 1, I64(0));
  ex.for_each_index(
      3 * nt, GG_LAMBDA(I64 c) {
        const I64 t = c / 3;
        const I32 o = nb[c];
        if (o <= t) return;  // (each edge once, from its smaller triangle; hull edges have none)
        const int j = nb[3 * I64(o)] == t ? 0 : nb[3 * I64(o) + 1] == t ? 1 : 2;
        const double* a = xy + 2 * I64(tri[3 * t]);
        const double* b = xy + 2 * I64(tri[3 * t + 1]);
        const double* e = xy + 2 * I64(tri[3 * t + 2]);
        const double* d = xy + 2 * I64(tri[3 * I64(o) + j]);
        int r = pred::incircle_fast(a, b, e, d);
        if (r == 0) {
          double* s = lease.acquire(std::uint32_t(t) * 2654435761u + std::uint32_t(o));
          r = pred::incircle(a, b, e, d, s);
          lease.release(s);
        }
        if (r != 0) return;
        mesh::uf_unite(parent, I32(t), o);
        atomic_add(joined, I64(1));
      });
  I64 nj = 0;
  ex.to_host(joined, 1, &nj);
  return mesh::number_classes(ex, parent, nt, nj);
}

// Whether corner c's edge has a ridge: once per edge (vor::has_ridge), and not between two
// triangles of one circle (their vertex is one).
GG_HD inline bool vor_ridge(const std::int32_t* nb, const std::int32_t* vid, std::int64_t c) {
  const std::int64_t t = c / 3;
  const std::int32_t o = nb[c];
  return vor::has_ridge(nb, t, int(c % 3)) && !(o >= 0 && vid[o] == vid[t]);
}

inline void voronoi_impl(const double* xy, std::int64_t n, const std::int32_t* tri,
                         const std::int32_t* nb, const std::int32_t* dup, std::int64_t nt,
                         const Voronoi2dOptions& run, DeviceVoronoiOutput& out, RunStats& st,
                         Voronoi2d* host, const ::gpugeom::detail::ExecContext* outer) {
  const auto t0 = std::chrono::steady_clock::now();
  Exec ex(run, outer);
  const ::gpugeom::detail::DevicePeak<Exec> peak(ex, st);
  using I32 = std::int32_t;
  using I64 = std::int64_t;
  // Voronoi vertices: one per circle, the triangles that share it exactly merged.
  auto V = vor_vertices(ex, xy, tri, nb, nt);
  const I32* vid = V.of.data();
  const I64 nv = V.count;
  auto vx = ex.template alloc<double>(std::size_t(2 * nv));
  double* v = vx.data();
  const I32* first = V.first.data();
  ex.for_each_index(
      nv, GG_LAMBDA(I64 j) { vor::circumcentre(xy, tri, first[j], v + 2 * j); });
  // Ridges: one per edge, numbered in (triangle, edge) order.
  auto rank = ex.template alloc<I64>(std::size_t(3 * nt + 1));
  I64* rk = rank.data();
  ex.exclusive_scan_of(
      3 * nt + 1, GG_LAMBDA(I64 c)->I64 { return c < 3 * nt && vor_ridge(nb, vid, c) ? 1 : 0; },
      rk);
  I64 nr = 0;
  ex.to_host(rk + 3 * nt, 1, &nr);
  auto rpb = ex.template alloc<I32>(std::size_t(2 * nr));
  auto rvb = ex.template alloc<I32>(std::size_t(2 * nr));
  auto rdb = ex.template alloc<double>(std::size_t(2 * nr));
  I32* rp = rpb.data();
  I32* rv = rvb.data();
  double* rd = rdb.data();
  ex.for_each_index(
      3 * nt, GG_LAMBDA(I64 c) {
        const I64 r = rk[c];
        if (rk[c + 1] == r) return;
        vor::ridge(xy, tri, nb, c / 3, int(c % 3), rp + 2 * r, rv + 2 * r, rd + 2 * r);
        for (int e = 0; e < 2; ++e)
          if (rv[2 * r + e] >= 0) rv[2 * r + e] = vid[rv[2 * r + e]];
      });
  // Cells: each vertex's walk starts at its key's corner; duplicates walk their original's.
  auto keyb = ex.template alloc<I64>(std::size_t(n));
  I64* key = keyb.data();
  ex.fill(key, n, I64(-1));
  ex.for_each_index(
      3 * nt, GG_LAMBDA(I64 c) { atomic_max(key + tri[c], vor::start_key(nb, c)); });
  const mesh::CellSource src_of{dup};
  auto missing = ex.template alloc<I64>(1);
  ex.transform_reduce_into(
      n, GG_LAMBDA(I64 i)->I64 { return !src_of.removed(i) && key[src_of(i)] < 0 ? 1 : 0; }, I64(0),
      thrust::plus<I64>(), missing.data());
  I64 nmiss = 0;
  ex.to_host(missing.data(), 1, &nmiss);
  if (nmiss)
    throw Error(ErrorCode::InvalidArgument,
                std::to_string(nmiss) +
                    " point(s) are not vertices of the triangulation: it does not belong to these "
                    "points");
  auto offb = ex.template alloc<I64>(std::size_t(n + 1));
  I64* off = offb.data();
  ex.exclusive_scan_of(
      n + 1,
      GG_LAMBDA(I64 i)->I64 {
        if (i >= n || src_of.removed(i)) return 0;
        const I64 c = vor::start_corner(key[src_of(i)]);
        const bool open = vor_open(nb, c);
        mesh::ClassRun run{};
        vor::walk_star(tri, nb, c, nt, [&](I64 t, int) { run.step(vid[t]); });
        return (open ? 1 : 0) + run.length(!open);
      },
      off);
  I64 ncv = 0;
  ex.to_host(off + n, 1, &ncv);
  auto cvb = ex.template alloc<I32>(std::size_t(ncv));
  I32* cv = cvb.data();
  ex.for_each_index(
      n, GG_LAMBDA(I64 i) {
        if (src_of.removed(i)) return;
        I32* o = cv + off[i];
        const I64 c = vor::start_corner(key[src_of(i)]);
        // An unbounded cell starts with -1: its walk starts at a corner whose clockwise side
        // is open (start_key prefers those).
        const bool open = vor_open(nb, c);
        I64 at = 0;
        if (open) o[at++] = -1;
        mesh::ClassRun run{};
        // (a closed cell's last run, when it is the first one's circle, was not counted)
        const I64 len = off[i + 1] - off[i];
        vor::walk_star(tri, nb, c, nt, [&](I64 t, int) {
          if (run.step(vid[t]) && at < len) o[at++] = vid[t];
        });
      });
  // The caller's arrays, checked before anything is written to them.
  const Voronoi2dBuffers& into = run.into;
  deliver::check(into.vertices, 2 * nv, "vertices");
  deliver::check(into.ridge_points, 2 * nr, "ridge_points");
  deliver::check(into.ridge_vertices, 2 * nr, "ridge_vertices");
  deliver::check(into.ridge_directions, 2 * nr, "ridge_directions");
  deliver::check(into.cell_offsets, n + 1, "cell_offsets");
  deliver::check(into.cell_vertices, ncv, "cell_vertices");
  deliver::check(into.simplex_vertex, nt, "simplex_vertex");
  if (host) {  // the host entry: into its HostVectors (on the CPU executor a parallel copy)
    deliver::to_host(ex, v, 2 * nv, into.vertices, host->vertices);
    deliver::to_host(ex, rp, 2 * nr, into.ridge_points, host->ridge_points);
    deliver::to_host(ex, rv, 2 * nr, into.ridge_vertices, host->ridge_vertices);
    deliver::to_host(ex, rd, 2 * nr, into.ridge_directions, host->ridge_directions);
    deliver::to_host(ex, off, n + 1, into.cell_offsets, host->cell_offsets);
    deliver::to_host(ex, cv, ncv, into.cell_vertices, host->cell_vertices);
    deliver::to_host(ex, vid, nt, into.simplex_vertex, host->simplex_vertex);
    host->num_points = n;
    host->num_vertices = nv;
    host->num_ridges = nr;
    host->num_cell_vertices = ncv;
    st.phase_ms.push_back({"voronoi", ms_since(t0)});
    return;
  }
  auto p_v = deliver::place(ex, vx, 2 * nv, into.vertices);
  auto p_rp = deliver::place(ex, rpb, 2 * nr, into.ridge_points);
  auto p_rv = deliver::place(ex, rvb, 2 * nr, into.ridge_vertices);
  auto p_rd = deliver::place(ex, rdb, 2 * nr, into.ridge_directions);
  auto p_off = deliver::place(ex, offb, n + 1, into.cell_offsets);
  auto p_cv = deliver::place(ex, cvb, ncv, into.cell_vertices);
  auto p_sv = deliver::place(ex, V.of, nt, into.simplex_vertex);
  ex.sync();  // the caller may read them now (and free them on any stream)
  out.num_vertices = nv;
  out.num_ridges = nr;
  out.num_cell_vertices = ncv;
  out.vertices = p_v.own();
  out.ridge_points = p_rp.own();
  out.ridge_vertices = p_rv.own();
  out.ridge_directions = p_rd.own();
  out.cell_offsets = p_off.own();
  out.cell_vertices = p_cv.own();
  out.simplex_vertex = p_sv.own();
  st.phase_ms.push_back({"voronoi", ms_since(t0)});
}
