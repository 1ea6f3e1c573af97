// Voronoi cells of 3D points in a box (issue 49): the steps that cells_kernels.inl describes,
// driven on the executor, with the periodic layer doubled until every cell is right. Included
// after cells_kernels.inl.

inline void voronoi_cells_impl(const double* xyz_in, std::int64_t n, bool input_on_host,
                               const VoronoiCellsOptions& opt, DeviceVoronoiCells* dev,
                               VoronoiCells* host) {
  using I8 = std::int8_t;
  using I32 = std::int32_t;
  using I64 = std::int64_t;
  using U64 = std::uint64_t;
  using vcells::CellJob;
  VoronoiCellsStats& st = host ? host->stats : dev->stats;
  auto t0 = std::chrono::steady_clock::now();
  Exec ex(opt);
  const ::gpugeom::detail::DevicePeak<Exec> peak(ex, st);
  // 1. The points, checked and (periodic axes) taken into the box.
  auto d_base = ex.template alloc<double>(std::size_t(3 * n));
  double* base = d_base.data();
  if (input_on_host)
    ex.from_host(xyz_in, 3 * n, base);
  else
    ex.copy(xyz_in, 3 * n, base);
  st.phase_ms.push_back({"upload", ms_since(t0)});
  double lo[3], hi[3], len[3];
  bool per[3];
  double volume = 1;
  for (int d = 0; d < 3; ++d) {
    lo[d] = opt.lo[d], hi[d] = opt.hi[d], per[d] = opt.periodic[d];
    len[d] = hi[d] - lo[d];
    volume *= len[d];
  }
  auto bad = ex.template alloc<I64>(1);
  ex.transform_reduce_into(
      n,
      GG_LAMBDA(I64 i)->I64 {
        I64 b = 0;
        for (int d = 0; d < 3; ++d) {
          double x = base[3 * i + d];
          if (!(fabs(x) <= DBL_MAX)) {  // (NaN or infinite)
            b = 1;
            continue;
          }
          if (!per[d]) {
            b |= x < lo[d] || x > hi[d];
            continue;
          }
          if (x < lo[d] || x >= hi[d]) {  // (modulo the box; rounding may leave hi: then lo)
            x = exact::sub_rn(x, exact::mul_rn(len[d], floor(exact::sub_rn(x, lo[d]) / len[d])));
            if (x >= hi[d] || x < lo[d]) x = lo[d];
            base[3 * i + d] = x;
          }
        }
        return b;
      },
      I64(0), thrust::plus<I64>(), bad.data());
  I64 nbad = 0;
  ex.to_host(bad.data(), 1, &nbad);
  if (nbad)
    throw Error(ErrorCode::InvalidInput,
                std::to_string(nbad) +
                    " point(s) have a coordinate that is not finite or lies outside the box "
                    "along an axis that does not wrap (VoronoiCellsOptions::lo, hi, periodic)");
  const bool any_periodic = per[0] || per[1] || per[2];
  double w = any_periodic ? 4 * std::cbrt(volume / double(std::max<I64>(n, 1))) : 0;
  for (int attempt = 1;; ++attempt) {
    // 1b. Images within w of the box along periodic axes, after the originals.
    t0 = std::chrono::steady_clock::now();
    int reach[3];
    double plo[3], phi[3];
    for (int d = 0; d < 3; ++d) {
      reach[d] = per[d] ? int(std::ceil(w / len[d])) : 0;
      plo[d] = per[d] ? lo[d] - w : lo[d];
      phi[d] = per[d] ? hi[d] + w : hi[d];
    }
    auto d_img = ex.template alloc<I64>(std::size_t(n + 1));
    I64* img = d_img.data();
    ex.exclusive_scan_of(
        n + 1,
        GG_LAMBDA(I64 i)->I64 {
          if (i >= n) return 0;
          I64 m = 1;
          for (int d = 0; d < 3; ++d) {
            int c = 0;
            for (int k = -reach[d]; k <= reach[d]; ++k) {
              const double x = exact::add_rn(base[3 * i + d], exact::mul_rn(k, len[d]));
              c += k == 0 || (x >= plo[d] && x <= phi[d]);
            }
            m *= c;
          }
          return m - 1;
        },
        img);
    I64 nimg = 0;
    ex.to_host(img + n, 1, &nimg);
    // ... and 8 far points, the corners of a cube 8 padded-box diagonals wide round it: none
    // cuts a cell inside the box (each is further from every point of the box than the box is
    // wide), but they make the tetrahedralisation three-dimensional for any input (1, 2, 3
    // points, or all on one plane).
    const I64 N = n + nimg + 8;
    if (N > I64(INT32_MAX))
      throw Error(ErrorCode::InvalidArgument, "the points and their periodic images number " +
                                                  std::to_string(N) + ", more than 2^31 - 1");
    auto d_aug = ex.template alloc<double>(std::size_t(3 * N));
    auto d_src = ex.template alloc<I32>(std::size_t(N));
    double* aug = d_aug.data();
    I32* src = d_src.data();
    ex.copy(base, 3 * n, aug);
    double far[24];
    {
      double diag = 0, c[3];
      for (int d = 0; d < 3; ++d)
        diag += (phi[d] - plo[d]) * (phi[d] - plo[d]), c[d] = plo[d] / 2 + phi[d] / 2;
      const double h = 4 * std::sqrt(diag);
      for (int k = 0; k < 8; ++k)
        for (int d = 0; d < 3; ++d) far[3 * k + d] = c[d] + ((k >> d) & 1 ? h : -h);
    }
    const I32 minus_one[8] = {-1, -1, -1, -1, -1, -1, -1, -1};
    ex.from_host(far, 24, aug + 3 * (n + nimg));
    ex.from_host(minus_one, 8, src + n + nimg);
    ex.for_each_index(
        n, GG_LAMBDA(I64 i) {
          src[i] = I32(i);
          if (!nimg) return;
          I64 at = n + img[i];
          const double* p = base + 3 * i;
          for (int a = -reach[0]; a <= reach[0]; ++a)
            for (int b = -reach[1]; b <= reach[1]; ++b)
              for (int c = -reach[2]; c <= reach[2]; ++c) {
                if (a == 0 && b == 0 && c == 0) continue;
                const int k[3] = {a, b, c};
                double x[3];
                bool in = true;
                for (int d = 0; d < 3; ++d) {
                  x[d] = exact::add_rn(p[d], exact::mul_rn(k[d], len[d]));
                  in &= k[d] == 0 || (x[d] >= plo[d] && x[d] <= phi[d]);
                }
                if (!in) continue;
                for (int d = 0; d < 3; ++d) aug[3 * at + d] = x[d];
                src[at++] = I32(i);
              }
        });
    st.phase_ms.push_back({"images", ms_since(t0)});
    st.images = nimg;
    st.attempts = attempt;
    // 2. The tetrahedralisation and its ridges: each original's neighbours, sorted.
    t0 = std::chrono::steady_clock::now();
    Delaunay3dOptions o = options_from<Delaunay3dOptions>(opt);
    check_count(N);
    DeviceTriangulation3d tri;
    const ::gpugeom::detail::ExecContext ctx = ex.context();  // (one stream, one memory count)
    entries.device(aug, N, o, tri, tri.stats, &ctx);
    st.phase_ms.push_back({"delaunay", ms_since(t0)});
    t0 = std::chrono::steady_clock::now();
    const I32* tet = tri.tetrahedra.get();
    const I32* tnb = tri.neighbors.get();
    const I32* dup = tri.num_duplicates ? tri.duplicate_of.get() : nullptr;
    const I64 nt = tri.num_tetrahedra;
    LeasePool<Exec> pool(ex, std::clamp<I64>(ex.concurrency(), 64, 1024), pred::kInsphereScratch);
    const ScratchLease lease = pool.view;
    auto V = vor3_classes(ex, aug, tet, tnb, nt, lease);
    auto d_len = ex.template alloc<I64>(std::size_t(6 * nt + 1));
    I64* rlen = d_len.data();
    vor3_ridge_lengths(ex, aug, tet, tnb, nt, V.of.data(), lease, rlen);
    auto d_rank = ex.template alloc<I64>(std::size_t(6 * nt + 1));
    I64* rank = d_rank.data();
    ex.exclusive_scan_of(
        6 * nt + 1, GG_LAMBDA(I64 c)->I64 { return c < 6 * nt && rlen[c + 1] != rlen[c]; }, rank);
    I64 nr = 0;
    ex.to_host(rank + 6 * nt, 1, &nr);
    auto d_keys = ex.template alloc<U64>(std::size_t(2 * nr));
    auto d_edges = ex.template alloc<I64>(std::size_t(2 * nr));
    U64* keys = d_keys.data();
    I64* edges = d_edges.data();
    auto d_from = ex.template alloc<I64>(std::size_t(n + 1));
    I64* from = d_from.data();
    ex.fill(from, n + 1, I64(0));
    ex.for_each_index(
        6 * nt, GG_LAMBDA(I64 c) {
          if (rlen[c + 1] == rlen[c]) return;
          int a, b;
          vor3_edge(int(c % 6), a, b);
          const I64 u = tet[4 * (c / 6) + a], v = tet[4 * (c / 6) + b];
          const I64 r = rank[c];
          keys[2 * r] = u < n ? (U64(u) << 32 | U64(v)) : ~U64(0);
          keys[2 * r + 1] = v < n ? (U64(v) << 32 | U64(u)) : ~U64(0);
          edges[2 * r] = edges[2 * r + 1] = c;
          if (u < n) atomic_add(from + u, I64(1));
          if (v < n) atomic_add(from + v, I64(1));
        });
    ex.sort_by_key(keys, edges, 2 * nr);
    // ... and the Voronoi vertices: one circumcentre per class
    const I32* vid = V.of.data();
    const I32* first = V.first.data();
    auto d_cc = ex.template alloc<double>(std::size_t(3 * V.count));
    double* cc = d_cc.data();
    ex.for_each_index(
        V.count, GG_LAMBDA(I64 j) { circumcentre3(aug, tet, first[j], cc + 3 * j); });
    auto d_from2 = ex.template alloc<I64>(std::size_t(n + 1));
    ex.exclusive_scan(from, d_from2.data(), n + 1);
    from = d_from2.data();
    st.phase_ms.push_back({"ridges", ms_since(t0)});
    // 3. Every cell, measured and counted, in the order of a Hilbert curve through the points
    // (neighbouring threads read neighbouring points and build cells alike).
    t0 = std::chrono::steady_clock::now();
    auto d_hkey = ex.template alloc<U64>(std::size_t(n));
    auto d_order = ex.template alloc<I32>(std::size_t(n));
    U64* hkey = d_hkey.data();
    I32* order = d_order.data();
    spatial::Box sbox;
    for (int d = 0; d < 3; ++d) sbox.lo[d] = plo[d], sbox.hi[d] = phi[d];
    ex.for_each_index(
        n, GG_LAMBDA(I64 i) {
          hkey[i] = spatial::hilbert_key<3>(aug + 3 * i, sbox);
          order[i] = I32(i);
        });
    ex.sort_by_key(hkey, order, n);
    auto d_vol = ex.template alloc<double>(std::size_t(n));
    auto d_area = ex.template alloc<double>(std::size_t(n));
    auto d_cen = ex.template alloc<double>(std::size_t(3 * n));
    auto d_counts = ex.template alloc<I32>(std::size_t(3 * n));
    auto d_flag = ex.template alloc<I8>(std::size_t(2 * n));
    I64 nslots = 0;  // (each cell's faces: room for one per plane)
    ex.to_host(from + n, 1, &nslots);
    nslots += 6 * n;
    auto d_splane = ex.template alloc<I32>(std::size_t(nslots));
    auto d_sarea = ex.template alloc<double>(std::size_t(nslots));
    CellJob J{};
    J.xyz = aug, J.src = src, J.dup = dup, J.nb_from = from, J.nb_key = keys, J.n = n;
    for (int d = 0; d < 3; ++d) J.plo[d] = plo[d], J.phi[d] = phi[d], J.periodic[d] = per[d];
    J.volume = d_vol.data(), J.area = d_area.data(), J.centroid = d_cen.data();
    J.nfaces = d_counts.data(), J.nverts = J.nfaces + n, J.nents = J.nverts + n;
    J.flag = d_flag.data(), J.how = J.flag + n;
    J.slot_plane = d_splane.data(), J.slot_area = d_sarea.data();
    J.nb_edge = edges, J.tet = tet, J.tnb = tnb, J.vid = vid, J.cc = cc, J.nt = nt;
    const I8* flag = J.flag;
    I8* how = J.how;
    ex.for_each_index(
        n, GG_LAMBDA(I64 i) { vcells::cell_direct_count(J, order[i]); });
    // ... the cells a wall cuts, cut from the box
    auto d_clip = ex.template alloc<I32>(std::size_t(n));
    I32* clip = d_clip.data();
    const I64 nclip = ex.compact_indices(
        n, GG_LAMBDA(I64 i)->bool { return how[i] == 1; }, clip);
    st.cells_cut = nclip;
    ex.for_each_index(
        nclip, GG_LAMBDA(I64 j) {
          using namespace vcells;
          double x[3 * kVertices + kFaces];
          I32 ints[2 * kEntries + 4 * kFaces + 3 * kVertices];
          I8 side[kVertices];
          const vcells::Room room{kFaces, kVertices, kEntries};
          cells::ConvexCell C{room.store(x, ints, side)};
          const I64 i = clip[j];
          cell_count(J, i, C);
          if (flag[i] == 2) how[i] = 2;
        });
    // ... the cells that outgrew a thread's room, again with room for all their planes
    auto d_big = ex.template alloc<I32>(std::size_t(n));
    I32* big = d_big.data();
    const I64 nbig = ex.compact_indices(
        n, GG_LAMBDA(I64 i)->bool { return flag[i] == 2; }, big);
    st.cell_overflows = nbig;
    auto d_kmax = ex.template alloc<I64>(1);
    vcells::Room room{0, 0, 0};
    I64 chunk = 0;
    if (nbig) {
      ex.transform_reduce_into(
          nbig, GG_LAMBDA(I64 j)->I64 { return from[big[j] + 1] - from[big[j]]; }, I64(0),
          thrust::maximum<I64>(), d_kmax.data());
      I64 kmax = 0;
      ex.to_host(d_kmax.data(), 1, &kmax);
      const I64 faces = kmax + 7;
      if (faces > (I64(1) << 24))
        throw Error(ErrorCode::Internal, "a Voronoi cell has " + std::to_string(kmax) +
                                             " neighbours, more than the cells can hold");
      room = vcells::Room{int(faces), int(2 * faces + 16), int(6 * faces + 32)};
      const I64 per_cell = 8 * room.doubles() + 4 * room.ints() + room.vertices;
      chunk = std::clamp<I64>((I64(256) << 20) / per_cell, 1, nbig);
    }
    vcells::over_big(ex, J, big, nbig, room, chunk, false);
    auto d_nflag = ex.template alloc<I64>(1);
    ex.transform_reduce_into(
        n, GG_LAMBDA(I64 i)->I64 { return flag[i] != 0; }, I64(0), thrust::plus<I64>(),
        d_nflag.data());
    I64 nflag = 0;
    ex.to_host(d_nflag.data(), 1, &nflag);
    st.phase_ms.push_back({"cells", ms_since(t0)});
    if (nflag) {
      if (!any_periodic)
        throw Error(ErrorCode::Internal,
                    std::to_string(nflag) + " Voronoi cell(s) could not be built");
      w *= 2;  // (some cell reaches past the images: a wider layer, and all again)
      continue;
    }
    // 4. Offsets; the faces gathered from their slots; the polygons, if asked for.
    t0 = std::chrono::steady_clock::now();
    auto d_foff = ex.template alloc<I64>(std::size_t(n + 1));
    auto d_voff = ex.template alloc<I64>(std::size_t(n + 1));
    auto d_eoff = ex.template alloc<I64>(std::size_t(n + 1));
    I64* foff = d_foff.data();
    I64* voff = d_voff.data();
    I64* eoff = d_eoff.data();
    const I32* cnt = d_counts.data();
    const bool polygons = opt.polygons;
    ex.exclusive_scan_of(
        n + 1, GG_LAMBDA(I64 i)->I64 { return i < n ? I64(cnt[i]) : 0; }, foff);
    I64 nf = 0, nv = 0, ne = 0;
    ex.to_host(foff + n, 1, &nf);
    if (polygons) {
      ex.exclusive_scan_of(
          n + 1, GG_LAMBDA(I64 i)->I64 { return i < n ? I64(cnt[n + i]) : 0; }, voff);
      ex.exclusive_scan_of(
          n + 1, GG_LAMBDA(I64 i)->I64 { return i < n ? I64(cnt[2 * n + i]) : 0; }, eoff);
      ex.to_host(voff + n, 1, &nv);
      ex.to_host(eoff + n, 1, &ne);
    }
    st.faces = nf;
    const VoronoiCellsBuffers& into = opt.into;
    deliver::check(into.volumes, n, "volumes");
    deliver::check(into.areas, n, "areas");
    deliver::check(into.centroids, 3 * n, "centroids");
    deliver::check(into.face_offsets, n + 1, "face_offsets");
    deliver::check(into.neighbors, nf, "neighbors");
    deliver::check(into.face_areas, nf, "face_areas");
    deliver::check(into.face_normals, 3 * nf, "face_normals");
    if (polygons) {
      deliver::check(into.face_vertex_offsets, nf + 1, "face_vertex_offsets");
      deliver::check(into.face_vertices, ne, "face_vertices");
      deliver::check(into.vertex_offsets, n + 1, "vertex_offsets");
      deliver::check(into.vertices, 3 * nv, "vertices");
    }
    auto d_nbr = ex.template alloc<I32>(std::size_t(nf));
    auto d_farea = ex.template alloc<double>(std::size_t(nf));
    auto d_fnrm = ex.template alloc<double>(std::size_t(3 * nf));
    I32* nbr = d_nbr.data();
    double* farea = d_farea.data();
    double* fnrm = d_fnrm.data();
    const I32* splane = d_splane.data();
    const double* sarea = d_sarea.data();
    ex.for_each_index(
        n, GG_LAMBDA(I64 i) {
          const I64 slot = from[i] + 6 * i, m = foff[i + 1] - foff[i];
          const double* p = aug + 3 * i;
          for (I64 j = 0; j < m; ++j) {
            const I64 o = foff[i] + j;
            const I32 plane = splane[slot + j];
            double* nr = fnrm + 3 * o;
            farea[o] = sarea[slot + j];
            if (plane < 6) {  // (a wall: -1 - its plane, Voro++'s numbering)
              nbr[o] = -1 - plane;
              nr[0] = nr[1] = nr[2] = 0;
              nr[plane / 2] = (plane & 1) ? 1 : -1;
              continue;
            }
            const I64 q = I64(keys[from[i] + (plane - 6)] & 0xffffffffu);
            nbr[o] = src[q];
            for (int d = 0; d < 3; ++d) nr[d] = exact::sub_rn(aug[3 * q + d], p[d]);
            const double len = sqrt(cells::dot3(nr, nr));
            for (int d = 0; d < 3; ++d) nr[d] = nr[d] / len;
          }
        });
    auto d_fvo = ex.template alloc<I64>(std::size_t(polygons ? nf + 1 : 0));
    auto d_fv = ex.template alloc<I32>(std::size_t(ne));
    auto d_vx = ex.template alloc<double>(std::size_t(3 * nv));
    if (polygons) {
      J.face_off = foff, J.vert_off = voff, J.ent_off = eoff;
      J.face_vert_off = d_fvo.data(), J.face_verts = d_fv.data(), J.vertices = d_vx.data();
      ex.fill(J.face_vert_off + nf, 1, ne);
      ex.for_each_index(
          n, GG_LAMBDA(I64 i) {
            i = order[i];
            if (how[i] == 0) vcells::cell_direct_write(J, i);
          });
      ex.for_each_index(
          nclip, GG_LAMBDA(I64 j) {
            using namespace vcells;
            const I64 i = clip[j];
            if (how[i] != 1) return;  // (over_big writes it)
            double x[3 * kVertices + kFaces];
            I32 ints[2 * kEntries + 4 * kFaces + 3 * kVertices];
            I8 side[kVertices];
            const vcells::Room rm{kFaces, kVertices, kEntries};
            cells::ConvexCell C{rm.store(x, ints, side)};
            cell_write(J, i, C);
          });
      vcells::over_big(ex, J, big, nbig, room, chunk, true);
    }
    st.phase_ms.push_back({"cells_write", ms_since(t0)});
    if (host) {
      host->num_points = n, host->num_faces = nf, host->num_face_vertices = ne;
      host->num_vertices = nv;
      deliver::to_host(ex, d_vol.data(), n, into.volumes, host->volumes);
      deliver::to_host(ex, d_area.data(), n, into.areas, host->areas);
      deliver::to_host(ex, d_cen.data(), 3 * n, into.centroids, host->centroids);
      deliver::to_host(ex, foff, n + 1, into.face_offsets, host->face_offsets);
      deliver::to_host(ex, d_nbr.data(), nf, into.neighbors, host->neighbors);
      deliver::to_host(ex, d_farea.data(), nf, into.face_areas, host->face_areas);
      deliver::to_host(ex, d_fnrm.data(), 3 * nf, into.face_normals, host->face_normals);
      if (polygons) {
        deliver::to_host(ex, d_fvo.data(), nf + 1, into.face_vertex_offsets,
                         host->face_vertex_offsets);
        deliver::to_host(ex, d_fv.data(), ne, into.face_vertices, host->face_vertices);
        deliver::to_host(ex, voff, n + 1, into.vertex_offsets, host->vertex_offsets);
        deliver::to_host(ex, d_vx.data(), 3 * nv, into.vertices, host->vertices);
      }
      return;
    }
    dev->num_points = n, dev->num_faces = nf, dev->num_face_vertices = ne, dev->num_vertices = nv;
    auto p_vol = deliver::place(ex, d_vol, n, into.volumes);
    auto p_area = deliver::place(ex, d_area, n, into.areas);
    auto p_cen = deliver::place(ex, d_cen, 3 * n, into.centroids);
    auto p_foff = deliver::place(ex, d_foff, n + 1, into.face_offsets);
    auto p_nbr = deliver::place(ex, d_nbr, nf, into.neighbors);
    auto p_farea = deliver::place(ex, d_farea, nf, into.face_areas);
    auto p_fnrm = deliver::place(ex, d_fnrm, 3 * nf, into.face_normals);
    deliver::Placed<Exec, I64> p_fvo, p_voff;
    deliver::Placed<Exec, I32> p_fv;
    deliver::Placed<Exec, double> p_vx;
    if (polygons) {
      p_fvo = deliver::place(ex, d_fvo, nf + 1, into.face_vertex_offsets);
      p_fv = deliver::place(ex, d_fv, ne, into.face_vertices);
      p_voff = deliver::place(ex, d_voff, n + 1, into.vertex_offsets);
      p_vx = deliver::place(ex, d_vx, 3 * nv, into.vertices);
    }
    ex.sync();  // the results (the caller's arrays among them) are complete
    dev->volumes = p_vol.own(), dev->areas = p_area.own();
    dev->centroids = p_cen.own(), dev->face_offsets = p_foff.own();
    dev->neighbors = p_nbr.own(), dev->face_areas = p_farea.own();
    dev->face_normals = p_fnrm.own();
    dev->face_vertex_offsets = p_fvo.own(), dev->face_vertices = p_fv.own();
    dev->vertex_offsets = p_voff.own(), dev->vertices = p_vx.own();
    return;
  }
}
