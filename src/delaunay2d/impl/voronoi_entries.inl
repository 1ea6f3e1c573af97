// The 2D Voronoi diagram's entries on one executor (del2d_backend.hpp's VoronoiEntries), included
// after voronoi.inl by each executor's unit (voronoi_cpu.cpp, voronoi_cuda.cu).

// voronoi2d(xy, n, opt, tri) on an executor that does not read host memory: the points cross the
// bus once, the triangulation and the diagram are made there, and only the results come back
// (through the executor's staged copies into the host vectors).
inline void voronoi_from_host(const double* xy, std::int64_t n, const Delaunay2dOptions& opt,
                              Voronoi2d& v, Triangulation2d* tri, Delaunay2dStats& stats) {
  const auto t0 = std::chrono::steady_clock::now();
  Exec ex(opt);
  const ::gpugeom::detail::DevicePeak<Exec> peak(ex, stats);
  auto up = ex.template alloc<double>(std::size_t(2 * n));
  ex.from_host(xy, 2 * n, up.data());
  stats.phase_ms.push_back({"upload", ms_since(t0)});
  Delaunay2dOptions o = opt;
  o.into = {};
  DeviceOutput d;
  const ::gpugeom::detail::ExecContext ctx = ex.context();
  entries.device(up.data(), n, o, d, stats, &ctx);
  DeviceVoronoiOutput unused;
  const auto vo = options_from<Voronoi2dOptions>(opt);
  voronoi_impl(up.data(), n, d.triangles.get(), d.neighbors.get(),
               d.num_duplicates ? d.duplicate_of.get() : nullptr, d.num_triangles, vo, unused,
               stats, &v, &ctx);
  if (!tri) return;
  const auto t1 = std::chrono::steady_clock::now();
  const OutBuffer<std::int32_t> none{};
  deliver::to_host(ex, d.triangles.get(), 3 * d.num_triangles, none, tri->triangles);
  deliver::to_host(ex, d.neighbors.get(), 3 * d.num_triangles, none, tri->neighbors);
  deliver::to_host(ex, d.duplicate_of.get(), n, none, tri->duplicate_of);
  tri->num_triangles = d.num_triangles;
  tri->num_duplicates = d.num_duplicates;
  stats.phase_ms.push_back({"copy_triangulation", ms_since(t1)});
}

// voronoi2d(xy, n, tri, opt): on the CPU executor over the caller's arrays where they are; on
// one that does not read host memory, the points and the triangulation go up once and only the
// diagram comes back.
inline void voronoi_of_host(const double* xy, std::int64_t n, const std::int32_t* tri,
                            const std::int32_t* nb, const std::int32_t* dup, std::int64_t nt,
                            const Voronoi2dOptions& opt, Voronoi2d& v) {
  DeviceVoronoiOutput unused;
  if constexpr (Exec::backend == Backend::Cpu) {
    voronoi_impl(xy, n, tri, nb, dup, nt, opt, unused, v.stats, &v, nullptr);
  } else {
    ::gpugeom::detail::voronoi_on_upload<2, 3, Exec>(
        xy, n, tri, nb, dup, nt, opt, v.stats,
        [&](const double* p, const std::int32_t* t, const std::int32_t* b, const std::int32_t* d,
            const ::gpugeom::detail::ExecContext* ctx) {
          voronoi_impl(p, n, t, b, d, nt, opt, unused, v.stats, &v, ctx);
        });
  }
}

const VoronoiEntries voronoi_entries{&voronoi_impl, &voronoi_of_host,
                                     Exec::backend == Backend::Cpu ? nullptr : &voronoi_from_host};
