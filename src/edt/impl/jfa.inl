// Jump flooding (thesis 3.1.3): approximate, kept only as a measured baseline. Each round every
// voxel looks at the 3^d voxels at distance `step` and keeps the best site it sees.
inline void jump_flood(Exec& ex, const Layout& L, const Metric& M, std::uint32_t* feat) {
  auto other = ex.template alloc<std::uint32_t>(std::size_t(L.count()));
  std::uint32_t* src = feat;
  std::uint32_t* dst = other.data();
  std::int64_t step = 1;
  while (step * 2 < (L.n[0] > L.n[1] ? (L.n[0] > L.n[2] ? L.n[0] : L.n[2])
                                     : (L.n[1] > L.n[2] ? L.n[1] : L.n[2])))
    step *= 2;
  const Layout Ly = L;
  const Metric Mt = M;
  for (; step >= 1; step /= 2) {
    const std::int64_t st = step;
    const std::uint32_t* in = src;
    std::uint32_t* o = dst;
    ex.for_each_index(
        L.count(), GG_LAMBDA(std::int64_t i) {
          std::int64_t v[3] = {i % Ly.n[0], (i / Ly.n[0]) % Ly.n[1], i / (Ly.n[0] * Ly.n[1])};
          std::uint32_t best = in[i];
          const int dz = Ly.nd == 3 ? 1 : 0;
          for (int oz = -dz; oz <= dz; ++oz)
            for (int oy = -1; oy <= 1; ++oy)
              for (int ox = -1; ox <= 1; ++ox) {
                const std::int64_t x = v[0] + ox * st, y = v[1] + oy * st, z = v[2] + oz * st;
                if (x < 0 || y < 0 || z < 0 || x >= Ly.n[0] || y >= Ly.n[1] || z >= Ly.n[2])
                  continue;
                const std::uint32_t c = in[x + Ly.n[0] * (y + Ly.n[1] * z)];
                if (c != kNone && (best == kNone || beats<Num>(Ly, Mt, c, best, v))) best = c;
              }
          o[i] = best;
        });
    std::uint32_t* t = src;
    src = dst;
    dst = t;
  }
  if (src != feat) ex.copy(src, L.count(), feat);
}
