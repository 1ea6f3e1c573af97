// delaunay2d_devices and delaunay3d_devices (include/gpugeom/multi_gpu.hpp): the blocks of
// gpugeom.dask's triangulation, one per device, in one process (docs/design-notes.md, "Several
// GPUs of one host: the blocks in one process"). The points are split among the blocks where the
// module prepared them (blocks/split_on.hpp, on the first device). Every block is triangulated with
// a ghost layer and the global hull's candidates on its device, where its passes run too
// (block_pass.hpp: its owned simplices, its border for the others, the output rows and face
// requests); the stars that may reach past its region are tested here against all the points
// (stars_final). A block whose stars are not all final is triangulated again with its own points,
// the hull's and the borders sent to it. The owned simplices' neighbours across blocks are matched
// by their faces, and the module puts them in a single call's order (assemble_blocks).
#include <omp.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <exception>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "gpugeom/blocks.hpp"
#include "gpugeom/multi_gpu.hpp"
#include "base/clock.hpp"
#include "base/on_threads.hpp"
#include "exec/dispatch.hpp"
#include "exec/peer_reads.hpp"
#include "blocks/convex_sample.hpp"
#include "blocks/final.hpp"
#include "blocks/owned.hpp"
#include "blocks/pass.hpp"
#include "delaunay2d/del2d_backend.hpp"
#include "delaunay3d/del3d_backend.hpp"

namespace gpugeom {

namespace {

using blocks_detail::OwnedBlocks;
using I64 = HostVector<std::int64_t>;

using detail::on_threads;

// The finality test's scans visit at most this many points per local point of the block; past
// that the block takes its second round, which needs no test (points on a sphere: every ball
// inside it spans the input, and without a bound the tests took 53 s at 10^7 points in 4 blocks
// against 0.9 s for a single call).
constexpr std::int64_t kScanBudget = 4;

bool degenerate(const Error& e) {
  return e.code() == ErrorCode::DegenerateInput;
}

// What differs between the dimensions: the module's single call, its block entry and frame, the
// ghost width.
template <int D>
struct Dim;

template <>
struct Dim<2> {
  using Options = Delaunay2dOptions;
  using Result = Triangulation2d;
  using Stats = Delaunay2dStats;
  // The ghost width in mean point spacings, and the depth of the strips along the sides of the
  // bounds in ghost widths, as gpugeom.dask's first round (_delaunay.py's _GHOST and
  // _STRIP_DEPTH): the simplices along the hull are long and flat, their balls' parts inside
  // the hull thin lenses along the sides, beyond any ghost layer that costs little.
  static constexpr double kGhost = 6.0, kStrip = 4.0;
  static Result triangulate(const double* p, std::int64_t n, const Options& o) {
    return delaunay2d(p, n, o);
  }
  static Result assemble(const double* p, std::int64_t n, const Options& o,
                         const del2d::BlocksFn& f) {
    Result r;
    GG_TABLE(o.backend, del2d, assembly).run(p, n, o, f, r);
    return r;
  }
  static void block(const Options& o, const blocks_detail::BlockTask& t,
                    const blocks_detail::FinalTest& test, blocks_detail::BlockRows& out) {
    GG_TABLE(o.backend, del2d, assembly).block(o, t, test, out);
  }
};

template <>
struct Dim<3> {
  using Options = Delaunay3dOptions;
  using Result = Triangulation3d;
  using Stats = Delaunay3dStats;
  static constexpr double kGhost = 4.0, kStrip = 0.5;
  static Result triangulate(const double* p, std::int64_t n, const Options& o) {
    return delaunay3d(p, n, o);
  }
  static Result assemble(const double* p, std::int64_t n, const Options& o,
                         const del3d::BlocksFn& f) {
    Result r;
    GG_TABLE(o.backend, del3d, assembly).run(p, n, o, f, r);
    return r;
  }
  static void block(const Options& o, const blocks_detail::BlockTask& t,
                    const blocks_detail::FinalTest& test, blocks_detail::BlockRows& out) {
    GG_TABLE(o.backend, del3d, assembly).block(o, t, test, out);
  }
};

std::vector<int> prime_factors(int n) {
  std::vector<int> out;
  for (int p = 2; p * p <= n; ++p)
    while (n % p == 0) out.push_back(p), n /= p;
  if (n > 1) out.push_back(n);
  return out;
}

// Cells per axis, their product k (as gpugeom.dask's choose_counts): each prime factor, largest
// first, splits the axis whose cells are then the longest (ties: the lower axis).
template <int D>
CellGrid block_grid(const PointBounds& b, int k) {
  CellGrid g;
  auto f = prime_factors(k);
  std::sort(f.rbegin(), f.rend());
  for (int p : f) {
    int best = 0;
    for (int j = 1; j < D; ++j)
      if ((b.hi[j] - b.lo[j]) / double(g.counts[j]) >
          (b.hi[best] - b.lo[best]) / double(g.counts[best]))
        best = j;
    g.counts[best] *= p;
  }
  for (int j = 0; j < D; ++j) {
    g.lo[j] = b.lo[j];
    g.width[j] = (b.hi[j] - b.lo[j]) / double(g.counts[j]);
  }
  return g;
}

// About `target` cells close to cubes over the bounds (one along a flat axis).
template <int D>
CellGrid cube_grid(const PointBounds& b, double target) {
  double vol = 1;
  int live = 0;
  for (int j = 0; j < D; ++j)
    if (b.hi[j] > b.lo[j]) vol *= b.hi[j] - b.lo[j], ++live;
  CellGrid g;
  const double side = live ? std::pow(vol / std::max(target, 1.0), 1.0 / live) : 1.0;
  for (int j = 0; j < D; ++j) {
    const double e = b.hi[j] - b.lo[j];
    g.counts[j] = e > 0 ? std::int64_t(std::clamp(std::ceil(e / side), 1.0, double(1 << 20))) : 1;
    g.lo[j] = b.lo[j];
    g.width[j] = e / double(g.counts[j]);
  }
  return g;
}

// The sorted union of sorted id lists, merged pairwise, shortest first (linear in their
// lengths: a sort of the concatenation took a second at 10^7 points, on one thread).
I64 merged(std::vector<const I64*> lists) {
  std::sort(lists.begin(), lists.end(),
            [](const I64* a, const I64* b) { return a->size() < b->size(); });
  I64 out, tmp;
  for (const I64* l : lists) {
    tmp.resize(out.size() + l->size());
    tmp.resize(std::size_t(
        std::set_union(out.begin(), out.end(), l->begin(), l->end(), tmp.begin()) - tmp.begin()));
    std::swap(out, tmp);
  }
  return out;
}

// Milliseconds of one pass summed over the blocks (they run at once, so the sums say where the
// blocks' time goes, not how long the phase took).
class PassTimes {
 public:
  template <class F>
  auto time(int pass, F&& f) {
    const double t = now_ms();
    struct Add {
      PassTimes& p;
      int pass;
      double t;
      ~Add() { p.add(pass, now_ms() - t); }
    } add{*this, pass, t};
    return f();
  }
  void add(int pass, double ms) { us_[pass] += std::int64_t(ms * 1000.0); }
  void report(std::vector<std::pair<std::string, double>>& phases) const {
    for (int i = 0; i < kPasses; ++i)
      if (us_[i] > 0)
        phases.push_back({std::string("blocks.sum.") + kNames[i], double(us_[i]) / 1e3});
  }
  enum { kGather, kTriangulate, kBlockPasses, kFinal, kOutput, kPasses };

 private:
  static constexpr const char* kNames[kPasses] = {"gather", "triangulate", "passes", "final",
                                                  "output"};
  std::atomic<std::int64_t> us_[kPasses] = {};
};

template <int D>
class Blocks {
 public:
  using T = Dim<D>;
  using Options = typename T::Options;

  Blocks(const blocks_detail::PreparedPoints& points, const std::vector<int>& devices,
         Backend backend, const Options& opt)
      : points_(points), n_(points.m), devices_(devices), backend_(backend), opt_(opt) {
    all_ = opt.threads > 0 ? opt.threads : omp_get_max_threads();
    threads_ = std::max(1, all_ / int(devices.size()));
  }

  OwnedBlocks run(typename T::Stats& st) {
    const double t0 = now_ms();
    setup(st.phase_ms);
    st.phase_ms.push_back({"blocks.split", now_ms() - t0});
    const double t1 = now_ms();
    on_threads(k_, [&](std::size_t b) { first_round(b); });
    st.phase_ms.push_back({"blocks.round1", now_ms() - t1});
    const double t2 = now_ms();
    std::vector<std::size_t> pending;
    for (std::size_t b = 0; b < k_; ++b)
      if (!blk_[b].done) pending.push_back(b);
    on_threads(pending.size(), [&](std::size_t i) { second_round(pending[i]); });
    st.phase_ms.push_back({"blocks.round2", now_ms() - t2});
    const double t3 = now_ms();
    OwnedBlocks out = neighbours();
    st.phase_ms.push_back({"blocks.neighbors", now_ms() - t3});
    times_.report(st.phase_ms);
    st.blocks = std::int64_t(k_);
    st.blocks_second_round = std::int64_t(pending.size());
    st.block_local_points = local_points_;
    return out;
  }

 private:
  struct Block {
    I64 own;  // global ids of the own points, increasing
    I64 ids;  // global ids of the local points, increasing
    HostVector<double> pts;
    bool done = false;
    std::vector<std::pair<std::int64_t, I64>> borders;  // (target block, global ids)
    blocks_detail::BlockRows rows;
  };

  Options block_options(std::size_t b) const {
    Options o = opt_;
    o.backend = backend_;
    o.device = backend_ == Backend::Cuda ? devices_[b] : -1;
    o.stream = nullptr;
    o.threads = threads_;
    o.into = {};
    return o;
  }

  // (phases: the split's parts, timed)
  void setup(std::vector<std::pair<std::string, double>>& phases) {
    double t = now_ms();
    const PointBounds pb = points_.bounds;
    grid_ = block_grid<D>(pb, int(devices_.size()));
    k_ = devices_.size();
    double vol = 1, scale = 0;
    int live = 0;
    for (int j = 0; j < D; ++j) {
      if (pb.hi[j] > pb.lo[j]) vol *= pb.hi[j] - pb.lo[j], ++live;
      scale = std::max({scale, std::fabs(pb.lo[j]), std::fabs(pb.hi[j])});
    }
    ghost_ = live ? T::kGhost * std::pow(vol / double(n_), 1.0 / live) : 1.0;
    margin_ = 1e-9 * scale;
    cells_.g = grid_;
    cells_.total = std::int64_t(k_);
    cells_.margin = margin_;
    // the regions: each cell grown by the ghost width (the last cell ends at the bounds), and
    // the strips along the sides of the bounds the cell lies on
    boxes_.resize(k_);
    strips_.resize(k_);
    blocks_detail::SplitLayout L;
    L.grid = grid_;
    L.blocks = std::int64_t(k_);
    const double depth = T::kStrip * ghost_;
    for (std::size_t b = 0; b < k_; ++b) {
      std::int64_t c = std::int64_t(b), idx[3] = {0, 0, 0};
      for (int j = D - 1; j >= 0; --j) idx[j] = c % grid_.counts[j], c /= grid_.counts[j];
      BlockBoxes& x = boxes_[b];
      for (int j = 0; j < D; ++j) {
        const double clo = grid_.lo[j] + double(idx[j]) * grid_.width[j];
        const double chi = idx[j] + 1 == grid_.counts[j]
                               ? pb.hi[j]
                               : grid_.lo[j] + double(idx[j] + 1) * grid_.width[j];
        x.region_lo[j] = clo - ghost_;
        x.region_hi[j] = chi + ghost_;
        x.bounds_lo[j] = pb.lo[j];
        x.bounds_hi[j] = pb.hi[j];
        L.lo.push_back(x.region_lo[j]);
        L.hi.push_back(x.region_hi[j]);
      }
      x.scale = scale;
      L.owner.push_back(std::int32_t(b));
      for (int j = 0; j < D; ++j) {
        if (!(pb.hi[j] > pb.lo[j])) continue;
        for (int high = 0; high < 2; ++high) {
          if (high ? idx[j] + 1 != grid_.counts[j] : idx[j] != 0) continue;
          Strips& st = strips_[b];
          for (int i = 0; i < D; ++i) {
            double a = pb.lo[i], e = pb.hi[i];
            if (i == j) (high ? a : e) = high ? pb.hi[j] - depth : pb.lo[j] + depth;
            st.lo.push_back(a), st.hi.push_back(e), L.lo.push_back(a), L.hi.push_back(e);
          }
          L.owner.push_back(std::int32_t(b));
        }
      }
    }
    // the bins of the finality test: about 16 points each
    bins_ = cube_grid<D>(pb, std::min(double(n_) / 16.0, double(1 << 24)));
    L.bins = bins_;
    phases.push_back({"blocks.split.bounds", now_ms() - t});
    // The split where the points were prepared (blocks/split_on.hpp). The blocks' ids are the
    // prepared points' places (distinct points on the curve), mapped to input indices at the
    // output: a block's simplices then name points near one another in memory (in the input's
    // order, random for random points, every vertex a pass read was a cache miss), and no
    // duplicate reaches a block. Ownership by the lowest id is a rule on these ids, as good as
    // any.
    blocks_detail::PointSplit sp = points_.split(L);
    phases.push_back({"blocks.split.copy", sp.ms_copy});
    phases.push_back({"blocks.split.bins", sp.ms_bins});
    phases.push_back({"blocks.split.regions", sp.ms_regions});
    q_ = std::move(sp.q);
    orig_ = std::move(sp.orig);
    cell_ = std::move(sp.cell);
    bin_order_ = std::move(sp.bin_order);
    bin_cuts_ = std::move(sp.bin_cuts);
    regions_ = std::move(sp.regions);
    // where each block's device can read the prepared points (the first device's), it gathers
    // its own there (exec/peer_reads.hpp: peer access for the blocks' life)
    source_.assign(k_, nullptr);
    for (std::size_t b = 0; b < k_; ++b) {
      if (backend_ == Backend::Cuda) {
        reads_.emplace_back(devices_[b], devices_[0]);
        if (!reads_.back().readable()) continue;
      }
      source_[b] = points_.pts;
    }
    t = now_ms();
    // the candidates for the global hull's extreme points, where the points are
    held_ = points_.hull();
    phases.push_back({"blocks.split.hull", now_ms() - t});
    t = now_ms();
    // every block's own points
    blk_.resize(k_);
    on_threads(k_, [&](std::size_t b) {
      Block& B = blk_[b];
      {  // (in order, on the block's threads)
        blocks_detail::ThreadScope scope(threads_);
        const HostVector<std::int32_t>& region = regions_[b];
        blocks_detail::ordered_compact(
            std::int64_t(region.size()),
            [&](std::int64_t q) { return cell_[std::size_t(region[std::size_t(q)])] == int(b); },
            [&](std::int64_t total) { B.own.resize(std::size_t(total)); },
            [&](std::int64_t q, std::int64_t r) {
              B.own[std::size_t(r)] = region[std::size_t(q)];
            });
      }
    });
    phases.push_back({"blocks.split.own", now_ms() - t});
    t = now_ms();
    frontiers();
    phases.push_back({"blocks.split.frontier", now_ms() - t});
  }

  // The bins beside the empty space each block's region reaches (blocks.hpp: empty_frontiers,
  // the rule gpugeom.dask's first round has): their points join the block's first round, where
  // the balls that span the empty space end on them (between clusters, round a Gaussian's
  // tail), and the finality test knows the block holds them (known_). At most a quarter of a
  // block's share of the points.
  void frontiers() {
    frontier_.assign(k_, I64{});
    known_.assign(k_, I64{});
    const std::int64_t nbins = std::int64_t(bin_cuts_.size()) - 1;
    HostVector<std::int32_t> counts(static_cast<std::size_t>(nbins));
    // (once for all the blocks, so on all the threads: a block's share of them made the pass
    // 52 ms of the H200's 2D split at 2·10^7 points)
#pragma omp parallel for num_threads(all_) schedule(static)
    for (std::int64_t i = 0; i < nbins; ++i)
      counts[std::size_t(i)] =
          std::int32_t(bin_cuts_[std::size_t(i + 1)] - bin_cuts_[std::size_t(i)]);
    std::vector<double> lo, hi;
    for (const BlockBoxes& x : boxes_)
      for (int j = 0; j < D; ++j) lo.push_back(x.region_lo[j]), hi.push_back(x.region_hi[j]);
    const BlockFrontiers f =
        empty_frontiers(counts.data(), bins_, D, lo.data(), hi.data(), std::int64_t(k_),
                        std::max<std::int64_t>(1, n_ / (4 * std::int64_t(k_))), ghost_, all_);
    on_threads(k_, [&](std::size_t b) {
      // the frontier bins' places, increasing: a bit per place, read in order (a sort of the
      // 10^6 places a block of a ball's surface holds at 10^7 points took tens of ms)
      if (f.offsets[b] == f.offsets[b + 1]) return;
      std::vector<std::uint64_t> bits(std::size_t(n_ + 63) / 64, 0);
      std::int64_t count = 0;
      for (std::int64_t q = f.offsets[b]; q < f.offsets[b + 1]; ++q) {
        const std::int64_t bin = f.bins[std::size_t(q)];
        for (std::int64_t r = bin_cuts_[std::size_t(bin)]; r < bin_cuts_[std::size_t(bin + 1)];
             ++r) {
          const std::int64_t p = bin_order_[std::size_t(r)];
          bits[std::size_t(p >> 6)] |= std::uint64_t(1) << (p & 63);
        }
        count += bin_cuts_[std::size_t(bin + 1)] - bin_cuts_[std::size_t(bin)];
      }
      I64& mine = frontier_[b];
      mine.reserve(std::size_t(count));
      for (std::size_t w = 0; w < bits.size(); ++w)
        for (std::uint64_t x = bits[w]; x; x &= x - 1)
          mine.push_back(std::int64_t(w * 64) + __builtin_ctzll(x));
      if (!mine.empty()) known_[b] = merged({&held_, &mine});
    });
  }

  HostVector<double> gather(const I64& ids) {
    return times_.time(PassTimes::kGather, [&] {
      HostVector<double> out(ids.size() * D);
      const std::int64_t m = std::int64_t(ids.size());
#pragma omp parallel for num_threads(threads_) schedule(static)
      for (std::int64_t i = 0; i < m; ++i)
        for (int j = 0; j < D; ++j)
          out[std::size_t(i * D + j)] = q_[std::size_t(ids[std::size_t(i)] * D + j)];
      return out;
    });
  }

  // The local points `ids` gathered and triangulated on the block's device, and the block's
  // passes run there (blocks/block_pass.hpp); in the first round with its border and the host's
  // finality test of the stars that may reach past its region (stars_final).
  void triangulate(std::size_t b, I64 ids, bool first) {
    Block& B = blk_[b];
    B.ids = std::move(ids);
    // the block's device gathers its points where it can read the prepared ones, else they
    // are gathered here and copied there
    const double* source = source_[b];
    if (!source) B.pts = gather(B.ids);
    const std::int64_t nl = std::int64_t(B.ids.size());
    HostVector<std::int32_t> in(B.ids.size()), bl(B.ids.size()), places(source ? B.ids.size() : 0);
#pragma omp parallel for num_threads(threads_) schedule(static)
    for (std::int64_t i = 0; i < nl; ++i) {
      const std::int64_t id = B.ids[std::size_t(i)];
      in[std::size_t(i)] = orig_[std::size_t(id)];
      bl[std::size_t(i)] = cell_[std::size_t(id)];
      if (source) places[std::size_t(i)] = std::int32_t(id);
    }
    blocks_detail::BlockTask t;
    t.points = B.pts.data();
    t.source = source;
    t.places = places.data();
    t.n = nl;
    t.ids = in.data();
    t.blk = bl.data();
    t.block = std::int64_t(b);
    if (first) {
      t.cells = &cells_;
      t.scale = boxes_[b].scale;
      t.boxes = &boxes_[b];
    }
    B.rows = {};
    T::block(
        block_options(b), t,
        [&](const blocks_detail::BlockRows& r) {
          // (a block that holds every point, as on a circle or sphere where all are the
          // hull's, is final without a test)
          if (covers_all(b) || nl == n_) return true;
          // (the rows' local vertices as places: the test reads them among all the points)
          const std::int64_t m = std::int64_t(r.test.size()) / (D + 1);
          HostVector<std::int32_t> rows(r.test.size());
          for (std::size_t i = 0; i < rows.size(); ++i)
            rows[i] = std::int32_t(B.ids[std::size_t(r.test[i])]);
          HostVector<std::uint8_t> all(static_cast<std::size_t>(m), 1);
          return blocks_detail::stars_final_within(
              q_.data(), D, rows.data(), m, all.data(), boxes_[b], q_.data(), bins_,
              bin_order_.data(), bin_cuts_.data(), known(b).data(), std::int64_t(known(b).size()),
              strips_[b].lo.data(), strips_[b].hi.data(), std::int64_t(strips_[b].lo.size() / D),
              threads_, kScanBudget * nl);
        },
        B.rows);
    times_.add(PassTimes::kTriangulate, B.rows.ms_triangulate);
    times_.add(PassTimes::kBlockPasses, B.rows.ms_passes);
    times_.add(PassTimes::kFinal, B.rows.ms_final);
    times_.add(PassTimes::kOutput, B.rows.ms_output);
    if (B.rows.final) local_points_ += nl;
    B.pts = {};
  }

  // the places block b holds besides its boxes: the hull's candidates and its frontier
  const I64& known(std::size_t b) const {
    return known_[b].empty() ? held_ : known_[b];
  }

  bool covers_all(std::size_t b) const {
    for (int j = 0; j < D; ++j)
      if (boxes_[b].region_lo[j] > boxes_[b].bounds_lo[j] ||
          boxes_[b].region_hi[j] < boxes_[b].bounds_hi[j])
        return false;
    return true;
  }

  void first_round(std::size_t b) {
    Block& B = blk_[b];
    if (B.own.empty()) {
      B.done = true;
      return;
    }
    try {
      const I64 region(regions_[b].begin(), regions_[b].end());
      triangulate(b, merged({&region, &frontier_[b], &held_}), true);
    } catch (const Error& e) {
      if (!degenerate(e) || covers_all(b)) throw;
      // no triangulation to take a border from: every own point goes to every block
      for (std::size_t t = 0; t < k_; ++t)
        if (t != b) B.borders.push_back({std::int64_t(t), B.own});
      B.rows = {};
      return;
    }
    for (auto& [t, local] : B.rows.borders) {
      I64 ids(local.size());
      for (std::size_t q = 0; q < local.size(); ++q) ids[q] = B.ids[std::size_t(local[q])];
      B.borders.push_back({t, std::move(ids)});
    }
    B.rows.borders = {};
    B.rows.test = {};
    B.done = B.rows.final;
  }

  void second_round(std::size_t b) {
    Block& B = blk_[b];
    std::vector<const I64*> lists{&B.own, &held_};
    for (auto& src : blk_)
      for (auto& [t, ids] : src.borders)
        if (t == std::int64_t(b)) lists.push_back(&ids);
    triangulate(b, merged(lists), false);
  }

  // Each block's face requests go to the block that matches them (by the face's lowest vertex),
  // and each block's neighbours across blocks come from the answers.
  OwnedBlocks neighbours() {
    const int d1 = D + 1;
    OwnedBlocks o;
    for (std::size_t b = 0; b < k_; ++b) o.offsets.push_back(o.offsets.back() + blk_[b].rows.count);
    // answers[c][b]: block c's answers to block b's requests (positions here, global across)
    std::vector<std::vector<std::pair<I64, I64>>> answers(k_, std::vector<std::pair<I64, I64>>(k_));
    on_threads(k_, [&](std::size_t c) {
      HostVector<std::int32_t> keys;  // (the blocks' 32-bit ids, as they come)
      I64 pos;
      HostVector<std::uint8_t> open;
      std::vector<std::size_t> from(k_ + 1, 0);
      for (std::size_t b = 0; b < k_; ++b) {
        const blocks_detail::BlockRows& x = blk_[b].rows;
        for (std::size_t r = 0; r < x.request_owner.size(); ++r) {
          if (x.request_owner[r] != std::int32_t(c)) continue;
          for (int j = 0; j < D; ++j) keys.push_back(x.request_key[r * D + std::size_t(j)]);
          pos.push_back(o.offsets[b] * d1 + x.request_pos[r]);
          open.push_back(x.request_open[r]);
        }
        from[b + 1] = pos.size();
      }
      const I64 across =
          match_faces(keys.data(), pos.data(), open.data(), std::int64_t(pos.size()), D, threads_);
      for (std::size_t b = 0; b < k_; ++b) {
        auto& [p, a] = answers[c][b];
        for (std::size_t i = from[b]; i < from[b + 1]; ++i) {
          p.push_back(pos[i] - o.offsets[b] * d1);
          a.push_back(across[i] >= 0 ? across[i] / d1 : -1);
        }
      }
    });
    // each block's rows stay where they were made, with their answers (owned_on.hpp)
    o.parts.resize(k_);
    on_threads(k_, [&](std::size_t b) {
      blocks_detail::OwnedPart& part = o.parts[b];
      for (std::size_t c = 0; c < k_; ++c) {
        part.pos.insert(part.pos.end(), answers[c][b].first.begin(), answers[c][b].first.end());
        part.across.insert(part.across.end(), answers[c][b].second.begin(),
                           answers[c][b].second.end());
      }
      blocks_detail::BlockRows& x = blk_[b].rows;
      part.simplices = std::move(x.simplices);
      part.neighbors = std::move(x.neighbors);
      part.count = x.count;
      part.device = x.device;
      x = {};
    });
    return o;
  }

  const blocks_detail::PreparedPoints& points_;
  // by place (the prepared points' order): the points, input indices, cells of the blocks' grid
  HostVector<double> q_;
  HostVector<std::int32_t> orig_, cell_;
  I64 bin_order_, bin_cuts_;                       // the finality test's bins: places by bin
  std::vector<HostVector<std::int32_t>> regions_;  // each block's places, increasing
  std::vector<const double*> source_;  // per block: the prepared points, where it can read them
  std::vector<detail::PeerReads> reads_;
  std::int64_t n_;  // distinct points
  std::vector<int> devices_;
  Backend backend_;
  Options opt_;
  int all_ = 1;      // the call's threads: the passes once for all the blocks
  int threads_ = 1;  // a block's share of them: the blocks run side by side
  std::size_t k_ = 0;
  CellGrid grid_, bins_;
  blocks_detail::BorderCells cells_;  // the blocks' cells for the borders (grid_, margin_)
  double ghost_ = 0, margin_ = 0;
  std::vector<BlockBoxes> boxes_;
  struct Strips {
    std::vector<double> lo, hi;  // D coordinates a box
  };
  std::vector<Strips> strips_;
  I64 held_;
  // per block: its places in the bins beside empty space, and those with held_ (increasing)
  std::vector<I64> frontier_, known_;
  std::vector<Block> blk_;
  std::atomic<std::int64_t> local_points_{0};
  PassTimes times_;
};

template <int D>
typename Dim<D>::Result run_devices(const double* p, std::int64_t n,
                                    const std::vector<int>& devices_in,
                                    const typename Dim<D>::Options& opt, const char* name) {
  if (opt.threads < 0)
    throw Error(ErrorCode::InvalidArgument, "threads must be 0 (all) or positive");
  if (opt.method != Method::Incremental)
    throw Error(ErrorCode::InvalidArgument,
                std::string(name) + " runs the incremental method in every block");
  std::vector<int> devices = devices_in;
  const Backend b = resolve_backend(opt.backend, devices.empty() ? -1 : devices[0]);
  if (devices.empty()) {
    const int count = b == Backend::Cuda ? query_device().device_count : 1;
    for (int d = 0; d < std::max(1, count); ++d) devices.push_back(d);
  }
  for (int d : devices)
    if (d < 0)
      throw Error(
          ErrorCode::InvalidArgument,
          std::string(name) + ": a device ordinal must be 0 or more, got " + std::to_string(d));
  // One block: the single call on the first device, where one device is listed, or where the
  // points lie on a convex surface (a circle, a sphere, a shell thinner than a sample's spacing:
  // blocks/convex_sample.hpp), so that every block would hold most of them and its balls would
  // span the hollow inside, past any ghost layer (2·10^7 points on a circle took four
  // triangulations on one H200, 0.93 s against 0.13 s for one call; a thin shell of 10^7 points
  // two rounds, 2.8 s against 0.85). The sample is read from the input as given (every
  // ceil(n / 4096)-th point, as gpugeom.dask reads its own), before the points are checked: a
  // sample with a NaN or an infinity says no, and the assembly's check refuses it.
  if (devices.size() == 1 || blocks_detail::on_convex_surface(p, D, n)) {
    typename Dim<D>::Options o = opt;
    o.backend = b;
    if (b == Backend::Cuda) o.device = devices[0];
    typename Dim<D>::Result r = Dim<D>::triangulate(p, n, o);
    r.stats.blocks = 1;
    return r;
  }
  // the assembly on the first device (the points prepared, the output ordered, as one call)
  typename Dim<D>::Options first = opt;
  first.backend = b;
  if (b == Backend::Cuda) first.device = devices[0];
  typename Dim<D>::Result r = Dim<D>::assemble(
      p, n, first, [&](typename Dim<D>::Stats& st, const blocks_detail::PreparedPoints& pts) {
        return Blocks<D>(pts, devices, b, opt).run(st);
      });
  r.stats.backend = b;
  return r;
}

}  // namespace

Triangulation2d delaunay2d_devices(const double* xy, std::int64_t n,
                                   const std::vector<int>& devices, const Delaunay2dOptions& opt) {
  del2d::check_count(n);
  return run_devices<2>(xy, n, devices, opt, "delaunay2d_devices");
}

Triangulation3d delaunay3d_devices(const double* xyz, std::int64_t n,
                                   const std::vector<int>& devices, const Delaunay3dOptions& opt) {
  del3d::check_count(n);
  return run_devices<3>(xyz, n, devices, opt, "delaunay3d_devices");
}

}  // namespace gpugeom
