// The digital sketch on an executor (sketch_backend.hpp), included inside the executor's
// namespace with Exec and edt_impl defined. One thread a point for the mapping, one a pixel for
// the colouring and the debris test, one a grid corner for the dual; the dual's triangles are
// written in corner raster order (a scan of the per-corner counts), so the arrays are the same
// on every executor.

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

}  // namespace digital_sketch_impl

inline void digital_sketch_dual_impl(const double* xy, std::int64_t n, const RunOptions& run,
                                     bool keep_colour, digital::Sketch& s) {
  using digital_sketch_impl::PixelGrid;
  Exec ex(run);
  auto t0 = std::chrono::steady_clock::now();
  auto phase = [&](const char* name) {
    ex.sync();
    const auto t1 = std::chrono::steady_clock::now();
    s.phase_ms.push_back({name, std::chrono::duration<double, std::milli>(t1 - t0).count()});
    t0 = t1;
  };
  const PixelGrid G{s.width, s.height};
  const std::int64_t np = G.w * G.h;
  const double ox = s.ox, oy = s.oy, h = s.h;
  // Phase 1a: each point to its pixel; the first point of a pixel (atomic minimum) is its site.
  auto pts = ex.template alloc<double>(std::size_t(2 * n));
  ex.from_host(xy, 2 * n, pts.data());
  auto pix = ex.template alloc<std::int32_t>(std::size_t(n));
  auto col = ex.template alloc<std::int32_t>(std::size_t(np));
  std::int32_t* pixel = pix.data();
  std::int32_t* colour = col.data();
  const double* P = pts.data();
  ex.fill(colour, np, std::numeric_limits<std::int32_t>::max());
  ex.for_each_index(
      n, GG_LAMBDA(std::int64_t i) {
        auto cell = [](double v, double lo, double hh, std::int64_t m) {
          const std::int64_t c = std::int64_t(floor((v - lo) / hh));
          return c < 0 ? std::int64_t(0) : (c > m - 1 ? m - 1 : c);
        };
        const std::int64_t p = cell(P[2 * i + 1], oy, h, G.h) * G.w + cell(P[2 * i], ox, h, G.w);
        pixel[i] = std::int32_t(p);
        atomic_min(&colour[p], std::int32_t(i));
      });
  auto miss = ex.template alloc<std::int32_t>(std::size_t(n));
  const std::int64_t nmiss = ex.compact_indices(
      n, GG_LAMBDA(std::int64_t i) { return colour[pixel[i]] != std::int32_t(i); }, miss.data());
  const std::int64_t nsites = n - nmiss;
  // The digital Voronoi diagram: PBA's feature transform over the sites' packed positions
  // (ties: the site first in raster order, as ≺); then each pixel takes its site's point (a
  // site pixel's own colour is its point already, and only site pixels are read).
  const edt::Layout L = edt::make_layout({G.h, G.w}, false, edt::Packing::Bits);
  {
    auto feat = ex.template alloc<std::uint32_t>(std::size_t(np));
    std::uint32_t* F = feat.data();
    ex.fill(F, np, edt::kNone);
    ex.for_each_index(
        n, GG_LAMBDA(std::int64_t i) {
          const std::int64_t p = pixel[i];
          if (colour[p] == std::int32_t(i)) F[p] = L.pack(G.x(p), G.y(p), 0);
        });
    phase("grid");
    edt_impl::feature_transform_held(ex, L, edt::Metric{}, F, nsites);
    ex.for_each_index(
        np, GG_LAMBDA(std::int64_t p) {
          const std::int64_t site = L.voxel_of(F[p]);
          if (site != p) colour[p] = colour[site];
        });
    phase("pba");
  }
  // Debris needs a pixel with no neighbour of its colour nearer its site (a strictly smaller
  // (squared distance, raster index): every other pixel has a path of its colour down to the
  // site). None anywhere: no debris. Else Alg. 4.3 on the host over the whole colouring.
  {
    auto cnt = ex.template alloc<std::int64_t>(1);
    ex.transform_reduce_into(
        np,
        GG_LAMBDA(std::int64_t p)->std::int64_t {
          const std::int32_t c = colour[p];
          const std::int64_t site = pixel[c];
          if (site == p) return 0;
          const std::int64_t d = G.d2(p, site), px = G.x(p), py = G.y(p);
          for (std::int64_t dy = -1; dy <= 1; ++dy)
            for (std::int64_t dx = -1; dx <= 1; ++dx) {
              const std::int64_t qx = px + dx, qy = py + dy;
              if ((!dx && !dy) || qx < 0 || qy < 0 || qx >= G.w || qy >= G.h) continue;
              const std::int64_t q = qy * G.w + qx;
              if (colour[q] != c) continue;
              const std::int64_t e = G.d2(q, site);
              if (e < d || (e == d && q < p)) return 0;
            }
          return 1;
        },
        std::int64_t(0), thrust::plus<std::int64_t>(), cnt.data());
    std::int64_t roots = 0;
    ex.to_host(cnt.data(), 1, &roots);
    s.pixel.resize(std::size_t(n));
    ex.to_host(pixel, n, s.pixel.data());
    if (roots > 0 || keep_colour) {
      s.colour.resize(std::size_t(np));
      ex.to_host(colour, np, s.colour.data());
    }
    if (roots > 0) {
      s.debris = digital::recolour_debris(G.w, G.h, s.pixel, s.colour);
      ex.from_host(s.colour.data(), np, colour);
    }
    if (!keep_colour) s.colour = {};
    phase("debris");
  }
  s.missing.resize(std::size_t(nmiss));
  ex.to_host(miss.data(), nmiss, s.missing.data());
  s.site_of.resize(std::size_t(n));
  {
    std::int32_t* so = miss.data();  // (reused: n entries)
    ex.for_each_index(
        n, GG_LAMBDA(std::int64_t i) { so[i] = colour[pixel[i]]; });
    ex.to_host(so, n, s.site_of.data());
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
  auto tri = ex.template alloc<std::int32_t>(std::size_t(3 * nt));
  std::int32_t* T = tri.data();
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
  s.triangles.resize(std::size_t(3 * nt));
  ex.to_host(T, 3 * nt, s.triangles.data());
  phase("dual");
  // Adjacency: half-edge 3t + k runs from vertex k of triangle t to vertex k + 1; each is paired
  // with its reverse by sorting the undirected edges (twin -1: on the boundary). An edge in
  // three triangles or more would be no triangulation's: refused as an internal error.
  {
    const std::int64_t nh = 3 * nt;
    auto keys = ex.template alloc<std::uint64_t>(std::size_t(nh));
    auto ids = ex.template alloc<std::int32_t>(std::size_t(nh));
    auto tw = ex.template alloc<std::int32_t>(std::size_t(nh));
    std::uint64_t* K = keys.data();
    std::int32_t* I = ids.data();
    std::int32_t* W = tw.data();
    ex.for_each_index(
        nh, GG_LAMBDA(std::int64_t e) {
          const std::uint32_t a = std::uint32_t(T[e]),
                              b = std::uint32_t(T[e - e % 3 + (e % 3 + 1) % 3]);
          K[e] = a < b ? std::uint64_t(a) << 32 | b : std::uint64_t(b) << 32 | a;
          I[e] = std::int32_t(e);
          W[e] = -1;
        });
    ex.sort_by_key(K, I, nh);
    auto bad = ex.template alloc<std::int64_t>(1);
    ex.transform_reduce_into(
        nh,
        GG_LAMBDA(std::int64_t i)->std::int64_t {
          const bool starts = i == 0 || K[i - 1] != K[i];
          if (starts && i + 1 < nh && K[i + 1] == K[i]) {
            W[I[i]] = I[i + 1], W[I[i + 1]] = I[i];
            return i + 2 < nh && K[i + 2] == K[i];
          }
          return 0;
        },
        std::int64_t(0), thrust::plus<std::int64_t>(), bad.data());
    std::int64_t nbad = 0;
    ex.to_host(bad.data(), 1, &nbad);
    if (nbad)
      throw Error(ErrorCode::Internal,
                  "digital sketch: " + std::to_string(nbad) + " edge(s) in three triangles");
    s.twin.resize(std::size_t(nh));
    ex.to_host(W, nh, s.twin.data());
  }
  phase("adjacency");
}
