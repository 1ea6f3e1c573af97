// What the structures that follow their points share (internal; DynamicDelaunay2d,
// DynamicDelaunay3d and DynamicHull3d, issue 47): the kept state behind an executor-independent
// interface (KeptUpdates, KeptState), its calls checked and timed, and the stats of the last
// call that succeeded.
#pragma once
#include <chrono>
#include <cstdint>
#include <memory>
#include <string>
#include <type_traits>
#include <utility>

#include "gpugeom/changes.hpp"
#include "gpugeom/common.hpp"

namespace gpugeom::detail {

// A structure's state on one executor (each module's impl/dynamic.inl): the points and the
// simplices (triangles, tetrahedra, hull facets), kept in the executor's memory between calls.
// Every call that throws leaves the state unchanged. The calls' statistics are the results'.
template <class Output, class DeviceOutput>
class KeptUpdates {
 public:
  using Stats = decltype(std::declval<Output&>().stats);
  virtual ~KeptUpdates() = default;
  // Appends n points (executor memory when on_device, else host memory), numbered from points()
  // on, and brings the triangulation up to date. Throws as the module's triangulate.
  virtual void insert(const double* p, std::int64_t n, bool on_device, Stats& st) = 0;
  // New coordinates for all points() points (as insert's), and the triangulation brought up to
  // date: repaired from the kept one where that is still a triangulation of the moved points,
  // else made afresh. Throws as insert.
  virtual void move(const double* p, bool on_device, Stats& st) = 0;
  // Removes `count` points by index (executor memory when on_device): they are no vertices any
  // more and keep their indices (duplicate_of kRemovedPoint). Throws Error(InvalidArgument) for
  // an index out of range, given twice or removed before, and as insert where too few points
  // would be left.
  virtual void remove(const std::int32_t* idx, std::int64_t count, bool on_device, Stats& st) = 0;
  virtual std::int64_t points() const = 0;     // all indices given so far
  virtual std::int64_t removed() const = 0;    // of them removed
  virtual std::int64_t simplices() const = 0;  // in the results
  // Copies of the current results: to host vectors, or to new executor arrays handed over.
  virtual void host_copy(Output& out) const = 0;
  virtual void device_copy(DeviceOutput& out) const = 0;
  // Which simplices the last update changed: with tracking on, each update keeps the state it
  // replaces (a second copy of the state between calls), and the changes compare the results
  // before and after it (mesh/simplex_changes.hpp). has_changes: an update ran with tracking on.
  virtual void track_changes(bool on) = 0;
  virtual bool has_changes() const = 0;
  virtual void host_changes(SimplexChanges& out) const = 0;
  virtual void device_changes(DeviceSimplexChanges& out) const = 0;
};

// A triangulation's state (DynamicDelaunay2d / 3d): also the duplicate map.
template <class Output, class DeviceOutput>
class KeptState : public KeptUpdates<Output, DeviceOutput> {
 public:
  virtual std::int64_t duplicates() const = 0;
};

// The arrays before the last update, kept while changes are tracked (KeptState::track_changes).
template <class Arrays>
struct Before {
  Arrays arrays;
  bool track = false, held = false;
  // now becomes next; the arrays it held are kept when tracking.
  void commit(Arrays& now, Arrays&& next) {
    if (track) arrays = std::move(now), held = true;
    now = std::move(next);
  }
  void set(bool on) {
    track = on;
    if (!on) arrays = Arrays(), held = false;
  }
};

template <class Kept>
struct DynamicState {
  using Stats = typename Kept::Stats;
  std::unique_ptr<Kept> kept;
  Backend backend = Backend::Cpu;
  Stats stats;

  // Appends n points (executor memory when on_device); check(total) refuses a total count the
  // structure cannot take. The stats are replaced only once the insertion succeeded.
  template <class Check>
  void insert(const double* p, std::int64_t n, bool on_device, Check check) {
    if (n < 0) throw Error(ErrorCode::InvalidArgument, "negative point count");
    check(kept->points() + n);
    timed([&](Stats& st) { kept->insert(p, n, on_device, st); });
  }
  // New coordinates for all n points (n must be the count kept).
  void move(const double* p, std::int64_t n, bool on_device) {
    if (n != kept->points())
      throw Error(ErrorCode::InvalidArgument,
                  "move: " + std::to_string(n) + " points given for a triangulation of " +
                      std::to_string(kept->points()) + " (give new coordinates for every point)");
    timed([&](Stats& st) { kept->move(p, on_device, st); });
  }
  // The changes of the last update (cls names the class in the message).
  SimplexChanges changes(const char* cls) const {
    require_changes(cls);
    SimplexChanges c;
    kept->host_changes(c);
    return c;
  }
  DeviceSimplexChanges device_changes(const char* cls) const {
    require_changes(cls);
    DeviceSimplexChanges c;
    kept->device_changes(c);
    c.backend = backend;
    return c;
  }
  // Removes count points by index.
  void remove(const std::int32_t* idx, std::int64_t count, bool on_device) {
    if (count < 0) throw Error(ErrorCode::InvalidArgument, "remove: negative index count");
    if (count > kept->points())
      throw Error(ErrorCode::InvalidArgument, "remove: " + std::to_string(count) +
                                                  " indices given for a triangulation of " +
                                                  std::to_string(kept->points()) + " points");
    timed([&](Stats& st) { kept->remove(idx, count, on_device, st); });
  }

 private:
  void require_changes(const char* cls) const {
    if (!kept->has_changes())
      throw Error(ErrorCode::InvalidArgument,
                  std::string(cls) +
                      "::changes: no update since track_changes(true); turn tracking on before "
                      "the update whose changes you want");
  }
  // Runs call(st) with fresh stats, kept (with the total time) once it succeeded.
  template <class Call>
  void timed(Call call) {
    Stats st;
    st.backend = backend;
    const auto t0 = std::chrono::steady_clock::now();
    call(st);
    st.phase_ms.push_back(
        {"total",
         std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count()});
    stats = std::move(st);
  }
};

}  // namespace gpugeom::detail
