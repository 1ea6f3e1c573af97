// Random sequences of insert, move and remove on a structure that follows its points
// (DynamicDelaunay2d, DynamicDelaunay3d, DynamicHull3d; issue 47), checked after every call
// against a fresh call on the points left, which the exact checker judges.
#pragma once
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "gpugeom/common.hpp"
#include "gpugeom/removed.hpp"

namespace gg_test {

// Traits: Point, Dyn (the dynamic class), Result (its host result), Options, kVerts (per simplex),
// kDim (of the points), and
//   Result fresh(const std::vector<Point>&, const Options&)   the from-scratch call
//   Result current(const Dyn&)                                 the dynamic object's results
//   void valid(const std::vector<Point>&, const Result&)       the exact checker and the rest
//   const std::int32_t* simplices(const Result&), neighbors(const Result&)
//   std::int64_t count(const Result&)
//   void expect_same(got, fresh, ids, n)    what else must equal the fresh call's (ids: the
//                                           points left, n: all points)
//   bool local_removal(const Stats&)        a removal that did not start over
//   bool enough_local(int local, int removes)
//   void shift(Point&, double scale, std::mt19937_64&)          a random displacement
// KeptTriangulation gives the triangulations' expect_same (the duplicate map, from
// Derived::dup), local_removal and enough_local.
template <class Derived>
struct KeptTriangulation {
  template <class Result>
  static void expect_same(const Result& got, const Result& fresh,
                          const std::vector<std::int32_t>& ids, std::size_t n) {
    std::vector<std::int32_t> want(n, gpugeom::kRemovedPoint);
    const auto fd = Derived::dup(fresh);
    for (std::size_t j = 0; j < ids.size(); ++j)
      want[std::size_t(ids[j])] = fd[j] >= 0 ? ids[std::size_t(fd[j])] : -1;
    EXPECT_EQ(Derived::dup(got), want);
  }
  // (the holes filled, not the points left made afresh)
  template <class Stats>  // (Delaunay2dStats, Delaunay3dStats)
  static bool local_removal(const Stats& st) {
    return st.remove_rebuilt == 0;
  }
  static bool enough_local(int local, int removes) { return local > removes / 2; }
};

template <class T>
class KeptOperations {
 public:
  using Point = typename T::Point;
  static constexpr int K = T::kVerts;
  using Simplex = std::array<std::int32_t, K>;

  KeptOperations(std::vector<Point> pts, typename T::Options opt, std::uint64_t seed)
      : pool_(std::move(pts)), opt_(opt), rng_(seed) {
    std::shuffle(pool_.begin(), pool_.end(), rng_);
    // a first chunk that is not degenerate
    std::size_t k = std::min(pool_.size(), std::size_t(K + 1 + rng_() % (pool_.size() / 4 + 1)));
    for (;;) {
      try {
        dyn_ = std::make_unique<typename T::Dyn>(&pool_.data()->x, std::int64_t(k), opt_);
        break;
      } catch (const gpugeom::Error& e) {
        EXPECT_EQ(e.code(), gpugeom::ErrorCode::DegenerateInput) << e.what();
        if (k == pool_.size()) return;
        k = std::min(pool_.size(), 2 * k);
      }
    }
    pts_.assign(pool_.begin(), pool_.begin() + std::ptrdiff_t(k));
    gone_.assign(k, 0);
    dyn_->track_changes(true);
    const auto r = T::current(*dyn_);
    before_.assign(T::simplices(r), T::simplices(r) + K * T::count(r));
  }
  bool started() const { return dyn_ != nullptr; }
  // The calls made (and removals refused), so that a test can see every kind ran.
  struct Calls {
    int inserts = 0, moves = 0, removes = 0, refused = 0;
    int refilled = 0;  // removals that did not start over (T::local_removal)
  };
  const Calls& calls() const { return calls_; }

  // One random call (insert, move or remove), then the check. An exception fails the test with
  // the call named.
  void step() {
    try {
      call();
    } catch (const std::exception& e) {
      ADD_FAILURE() << last_ << ": " << e.what();
    }
  }

 private:
  void call() {
    updated_ = true;
    const std::size_t left = pool_.size() - pts_.size();
    const int what = int(rng_() % 3);
    if (what == 0 && left) {
      const std::size_t add = std::min(left, 1 + rng_() % (left / 3 + 1));
      last_ = "insert " + std::to_string(add) + " into " + std::to_string(pts_.size());
      SCOPED_TRACE(last_);
      dyn_->insert(&pool_[pts_.size()].x, std::int64_t(add));
      for (std::size_t i = 0; i < add; ++i) pts_.push_back(pool_[pts_.size()]), gone_.push_back(0);
      ++calls_.inserts;
    } else if (what == 1) {
      // small moves (repaired) and large ones (rebuilt), removed points' coordinates included
      const double scale = (rng_() % 2 ? 1e-3 : 0.3) * spacing();
      std::vector<Point> q = pts_;
      for (auto& p : q) T::shift(p, scale, rng_);
      last_ = "move by " + std::to_string(scale);
      SCOPED_TRACE(last_);
      dyn_->move(&q.data()->x, std::int64_t(q.size()));
      pts_ = q;
      ++calls_.moves;
    } else {
      std::vector<std::int32_t> live;
      for (std::size_t i = 0; i < pts_.size(); ++i)
        if (!gone_[i]) live.push_back(std::int32_t(i));
      std::shuffle(live.begin(), live.end(), rng_);
      const std::size_t r = std::min(live.size(), 1 + rng_() % (live.size() / 4 + 1));
      live.resize(r);
      last_ = "remove " + std::to_string(r) + " of " + std::to_string(pts_.size());
      SCOPED_TRACE(last_);
      try {
        dyn_->remove(live.data(), std::int64_t(r));
        for (std::int32_t i : live) gone_[std::size_t(i)] = 1;
        ++calls_.removes;
        calls_.refilled += T::local_removal(dyn_->stats());
      } catch (const gpugeom::Error& e) {
        ++calls_.refused;
        updated_ = false;
        // too few points left, or none in general position: refused, nothing changed
        EXPECT_EQ(e.code(), gpugeom::ErrorCode::DegenerateInput) << e.what();
      }
    }
    check();
  }

 public:
  // After every call: the same simplices (and T::expect_same's arrays) as a fresh call on the
  // points left (renumbered), which the exact checker judges; neighbours consistent.
  void check() {
    std::vector<Point> live;
    std::vector<std::int32_t> ids;
    for (std::size_t i = 0; i < pts_.size(); ++i)
      if (!gone_[i]) live.push_back(pts_[i]), ids.push_back(std::int32_t(i));
    const auto got = T::current(*dyn_);
    ASSERT_EQ(dyn_->num_points(), std::int64_t(pts_.size()));
    ASSERT_EQ(dyn_->num_removed(), std::int64_t(pts_.size() - live.size()));
    const auto fresh = T::fresh(live, opt_);
    T::valid(live, fresh);
    if (live.size() == pts_.size()) T::valid(pts_, got);
    EXPECT_EQ(set_of(T::simplices(got), T::count(got), nullptr),
              set_of(T::simplices(fresh), T::count(fresh), &ids));
    T::expect_same(got, fresh, ids, pts_.size());
    expect_neighbours(T::simplices(got), T::neighbors(got), T::count(got));
    if (updated_) expect_changes(T::simplices(got), T::count(got));
  }

 private:
  static std::vector<Simplex> set_of(const std::int32_t* s, std::int64_t n,
                                     const std::vector<std::int32_t>* ids) {
    std::vector<Simplex> out(static_cast<std::size_t>(n));
    for (std::int64_t c = 0; c < n; ++c) {
      Simplex a;
      for (int k = 0; k < K; ++k) a[k] = ids ? (*ids)[std::size_t(s[K * c + k])] : s[K * c + k];
      std::sort(a.begin(), a.end());
      out[std::size_t(c)] = a;
    }
    std::sort(out.begin(), out.end());
    return out;
  }
  // changes() of the update just made, against the results before it (before_) and now: a
  // simplex with a previous index has that simplex's vertices, a new one is not among the old,
  // and the removed list is the old ones no new simplex names. Then before_ moves on.
  void expect_changes(const std::int32_t* s, std::int64_t n) {
    const auto c = dyn_->changes();
    const std::int64_t nb = std::int64_t(before_.size()) / K;
    ASSERT_EQ(c.num_simplices, n);
    ASSERT_EQ(c.num_previous, nb);
    ASSERT_EQ(std::int64_t(c.previous_index.size()), n);
    auto sorted = [](const std::int32_t* v) {
      Simplex a;
      for (int k = 0; k < K; ++k) a[k] = v[k];
      std::sort(a.begin(), a.end());
      return a;
    };
    std::vector<Simplex> old(static_cast<std::size_t>(nb));
    for (std::int64_t i = 0; i < nb; ++i)
      old[std::size_t(i)] = sorted(&before_[std::size_t(K * i)]);
    std::vector<Simplex> old_set = old;
    std::sort(old_set.begin(), old_set.end());
    std::vector<char> named(static_cast<std::size_t>(nb), 0);
    std::int64_t fresh = 0;
    for (std::int64_t i = 0; i < n; ++i) {
      const std::int32_t p = c.previous_index[std::size_t(i)];
      const Simplex a = sorted(s + K * i);
      if (p < 0) {
        ++fresh;
        EXPECT_FALSE(std::binary_search(old_set.begin(), old_set.end(), a)) << "simplex " << i;
        continue;
      }
      ASSERT_LT(p, nb);
      EXPECT_EQ(old[std::size_t(p)], a) << "simplex " << i;
      EXPECT_EQ(named[std::size_t(p)], 0) << "previous " << p << " named twice";
      named[std::size_t(p)] = 1;
    }
    std::vector<std::int32_t> gone;
    for (std::int64_t i = 0; i < nb; ++i)
      if (!named[std::size_t(i)]) gone.push_back(std::int32_t(i));
    EXPECT_EQ(c.num_new, fresh);
    EXPECT_EQ(c.num_removed, std::int64_t(gone.size()));
    EXPECT_EQ(std::vector<std::int32_t>(c.removed.begin(), c.removed.end()), gone);
    before_.assign(s, s + K * n);
  }
  // Each neighbour shares the face opposite vertex k and names this simplex back.
  static void expect_neighbours(const std::int32_t* s, const std::int32_t* nb, std::int64_t n) {
    for (std::int64_t c = 0; c < n; ++c)
      for (int k = 0; k < K; ++k) {
        const std::int32_t o = nb[K * c + k];
        if (o < 0) continue;
        ASSERT_LT(o, n);
        int shared = 0, back = 0;
        for (int j = 0; j < K; ++j)
          for (int i = 0; i < K; ++i) {
            if (i != k && s[K * o + j] == s[K * c + i]) ++shared;
            if (i == 0 && nb[K * o + j] == c) ++back;
          }
        ASSERT_EQ(shared, K - 1) << "simplex " << c << " face " << k;
        ASSERT_EQ(back, 1) << "simplex " << c << " face " << k;
      }
  }
  double spacing() const {
    double lo[3] = {1e300, 1e300, 1e300}, hi[3] = {-1e300, -1e300, -1e300};
    for (const auto& p : pts_)
      for (int d = 0; d < T::kDim; ++d)
        lo[d] = std::min(lo[d], (&p.x)[d]), hi[d] = std::max(hi[d], (&p.x)[d]);
    double vol = 1;
    for (int d = 0; d < T::kDim; ++d) vol *= hi[d] - lo[d] + 1e-300;
    return std::pow(vol / double(pts_.size()), 1.0 / T::kDim);
  }

  std::vector<Point> pool_;  // every point that may be given, in the order given
  std::vector<Point> pts_;   // the points given so far (moved coordinates)
  std::vector<char> gone_;   // removed
  typename T::Options opt_;
  std::mt19937_64 rng_;
  std::unique_ptr<typename T::Dyn> dyn_;
  Calls calls_;
  std::string last_;
  std::vector<std::int32_t> before_;  // the results' simplices before the last update
  bool updated_ = false;              // the last call changed the state
};

// Random calls on each case (steps of them), checked after each; every kind of call ran.
template <class T, class Cases>
void random_operations(const Cases& cases, const typename T::Options& opt, std::uint64_t seed,
                       int runs, int steps) {
  typename KeptOperations<T>::Calls all;
  for (const auto& c : cases)
    for (int r = 0; r < runs; ++r) {
      SCOPED_TRACE(c.name + " run " + std::to_string(r));
      KeptOperations<T> k(c.pts, opt, seed++);
      if (!k.started()) continue;
      for (int i = 0; i < steps && !::testing::Test::HasFailure(); ++i) k.step();
      all.inserts += k.calls().inserts, all.moves += k.calls().moves;
      all.removes += k.calls().removes, all.refused += k.calls().refused;
      all.refilled += k.calls().refilled;
    }
  EXPECT_GT(all.inserts, 0);
  EXPECT_GT(all.moves, 0);
  EXPECT_GT(all.removes, 0);
  EXPECT_GT(all.refused, 0);  // some removal left too few points
  EXPECT_TRUE(T::enough_local(all.refilled, all.removes))
      << all.refilled << " of " << all.removes << " removals did not start over";
}

// changes() (issue 47): refused until an update ran with tracking on; then what the last update
// changed, on the host and in executor memory alike (CPU executor: host memory);
// track_changes(false) ends it. p: at least 2510 points, not degenerate. (What changes() says is
// checked after every random operation: KeptOperations.)
template <class T>
void changes_need_tracking(const std::vector<typename T::Point>& p,
                           const typename T::Options& opt) {
  typename T::Dyn d(&p.data()->x, 2000, opt);
  auto refused = [&] {
    try {
      (void)d.changes();
    } catch (const gpugeom::Error& e) {
      return e.code() == gpugeom::ErrorCode::InvalidArgument;
    }
    return false;
  };
  EXPECT_TRUE(refused());
  d.insert(&p[2000].x, 10);
  EXPECT_TRUE(refused());  // (tracking was off during that update)
  d.track_changes(true);
  EXPECT_TRUE(refused());
  const auto before = T::current(d);
  d.insert(&p[2010].x, 500);
  const auto c = d.changes();
  const auto dc = d.device_changes();
  EXPECT_EQ(c.num_previous, T::count(before));
  EXPECT_GT(c.num_new, 0);
  EXPECT_GT(c.num_removed, 0);
  EXPECT_LT(c.num_removed, c.num_previous);  // (most simplices stay)
  ASSERT_EQ(dc.num_simplices, c.num_simplices);
  ASSERT_EQ(dc.backend, gpugeom::Backend::Cpu);
  EXPECT_TRUE(
      std::equal(c.previous_index.begin(), c.previous_index.end(), dc.previous_index.get()));
  EXPECT_TRUE(std::equal(c.removed.begin(), c.removed.end(), dc.removed.get()));
  d.track_changes(false);
  EXPECT_TRUE(refused());
}

}  // namespace gg_test
