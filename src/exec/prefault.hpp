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

class Prefault {
 public:
  Prefault() = default;
  Prefault(const Prefault&) = delete;
  Prefault& operator=(const Prefault&) = delete;
  ~Prefault() { wait(); }
  // Spans to fault in (call before start()).
  void add(void* p, std::size_t bytes) {
    if (p && bytes) spans_.emplace_back(static_cast<char*>(p), bytes);
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
