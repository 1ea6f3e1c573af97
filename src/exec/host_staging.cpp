// Pinned staging for large host <-> device copies (see host_staging.hpp).
#include "exec/host_staging.hpp"

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <mutex>
#include <omp.h>
#include <string>

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

// memcpy over the cores: one thread cannot keep up with the link.
void parallel_copy(void* dst, const void* src, std::size_t bytes) {
  const int nt = std::max(1, std::min(omp_get_max_threads(), int(bytes >> 20)));
#pragma omp parallel num_threads(nt)
  {
    const std::size_t per = (bytes + nt - 1) / nt;
    const std::size_t a = std::min(bytes, per * std::size_t(omp_get_thread_num()));
    const std::size_t b = std::min(bytes, a + per);
    if (b > a) std::memcpy(static_cast<char*>(dst) + a, static_cast<const char*>(src) + a, b - a);
  }
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
