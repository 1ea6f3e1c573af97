// Faulting in the pages of result arrays while the device computes (internal). A fresh result
// array costs its page faults on first write: on the lent H100 host, copying out of pinned
// staging into fresh pages runs at 8-30 GB/s on 16 threads (4 kB or huge pages), into touched pages
// at 66 GB/s (bench/bench_bus.cu). A module that knows a bound of its result before the device work
// starts sizes the host arrays to it (HostVector: no fill) and hands them here; host threads fault
// them in during the device work, and the copy back then runs at the transfer's rate.
#pragma once
#include <cstddef>
#include <thread>
#include <utility>
#include <vector>

namespace gpugeom::detail {

// Asks for transparent huge pages on a HostAllocator block (from 2 MB up, as host_map mapped
// it; anything else is left alone) before its first touch. Only the CUDA executor's results
// ask (deliver.hpp, Prefault::add): there the copy back from pinned staging faults the pages on
// every host thread, and on the lent GPU host huge pages made that 2.5 times faster (10^7
// points in 3D: 945 against 1 137 ms end to end). The CPU executor's results are written by its
// own threads, where on a host that must make each huge page first (direct compaction, a virtual
// machine's reported free memory) the first touch stalled: 750 against 207 ms for 216 MB on the
// 2-core machine. docs/design-notes.md, issue 53's fourth step.
void advise_huge_pages(void* p, std::size_t bytes) noexcept;

class Prefault {
 public:
  Prefault() = default;
  Prefault(const Prefault&) = delete;
  Prefault& operator=(const Prefault&) = delete;
  ~Prefault() { wait(); }
  // Spans to fault in (call before start()).
  void add(void* p, std::size_t bytes) {
    if (!p || !bytes) return;
    advise_huge_pages(p, bytes);  // (the GPU's results: see above)
    spans_.emplace_back(static_cast<char*>(p), bytes);
  }
  // Faults the spans in on a background thread and its helpers (all host threads but two: the
  // caller keeps driving the device). Nothing to do below a few megabytes.
  void start();
  // Returns once every page is in (a no-op when nothing was started).
  void wait() noexcept {
    if (t_.joinable()) t_.join();
  }

 private:
  std::vector<std::pair<char*, std::size_t>> spans_;
  std::thread t_;
};

}  // namespace gpugeom::detail
