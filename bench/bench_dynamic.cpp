// gpugeom_bench_dynamic: triangulations that follow their points (issue 47). For each
// dist:n:k (2D; after --3d, 3D), k of n points inserted into the triangulation of the other
// n - k, timed beside a fresh triangulation of all n in the same run:
//   fresh e2e   delaunay2d on the n host points, host arrays out
//   fresh dev   delaunay2d_device on the n points already on the device
//   insert      DynamicDelaunay2d::insert of the k host points (the state brought up to date on
//               the executor; the object built beforehand, untimed)
//   insert e2e  the same plus triangulation() (the caller's host arrays out)
//   insert dev  insert_device of the k points already on the device (from_device beforehand)
// With --move f, every point of dist:n is moved by a normal step of f times the mean
// spacing instead: move / move e2e / move dev, beside a fresh triangulation of the moved points.
// With --remove (for the rows after it), k of the n points are removed instead (a fixed random
// choice): remove / remove e2e (plus the results), beside a fresh triangulation of the n - k
// points left (fresh e2e, and fresh dev from device points).
// With --hull (for the rows after it), the same for DynamicHull3d beside convex_hull3d (3D
// points: ball, sphere, uniform, ...).
// Medians of --reps runs; the last insert's phases are printed, and the result is checked
// against the fresh one (the same triangles).
#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <random>
#include <string>
#include <type_traits>
#include <vector>

#include "bench_csv.hpp"
#include "displace.hpp"
#include "gpugeom/delaunay2d.hpp"
#include "gpugeom/delaunay3d.hpp"
#include "gpugeom/generate.hpp"
#include "gpugeom/hull3d.hpp"
#include "verify.hpp"
#include <memory>

#ifdef GPUGEOM_HAVE_CUDA
#include <cuda_runtime.h>
#endif

using namespace gpugeom;

namespace {
using clk = std::chrono::steady_clock;

// Median of reps timings of run(); prepare() runs untimed before each.
double median_ms(int reps, const std::function<void()>& prepare, const std::function<void()>& run) {
  std::vector<double> t;
  for (int r = 0; r < reps; ++r) {
    prepare();
    const auto t0 = clk::now();
    run();
    t.push_back(bench::ms_since(t0));
  }
  std::sort(t.begin(), t.end());
  return t[t.size() / 2];
}

void print_phases(const RunStats& s) {
  const auto counters = s.counter_map();
  std::printf("    insert phases:");
  for (const auto& [name, ms] : s.phase_ms) std::printf(" %s %.2f", name.c_str(), ms);
  for (const char* c : {"inserted_points", "batches", "flips", "flip_rounds", "start_walk_steps",
                        "move_rounds", "move_taken_out", "move_grown", "hole_vertices",
                        "splayed_vertices", "hull_candidates", "removed_vertices"}) {
    const auto it = counters.find(c);
    if (it != counters.end()) std::printf(" | %s %lld", c, (long long)it->second);
  }
  std::printf("\n");
}

struct Row {
  std::string dist;
  std::int64_t n = 0, k = 0;
  int dim = 2;
  double move = 0;  // > 0: every point moved by this many mean spacings
  bool remove = false, hull = false;
};

Row parse(const std::string& s) {
  Row r;
  const auto a = s.find(':'), b = s.rfind(':');
  if (a == std::string::npos || a == b) {
    std::fprintf(stderr, "expected dist:n:k, got %s\n", s.c_str());
    std::exit(2);
  }
  r.dist = s.substr(0, a);
  r.n = std::int64_t(std::stod(s.substr(a + 1, b - a - 1)));
  r.k = std::int64_t(std::stod(s.substr(b + 1)));
  return r;
}

// What differs between 2D and 3D.
struct Two {
  using Point = Point2;
  using Options = Delaunay2dOptions;
  using Dynamic = DynamicDelaunay2d;
  static std::vector<Point2> points(const std::string& d, std::int64_t n) {
    return generate2d(d, n, 7);
  }
  static auto fresh(const std::vector<Point2>& p, const Options& o) { return delaunay2d(p, o); }
  static auto fresh_device(const double* d, std::int64_t n, const Options& o) {
    return delaunay2d_device(d, n, o);
  }
  static auto result(const Dynamic& d) { return d.triangulation(); }
  // Flat vertex lists of 3 put back in canonical form (each rotated to its least, rows sorted).
  static std::vector<std::int32_t> canonical(const std::vector<std::int32_t>& v) {
    auto c = verify::canonical_triangles(v.data(), std::int64_t(v.size() / 3));
    return std::vector<std::int32_t>(&c.data()->front(), &c.data()->front() + 3 * c.size());
  }
  static auto simplices(const Triangulation2d& t) {
    auto c = verify::canonical_triangles(t.triangles.data(), t.num_triangles);
    return std::vector<std::int32_t>(&c.data()->front(), &c.data()->front() + 3 * c.size());
  }
  // Which path a move or a removal took (the triangulations' stats counters).
  template <class Stats>  // (Delaunay2dStats, Delaunay3dStats)
  static const char* moved(const Stats& s) {
    return s.move_rebuilt ? "rebuilt" : "repaired";
  }
  template <class Stats>
  static const char* removed(const Stats& s) {
    return s.remove_rebuilt ? "rebuilt" : "holes filled";
  }
};
struct Three {
  using Point = Point3;
  using Options = Delaunay3dOptions;
  using Dynamic = DynamicDelaunay3d;
  static std::vector<Point3> points(const std::string& d, std::int64_t n) {
    return generate3d(d, n, 7);
  }
  static auto fresh(const std::vector<Point3>& p, const Options& o) { return delaunay3d(p, o); }
  static auto fresh_device(const double* d, std::int64_t n, const Options& o) {
    return delaunay3d_device(d, n, o);
  }
  static auto result(const Dynamic& d) { return d.tetrahedralisation(); }
  // Flat vertex lists of 4 put back in canonical form (each sorted, rows sorted).
  static std::vector<std::int32_t> canonical(const std::vector<std::int32_t>& v) {
    std::vector<std::array<std::int32_t, 4>> c(v.size() / 4);
    for (std::size_t i = 0; i < c.size(); ++i) {
      for (int k = 0; k < 4; ++k) c[i][std::size_t(k)] = v[4 * i + std::size_t(k)];
      std::sort(c[i].begin(), c[i].end());
    }
    std::sort(c.begin(), c.end());
    std::vector<std::int32_t> out;
    for (const auto& a : c) out.insert(out.end(), a.begin(), a.end());
    return out;
  }
  static auto simplices(const Triangulation3d& t) {
    std::vector<std::array<std::int32_t, 4>> c(t.num_tetrahedra);
    for (std::size_t i = 0; i < c.size(); ++i) {
      for (int k = 0; k < 4; ++k) c[i][std::size_t(k)] = t.tetrahedra[4 * i + std::size_t(k)];
      std::sort(c[i].begin(), c[i].end());
    }
    std::sort(c.begin(), c.end());
    std::vector<std::int32_t> v;
    for (const auto& a : c) v.insert(v.end(), a.begin(), a.end());
    return v;
  }
  static const char* moved(const Delaunay3dStats& s) { return Two::moved(s); }
  static const char* removed(const Delaunay3dStats& s) { return Two::removed(s); }
};
struct Hull {
  using Point = Point3;
  using Options = Hull3dOptions;
  using Dynamic = DynamicHull3d;
  static std::vector<Point3> points(const std::string& d, std::int64_t n) {
    return generate3d(d, n, 7);
  }
  static auto fresh(const std::vector<Point3>& p, const Options& o) { return convex_hull3d(p, o); }
  static auto fresh_device(const double* d, std::int64_t n, const Options& o) {
    return convex_hull3d_device(d, n, o);
  }
  static auto result(const Dynamic& d) { return d.hull(); }
  static std::vector<std::int32_t> canonical(const std::vector<std::int32_t>& v) {
    return Two::canonical(v);
  }
  static auto simplices(const ConvexHull3d& h) {
    return Two::canonical(std::vector<std::int32_t>(h.triangles.begin(), h.triangles.end()));
  }
  static const char* moved(const Hull3dStats&) { return "hull of all"; }
  static const char* removed(const Hull3dStats& s) {
    return s.removed_vertices ? "hull of all left" : "no vertex: kept";
  }
};

template <class D>
const char* label() {
  return std::is_same<D, Hull>::value ? "hull" : std::is_same<D, Two>::value ? "2D" : "3D";
}

template <class D>
void run_row(const Row& row, Backend b, int reps) {
  constexpr int dim = sizeof(typename D::Point) / sizeof(double);
  const auto p = D::points(row.dist, row.n);
  const std::int64_t n = std::int64_t(p.size()), k = std::min(row.k, n - 4), base = n - k;
  typename D::Options o;
  o.backend = b;
  decltype(D::fresh(p, o)) fresh;
  const double fresh_e2e = median_ms(
      reps, [] {}, [&] { fresh = D::fresh(p, o); });
  std::unique_ptr<typename D::Dynamic> d;
  const double ins = median_ms(
      reps, [&] { d = std::make_unique<typename D::Dynamic>(&p.data()->x, base, o); },
      [&] { d->insert(&p[std::size_t(base)].x, k); });
  print_phases(d->stats());
  decltype(fresh) got;
  const double ins_e2e = median_ms(
      reps, [&] { d = std::make_unique<typename D::Dynamic>(&p.data()->x, base, o); },
      [&] {
        d->insert(&p[std::size_t(base)].x, k);
        got = D::result(*d);
      });
  const bool same = D::simplices(got) == D::simplices(fresh);
  double fresh_dev = -1, ins_dev = -1;
#ifdef GPUGEOM_HAVE_CUDA
  if (b == Backend::Cuda) {
    double* dp = nullptr;
    const std::size_t bytes = p.size() * sizeof(typename D::Point);
    if (cudaMalloc(&dp, bytes) == cudaSuccess &&
        cudaMemcpy(dp, p.data(), bytes, cudaMemcpyHostToDevice) == cudaSuccess) {
      fresh_dev = median_ms(
          reps, [] {}, [&] { D::fresh_device(dp, n, o); });
      ins_dev = median_ms(
          reps,
          [&] { d = std::make_unique<typename D::Dynamic>(D::Dynamic::from_device(dp, base, o)); },
          [&] { d->insert_device(dp + dim * base, k); });
    }
    cudaFree(dp);
  }
#endif
  std::printf(
      "%s %-10s %-5s n=%-10lld k=%-9lld fresh e2e %9.2f  fresh dev %9.2f  insert %9.2f  "
      "insert e2e %9.2f  insert dev %9.2f  (dev ratio %.3f)  %s\n",
      label<D>(), row.dist.c_str(), b == Backend::Cuda ? "cuda" : "cpu", (long long)n, (long long)k,
      fresh_e2e, fresh_dev, ins, ins_e2e, ins_dev,
      fresh_dev > 0 ? ins_dev / fresh_dev : ins / fresh_e2e,
      same ? "same simplices" : "DIFFERENT SIMPLICES");
  std::fflush(stdout);
}
// k of n points removed from the triangulation of all n, beside a fresh one of those left.
template <class D>
void run_remove(const Row& row, Backend b, int reps) {
  constexpr int dim = sizeof(typename D::Point) / sizeof(double);
  const auto p = D::points(row.dist, row.n);
  const std::int64_t n = std::int64_t(p.size()), k = std::min(row.k, n - 4);
  const std::vector<std::int32_t> idx = bench::removal_choice(n, k);
  std::vector<char> gone(std::size_t(n), 0);
  for (std::int32_t i : idx) gone[std::size_t(i)] = 1;
  std::vector<typename D::Point> live;
  std::vector<std::int32_t> ids;
  for (std::int64_t i = 0; i < n; ++i)
    if (!gone[std::size_t(i)]) live.push_back(p[std::size_t(i)]), ids.push_back(std::int32_t(i));
  typename D::Options o;
  o.backend = b;
  decltype(D::fresh(p, o)) fresh;
  const double fresh_e2e = median_ms(
      reps, [] {}, [&] { fresh = D::fresh(live, o); });
  std::unique_ptr<typename D::Dynamic> d;
  auto build = [&] { d = std::make_unique<typename D::Dynamic>(&p.data()->x, n, o); };
  const double rm = median_ms(reps, build, [&] { d->remove(idx.data(), k); });
  print_phases(d->stats());
  const char* path = D::removed(d->stats());
  decltype(fresh) got;
  const double rm_e2e = median_ms(reps, build, [&] {
    d->remove(idx.data(), k);
    got = D::result(*d);
  });
  auto mapped = D::simplices(fresh);
  for (auto& v : mapped) v = ids[std::size_t(v)];
  auto want = D::simplices(got);  // (canonical: sorted rows; re-sort after the mapping)
  const bool same = D::canonical(mapped) == want;
  double fresh_dev = -1;
#ifdef GPUGEOM_HAVE_CUDA
  if (b == Backend::Cuda) {
    double* dp = nullptr;
    const std::size_t bytes = live.size() * sizeof(typename D::Point);
    if (cudaMalloc(&dp, bytes) == cudaSuccess &&
        cudaMemcpy(dp, live.data(), bytes, cudaMemcpyHostToDevice) == cudaSuccess)
      fresh_dev = median_ms(
          reps, [] {}, [&] { D::fresh_device(dp, std::int64_t(live.size()), o); });
    cudaFree(dp);
  }
#endif
  std::printf(
      "%s %-10s %-5s n=%-10lld removed=%-9lld fresh e2e %9.2f  fresh dev %9.2f  remove %9.2f  "
      "remove e2e %9.2f  (ratio to fresh %.3f)  %s, %s\n",
      label<D>(), row.dist.c_str(), b == Backend::Cuda ? "cuda" : "cpu", (long long)n, (long long)k,
      fresh_e2e, fresh_dev, rm, rm_e2e, fresh_dev > 0 ? rm / fresh_dev : rm / fresh_e2e, path,
      same ? "same simplices" : "DIFFERENT SIMPLICES");
  std::fflush(stdout);
}

// All n points of a distribution moved by a normal step of f times the mean spacing.
template <class D>
void run_move(const Row& row, double f, Backend b, int reps) {
  constexpr int dim = sizeof(typename D::Point) / sizeof(double);
  const auto p = D::points(row.dist, row.n);
  const std::int64_t n = std::int64_t(p.size());
  const std::vector<typename D::Point> q = bench::displaced<dim>(p, f);
  typename D::Options o;
  o.backend = b;
  decltype(D::fresh(p, o)) fresh;
  const double fresh_e2e = median_ms(
      reps, [] {}, [&] { fresh = D::fresh(q, o); });
  std::unique_ptr<typename D::Dynamic> d;
  auto build = [&] { d = std::make_unique<typename D::Dynamic>(&p.data()->x, n, o); };
  const double mv = median_ms(reps, build, [&] { d->move(&q.data()->x, n); });
  print_phases(d->stats());
  const char* path = D::moved(d->stats());
  decltype(fresh) got;
  const double mv_e2e = median_ms(reps, build, [&] {
    d->move(&q.data()->x, n);
    got = D::result(*d);
  });
  const bool same = D::simplices(got) == D::simplices(fresh);
  double fresh_dev = -1, mv_dev = -1;
#ifdef GPUGEOM_HAVE_CUDA
  if (b == Backend::Cuda) {
    double *dp = nullptr, *dq = nullptr;
    const std::size_t bytes = p.size() * sizeof(typename D::Point);
    if (cudaMalloc(&dp, bytes) == cudaSuccess && cudaMalloc(&dq, bytes) == cudaSuccess &&
        cudaMemcpy(dp, p.data(), bytes, cudaMemcpyHostToDevice) == cudaSuccess &&
        cudaMemcpy(dq, q.data(), bytes, cudaMemcpyHostToDevice) == cudaSuccess) {
      fresh_dev = median_ms(
          reps, [] {}, [&] { D::fresh_device(dq, n, o); });
      mv_dev = median_ms(
          reps,
          [&] { d = std::make_unique<typename D::Dynamic>(D::Dynamic::from_device(dp, n, o)); },
          [&] { d->move_device(dq, n); });
    }
    cudaFree(dp);
    cudaFree(dq);
  }
#endif
  std::printf(
      "%s %-10s %-5s n=%-10lld moved %-6g fresh e2e %9.2f  fresh dev %9.2f  move %9.2f  move "
      "e2e %9.2f  move dev %9.2f  (dev ratio %.3f)  %s, %s\n",
      label<D>(), row.dist.c_str(), b == Backend::Cuda ? "cuda" : "cpu", (long long)n, f, fresh_e2e,
      fresh_dev, mv, mv_e2e, mv_dev, fresh_dev > 0 ? mv_dev / fresh_dev : mv / fresh_e2e, path,
      same ? "same simplices" : "DIFFERENT SIMPLICES");
  std::fflush(stdout);
}
}  // namespace

int main(int argc, char** argv) {
  int reps = 3, dim = 2;
  double move = 0;
  bool removing = false, hull = false;
  std::string which = "all";
  std::vector<Row> rows;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--reps" && i + 1 < argc)
      reps = std::max(1, std::atoi(argv[++i]));
    else if (a == "--backend" && i + 1 < argc)
      which = argv[++i];
    else if (a == "--3d")
      dim = 3;
    else if (a == "--2d")
      dim = 2;
    else if (a == "--move" && i + 1 < argc)
      move = std::atof(argv[++i]);
    else if (a == "--remove")
      removing = true;
    else if (a == "--hull")
      hull = true;
    else {
      rows.push_back(parse(a));
      rows.back().dim = dim;
      rows.back().move = move;
      rows.back().remove = removing;
      rows.back().hull = hull;
    }
  }
  if (rows.empty()) rows = {{"uniform", 1000000, 1000}, {"uniform", 1000000, 100000}};
  const DeviceInfo dev = query_device();
  std::printf(
      "gpugeom_bench_dynamic: Delaunay and hulls, k of n points inserted (ms, median of %d)%s%s\n",
      reps, dev.available ? "; GPU: " : "", dev.available ? dev.name.c_str() : "");
  for (Backend b : bench::backends(which))
    for (const Row& r : rows)
      r.hull&& r.move > 0        ? run_move<Hull>(r, r.move, b, reps)
      : r.hull&& r.remove        ? run_remove<Hull>(r, b, reps)
      : r.hull                   ? run_row<Hull>(r, b, reps)
      : r.move > 0 && r.dim == 2 ? run_move<Two>(r, r.move, b, reps)
      : r.move > 0               ? run_move<Three>(r, r.move, b, reps)
      : r.remove&& r.dim == 2    ? run_remove<Two>(r, b, reps)
      : r.remove                 ? run_remove<Three>(r, b, reps)
      : r.dim == 2               ? run_row<Two>(r, b, reps)
                                 : run_row<Three>(r, b, reps);
  return 0;
}
