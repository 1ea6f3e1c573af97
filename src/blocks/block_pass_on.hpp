// A block's passes over its triangulation where it was made (block_pass.hpp), on either
// executor: the modules' block entries (impl/assemble.inl) triangulate the block's points on its
// device and call block_pass with the result there. Every rule is simplex_rules.hpp's, as in the
// host passes gpugeom.dask runs (borders.cpp, output.cpp), and every list is made in order
// (compact_indices), so the rows are the same on both executors and any thread count.
#pragma once
#include <cstdint>
#include <limits>
#include <memory>
#include <string>

#include "base/clock.hpp"
#include "base/hd.hpp"
#include "blocks/block_pass.hpp"
#include "blocks/simplex_rules.hpp"
#include "exec/atomics.hpp"
#include "exec/exec_context.hpp"
#include "gpugeom/common.hpp"

namespace gpugeom::blocks_detail {

// Flags per simplex.
enum : std::uint8_t { kRequired = 1, kOwned = 2, kTest = 4 };

// The block's cell, grown by the margin (a struct, so that a lambda copies it).
struct OwnBox {
  double lo[3] = {}, hi[3] = {};
};

// pts: the task's n points in the executor's memory; s, nb: the m simplices of its triangulation
// and their neighbours there (D + 1 each, int32, -1 on the hull).
template <int D, class Exec>
void block_pass(Exec& ex, const double* pts, const std::int32_t* s, const std::int32_t* nb,
                std::int64_t m, const BlockTask& t, const FinalTest& final_test, BlockRows& out) {
  constexpr int d1 = D + 1;
  const std::int64_t n = t.n;
  if (m * d1 > std::int64_t(std::numeric_limits<std::int32_t>::max()))
    throw Error(ErrorCode::Unsupported,
                "a block of " + std::to_string(m) +
                    " simplices is too large for its 32-bit output rows: list more devices");
  auto t0 = Clock::now();
  auto blk_b = ex.template alloc<std::int32_t>(std::size_t(n));
  ex.from_host(t.blk, n, blk_b.data());
  const std::int32_t* blk = blk_b.data();
  const std::int32_t block = std::int32_t(t.block);
  const bool first = t.cells != nullptr;
  const BorderCells cells = first ? *t.cells : BorderCells{};
  const Slabs slabs = first ? slabs_of(*t.boxes, D) : Slabs{};
  const double scale = t.scale;
  OwnBox own_box;
  if (first) cells.box(t.block, D, own_box.lo, own_box.hi);
  // the border as bits: per point a word per 32 blocks, a bit per block it goes to
  const std::int64_t words = first ? (cells.total + 31) / 32 : 0;
  auto mark_b = ex.template alloc<std::uint32_t>(std::size_t(n * words));
  std::uint32_t* mark = mark_b.data();
  if (first) ex.fill(mark, n * words, std::uint32_t(0));
  auto flags_b = ex.template alloc<std::uint8_t>(std::size_t(m));
  std::uint8_t* flags = flags_b.data();
  ex.for_each_index(
      m, GG_LAMBDA(std::int64_t i) {
        const std::int32_t* v = s + i * d1;
        std::uint32_t own = 0;
        for (int k = 0; k < d1; ++k)
          if (blk[v[k]] == block) own |= 1u << k;
        std::uint8_t f = own ? kRequired : 0;
        if (blk[v[lowest_at(v, d1)]] == block) f |= kOwned;
        if (first && own) {
          bool inside = false;
          simplex_borders<D>(pts, v, nb + i * d1, own, block, cells, own_box.lo, own_box.hi, scale,
                             &slabs, &inside, [&](std::int64_t to, std::uint32_t places) {
                               for (int k = 0; k < d1; ++k)
                                 if ((places >> k) & 1u)
                                   atomic_or(&mark[std::int64_t(v[k]) * words + to / 32],
                                             std::uint32_t(1u << (to % 32)));
                             });
          if (!inside) f |= kTest;  // (a ball that may reach past the region is tested)
        }
        flags[i] = f;
      });
  auto rows_b = ex.template alloc<std::int32_t>(std::size_t(m));
  std::int32_t* rows = rows_b.data();
  const std::int64_t count = ex.compact_indices(
      m, GG_LAMBDA(std::int64_t i) { return (flags[i] & kOwned) != 0; }, rows);
  if (first) {
    // the simplices to test, as their vertices
    auto list_b = ex.template alloc<std::int32_t>(std::size_t(m));
    std::int32_t* list = list_b.data();
    const std::int64_t nt = ex.compact_indices(
        m, GG_LAMBDA(std::int64_t i) { return (flags[i] & kTest) != 0; }, list);
    auto tv_b = ex.template alloc<std::int32_t>(std::size_t(nt * d1));
    std::int32_t* tv = tv_b.data();
    ex.for_each_index(
        nt * d1,
        GG_LAMBDA(std::int64_t q) { tv[q] = s[std::int64_t(list[q / d1]) * d1 + q % d1]; });
    out.test.resize(std::size_t(nt * d1));
    ex.to_host(tv, nt * d1, out.test.data());
    // per other block, its border
    auto who_b = ex.template alloc<std::int32_t>(std::size_t(n));
    std::int32_t* who = who_b.data();
    for (std::int64_t to = 0; to < cells.total; ++to) {
      if (to == t.block) continue;
      const std::uint32_t bit = 1u << (to % 32);
      const std::uint32_t* word = mark + to / 32;
      const std::int64_t c = ex.compact_indices(
          n, GG_LAMBDA(std::int64_t v) { return (word[v * words] & bit) != 0; }, who);
      if (!c) continue;
      HostVector<std::int32_t> h(static_cast<std::size_t>(c));
      ex.to_host(who, c, h.data());
      out.borders.push_back({to, std::move(h)});
    }
    out.ms_passes = ms_since(t0);
    t0 = Clock::now();
    const bool done = final_test(out);
    out.ms_final = ms_since(t0);
    t0 = Clock::now();
    if (!done) return;
  }
  out.final = true;
  // the output rows: each owned simplex's row, then per face its code (simplex_rules.hpp)
  auto ids_b = ex.template alloc<std::int32_t>(std::size_t(n));
  ex.from_host(t.ids, n, ids_b.data());
  const std::int32_t* ids = ids_b.data();
  auto pos_b = ex.template alloc<std::int32_t>(std::size_t(m));
  std::int32_t* pos = pos_b.data();
  ex.fill(pos, m, std::int32_t(-1));
  ex.for_each_index(
      count, GG_LAMBDA(std::int64_t r) { pos[rows[r]] = std::int32_t(r); });
  const std::int64_t cellsn = count * d1;
  auto os_b = ex.template alloc<std::int32_t>(std::size_t(cellsn));
  auto on_b = ex.template alloc<std::int32_t>(std::size_t(cellsn));
  std::int32_t* os = os_b.data();
  std::int32_t* on = on_b.data();
  ex.for_each_index(
      cellsn, GG_LAMBDA(std::int64_t c) {
        const std::int64_t row = rows[c / d1];
        const int k = int(c % d1);
        const std::int32_t* v = s + row * d1;
        const std::int32_t to = nb[row * d1 + k];
        os[c] = ids[v[k]];
        on[c] = std::int32_t(face_code(v, d1, k, to, to < 0 ? -1 : std::int64_t(pos[to]),
                                       [&](std::int32_t u) { return blk[u]; }));
      });
  auto req_b = ex.template alloc<std::int32_t>(std::size_t(cellsn));
  std::int32_t* req = req_b.data();
  const std::int64_t q = ex.compact_indices(
      cellsn, GG_LAMBDA(std::int64_t c) { return on[c] < -1; }, req);
  auto key_b = ex.template alloc<std::int32_t>(std::size_t(q * D));
  auto owner_b = ex.template alloc<std::int32_t>(std::size_t(q));
  auto open_b = ex.template alloc<std::uint8_t>(std::size_t(q));
  std::int32_t* key = key_b.data();
  std::int32_t* owner = owner_b.data();
  std::uint8_t* open = open_b.data();
  ex.for_each_index(
      q, GG_LAMBDA(std::int64_t i) {
        const std::int64_t c = req[i];
        open[i] = on[c] == -3 ? 1 : 0;
        const std::int32_t* v = s + std::int64_t(rows[c / d1]) * d1;
        const std::int32_t low = request_key(
            v, d1, int(c % d1), [&](std::int32_t u) { return ids[u]; }, key + i * D);
        owner[i] = blk[low];
      });
  ex.for_each_index(
      q, GG_LAMBDA(std::int64_t i) { on[req[i]] = -2; });
  out.request_pos.resize(std::size_t(q));
  out.request_key.resize(std::size_t(q * D));
  out.request_owner.resize(std::size_t(q));
  out.request_open.resize(std::size_t(q));
  ex.to_host(req, q, out.request_pos.data());
  ex.to_host(key, q * D, out.request_key.data());
  ex.to_host(owner, q, out.request_owner.data());
  ex.to_host(open, q, out.request_open.data());
  out.count = count;
  if constexpr (Exec::backend == Backend::Cuda) out.device = ex.device();
  out.simplices = os_b.hand_over();  // (after the copies above, which waited for the stream)
  out.neighbors = on_b.hand_over();
  out.ms_output = ms_since(t0);
}

// A block's triangulation where the executor holds it (the module's device entry's arrays).
struct DeviceSimplices {
  std::shared_ptr<std::int32_t> s, nb;
  std::int64_t m = 0;
};

// The task's points gathered from `source` by their places, into pts (executor memory): a
// sixth of the bytes cross from the host, a place and not D coordinates. (Apart from run_block:
// a device lambda may not sit in a template over the caller's lambda type.)
template <int D, class Exec>
void gather_places(Exec& ex, const BlockTask& t, double* pts) {
  auto places_b = ex.template alloc<std::int32_t>(std::size_t(t.n));
  ex.from_host(t.places, t.n, places_b.data());
  const std::int32_t* places = places_b.data();
  const double* source = t.source;
  ex.for_each_index(
      t.n * D,
      GG_LAMBDA(std::int64_t i) { pts[i] = source[std::int64_t(places[i / D]) * D + i % D]; });
}

// The modules' block entry (Assembly::block): the task's points copied or gathered to the
// executor once, triangulated there by triangulate(points, context) (the module's device entry,
// on this executor's stream and memory), and the passes.
template <int D, class Exec, class Triangulate>
void run_block(Exec& ex, const BlockTask& t, const FinalTest& final_test, BlockRows& out,
               Triangulate&& triangulate) {
  const auto t0 = Clock::now();
  auto pts = ex.template alloc<double>(std::size_t(t.n * D));
  if (t.source)
    gather_places<D>(ex, t, pts.data());
  else
    ex.from_host(t.points, t.n * D, pts.data());
  const detail::ExecContext ctx = ex.context();
  const DeviceSimplices tri = triangulate(pts.data(), &ctx);
  out.ms_triangulate = ms_since(t0);
  block_pass<D>(ex, pts.data(), tri.s.get(), tri.nb.get(), tri.m, t, final_test, out);
}

}  // namespace gpugeom::blocks_detail
