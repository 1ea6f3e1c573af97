// Pinned staging for large host <-> device copies (see host_staging.hpp).
#include "exec/host_staging.hpp"

#include <algorithm>
#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <mutex>
#include <omp.h>
#include <string>
#include <thread>
#include <vector>

#include "gpugeom/common.hpp"

namespace gpugeom::staging {

namespace {

constexpr std::size_t kChunk = std::size_t(32) << 20;

void check(cudaError_t e, const char* what) {
  if (e != cudaSuccess)
    throw Error(e == cudaErrorMemoryAllocation ? ErrorCode::OutOfMemory : ErrorCode::Cuda,
                std::string(what) + ": " + cudaGetErrorString(e));
}

// Two pinned buffers and their events, made once per process on first use and kept (pinning
// is slow; keeping 64 MB pinned is cheap). One copy at a time uses them.
struct Pool {
  void* buf[2] = {nullptr, nullptr};
  cudaEvent_t ev[2];
  std::mutex busy;
  Pool() {
    for (int i = 0; i < 2; ++i) {
      check(cudaMallocHost(&buf[i], kChunk), "pinned staging buffer");
      check(cudaEventCreateWithFlags(&ev[i], cudaEventDisableTiming), "staging event");
    }
  }
};
Pool& pool() {
  static Pool* p = [] {
    Pool* q = new Pool;
    // Freed before the CUDA runtime's own exit handler runs (registered after it), so leak
    // checkers see no pinned memory left behind.
    std::atexit([] {
      Pool& r = pool();
      for (int i = 0; i < 2; ++i) {
        (void)cudaFreeHost(r.buf[i]);
        (void)cudaEventDestroy(r.ev[i]);
      }
    });
    return q;
  }();
  return *p;
}

// One pinned page for small reads, made on first use (apart from the large buffers, so that
// a program that only reads counters never pins 64 MB).
struct Mailbox {
  void* buf = nullptr;
  std::mutex busy;
  Mailbox() { check(cudaMallocHost(&buf, kMailBytes), "pinned mailbox"); }
};
Mailbox& mailbox() {
  static Mailbox* m = [] {
    Mailbox* q = new Mailbox;
    std::atexit([] { (void)cudaFreeHost(mailbox().buf); });
    return q;
  }();
  return *m;
}

// memcpy over the cores: one thread cannot keep up with the link. Not an OpenMP region: its
// closing barrier waits for every thread, and on a virtual machine a core left idle while the
// GPU works can take milliseconds to wake (seen on the lent H100 host: a 24 MB copy at 1.0 ms
// most times, 3.5-6.6 ms after idle). Here the calling thread and whichever helpers are awake
// take 1 MB pieces from a shared counter, and the copy is done when the pieces are, whether or
// not every helper ever woke up.
class CopyPool {
 public:
  static CopyPool& get() {
    static CopyPool p;
    return p;
  }
  void copy(void* dst, const void* src, std::size_t bytes) {
    Job j;
    j.dst = static_cast<char*>(dst);
    j.src = static_cast<const char*>(src);
    j.bytes = bytes;
    j.pieces = (bytes + kPiece - 1) / kPiece;
    if (helpers_.empty() || j.pieces < 2) {
      std::memcpy(dst, src, bytes);
      return;
    }
    {
      std::lock_guard<std::mutex> lk(m_);
      job_ = &j;
      ++gen_;
    }
    cv_.notify_all();
    work(j);
    while (j.done.load(std::memory_order_acquire) < j.pieces) std::this_thread::yield();
    // Withdraw the job; helpers that took it are awake and leave at once (no pieces left).
    std::unique_lock<std::mutex> lk(m_);
    job_ = nullptr;
    idle_.wait(lk, [&] { return active_ == 0; });
  }

 private:
  static constexpr std::size_t kPiece = std::size_t(1) << 20;
  struct Job {
    char* dst;
    const char* src;
    std::size_t bytes = 0, pieces = 0;
    std::atomic<std::size_t> next{0}, done{0};
  };
  static void work(Job& j) {
    for (std::size_t i; (i = j.next.fetch_add(1, std::memory_order_relaxed)) < j.pieces;) {
      const std::size_t off = i * kPiece, len = std::min(kPiece, j.bytes - off);
      std::memcpy(j.dst + off, j.src + off, len);
      j.done.fetch_add(1, std::memory_order_release);
    }
  }
  CopyPool() {
    const int n = std::max(1, omp_get_max_threads()) - 1;
    for (int i = 0; i < n; ++i) helpers_.emplace_back([this] { loop(); });
  }
  ~CopyPool() {
    {
      std::lock_guard<std::mutex> lk(m_);
      stop_ = true;
    }
    cv_.notify_all();
    for (auto& t : helpers_) t.join();
  }
  void loop() {
    std::uint64_t seen = 0;
    for (;;) {
      Job* j = nullptr;
      {
        std::unique_lock<std::mutex> lk(m_);
        cv_.wait(lk, [&] { return stop_ || gen_ != seen; });
        if (stop_) return;
        seen = gen_;
        j = job_;
        if (!j) continue;
        ++active_;
      }
      work(*j);
      std::lock_guard<std::mutex> lk(m_);
      if (--active_ == 0) idle_.notify_all();
    }
  }
  std::vector<std::thread> helpers_;
  std::mutex m_;
  std::condition_variable cv_, idle_;
  Job* job_ = nullptr;
  std::uint64_t gen_ = 0;
  int active_ = 0;
  bool stop_ = false;
};

void parallel_copy(void* dst, const void* src, std::size_t bytes) {
  CopyPool::get().copy(dst, src, bytes);
}

}  // namespace

void to_host(void* host, const void* device, std::size_t bytes, cudaStream_t s) {
  Pool& p = pool();
  std::lock_guard<std::mutex> lock(p.busy);
  const std::size_t chunks = (bytes + kChunk - 1) / kChunk;
  auto issue = [&](std::size_t c) {
    const std::size_t off = c * kChunk, len = std::min(kChunk, bytes - off);
    check(cudaMemcpyAsync(p.buf[c % 2], static_cast<const char*>(device) + off, len,
                          cudaMemcpyDeviceToHost, s),
          "copy to host");
    check(cudaEventRecord(p.ev[c % 2], s), "staging event");
  };
  issue(0);
  for (std::size_t c = 0; c < chunks; ++c) {
    check(cudaEventSynchronize(p.ev[c % 2]), "copy to host");
    if (c + 1 < chunks) issue(c + 1);  // its buffer was emptied in the previous step
    const std::size_t off = c * kChunk, len = std::min(kChunk, bytes - off);
    parallel_copy(static_cast<char*>(host) + off, p.buf[c % 2], len);
  }
}

void small_to_host(void* host, const void* device, std::size_t bytes, cudaStream_t s) {
  Mailbox& m = mailbox();
  std::lock_guard<std::mutex> lock(m.busy);
  check(cudaMemcpyAsync(m.buf, device, bytes, cudaMemcpyDeviceToHost, s), "copy to host");
  check(cudaStreamSynchronize(s), "copy to host");
  std::memcpy(host, m.buf, bytes);
}

void from_host(void* device, const void* host, std::size_t bytes, cudaStream_t s) {
  Pool& p = pool();
  std::lock_guard<std::mutex> lock(p.busy);
  const std::size_t chunks = (bytes + kChunk - 1) / kChunk;
  for (std::size_t c = 0; c < chunks; ++c) {
    // the buffer is free once the transfer issued from it two chunks ago is done
    if (c >= 2) check(cudaEventSynchronize(p.ev[c % 2]), "copy to device");
    const std::size_t off = c * kChunk, len = std::min(kChunk, bytes - off);
    parallel_copy(p.buf[c % 2], static_cast<const char*>(host) + off, len);
    check(cudaMemcpyAsync(static_cast<char*>(device) + off, p.buf[c % 2], len,
                          cudaMemcpyHostToDevice, s),
          "copy to device");
    check(cudaEventRecord(p.ev[c % 2], s), "staging event");
  }
  check(cudaStreamSynchronize(s), "copy to device");
}

}  // namespace gpugeom::staging
