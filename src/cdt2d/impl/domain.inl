// Holes, the outside and regions of a constrained triangulation on the executor, one algorithm
// for both; included inside gpugeom::cdt::{cpu,cuda}_impl after recover.inl.
//
// Triangle's semantics for .poly files: a hole removes the triangles reachable from the triangle
// holding its point without crossing a segment, Domain::Enclosed also those reachable from the
// hull edges on no segment, and a region gives its attribute to the kept triangles it reaches
// (the first region given, where several reach one). "Reachable without crossing a segment" is
// one relation, so each is a property of a connected component of the triangles joined across
// edges on no segment: the components come from a lock-free union-find (mesh/union_find.hpp), the
// seeds mark their components' roots, and the kept triangles are compacted (neighbours across a
// removed triangle become -1). The points are located by visibility walks (locate/walk.hpp).

struct DomainResult {
  typename Exec::template Buffer<std::int32_t> tri, nbr, seg;
  typename Exec::template Buffer<double> attribute;  // (empty without regions)
  std::int64_t kept = 0;
};

inline DomainResult apply_domain(Exec& ex, const MeshView& m, std::int64_t nt,
                                 const Cdt2dOptions& opt) {
  DomainResult out;
  // The hole points, then the region points, located.
  std::vector<double> q;
  for (const auto& h : opt.holes) q.insert(q.end(), {h.x, h.y});
  for (const auto& g : opt.regions) q.insert(q.end(), {g.x, g.y});
  const std::int64_t nh = std::int64_t(opt.holes.size()), nq = std::int64_t(q.size() / 2);
  auto dq = ex.template alloc<double>(std::max<std::size_t>(q.size(), 1));
  ex.from_host(q.data(), std::int64_t(q.size()), dq.data());
  auto loc = ex.template alloc<std::int32_t>(std::size_t(std::max<std::int64_t>(nq, 1)));
  std::vector<double> attrs;
  for (const auto& g : opt.regions) attrs.push_back(g.attribute);
  auto dattr = ex.template alloc<double>(std::max<std::size_t>(attrs.size(), 1));
  ex.from_host(attrs.data(), std::int64_t(attrs.size()), dattr.data());
  {
    const locate_detail::Mesh<2> wm{m.xy, 0, m.tri, m.nbr, nt};
    const double* Q = dq.data();
    std::int32_t* L = loc.data();
    ex.for_each_index(
        nq, GG_LAMBDA(std::int64_t i) {
          double s[pred::kOrient2dScratch];
          L[i] = locate_detail::walk(wm, 0, Q + 2 * i, s);
        });
  }
  // Components across edges on no segment; each triangle then points at its component's root.
  auto parent = ex.template alloc<std::int32_t>(std::size_t(nt));
  std::int32_t* P = parent.data();
  ex.for_each_index(
      nt, GG_LAMBDA(std::int64_t t) { P[t] = std::int32_t(t); });
  ex.for_each_index(
      nt, GG_LAMBDA(std::int64_t t) {
        for (int k = 0; k < 3; ++k) {
          const std::int32_t o = m.nbr[3 * t + k];
          if (o > t && m.seg[3 * t + k] < 0) mesh::uf_unite(P, std::int32_t(t), o);
        }
      });
  ex.for_each_index(
      nt, GG_LAMBDA(std::int64_t t) { P[t] = mesh::uf_find(P, std::int32_t(t)); });
  // Seeds mark their roots: removed, or the first region reaching it.
  auto removed = ex.template alloc<std::int8_t>(std::size_t(nt));
  auto region = ex.template alloc<std::int32_t>(std::size_t(nt));
  std::int8_t* R = removed.data();
  std::int32_t* G = region.data();
  ex.fill(R, nt, std::int8_t(0));
  ex.fill(G, nt, std::int32_t(INT32_MAX));
  if (opt.domain == Cdt2dOptions::Domain::Enclosed)
    ex.for_each_index(
        nt, GG_LAMBDA(std::int64_t t) {
          for (int k = 0; k < 3; ++k)
            if (m.nbr[3 * t + k] < 0 && m.seg[3 * t + k] < 0) R[P[t]] = 1;
        });
  {
    const std::int32_t* L = loc.data();
    ex.for_each_index(
        nq, GG_LAMBDA(std::int64_t i) {
          const std::int32_t t = L[i];
          if (t < 0) return;  // outside the hull: nothing
          if (i < nh)
            R[P[t]] = 1;
          else
            atomic_min(G + P[t], std::int32_t(i - nh));
        });
  }
  // Compaction: the kept triangles in order.
  auto index = ex.template alloc<std::int32_t>(std::size_t(nt) + 1);
  std::int32_t* I = index.data();
  ex.exclusive_scan_of(
      nt + 1, GG_LAMBDA(std::int64_t t)->std::int32_t { return t < nt && !R[P[t]] ? 1 : 0; }, I);
  std::int32_t kept = 0;
  ex.to_host(I + nt, 1, &kept);
  out.kept = kept;
  const std::size_t K3 = 3 * std::size_t(std::max<std::int32_t>(kept, 1));
  out.tri = ex.template alloc<std::int32_t>(K3);
  out.nbr = ex.template alloc<std::int32_t>(K3);
  out.seg = ex.template alloc<std::int32_t>(K3);
  const bool regions = !opt.regions.empty();
  if (regions)
    out.attribute = ex.template alloc<double>(std::size_t(std::max<std::int32_t>(kept, 1)));
  std::int32_t *T = out.tri.data(), *N = out.nbr.data(), *S = out.seg.data();
  double* A = regions ? out.attribute.data() : nullptr;
  const double* AT = dattr.data();
  ex.for_each_index(
      nt, GG_LAMBDA(std::int64_t t) {
        if (R[P[t]]) return;
        const std::int64_t i = I[t];
        for (int k = 0; k < 3; ++k) {
          const std::int32_t o = m.nbr[3 * t + k];
          T[3 * i + k] = m.tri[3 * t + k];
          N[3 * i + k] = o < 0 || R[P[o]] ? -1 : I[o];
          S[3 * i + k] = m.seg[3 * t + k];
        }
        if (A) A[i] = G[P[t]] == INT32_MAX ? 0.0 : AT[G[P[t]]];
      });
  return out;
}
