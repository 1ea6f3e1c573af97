/// @file
/// The host arrays results come in: std::vector with an allocator made for arrays the library
/// writes whole (issue 18, "results at bus speed").
///
/// A plain std::vector<T>(n) writes n zeros on one thread before the library can copy a result
/// into it; on the lent H100 host that took 177 ms for 256 MB, 35x the 5 ms the link needs to
/// bring the same bytes back. A HostVector's resize(n) leaves new elements of arithmetic type
/// uninitialised (as `new T[n]` does), and blocks from 2 MB up are fresh, 2 MB-aligned pages
/// (huge pages asked for where the GPU's results are copied in; not where the CPU executor's
/// threads write them, as making one can stall the thread that touches it first): the library's
/// copy back then touches each page once, on all the threads that copy.
///
/// Everything else is std::vector: data(), size(), iterators, move, swap. Use resize(n, value)
/// or assign(n, value) where elements must start with a value. To hand the memory elsewhere
/// (a NumPy array, say), move the vector into an owner that outlives the view.
#pragma once
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <new>
#include <type_traits>
#include <utility>
#include <vector>

namespace gpugeom {

namespace detail {
/// Large blocks: anonymous pages mapped for the block, 2 MB-aligned, unmapped when freed
/// (never recycled through the C heap, so they come back untouched). Throws std::bad_alloc.
void* host_map(std::size_t bytes);
void host_unmap(void* p, std::size_t bytes) noexcept;
constexpr std::size_t kHostMapMin = std::size_t(2) << 20;
}  // namespace detail

template <class T>
/// The allocator of HostVector: memory that is not zero-filled on allocation, so that the threads
/// that write a result fault its pages in themselves.
struct HostAllocator {
  /// The element type.
  using value_type = T;
  HostAllocator() noexcept = default;
  template <class U>
  HostAllocator(const HostAllocator<U>&) noexcept {}

  /// n elements, uninitialised.
  T* allocate(std::size_t n) {
    if (n > std::size_t(-1) / sizeof(T)) throw std::bad_alloc();
    const std::size_t bytes = n * sizeof(T);
    if (bytes >= detail::kHostMapMin) return static_cast<T*>(detail::host_map(bytes));
    return static_cast<T*>(
        ::operator new(bytes, std::align_val_t(alignof(T) > 16 ? alignof(T) : 16)));
  }
  /// Frees what allocate gave.
  void deallocate(T* p, std::size_t n) noexcept {
    const std::size_t bytes = n * sizeof(T);
    if (bytes >= detail::kHostMapMin)
      detail::host_unmap(p, bytes);
    else
      ::operator delete(p, std::align_val_t(alignof(T) > 16 ? alignof(T) : 16));
  }
  /// Default construction of arithmetic elements does nothing: the library writes them all.
  /// Default-initialises (leaves trivial types unset: the point of the allocator).
  template <class U>
  void construct(U* p) noexcept(std::is_nothrow_default_constructible_v<U>) {
    ::new (static_cast<void*>(p)) U;
  }
  /// Constructs from args, as std::allocator does.
  template <class U, class... Args>
  void construct(U* p, Args&&... args) {
    ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
  }
  template <class U>
  bool operator==(const HostAllocator<U>&) const noexcept {
    return true;
  }
  template <class U>
  bool operator!=(const HostAllocator<U>&) const noexcept {
    return false;
  }
};

template <class T>
/// A std::vector whose growth leaves elements uninitialised: the host arrays of every result.
using HostVector = std::vector<T, HostAllocator<T>>;

/// Element-wise comparison with a plain vector (tests and callers compare results with
/// expectations held in std::vector).
/// Element-wise equality with a std::vector of another allocator.
template <class T, class A, class = std::enable_if_t<!std::is_same_v<A, HostAllocator<T>>>>
bool operator==(const HostVector<T>& a, const std::vector<T, A>& b) {
  return a.size() == b.size() && std::equal(a.begin(), a.end(), b.begin());
}
/// Element-wise equality with a std::vector of another allocator.
template <class T, class A, class = std::enable_if_t<!std::is_same_v<A, HostAllocator<T>>>>
bool operator==(const std::vector<T, A>& a, const HostVector<T>& b) {
  return b == a;
}

}  // namespace gpugeom
