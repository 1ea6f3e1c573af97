// Pinned staging for large host <-> device copies (see host_staging.hpp).
#include "exec/host_staging.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
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
// Parts of a chunk handed between the host copy and the link (4 MB each).
constexpr std::size_t kPart = std::size_t(4) << 20;
constexpr std::size_t kParts = kChunk / kPart;

void check(cudaError_t e, const char* what) {
  if (e != cudaSuccess)
    throw Error(e == cudaErrorMemoryAllocation ? ErrorCode::OutOfMemory : ErrorCode::Cuda,
                std::string(what) + ": " + cudaGetErrorString(e));
}

// Two pinned buffers and their events per device, made on the device's first large copy and
// kept (pinning is slow; keeping 64 MB pinned is cheap). One copy at a time per device uses
// them; copies on different devices run side by side.
struct Pool {
  void* buf[2] = {nullptr, nullptr};
  cudaEvent_t ev[2];
  cudaEvent_t part[2][kParts];  // the parts of a chunk coming back (to_host)
  std::mutex busy;
  Pool() {  // on the current device, whose streams record the events
    for (int i = 0; i < 2; ++i) {
      check(cudaMallocHost(&buf[i], kChunk), "pinned staging buffer");
      check(cudaEventCreateWithFlags(&ev[i], cudaEventDisableTiming), "staging event");
      for (auto& e : part[i])
        check(cudaEventCreateWithFlags(&e, cudaEventDisableTiming), "staging event");
    }
  }
  void release() {
    for (int i = 0; i < 2; ++i) {
      (void)cudaFreeHost(buf[i]);
      (void)cudaEventDestroy(ev[i]);
      for (auto& e : part[i]) (void)cudaEventDestroy(e);
    }
  }
};
struct Pools {
  std::mutex m;
  std::vector<Pool*> per_device;
};
Pools& pools() {
  static Pools* p = [] {
    Pools* q = new Pools;
    // Freed before the CUDA runtime's own exit handler runs (registered after it), so leak
    // checkers see no pinned memory left behind.
    std::atexit([] {
      for (Pool* x : pools().per_device)
        if (x) x->release();
    });
    return q;
  }();
  return *p;
}
// The staging pool of the calling thread's current device (the executor's).
Pool& pool() {
  int dev = 0;
  check(cudaGetDevice(&dev), "staging: current device");
  Pools& P = pools();
  std::lock_guard<std::mutex> lk(P.m);
  if (P.per_device.size() <= std::size_t(dev)) P.per_device.resize(std::size_t(dev) + 1, nullptr);
  Pool*& p = P.per_device[std::size_t(dev)];
  if (!p) p = new Pool;
  return *p;
}

// One pinned page per host thread for small reads, made on first use (apart from the large
// buffers, so that a program that only reads counters never pins 64 MB). Per thread, since a
// read waits for its stream: a shared page would make threads wait for each other's streams.
struct Mailbox {
  void* buf = nullptr;
  Mailbox() { check(cudaMallocHost(&buf, kMailBytes), "pinned mailbox"); }
  ~Mailbox() { (void)cudaFreeHost(buf); }
};
Mailbox& mailbox() {
  thread_local Mailbox m;
  return m;
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
  // Copies `bytes`; when `ready` is given, the calling thread calls ready(from, to) each time
  // the copied prefix has grown by kStep bytes (and at the end), so that a transfer of that
  // part can start while the rest is still being copied.
  template <class Ready>
  void copy(void* dst, const void* src, std::size_t bytes, Ready ready) {
    Job j;
    j.dst = static_cast<char*>(dst);
    j.src = static_cast<const char*>(src);
    j.bytes = bytes;
    j.pieces = (bytes + kPiece - 1) / kPiece;
    if (helpers_.empty() || j.pieces < 2 || j.pieces > kMaxPieces) {
      for (std::size_t at = 0; at < bytes; at += kStep) {
        const std::size_t len = std::min(kStep, bytes - at);
        std::memcpy(j.dst + at, j.src + at, len);
        ready(at, at + len);
      }
      return;
    }
    // Copies for other devices at once (several devices of one process) wait for the pool:
    // a job is a chunk of a few milliseconds, and every core at half the time each beats one
    // core alone (two devices' results came back no faster than one device's that way).
    std::unique_lock<std::mutex> mine(use_);
    publish(j);
    std::size_t prefix = 0, reported = 0;  // pieces known done in a row; bytes handed on
    auto advance = [&] {
      while (prefix < j.pieces && j.flag[prefix].load(std::memory_order_acquire)) ++prefix;
      const std::size_t b = std::min(prefix * kPiece, bytes);
      if (b > reported && (b - reported >= kStep || b == bytes)) {
        ready(reported, b);
        reported = b;
      }
    };
    for (std::size_t i; (i = take(j)) < j.pieces;) {
      do_piece(j, i);
      advance();
    }
    while (reported < bytes) {
      advance();
      if (reported < bytes) std::this_thread::yield();
    }
    withdraw();
  }
  void copy(void* dst, const void* src, std::size_t bytes) {
    copy(dst, src, bytes, [](std::size_t, std::size_t) {});
  }
  // The same as one job whose pieces wait for their source: whoever takes the piece at offset
  // `off` first calls before(ctx, off), which returns once that part of src is there (false:
  // it never will; the copy then reports failure). One job per chunk rather than one per part:
  // handing out a job costs a wake-up of the helpers.
  using Before = bool (*)(const void* ctx, std::size_t off);
  bool copy_when(void* dst, const void* src, std::size_t bytes, Before before, const void* ctx) {
    Job j;
    j.dst = static_cast<char*>(dst);
    j.src = static_cast<const char*>(src);
    j.bytes = bytes;
    j.pieces = (bytes + kPiece - 1) / kPiece;
    j.before = before;
    j.ctx = ctx;
    if (helpers_.empty() || j.pieces < 2 || j.pieces > kMaxPieces) {
      for (std::size_t i = 0; i < j.pieces; ++i) do_piece(j, i);
      return !j.failed.load();
    }
    std::unique_lock<std::mutex> mine(use_);  // (as copy: other devices' jobs wait)
    run(j);
    return !j.failed.load();
  }

  static constexpr std::size_t kStep = kPart;

 private:
  static constexpr std::size_t kPiece = std::size_t(1) << 20;
  static constexpr std::size_t kMaxPieces = kChunk / kPiece;
  struct Job {
    char* dst;
    const char* src;
    std::size_t bytes = 0, pieces = 0;
    std::atomic<std::size_t> next{0};
    std::atomic<bool> flag[kMaxPieces] = {};  // piece i copied
    Before before = nullptr;                  // see copy_when
    const void* ctx = nullptr;
    std::atomic<bool> failed{false};
  };
  static std::size_t take(Job& j) { return j.next.fetch_add(1, std::memory_order_relaxed); }
  static void do_piece(Job& j, std::size_t i) {
    const std::size_t off = i * kPiece, len = std::min(kPiece, j.bytes - off);
    if (j.before && !j.before(j.ctx, off))
      j.failed.store(true, std::memory_order_relaxed);
    else
      std::memcpy(j.dst + off, j.src + off, len);
    j.flag[i].store(true, std::memory_order_release);
  }
  // Hands job j to the helpers (those awake start on it; the others when they wake).
  void publish(Job& j) {
    {
      std::lock_guard<std::mutex> lk(m_);
      job_ = &j;
      ++gen_;
      posted_.store(gen_, std::memory_order_release);
    }
    cv_.notify_all();
  }
  // Withdraws the job once its pieces are done; helpers that took it are awake and leave at
  // once (no pieces left).
  void withdraw() {
    std::unique_lock<std::mutex> lk(m_);
    job_ = nullptr;
    idle_.wait(lk, [&] { return active_ == 0; });
  }
  // Runs job j on the calling thread and whichever helpers wake, until every piece is done.
  void run(Job& j) {
    publish(j);
    work(j);
    for (std::size_t i = 0; i < j.pieces; ++i)
      while (!j.flag[i].load(std::memory_order_acquire)) std::this_thread::yield();
    withdraw();
  }
  static void work(Job& j) {
    for (std::size_t i; (i = take(j)) < j.pieces;) do_piece(j, i);
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
      // The next job (the next chunk of the same transfer) usually comes within microseconds:
      // wait for it awake for a while before sleeping, since a sleeping helper can take
      // milliseconds to wake on a virtual machine.
      const auto until = std::chrono::steady_clock::now() + std::chrono::milliseconds(2);
      while (posted_.load(std::memory_order_acquire) == seen &&
             std::chrono::steady_clock::now() < until)
        std::this_thread::yield();
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
  std::mutex use_;  // one job at a time (copies for several devices at once wait: see copy)
  std::mutex m_;
  std::condition_variable cv_, idle_;
  Job* job_ = nullptr;
  std::uint64_t gen_ = 0;
  std::atomic<std::uint64_t> posted_{0};  // gen_, for helpers waiting awake
  int active_ = 0;
  bool stop_ = false;
};

}  // namespace

void to_host(void* host, const void* device, std::size_t bytes, cudaStream_t s) {
  Pool& p = pool();
  std::lock_guard<std::mutex> lock(p.busy);
  constexpr std::size_t kStep = CopyPool::kStep;
  const std::size_t chunks = (bytes + kChunk - 1) / kChunk;
  auto len_of = [&](std::size_t c) { return std::min(kChunk, bytes - c * kChunk); };
  // Chunk c comes over in parts of kStep, each with its own event, so the cores copy a part
  // out of the pinned buffer while the link brings the next.
  auto issue = [&](std::size_t c) {
    const std::size_t off = c * kChunk, len = len_of(c);
    for (std::size_t q = 0; q * kStep < len; ++q) {
      const std::size_t at = q * kStep, part = std::min(kStep, len - at);
      check(cudaMemcpyAsync(static_cast<char*>(p.buf[c % 2]) + at,
                            static_cast<const char*>(device) + off + at, part,
                            cudaMemcpyDeviceToHost, s),
            "copy to host");
      check(cudaEventRecord(p.part[c % 2][q], s), "staging event");
    }
  };
  issue(0);
  for (std::size_t c = 0; c < chunks; ++c) {
    if (c + 1 < chunks) issue(c + 1);  // its buffer was emptied in the previous step
    const std::size_t off = c * kChunk, len = len_of(c);
    // A piece is copied once the part holding it has arrived (its event).
    struct Parts {
      const cudaEvent_t* ev;
      static bool arrived(const void* ctx, std::size_t at) {
        return cudaEventSynchronize(static_cast<const Parts*>(ctx)->ev[at / kPart]) == cudaSuccess;
      }
    } parts{p.part[c % 2]};
    if (!CopyPool::get().copy_when(static_cast<char*>(host) + off, p.buf[c % 2], len,
                                   &Parts::arrived, &parts)) {
      check(cudaStreamSynchronize(s), "copy to host");  // reports the transfer's error
      throw Error(ErrorCode::Cuda, "copy to host: a staged part never arrived");
    }
  }
}

void small_to_host(void* host, const void* device, std::size_t bytes, cudaStream_t s) {
  Mailbox& m = mailbox();
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
    char* buf = static_cast<char*>(p.buf[c % 2]);
    char* dst = static_cast<char*>(device) + off;
    // Each part goes over the link as soon as it is in the pinned buffer, while the cores copy
    // the next part (the transfer and the host copy overlap instead of adding up).
    CopyPool::get().copy(
        buf, static_cast<const char*>(host) + off, len, [&](std::size_t from, std::size_t to) {
          check(cudaMemcpyAsync(dst + from, buf + from, to - from, cudaMemcpyHostToDevice, s),
                "copy to device");
        });
    check(cudaEventRecord(p.ev[c % 2], s), "staging event");
  }
  check(cudaStreamSynchronize(s), "copy to device");
}

}  // namespace gpugeom::staging
