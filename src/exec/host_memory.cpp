// Large result blocks of HostAllocator (include/gpugeom/host_vector.hpp): fresh anonymous
// pages, 2 MB-aligned, so that each whole 2 MB can be a huge page. Huge pages are asked for
// (advise_huge_pages) only for the CUDA executor's results, whose copy back they made faster on
// the lent GPU host (bench/bench_bus.cu: touching 256 MB of fresh 4 kB pages costs 155 ms on
// one thread and 31 ms on 16; with huge pages 77 and 12 ms). Where the kernel must make a huge
// page first (direct compaction, the default `defrag` policy for blocks that ask), or where a
// virtual machine's host must back it again (free page reporting), the faulting thread waits:
// on the 2-core machine the CPU executor's 216 MB of a 10^6-point 3D triangulation took 750 ms
// to write with huge pages asked for and 207 ms without (docs/design-notes.md, issue 53's fourth
// step). A kernel set to give huge pages to every block (THP "always") still gives them.
#include <algorithm>
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <new>
#include <sys/mman.h>
#include <thread>
#include <vector>

#include "exec/prefault.hpp"
#include "gpugeom/host_vector.hpp"

#ifndef MADV_POPULATE_WRITE
#define MADV_POPULATE_WRITE 23  // Linux 5.14; older kernels refuse it (the touch loop runs)
#endif

namespace gpugeom::detail {

namespace {
constexpr std::uintptr_t kHuge = std::uintptr_t(2) << 20, kPage = 4096;
std::size_t whole_pages(std::size_t bytes) {
  return (bytes + kPage - 1) & ~std::size_t(kPage - 1);
}
}  // namespace

// Mapped with a huge page of slack and trimmed to start on a 2 MB boundary, so that every
// whole 2 MB of the block can be a huge page where the kernel gives them unasked.
void* host_map(std::size_t bytes) {
  const std::size_t len = whole_pages(bytes), span = len + kHuge;
  void* m = mmap(nullptr, span, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
  if (m == MAP_FAILED) throw std::bad_alloc();
  const std::uintptr_t b = reinterpret_cast<std::uintptr_t>(m);
  const std::uintptr_t a = (b + kHuge - 1) & ~(kHuge - 1);
  if (a > b) (void)munmap(m, a - b);
  if (b + span > a + len) (void)munmap(reinterpret_cast<void*>(a + len), b + span - (a + len));
  return reinterpret_cast<void*>(a);
}

void advise_huge_pages(void* p, std::size_t bytes) noexcept {
  const std::uintptr_t a = reinterpret_cast<std::uintptr_t>(p);
  if (!p || bytes < kHostMapMin || (a & (kHuge - 1))) return;  // (not a host_map block)
#ifdef MADV_HUGEPAGE
  (void)madvise(p, whole_pages(bytes), MADV_HUGEPAGE);  // a failure only means small pages
#endif
}

void host_unmap(void* p, std::size_t bytes) noexcept {
  if (p) (void)munmap(p, whole_pages(bytes));
}

void Prefault::start() {
  std::size_t total = 0;
  for (auto& s : spans_) total += s.second;
  if (total < (std::size_t(8) << 20) || t_.joinable()) return;
  try {
    t_ = std::thread([spans = spans_] {
      // 8 MB pieces taken from a shared counter by all host threads but two.
      constexpr std::size_t kPiece = std::size_t(8) << 20;
      std::vector<std::pair<char*, std::size_t>> pieces;
      for (auto& s : spans)
        for (std::size_t at = 0; at < s.second; at += kPiece)
          pieces.emplace_back(s.first + at, std::min(kPiece, s.second - at));
      std::atomic<std::size_t> next{0};
      auto work = [&] {
        for (std::size_t i; (i = next.fetch_add(1)) < pieces.size();) {
          char* p = pieces[i].first;
          const std::size_t len = pieces[i].second;
          // The kernel faults the whole range in at once, where it can (page-aligned start).
          const std::uintptr_t a = reinterpret_cast<std::uintptr_t>(p);
          const std::uintptr_t b = (a + kPage - 1) & ~(kPage - 1);
          bool done = false;
          if (b < a + len)
            done = madvise(reinterpret_cast<void*>(b), (a + len - b) & ~(kPage - 1),
                           MADV_POPULATE_WRITE) == 0;
          if (!done)
            for (std::size_t k = 0; k < len; k += kPage) reinterpret_cast<volatile char*>(p)[k] = 0;
        }
      };
      const unsigned hw = std::max(3u, std::thread::hardware_concurrency());
      const std::size_t helpers = std::min<std::size_t>(hw - 3, pieces.size());
      std::vector<std::thread> th;
      try {
        for (std::size_t k = 0; k < helpers; ++k) th.emplace_back(work);
      } catch (...) {  // no more threads: fewer hands, same work (an optimisation only)
      }
      work();
      for (auto& t : th) t.join();
    });
  } catch (...) {  // no thread to be had: the copy back faults the pages in itself
  }
}

}  // namespace gpugeom::detail
