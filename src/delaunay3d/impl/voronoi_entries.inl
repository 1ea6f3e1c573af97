// The 3D Voronoi diagram's and the cells' entries on one executor (voronoi3d_backend.hpp's
// VoronoiEntries), included last by each executor's unit (voronoi3d_cpu.cpp, voronoi3d_cuda.cu).

// voronoi3d(xyz, n, opt, tri) on an executor that does not read host memory: the points cross the
// bus once, the tetrahedralisation and the diagram are made there, and only the results come
// back (through the executor's staged copies into the host vectors).
inline void voronoi_from_host(const double* xyz, std::int64_t n, const Delaunay3dOptions& opt,
                              Voronoi3d& v, Triangulation3d* tri) {
  const auto t0 = std::chrono::steady_clock::now();
  Exec ex(opt);
  const ::gpugeom::detail::DevicePeak<Exec> peak(ex, v.stats);  // (the whole call's)
  auto up = ex.template alloc<double>(std::size_t(3 * n));
  ex.from_host(xyz, 3 * n, up.data());
  v.stats.phase_ms.push_back({"upload", ms_since(t0)});
  Delaunay3dOptions o = opt;
  o.into = {};
  DeviceTriangulation3d d;  // (voronoi3d checked n)
  d.stats.backend = Exec::backend;
  const ::gpugeom::detail::ExecContext ctx = ex.context();
  entries.device(up.data(), n, o, d, d.stats, &ctx);
  DeviceVoronoi3d unused;
  const auto vo = options_from<Voronoi3dOptions>(opt);
  voronoi3d_impl(up.data(), n, d.tetrahedra.get(), d.neighbors.get(),
                 d.num_duplicates ? d.duplicate_of.get() : nullptr, d.num_tetrahedra, vo, unused,
                 v.stats, &v, &ctx);
  if (!tri) return;
  const auto t1 = std::chrono::steady_clock::now();
  const OutBuffer<std::int32_t> none{};
  deliver::to_host(ex, d.tetrahedra.get(), 4 * d.num_tetrahedra, none, tri->tetrahedra);
  deliver::to_host(ex, d.neighbors.get(), 4 * d.num_tetrahedra, none, tri->neighbors);
  deliver::to_host(ex, d.duplicate_of.get(), n, none, tri->duplicate_of);
  deliver::to_host(ex, d.vertex_to_simplex.get(), n, none, tri->vertex_to_simplex);
  deliver::to_host(ex, d.hull_facets.get(), 3 * d.num_hull_facets, none, tri->hull_facets);
  tri->num_tetrahedra = d.num_tetrahedra;
  tri->num_hull_facets = d.num_hull_facets;
  tri->num_duplicates = d.num_duplicates;
  tri->stats = d.stats;
  tri->stats.phase_ms.push_back({"copy_tetrahedralisation", ms_since(t1)});
}

// voronoi3d(xyz, n, tri, opt): on the CPU executor over the caller's arrays where they are; on
// one that does not read host memory, the points and the tetrahedralisation go up once and only
// the diagram comes back.
inline void voronoi_of_host(const double* xyz, std::int64_t n, const std::int32_t* tet,
                            const std::int32_t* nb, const std::int32_t* dup, std::int64_t nt,
                            const Voronoi3dOptions& opt, Voronoi3d& v) {
  DeviceVoronoi3d unused;
  if constexpr (Exec::backend == Backend::Cpu) {
    voronoi3d_impl(xyz, n, tet, nb, dup, nt, opt, unused, v.stats, &v, nullptr);
  } else {
    ::gpugeom::detail::voronoi_on_upload<3, 4, Exec>(
        xyz, n, tet, nb, dup, nt, opt, v.stats,
        [&](const double* p, const std::int32_t* t, const std::int32_t* b, const std::int32_t* d,
            const ::gpugeom::detail::ExecContext* ctx) {
          voronoi3d_impl(p, n, t, b, d, nt, opt, unused, v.stats, &v, ctx);
        });
  }
}

const VoronoiEntries voronoi_entries{&voronoi3d_impl, &voronoi_of_host,
                                     Exec::backend == Backend::Cpu ? nullptr : &voronoi_from_host,
                                     &voronoi_cells_impl};
