// Problem bodies, compiled once per executor (included inside bench::cpu_impl / cuda_impl).
// Every timed region ends with ex.sync(), so host clocks measure finished device work.
namespace {

double now_ms() {
  return std::chrono::duration<double, std::milli>(
             std::chrono::steady_clock::now().time_since_epoch())
      .count();
}

double median_ms(Exec& ex, int reps, const std::function<void()>& f) {
  f();  // warm-up: module load, allocator pools
  ex.sync();
  std::vector<double> t;
  for (int r = 0; r < reps; ++r) {
    const double t0 = now_ms();
    f();
    ex.sync();
    t.push_back(now_ms() - t0);
  }
  std::sort(t.begin(), t.end());
  return t[t.size() / 2];
}

spatial::Box box_of(const std::vector<double>& c, int dim) {
  spatial::Box b{};
  for (int d = 0; d < dim; ++d) {
    b.lo[d] = 1e300, b.hi[d] = -1e300;
    for (std::size_t i = d; i < c.size(); i += dim)
      b.lo[d] = std::min(b.lo[d], c[i]), b.hi[d] = std::max(b.hi[d], c[i]);
  }
  return b;
}

}  // namespace

Phases run(const ProblemInput& in) {
  Exec ex;
  Phases ph;
  const std::int64_t n = std::int64_t(in.coords.size() / in.dim);
  auto dp = ex.template alloc<double>(in.coords.size());
  ph["upload"] = median_ms(ex, in.reps, [&] {
    ex.from_host(in.coords.data(), std::int64_t(in.coords.size()), dp.data());
  });
  if (in.problem == "hilbert") {
    auto order = ex.template alloc<std::int32_t>(n);
    const spatial::Box box = box_of(in.coords, in.dim);
    ph["compute"] = median_ms(ex, in.reps, [&] {
      if (in.dim == 2)
        hilbert_sort<2>(ex, dp.data(), n, order.data(), box);
      else
        hilbert_sort<3>(ex, dp.data(), n, order.data(), box);
    });
    std::vector<std::int32_t> h(n);
    ph["download"] = median_ms(ex, in.reps, [&] { ex.to_host(order.data(), n, h.data()); });
    return ph;
  }
  // Predicate throughput: tuple i takes points i, i+1, ... (mod n), so tuples are local when
  // the input is Hilbert-sorted and near-degenerate when the distribution is. "insphere" and
  // "orient3d" run the three-tier pass (filter; integer and translated stages with SoS on many
  // small slots; the full expansion on what remains); the "-full" variants the two-tier one
  // (filter; full expansion and SoS on large slots), as the library did before the middle tier.
  const bool full = in.problem.size() > 5 && in.problem.substr(in.problem.size() - 5) == "-full";
  const std::string base = full ? in.problem.substr(0, in.problem.size() - 5) : in.problem;
  const bool sphere = base == "insphere";
  if (!sphere && base != "orient3d")
    throw Error(ErrorCode::InvalidArgument, "unknown problem " + in.problem);
  if (in.dim != 3) throw Error(ErrorCode::InvalidArgument, in.problem + " needs 3D points");
  auto out = ex.template alloc<std::int8_t>(n);
  const double* p = dp.data();
  auto P = [=] GG_HD(std::int64_t i, int j) { return p + ((i + j * 7) % n) * 3; };
  auto I = [=] GG_HD(std::int64_t i, int j) { return int((i + j * 7) % n); };
  auto fast = GG_LAMBDA(std::int64_t i)->int {
    if (sphere) return pred::insphere_fast(P(i, 0), P(i, 1), P(i, 2), P(i, 3), P(i, 4));
    return pred::orient3d_fast(P(i, 0), P(i, 1), P(i, 2), P(i, 3));
  };
  auto mid = GG_LAMBDA(std::int64_t i, double* s)->int {
    if (sphere)
      return pred::insphere_sos_mid(P(i, 0), I(i, 0), P(i, 1), I(i, 1), P(i, 2), I(i, 2), P(i, 3),
                                    I(i, 3), P(i, 4), I(i, 4), s);
    return pred::orient3d_sos_mid(P(i, 0), I(i, 0), P(i, 1), I(i, 1), P(i, 2), I(i, 2), P(i, 3),
                                  I(i, 3), s);
  };
  auto last = GG_LAMBDA(std::int64_t i, double* s)->int {
    if (sphere)
      return pred::insphere_sos_last(P(i, 0), I(i, 0), P(i, 1), I(i, 1), P(i, 2), I(i, 2), P(i, 3),
                                     I(i, 3), P(i, 4), I(i, 4), s);
    return pred::orient3d_sos_last(P(i, 0), I(i, 0), P(i, 1), I(i, 1), P(i, 2), I(i, 2), P(i, 3),
                                   I(i, 3), s);
  };
  const int mid_doubles = sphere ? pred::kInsphereSosMidScratch : pred::kOrient3dSosMidScratch;
  const int last_doubles = sphere ? pred::kInsphereScratch : pred::kOrient3dScratch;
  SplitPassResult res;
  ph["compute"] = median_ms(ex, in.reps, [&] {
    res = full ? split_pass(ex, n, out.data(), fast, last, last_doubles)
               : split_pass(ex, n, out.data(), fast, mid, mid_doubles, last, last_doubles);
  });
  ph["exact_fraction"] = double(res.exact_items) / double(n);
  ph["last_fraction"] = double(full ? res.exact_items : res.last_items) / double(n);
  std::vector<std::int8_t> h(n);
  ph["download"] = median_ms(ex, in.reps, [&] { ex.to_host(out.data(), n, h.data()); });
  return ph;
}
