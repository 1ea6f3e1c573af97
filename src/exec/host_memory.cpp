// Large result blocks of HostAllocator (include/gpugeom/host_vector.hpp): fresh anonymous
// pages, huge pages asked for. Measured on the lent H100 host (bench/bench_bus.cu): touching
// 256 MB of fresh 4 kB pages costs 155 ms on one thread and 31 ms on 16; with huge pages 77 and
// 12 ms. The library's copies into these blocks run on all threads, so they get the last rate.
#include <cstddef>
#include <cstdint>
#include <new>
#include <sys/mman.h>

#include "gpugeom/host_vector.hpp"

namespace gpugeom::detail {

namespace {
constexpr std::uintptr_t kHuge = std::uintptr_t(2) << 20, kPage = 4096;
std::size_t whole_pages(std::size_t bytes) {
  return (bytes + kPage - 1) & ~std::size_t(kPage - 1);
}
}  // namespace

// Mapped with a huge page of slack and trimmed to start on a 2 MB boundary, so that every
// whole 2 MB of the block can be a huge page.
void* host_map(std::size_t bytes) {
  const std::size_t len = whole_pages(bytes), span = len + kHuge;
  void* m = mmap(nullptr, span, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
  if (m == MAP_FAILED) throw std::bad_alloc();
  const std::uintptr_t b = reinterpret_cast<std::uintptr_t>(m);
  const std::uintptr_t a = (b + kHuge - 1) & ~(kHuge - 1);
  if (a > b) (void)munmap(m, a - b);
  if (b + span > a + len) (void)munmap(reinterpret_cast<void*>(a + len), b + span - (a + len));
  void* p = reinterpret_cast<void*>(a);
#ifdef MADV_HUGEPAGE
  (void)madvise(p, len, MADV_HUGEPAGE);  // a failure only means small pages
#endif
  return p;
}

void host_unmap(void* p, std::size_t bytes) noexcept {
  if (p) (void)munmap(p, whole_pages(bytes));
}

}  // namespace gpugeom::detail
