// Handing a computation's output arrays to the caller (internal), the one way every capability
// does it: into the caller's own arrays (OutBuffer, the `into` options) when given, else into
// arrays of the library's: HostVector for the host entry points, executor memory handed over as
// a shared pointer for the device entry points (on the CPU executor "device" memory is host
// memory). Outputs whose length depends on the result (triangles, facets) are checked once the
// length is known and before anything is written, so a refused call leaves the caller's arrays
// untouched.
#pragma once
#include <cstdint>
#include <memory>
#include <string>

#include "gpugeom/common.hpp"
#include "exec/prefault.hpp"
#include "gpugeom/host_vector.hpp"

namespace gpugeom::deliver {

// Throws Error(InvalidArgument) when `into` is given and holds fewer than `need` elements (or
// not exactly `need` where `exact`), naming the option and both lengths.
template <class T>
void check(const OutBuffer<T>& into, std::int64_t need, const char* name, bool exact = false) {
  if (!into) return;
  if (into.size < 0 || (exact ? into.size != need : into.size < need))
    throw Error(ErrorCode::InvalidArgument, std::string("into.") + name + " holds " +
                                                std::to_string(into.size) +
                                                " elements; this result needs " +
                                                (exact ? "" : "at least ") + std::to_string(need));
}

// Host entry: `count` elements of executor memory to the caller's host array, or to `host`.
template <class Exec, class T>
void to_host(Exec& ex, const T* src, std::int64_t count, const OutBuffer<T>& into,
             HostVector<T>& host) {
  T* dst = into.data;
  if (!dst) {
    host.resize(std::size_t(count));  // (no fill: the copy touches the pages)
    dst = host.data();
    if constexpr (Exec::backend == Backend::Cuda)
      detail::advise_huge_pages(dst, std::size_t(count) * sizeof(T));  // (prefault.hpp says why)
  }
  ex.to_host(src, count, dst);
}

// Host entry: `count` copies of v, where the executor holds no array for them.
template <class Exec, class T>
void fill_host(Exec& ex, std::int64_t count, T v, const OutBuffer<T>& into, HostVector<T>& host) {
  T* dst = into.data;
  if (!dst) {
    host.resize(std::size_t(count));
    dst = host.data();
    if constexpr (Exec::backend == Backend::Cuda)
      detail::advise_huge_pages(dst, std::size_t(count) * sizeof(T));
  }
  ex.fill_host(dst, count, v);
}

// Device entry: the first `count` elements of the executor array `buf` to the caller's array
// (a copy on the executor; returns null), or `buf` itself, handed over. The copy is queued on
// the executor; call ex.sync() before the caller may read it (the device entries return once
// their results are ready), and on CUDA before hand_over's owner may free it (the caller may
// drop it on another thread or after using it on another stream): use in two steps, place()
// then own().
template <class Exec, class T>
struct Placed {
  typename Exec::template Buffer<T>* buf = nullptr;  // the library's array, unless copied away
  std::shared_ptr<T> own() { return buf ? buf->hand_over() : std::shared_ptr<T>(); }
};
template <class Exec, class T>
Placed<Exec, T> place(Exec& ex, typename Exec::template Buffer<T>& buf, std::int64_t count,
                      const OutBuffer<T>& into) {
  if (!into) return {&buf};
  if (count > 0) ex.copy(buf.data(), count, into.data);
  return {};
}

// Device entry, for an array already handed over (shared, e.g. another capability's result):
// its first `count` elements copied to the caller's array, where given (queued on the executor,
// as place()'s). Returns whether it was: the caller drops the array after ex.sync().
template <class Exec, class T>
bool place_shared(Exec& ex, const std::shared_ptr<T>& arr, std::int64_t count,
                  const OutBuffer<T>& into) {
  if (!into) return false;
  if (count > 0) ex.copy(arr.get(), count, into.data);
  return true;
}

}  // namespace gpugeom::deliver

namespace gpugeom {
// The executor of a device entry point: the CPU's where Backend::Cpu was asked for (its
// "device" memory is host memory), else CUDA's, ignoring GPUGEOM_BACKEND (a device pointer
// cannot be read on the CPU); throws Error(Unsupported), naming `entry`, where no CUDA device
// can be used.
Backend device_entry_backend(Backend requested, int device, const char* entry);
}  // namespace gpugeom
