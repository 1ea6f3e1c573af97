// The Voronoi diagram of a triangulation in the executor's memory, computed there (the device
// entry, voronoi2d_device): the same arrays, in the same order, as voronoi2d's loop makes on
// the host, from the same per-element pieces (voronoi_core.hpp). Included inside
// gpugeom::del2d::{cpu,cuda}_impl.

struct VorSource {  // the point whose cell a point has: itself, or the one it duplicates
  const std::int32_t* dup;
  GG_HD std::int64_t operator()(std::int64_t i) const { return dup && dup[i] >= 0 ? dup[i] : i; }
  // A point removed from a kept triangulation (DynamicDelaunay2d: kRemovedPoint in the duplicate
  // map) has no cell: its cell is empty.
  GG_HD bool removed(std::int64_t i) const { return dup && dup[i] == kRemovedPoint; }
};
// Whether the walk from corner c (a start corner) goes round an unbounded cell.
GG_HD inline bool vor_open(const std::int32_t* nb, std::int64_t c) {
  return nb[3 * (c / 3) + (c % 3 + 2) % 3] < 0;
}

inline void voronoi_impl(const double* xy, std::int64_t n, const std::int32_t* tri,
                         const std::int32_t* nb, const std::int32_t* dup, std::int64_t nt,
                         const RunOptions& run, DeviceVoronoiOutput& out, Stats& st,
                         Voronoi2d* host) {
  const auto t0 = std::chrono::steady_clock::now();
  Exec ex(run);
  const ::gpugeom::detail::DevicePeak<Exec> peak(ex, st);
  using I32 = std::int32_t;
  using I64 = std::int64_t;
  // Voronoi vertices: the circumcentres.
  auto vx = ex.template alloc<double>(std::size_t(2 * nt));
  double* v = vx.data();
  ex.for_each_index(
      nt, GG_LAMBDA(I64 t) { vor::circumcentre(xy, tri, t, v + 2 * t); });
  // Ridges: one per edge, numbered in (triangle, edge) order.
  auto rank = ex.template alloc<I64>(std::size_t(3 * nt + 1));
  I64* rk = rank.data();
  ex.exclusive_scan_of(
      3 * nt + 1,
      GG_LAMBDA(I64 c)->I64 { return c < 3 * nt && vor::has_ridge(nb, c / 3, int(c % 3)) ? 1 : 0; },
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
      });
  // Cells: each vertex's walk starts at its key's corner; duplicates walk their original's.
  auto keyb = ex.template alloc<I64>(std::size_t(n));
  I64* key = keyb.data();
  ex.fill(key, n, I64(-1));
  ex.for_each_index(
      3 * nt, GG_LAMBDA(I64 c) { atomic_max(key + tri[c], vor::start_key(nb, c)); });
  const VorSource src_of{dup};
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
        I64 len = vor_open(nb, c) ? 1 : 0;
        vor::walk_star(tri, nb, c, nt, [&](I64, int) { ++len; });
        return len;
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
        I64 at = 0;
        if (vor_open(nb, c)) o[at++] = -1;
        vor::walk_star(tri, nb, c, nt, [&](I64 t, int) { o[at++] = I32(t); });
      });
  if (host) {  // the host entry: into its HostVectors (on the CPU executor a parallel copy)
    const OutBuffer<double> nd{};
    const OutBuffer<I32> ni{};
    const OutBuffer<I64> nl{};
    deliver::to_host(ex, v, 2 * nt, nd, host->vertices);
    deliver::to_host(ex, rp, 2 * nr, ni, host->ridge_points);
    deliver::to_host(ex, rv, 2 * nr, ni, host->ridge_vertices);
    deliver::to_host(ex, rd, 2 * nr, nd, host->ridge_directions);
    deliver::to_host(ex, off, n + 1, nl, host->cell_offsets);
    deliver::to_host(ex, cv, ncv, ni, host->cell_vertices);
    st.phase_ms.push_back({"voronoi", ms_since(t0)});
    return;
  }
  ex.sync();  // the caller may read them now (and free them on any stream)
  out.num_vertices = nt;
  out.num_ridges = nr;
  out.num_cell_vertices = ncv;
  out.vertices = vx.hand_over();
  out.ridge_points = rpb.hand_over();
  out.ridge_vertices = rvb.hand_over();
  out.ridge_directions = rdb.hand_over();
  out.cell_offsets = offb.hand_over();
  out.cell_vertices = cvb.hand_over();
  st.phase_ms.push_back({"voronoi", ms_since(t0)});
}
