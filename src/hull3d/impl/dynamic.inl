// A 3D convex hull kept on the executor between calls (DynamicHull3d, issue 47). Included inside
// gpugeom::hull3d::{cpu,cuda}_impl after hull.inl.
//
// Kept: the points in input order, the removal flags, and the hull's arrays (facets, neighbours,
// extreme points, planes) in input indices.
//
// Why a hull of few points is the hull of all: the output is the hull of the extreme points E
// alone (hull.inl's second pass makes it so where the first pass kept a point that is not
// extreme), and the perturbation depends on the points alone (predicates/sos.hpp), so the output
// is a function of E (each point of E named by its first copy's index). A point that is not
// extreme in a set is not extreme in any larger set, so
// - insert: the extreme points of the old and new points together are among E and the new
//   points, and of those only the ones not strictly inside the old hull: the hull of those
//   candidates is the hull of all (a few thousand points for 10^6 in a ball, whatever n is),
//   and where every new point is strictly inside, the old hull is the new one;
// - remove: where no removed point is a vertex, E is unchanged and so is the hull; otherwise
//   points inside may become extreme, and the hull is made from all points left;
// - move: any point may become extreme; the hull is made from all the moved points.
// The candidates keep increasing input order, so of several copies the first stays the vertex,
// as in a fresh call. The facets' order in the arrays may differ from a fresh call's.

struct KeptHull {
  typename Exec::template Buffer<double> xyz;        // 3 n, input order
  typename Exec::template Buffer<std::int8_t> gone;  // n (1: removed), when nremoved > 0
  std::int64_t n = 0, nremoved = 0;
  Facets facets;                                          // input indices
  typename Exec::template Buffer<std::int32_t> vertices;  // increasing input indices
  typename Exec::template Buffer<double> eq;              // 4 per facet
  std::int64_t nv = 0;
  const std::int8_t* gone_map() const { return nremoved ? gone.data() : nullptr; }
};

// The hull of `count` candidate points (coordinates p; input indices ids, increasing, or null
// where they are all of K's points in order) into K, whose points are already the new ones.
inline void hull_of(Exec& ex, KeptHull& K, const double* p, const std::int32_t* ids,
                    std::int64_t count, const Hull3dOptions& opt, Hull3dStats& st) {
  if (count < 4)
    throw Error(ErrorCode::DegenerateInput,
                "fewer than 4 points (" + std::to_string(count) +
                    ") would be left: a convex hull in 3D needs 4 points not on one plane");
  Result R = hull_core(ex, p, count, opt, st);
  const auto t0 = Clock::now();
  std::int32_t* t = R.facets.simplices.data();
  std::int32_t* v = R.vertices.data();
  if (ids) {
    ex.for_each_index(
        3 * R.facets.count, GG_LAMBDA(std::int64_t i) { t[i] = ids[t[i]]; });
    ex.for_each_index(
        R.num_vertices, GG_LAMBDA(std::int64_t j) { v[j] = ids[v[j]]; });  // (stays increasing)
  }
  K.eq = ex.template alloc<double>(std::size_t(4 * R.facets.count));
  planes(ex, K.xyz.data(), K.n, t, R.facets.count, K.eq.data());
  K.facets = std::move(R.facets);
  K.vertices = std::move(R.vertices);
  K.nv = R.num_vertices;
  st.hull_candidates = count;
  st.phase_ms.emplace_back("kept_indices", ms_since(t0));
}

// The hull of every point of K not removed (gathered only where some are).
inline void hull_of_live(Exec& ex, KeptHull& K, const Hull3dOptions& opt, Hull3dStats& st) {
  if (!K.gone_map()) return hull_of(ex, K, K.xyz.data(), nullptr, K.n, opt, st);
  const auto L = mesh::gather_live<3>(ex, K.xyz.data(), K.n, K.gone_map());
  hull_of(ex, K, L.p.data(), L.ids.data(), L.count, opt, st);
}

// Which of the points K appended to old's may lie outside old's hull or on it (input indices,
// increasing): those that the floating-point orientation against some facet does not place
// strictly inside (an undecided test counts as outside: a candidate too many is harmless, the
// hull drops it), or all of them where testing each against every facet is more work than
// kFilterWork (a hull of them costs less then). The points are validated first. [synchronises]
constexpr std::int64_t kFilterWork =
    Exec::backend == Backend::Cuda ? std::int64_t(1) << 28 : std::int64_t(1) << 22;
inline typename Exec::template Buffer<std::int32_t> maybe_outside(Exec& ex, const KeptHull& old,
                                                                  const KeptHull& K,
                                                                  std::int64_t& count) {
  const std::int64_t add = K.n - old.n, n_old = old.n, nf = old.facets.count;
  const double* p = K.xyz.data();
  const mesh::Bounds<3> box = mesh::bounds<3>(ex, p + 3 * n_old, add);
  if (box.bad) throw_bad(box.bad);
  auto ids = ex.template alloc<std::int32_t>(std::size_t(add));
  if (add * nf > kFilterWork) {
    std::int32_t* o = ids.data();
    ex.for_each_index(
        add, GG_LAMBDA(std::int64_t i) { o[i] = std::int32_t(n_old + i); });
    count = add;
    return ids;
  }
  // one thread per (point, facet): a point per thread would run 10^4 facets in a row on a
  // thousand GPU threads (50 ms for 10^3 points into a ball of 10^6 on the H200)
  const std::int32_t* t = old.facets.simplices.data();
  auto d_out = ex.template alloc<std::int32_t>(std::size_t(add));
  std::int32_t* outside = d_out.data();
  ex.fill(outside, add, std::int32_t(0));
  ex.for_each_index(
      add * nf, GG_LAMBDA(std::int64_t e) {
        const std::int64_t i = e / nf, f = e % nf;  // facets counter-clockwise seen from outside
        if (pred::orient3d_fast(p + 3 * std::int64_t(t[3 * f]), p + 3 * std::int64_t(t[3 * f + 1]),
                                p + 3 * std::int64_t(t[3 * f + 2]), p + 3 * (n_old + i)) >= 0)
          atomic_exchange(&outside[i], std::int32_t(1));
      });
  count = ex.compact_indices(
      add, GG_LAMBDA(std::int64_t i) { return outside[i] != 0; }, ids.data());
  const std::int32_t base = std::int32_t(n_old);
  std::int32_t* o = ids.data();
  ex.for_each_index(
      count, GG_LAMBDA(std::int64_t j) { o[j] += base; });
  return ids;
}

// The old hull's vertices and the `count` points `ids` (input indices above them), as
// candidates.
inline mesh::LivePoints<Exec> vertices_and(Exec& ex, const KeptHull& old, const KeptHull& K,
                                           const std::int32_t* more, std::int64_t count) {
  mesh::LivePoints<Exec> C;
  C.count = old.nv + count;
  C.ids = ex.template alloc<std::int32_t>(std::size_t(C.count));
  std::int32_t* ids = C.ids.data();
  ex.copy(old.vertices.data(), old.nv, ids);
  ex.copy(more, count, ids + old.nv);
  mesh::gather<3>(ex, K.xyz.data(), C);
  return C;
}

// A copy of K's hull arrays (a removal that leaves the hull as it was, while the arrays before
// it are kept for changes()).
inline void copy_hull(Exec& ex, const KeptHull& from, KeptHull& to) {
  const std::int64_t nf = from.facets.count;
  to.facets.count = nf;
  to.facets.simplices = ex.template alloc<std::int32_t>(std::size_t(3 * nf));
  to.facets.neighbors = ex.template alloc<std::int32_t>(std::size_t(3 * nf));
  to.vertices = ex.template alloc<std::int32_t>(std::size_t(from.nv));
  to.eq = ex.template alloc<double>(std::size_t(4 * nf));
  ex.copy(from.facets.simplices.data(), 3 * nf, to.facets.simplices.data());
  ex.copy(from.facets.neighbors.data(), 3 * nf, to.facets.neighbors.data());
  ex.copy(from.vertices.data(), from.nv, to.vertices.data());
  ex.copy(from.eq.data(), 4 * nf, to.eq.data());
  to.nv = from.nv;
}

// How many of the `count` indices idx name a vertex of K. [synchronises]
inline std::int64_t removed_vertices(Exec& ex, const KeptHull& K, const std::int32_t* idx,
                                     std::int64_t count) {
  auto d_is = ex.template alloc<std::int8_t>(std::size_t(K.n));
  std::int8_t* is = d_is.data();
  const std::int32_t* v = K.vertices.data();
  ex.fill(is, K.n, std::int8_t(0));
  ex.for_each_index(
      K.nv, GG_LAMBDA(std::int64_t j) { is[v[j]] = 1; });
  auto d_hit = ex.template alloc<std::int8_t>(std::size_t(count));
  std::int8_t* hit = d_hit.data();
  ex.for_each_index(
      count, GG_LAMBDA(std::int64_t j) { hit[j] = is[idx[j]]; });
  return mesh::count_flags(ex, hit, count);
}

class KeptHullOn final : public Kept {
 public:
  explicit KeptHullOn(const Hull3dOptions& opt) : opt_(opt) { opt_.into = Hull3dBuffers(); }
  void insert(const double* xyz, std::int64_t n, bool on_device, Hull3dStats& st) override {
    if (n == 0 && K_.n) return;
    Exec ex(opt_);
    const ::gpugeom::detail::DevicePeak<Exec> peak(ex, st);
    ::gpugeom::detail::require_device_memory(ex, K_.nv + n, kLeastBytesPerPoint, "a convex hull",
                                             "points");
    KeptHull R = with_points(ex, xyz, n, on_device, false, st);
    if (!K_.n) {
      hull_of_live(ex, R, opt_, st);
    } else {
      // Only the old vertices and the new points not strictly inside can be extreme now.
      const auto t0 = Clock::now();
      std::int64_t out = 0;
      auto more = maybe_outside(ex, K_, R, out);
      st.outside_points = out;
      st.phase_ms.emplace_back("inside_test", ms_since(t0));
      if (out) {
        const auto C = vertices_and(ex, K_, R, more.data(), out);
        hull_of(ex, R, C.p.data(), C.ids.data(), C.count, opt_, st);
      } else {
        copy_hull(ex, K_, R);  // (every new point strictly inside: the same hull)
      }
    }
    commit(ex, std::move(R));
  }
  void move(const double* xyz, bool on_device, Hull3dStats& st) override {
    Exec ex(opt_);
    const ::gpugeom::detail::DevicePeak<Exec> peak(ex, st);
    ::gpugeom::detail::require_device_memory(ex, K_.n, kLeastBytesPerPoint, "a convex hull",
                                             "points");
    KeptHull R = with_points(ex, xyz, K_.n, on_device, true, st);
    hull_of_live(ex, R, opt_, st);
    commit(ex, std::move(R));
  }
  void remove(const std::int32_t* idx, std::int64_t count, bool on_device,
              Hull3dStats& st) override {
    if (count == 0) return;
    Exec ex(opt_);
    const ::gpugeom::detail::DevicePeak<Exec> peak(ex, st);
    typename Exec::template Buffer<std::int32_t> up;
    if (!on_device) {
      up = ex.template alloc<std::int32_t>(std::size_t(count));
      ex.from_host(idx, count, up.data());
      idx = up.data();
    }
    auto gone = mesh::removal_flags(ex, K_.gone_map(), K_.n, idx, count);
    KeptHull R = with_points(ex, nullptr, 0, false, false, st);
    R.gone = std::move(gone);
    R.nremoved = K_.nremoved + count;
    const std::int64_t hit = removed_vertices(ex, K_, idx, count);
    st.removed_vertices = hit;
    if (hit)
      hull_of_live(ex, R, opt_, st);
    else
      copy_hull(ex, K_, R);  // (no extreme point went: the same hull)
    commit(ex, std::move(R));
  }
  std::int64_t points() const override { return K_.n; }
  std::int64_t removed() const override { return K_.nremoved; }
  std::int64_t simplices() const override { return K_.facets.count; }
  std::int64_t vertices() const override { return K_.nv; }
  void track_changes(bool on) override { before_.set(on); }
  bool has_changes() const override { return before_.held; }
  void host_changes(SimplexChanges& out) const override {
    Exec ex(opt_);
    const KeptHull& B = before_.arrays;
    mesh::host_changes<3>(ex, B.facets.simplices.data(), B.facets.count, K_.facets.simplices.data(),
                          K_.facets.count, out);
  }
  void device_changes(DeviceSimplexChanges& out) const override {
    Exec ex(opt_);
    const KeptHull& B = before_.arrays;
    mesh::device_changes<3>(ex, B.facets.simplices.data(), B.facets.count,
                            K_.facets.simplices.data(), K_.facets.count, out);
  }
  void host_copy(Output& out) const override {
    Exec ex(opt_);
    const std::int64_t nf = K_.facets.count;
    out.num_facets = nf;
    out.num_vertices = K_.nv;
    out.triangles.resize(std::size_t(3 * nf));
    out.neighbors.resize(std::size_t(3 * nf));
    out.vertices.resize(std::size_t(K_.nv));
    out.equations.resize(std::size_t(4 * nf));
    ex.to_host(K_.facets.simplices.data(), 3 * nf, out.triangles.data());
    ex.to_host(K_.facets.neighbors.data(), 3 * nf, out.neighbors.data());
    ex.to_host(K_.vertices.data(), K_.nv, out.vertices.data());
    ex.to_host(K_.eq.data(), 4 * nf, out.equations.data());
  }
  void device_copy(DeviceOutput& out) const override {
    Exec ex(opt_);
    KeptHull C;
    copy_hull(ex, K_, C);
    ex.sync();  // (the caller may read them, and free them on any stream)
    out.num_facets = C.facets.count;
    out.num_vertices = C.nv;
    out.triangles = C.facets.simplices.hand_over();
    out.neighbors = C.facets.neighbors.hand_over();
    out.vertices = C.vertices.hand_over();
    out.equations = C.eq.hand_over();
  }

 private:
  // The kept points with `add` more appended (host memory, or executor memory when on_device),
  // or all n replaced (move); the hull arrays still empty.
  KeptHull with_points(Exec& ex, const double* xyz, std::int64_t add, bool on_device, bool replace,
                       Hull3dStats& st) const {
    const auto t0 = Clock::now();
    const std::int64_t keep = replace ? 0 : K_.n, n = keep + add;
    KeptHull R;
    R.n = n;
    R.xyz = ex.template alloc<double>(std::size_t(3 * n));
    if (keep) ex.copy(K_.xyz.data(), 3 * keep, R.xyz.data());
    if (add && on_device)
      ex.copy(xyz, 3 * add, R.xyz.data() + 3 * keep);
    else if (add)
      ex.from_host(xyz, 3 * add, R.xyz.data() + 3 * keep);
    R.gone = mesh::extend_flags(ex, K_.gone_map(), K_.n, n);
    R.nremoved = K_.nremoved;
    st.phase_ms.emplace_back("append", ms_since(t0));
    return R;
  }
  void commit(Exec& ex, KeptHull&& next) {
    ex.sync();  // (everything that could throw has run)
    before_.commit(K_, std::move(next));
  }

  Hull3dOptions opt_;
  KeptHull K_;
  ::gpugeom::detail::Before<KeptHull> before_;
};
