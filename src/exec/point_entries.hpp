// The table of entries of a capability computed from points alone (2D and 3D Delaunay, the 3D
// hull), and the public entries' bodies over it (internal). The three modules' tables had the
// same three pointers under different names; the public entries the same body around them.
#pragma once
#include <cstdint>
#include <memory>
#include <string>
#include <type_traits>
#include <utility>

#include "exec/deliver.hpp"
#include "exec/dispatch.hpp"
#include "exec/exec_context.hpp"
#include "gpugeom/common.hpp"

namespace gpugeom::detail {

// Options: the capability's (deriving from RunOptions). HostResult, DeviceResult: its results in
// each memory space, whose fields the backends fill (their backend and counts the entries below
// set). Kept: its dynamic class's state (exec/dynamic_state.hpp).
template <class Options, class HostResult, class DeviceResult, class Kept>
struct PointEntries {
  using Host = HostResult;
  using Device = DeviceResult;
  using RunStats = decltype(std::declval<HostResult&>().stats);
  // A dynamic structure's state on this executor, before its first points.
  std::unique_ptr<Kept> (*make_kept)(const Options& opt);
  // host: n points in host memory; device: n points in the executor's memory, run on `outer`'s
  // stream and memory where given (a capability calling this one: exec/exec_context.hpp), else
  // on the options'. Both validate the coordinates on the executor (throw Error) and honour
  // opt.into. (The public entries' checks of n and the options are the caller's.)
  void (*host)(const double* p, std::int64_t n, const Options& opt, HostResult& out,
               RunStats& stats);
  void (*device)(const double* p, std::int64_t n, const Options& opt, DeviceResult& out,
                 RunStats& stats, const ExecContext* outer);
};

// A table's make_kept on one executor: the state K (deriving from Kept) with the options the
// executor keeps across calls (its kept_options).
template <class Kept, class K, class Exec, class Options>
std::unique_ptr<Kept> make_kept_on(const Options& opt) {
  return std::make_unique<K>(Exec::kept_options(opt));
}

// The public host entry's run, after its checks: the executor the options resolve to.
// pick(backend) gives the module's table on that executor (GG_PICK below).
template <class Pick, class Options>
auto run_host_entry(Pick pick, const double* p, std::int64_t n, const Options& opt) {
  using Table = std::decay_t<decltype(pick(Backend::Cpu))>;
  typename Table::Host r;
  const Backend b = resolve_backend(opt.backend, opt.device);
  r.stats.backend = b;
  pick(b).host(p, n, opt, r, r.stats);
  return r;
}

// The public device entry's run, after its checks: the executor that holds the caller's memory
// (`name` is the entry's, for the error when there is none).
template <class Pick, class Options>
auto run_device_entry(Pick pick, const double* device_p, std::int64_t n, const Options& opt,
                      const char* name) {
  using Table = std::decay_t<decltype(pick(Backend::Cpu))>;
  typename Table::Device r;
  const Backend b = device_entry_backend(opt.backend, opt.device, name);
  r.backend = r.stats.backend = b;
  r.num_points = n;
  pick(b).device(device_p, n, opt, r, r.stats, nullptr);
  return r;
}

}  // namespace gpugeom::detail

// A function from a backend to module NS's table of entries (exec/dispatch.hpp's GG_ENTRIES).
#define GG_PICK(ns) [](::gpugeom::Backend b_) -> const ns::Entries& { return GG_ENTRIES(b_, ns); }
