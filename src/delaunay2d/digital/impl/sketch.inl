// The digital sketch on an executor (sketch_backend.hpp), included inside the executor's
// namespace with Exec and edt_impl defined. One thread a point for the mapping, one a pixel for
// the colouring and the debris test, one a grid corner for the dual; the dual's triangles are
// written in corner raster order (a scan of the per-corner counts), so the arrays are the same
// on every executor. The arrays stay on the executor (HeldSketch) for the shifting phase and the
// Triangulator; only the boundary (for the hull fill) and the counts come to the host.

namespace digital_sketch_impl {

// The grid point (x, y) of pixel p, and squared distances between pixels.
struct PixelGrid {
  std::int64_t w, h;
  GG_INLINE std::int64_t x(std::int64_t p) const { return p % w; }
  GG_INLINE std::int64_t y(std::int64_t p) const { return p / w; }
  GG_INLINE std::int64_t d2(std::int64_t p, std::int64_t q) const {
    const std::int64_t dx = x(p) - x(q), dy = y(p) - y(q);
    return dx * dx + dy * dy;
  }
  // Orientation of three pixels' grid points (exact: coordinates below 2^16).
  GG_INLINE std::int64_t orient(std::int64_t a, std::int64_t b, std::int64_t c) const {
    return (x(b) - x(a)) * (y(c) - y(a)) - (y(b) - y(a)) * (x(c) - x(a));
  }
};

// Where a rim vertex is: its grid point (pixel given) or its own coordinates.
struct RimCoords {
  const double* p;
  const std::int32_t* pixel;
  std::int64_t w;
  GG_INLINE void at(std::int32_t v, double& x, double& y) const {
    if (pixel) {
      x = double(pixel[v] % w), y = double(pixel[v] / w);
    } else {
      x = p[2 * std::int64_t(v)], y = p[2 * std::int64_t(v) + 1];
    }
  }
};

}  // namespace digital_sketch_impl

// The boundary half-edges (twin -1) of nt triangles on the executor, brought to the host in id
// order with their start vertices' coordinates.
inline std::vector<digital::RimEdge> rim_records(Exec& ex, const std::int32_t* tri,
                                                 const std::int32_t* twin, std::int64_t nt,
                                                 digital_sketch_impl::RimCoords c) {
  auto ids = ex.template alloc<std::int32_t>(std::size_t(3 * nt));
  const std::int64_t nr = ex.compact_indices(
      3 * nt, GG_LAMBDA(std::int64_t e) { return twin[e] < 0; }, ids.data());
  auto rec = ex.template alloc<digital::RimEdge>(std::size_t(nr));
  digital::RimEdge* R = rec.data();
  const std::int32_t* I = ids.data();
  ex.for_each_index(
      nr, GG_LAMBDA(std::int64_t j) {
        const std::int32_t e = I[j];
        digital::RimEdge r;
        r.e = e, r.a = tri[e], r.b = tri[e - e % 3 + (e % 3 + 1) % 3];
        c.at(r.a, r.x, r.y);
        R[j] = r;
      });
  std::vector<digital::RimEdge> out(static_cast<std::size_t>(nr));
  ex.to_host(R, nr, out.data());
  return out;
}

// The sketch's arrays on the executor (sketch.hpp's Sketch names them).
struct HeldSketch {
  typename Exec::template Buffer<std::int32_t> pixel, colour, site_of, missing, tri, twin;
  std::int64_t nmiss = 0, nt = 0;
};

// P: the n points in executor memory; s: the frame (width, height, ox, oy, h). Fills s's counts
// (debris, pinched, hull_triangles) and phase times; its arrays stay empty (download_sketch).
inline HeldSketch sketch_on(Exec& ex, const double* P, std::int64_t n, digital::Sketch& s) {
  using digital_sketch_impl::PixelGrid;
  HeldSketch H;
  auto t0 = std::chrono::steady_clock::now();
  auto phase = [&](const char* name) {
    ex.sync();
    const auto t1 = std::chrono::steady_clock::now();
    s.phase_ms.push_back({name, std::chrono::duration<double, std::milli>(t1 - t0).count()});
    t0 = t1;
  };
  const PixelGrid G{s.width, s.height};
  const std::int64_t np = G.w * G.h;
  // Phase 1a (edt/impl/point_voronoi.inl): each point to its pixel, the first point of a pixel
  // its site, then PBA's feature transform gives each pixel its nearest site's point.
  point_voronoi_impl::CellFrame F;
  F.nd = 2, F.n[0] = G.w, F.n[1] = G.h, F.o[0] = s.ox, F.o[1] = s.oy, F.h = s.h;
  PointVoronoi V = map_point_sites(ex, P, n, F);
  phase("grid");
  colour_cells(ex, n, F, V);
  H.nmiss = V.nmiss;
  H.pixel = std::move(V.cell);
  H.colour = std::move(V.colour);
  H.missing = std::move(V.missing);
  std::int32_t* pixel = H.pixel.data();
  std::int32_t* colour = H.colour.data();
  phase("pba");
  // Debris (pixels not 8-connected to their site through their colour). Each pixel steps to its
  // neighbour of its colour with the least (squared distance to its site, raster index) below
  // its own, if any: from every pixel these steps descend to its site or to a root (a pixel with
  // no such neighbour). Where no root exists there is no debris. Else the descents are followed
  // to their ends by pointer jumping; the pixels that end at a root (candidates: every debris
  // pixel is one, most are not debris) are tested for a connection through other pixels of
  // their colour on the executor, and only the debris goes to the host, with the colouring, for
  // Alg. 4.3 (sketch_backend.hpp); the pixels it recolours come back.
  {
    auto up_a = ex.template alloc<std::int32_t>(std::size_t(np));
    std::int32_t* up = up_a.data();
    auto cnt = ex.template alloc<std::int64_t>(1);
    ex.transform_reduce_into(
        np,
        GG_LAMBDA(std::int64_t p)->std::int64_t {
          const std::int32_t c = colour[p];
          const std::int64_t site = pixel[c];
          up[p] = std::int32_t(p);
          if (site == p) return 0;
          std::int64_t bd = G.d2(p, site), bq = p;
          const std::int64_t px = G.x(p), py = G.y(p);
          for (std::int64_t dy = -1; dy <= 1; ++dy)
            for (std::int64_t dx = -1; dx <= 1; ++dx) {
              const std::int64_t qx = px + dx, qy = py + dy;
              if ((!dx && !dy) || qx < 0 || qy < 0 || qx >= G.w || qy >= G.h) continue;
              const std::int64_t q = qy * G.w + qx;
              if (colour[q] != c) continue;
              const std::int64_t e = G.d2(q, site);
              if (e < bd || (e == bd && q < bq)) bd = e, bq = q;
            }
          up[p] = std::int32_t(bq);
          return bq == p;
        },
        std::int64_t(0), thrust::plus<std::int64_t>(), cnt.data());
    std::int64_t roots = 0;
    ex.to_host(cnt.data(), 1, &roots);
    if (roots > 0) {
      auto up_b = ex.template alloc<std::int32_t>(std::size_t(np));
      for (int jump = 0; jump < 64; ++jump) {
        const std::int32_t* from = up;
        std::int32_t* to = up_b.data();
        ex.transform_reduce_into(
            np,
            GG_LAMBDA(std::int64_t p)->std::int64_t {
              const std::int32_t u = from[from[p]];
              to[p] = u;
              return u != from[p];
            },
            std::int64_t(0), thrust::plus<std::int64_t>(), cnt.data());
        std::swap(up_a, up_b);
        up = up_a.data();
        std::int64_t moved = 0;
        ex.to_host(cnt.data(), 1, &moved);
        if (!moved) break;
      }
      const std::int32_t* end = up;
      auto cand_d = ex.template alloc<std::int32_t>(std::size_t(np));
      std::int32_t* cand = cand_d.data();
      std::int64_t nc = ex.compact_indices(
          np, GG_LAMBDA(std::int64_t p) { return end[p] != pixel[colour[p]]; }, cand);
      s.debris_candidates = nc;
      // Among the candidates, those 8-connected through their colour to a pixel that is not one
      // (so to their site) are connected too: marks (0 not a candidate, 1 a candidate, 2 one
      // found connected) spread until they stop. Only what is left, the debris, goes on.
      if (nc > 0) {
        std::int32_t* mark = up_b.data();  // (free again: the descents' ends are in up_a)
        ex.fill(mark, np, std::int32_t(0));
        ex.for_each_index(
            nc, GG_LAMBDA(std::int64_t j) { mark[cand[j]] = 1; });
        // (four sweeps a look: the last one's count of new marks says whether they stopped)
        for (int sweep = 0;; ++sweep) {
          for (int k = 0; k < 4; ++k)
            ex.transform_reduce_into(
                nc,
                GG_LAMBDA(std::int64_t j)->std::int64_t {
                  const std::int32_t a = cand[j];
                  if (atomic_load(mark + a) != 1) return 0;
                  const std::int64_t ax = G.x(a), ay = G.y(a);
                  for (std::int64_t dy = -1; dy <= 1; ++dy)
                    for (std::int64_t dx = -1; dx <= 1; ++dx) {
                      const std::int64_t qx = ax + dx, qy = ay + dy;
                      if ((!dx && !dy) || qx < 0 || qy < 0 || qx >= G.w || qy >= G.h) continue;
                      const std::int64_t q = qy * G.w + qx;
                      if (colour[q] == colour[a] && atomic_load(mark + q) != 1) {
                        atomic_max(mark + a, std::int32_t(2));
                        return 1;
                      }
                    }
                  return 0;
                },
                std::int64_t(0), thrust::plus<std::int64_t>(), cnt.data());
          std::int64_t moved = 0;
          ex.to_host(cnt.data(), 1, &moved);
          if (!moved) break;
          if (sweep > 1000000) throw Error(ErrorCode::Internal, "digital sketch: debris marks");
        }
        std::int32_t* debris = up_a.data();
        nc = ex.copy_if(
            cand, nc, debris, GG_LAMBDA(std::int32_t a) { return mark[a] == 1; });
        cand = debris;
      }
      if (nc > 0) {
        // Alg. 4.3 reads only the 3x3 blocks around the debris: their colours and those
        // colours' site pixels go to the host, not the whole grid.
        auto blk = ex.template alloc<std::int32_t>(std::size_t(18 * nc));
        std::int32_t* B = blk.data();
        const std::int32_t* D = cand;
        ex.for_each_index(
            nc, GG_LAMBDA(std::int64_t j) {
              const std::int64_t ax = G.x(D[j]), ay = G.y(D[j]);
              for (int k = 0; k < 9; ++k) {
                const std::int64_t qx = ax + k % 3 - 1, qy = ay + k / 3 - 1;
                const bool in = qx >= 0 && qy >= 0 && qx < G.w && qy < G.h;
                const std::int32_t c = in ? colour[qy * G.w + qx] : -1;
                B[18 * j + k] = c, B[18 * j + 9 + k] = in ? pixel[c] : -1;
              }
            });
        std::vector<std::int32_t> hd(static_cast<std::size_t>(nc)),
            hb(static_cast<std::size_t>(18 * nc));
        ex.to_host(cand, nc, hd.data());
        ex.to_host(B, 18 * nc, hb.data());
        const std::vector<std::int32_t> changed = digital::recolour_debris(G.w, G.h, hd, hb);
        const std::int64_t nd = std::int64_t(changed.size() / 2);
        s.debris = nd;
        if (nd) {
          auto ch_d = ex.template alloc<std::int32_t>(std::size_t(2 * nd));
          ex.from_host(changed.data(), 2 * nd, ch_d.data());
          const std::int32_t* ch = ch_d.data();
          ex.for_each_index(
              nd, GG_LAMBDA(std::int64_t j) { colour[ch[2 * j]] = ch[2 * j + 1]; });
        }
      }
    }
    phase("debris");
  }
  H.site_of = ex.template alloc<std::int32_t>(std::size_t(n));
  {
    std::int32_t* so = H.site_of.data();
    ex.for_each_index(
        n, GG_LAMBDA(std::int64_t i) { so[i] = colour[pixel[i]]; });
  }
  // Phase 1b: per grid corner, its cells (x, y), (x + 1, y), (x + 1, y + 1), (x, y + 1) in
  // counter-clockwise order: three colours give a triangle (none where one cell crosses the
  // corner diagonally: that cell separates the two others), four give two, split along the
  // diagonal that leaves both counter-clockwise.
  const std::int64_t nc = (G.w - 1) * (G.h - 1);
  auto corner = [=] GG_HD(std::int64_t k, std::int32_t d[4], int& pinched) -> int {
    const std::int64_t x = k % (G.w - 1), y = k / (G.w - 1);
    const std::int32_t c[4] = {colour[y * G.w + x], colour[y * G.w + x + 1],
                               colour[(y + 1) * G.w + x + 1], colour[(y + 1) * G.w + x]};
    int m = 0;
    for (int j = 0; j < 4; ++j) {
      bool seen = false;
      for (int i = 0; i < m; ++i) seen |= d[i] == c[j];
      if (!seen) d[m++] = c[j];
    }
    pinched = m == 3 && (c[0] == c[2] || c[1] == c[3]);
    if (pinched) return 0;
    return m == 3 ? 1 : (m == 4 ? 2 : 0);
  };
  auto offs = ex.template alloc<std::int64_t>(std::size_t(nc + 1));
  std::int64_t* off = offs.data();
  ex.exclusive_scan_of(
      nc + 1,
      GG_LAMBDA(std::int64_t k)->std::int64_t {
        if (k == nc) return 0;
        std::int32_t d[4];
        int pin = 0;
        return std::int64_t(corner(k, d, pin));
      },
      off);
  auto pcount = ex.template alloc<std::int64_t>(1);
  ex.transform_reduce_into(
      nc,
      GG_LAMBDA(std::int64_t k)->std::int64_t {
        std::int32_t d[4];
        int pin = 0;
        corner(k, d, pin);
        return pin;
      },
      std::int64_t(0), thrust::plus<std::int64_t>(), pcount.data());
  std::int64_t nt = 0;
  ex.to_host(off + nc, 1, &nt);
  ex.to_host(pcount.data(), 1, &s.pinched);
  H.tri = ex.template alloc<std::int32_t>(std::size_t(3 * nt));
  H.nt = nt;
  std::int32_t* T = H.tri.data();
  ex.for_each_index(
      nc, GG_LAMBDA(std::int64_t k) {
        std::int32_t d[4];
        int pin = 0;
        const int m = corner(k, d, pin);
        if (!m) return;
        std::int32_t* o = T + 3 * off[k];
        if (m == 1) {
          o[0] = d[0], o[1] = d[1], o[2] = d[2];
          return;
        }
        auto orient = [&](std::int32_t a, std::int32_t b, std::int32_t c) {
          return G.orient(pixel[a], pixel[b], pixel[c]);
        };
        const bool first = orient(d[0], d[1], d[2]) > 0 && orient(d[0], d[2], d[3]) > 0;
        const int a = first ? 0 : 1;
        o[0] = d[a], o[1] = d[a + 1], o[2] = d[a + 2];
        o[3] = d[a], o[4] = d[a + 2], o[5] = d[(a + 3) % 4];
      });
  phase("dual");
  // Adjacency (mesh/half_edges.hpp). An edge in three triangles or more would be no
  // triangulation's: refused as an internal error.
  H.twin = ex.template alloc<std::int32_t>(std::size_t(3 * nt));
  const std::int64_t nbad = mesh::pair_half_edges(ex, T, nt, H.twin.data());
  if (nbad)
    throw Error(ErrorCode::Internal,
                "digital sketch: " + std::to_string(nbad) + " edge(s) in three triangles");
  phase("adjacency");
  // The truncated diagram's dual made a triangulation of its vertices' convex hull: the pockets'
  // triangles appended, their half-edges paired with the boundary's.
  const std::vector<digital::RimEdge> rim =
      rim_records(ex, T, H.twin.data(), nt, {nullptr, pixel, G.w});
  const digital::HullFill fill = digital::fill_to_hull(rim, nt);
  if (!fill.disk) {  // (no disk: the sketch has no triangulation to offer; callers fall back)
    s.not_disk = 1, H.nt = 0;
    phase("hull_fill");
    return H;
  }
  const std::int64_t added = std::int64_t(fill.triangles.size() / 3);
  s.hull_triangles = added;
  if (added) {
    const std::int64_t all = nt + added;
    auto t2 = ex.template alloc<std::int32_t>(std::size_t(3 * all));
    auto w2 = ex.template alloc<std::int32_t>(std::size_t(3 * all));
    ex.copy(H.tri.data(), 3 * nt, t2.data());
    ex.copy(H.twin.data(), 3 * nt, w2.data());
    ex.from_host(fill.triangles.data(), 3 * added, t2.data() + 3 * nt);
    ex.from_host(fill.twin.data(), 3 * added, w2.data() + 3 * nt);
    std::int32_t* W = w2.data();
    const std::int64_t old = 3 * nt;
    ex.for_each_index(
        3 * added, GG_LAMBDA(std::int64_t j) {
          const std::int32_t o = W[old + j];
          if (o >= 0 && o < old) W[o] = std::int32_t(old + j);
        });
    H.tri = std::move(t2), H.twin = std::move(w2), H.nt = all;
  }
  phase("hull_fill");
  return H;
}
