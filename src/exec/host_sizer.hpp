// Result arrays sized on other threads while the executor works (host side, both executors):
// zero-filling and first-touching hundreds of megabytes of std::vector costs as much as copying
// them (a page fault per 4 kB on the lent machine: 116 MB took 66 ms). Each array gets its own
// thread, and huge pages where the kernel offers them (a fault per 2 MB). The caller sizes each
// array for an upper bound of the result and cuts it to size once the result is known (cutting
// keeps the pages).
#pragma once
#include <cstdint>
#include <deque>
#include <exception>
#include <new>
#include <string>
#include <sys/mman.h>
#include <thread>
#include <vector>

#include "gpugeom/common.hpp"

namespace gpugeom {

class HostSizer {
 public:
  HostSizer() = default;
  HostSizer(const HostSizer&) = delete;
  HostSizer& operator=(const HostSizer&) = delete;
  ~HostSizer() {
    for (auto& t : threads_)
      if (t.joinable()) t.join();
  }

  // Starts sizing v to n copies of fill (v must outlive join()). `what` names it in the error.
  template <class T>
  void add(std::vector<T>& v, std::int64_t n, T fill, const char* what) {
    errors_.emplace_back();
    std::exception_ptr* err = &errors_.back();
    threads_.emplace_back([&v, n, fill, what, err] {
      try {
        v.clear();
        v.reserve(std::size_t(n));
        advise_huge(v.data(), std::size_t(n) * sizeof(T));
        v.assign(std::size_t(n), fill);
      } catch (const std::bad_alloc&) {  // an exception may not leave a thread
        *err = std::make_exception_ptr(
            Error(ErrorCode::OutOfMemory, "host allocation of " +
                                              std::to_string(std::size_t(n) * sizeof(T)) +
                                              " bytes for the " + what + " failed"));
      }
    });
  }

  // Waits for every array; a failed allocation surfaces here as Error(OutOfMemory).
  void join() {
    for (auto& t : threads_)
      if (t.joinable()) t.join();
    for (const auto& e : errors_)
      if (e) std::rethrow_exception(e);
  }

  bool started() const { return !threads_.empty(); }

 private:
  static void advise_huge(void* p, std::size_t bytes) {
#ifdef MADV_HUGEPAGE
    const std::uintptr_t a = (reinterpret_cast<std::uintptr_t>(p) + 0x1FFFFF) & ~0x1FFFFFull;
    const std::uintptr_t e = (reinterpret_cast<std::uintptr_t>(p) + bytes) & ~0x1FFFFFull;
    if (e > a) (void)madvise(reinterpret_cast<void*>(a), e - a, MADV_HUGEPAGE);
#else
    (void)p;
    (void)bytes;
#endif
  }
  // (a deque: its elements stay put while threads write into them)
  std::vector<std::thread> threads_;
  std::deque<std::exception_ptr> errors_;
};

}  // namespace gpugeom
