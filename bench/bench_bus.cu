// gpugeom_bench_bus: what moving a result between the device and host memory costs on this
// machine, by kind of host memory (the facts the host path of every capability is designed
// from; docs/performance.md, "results at bus speed"). For each size: pinned transfers both
// ways, pageable transfers, first touch of fresh memory (1 and all threads, with and without
// huge pages), pinning fresh and touched memory (cudaMallocHost, cudaHostRegister), and host
// copies from pinned memory into fresh and into touched memory on all threads.
// Usage: gpugeom_bench_bus [MB ...]   (default 64 256 1024)
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <sys/mman.h>
#include <thread>
#include <vector>

#include <cuda_runtime.h>

namespace {

double now_ms() {
  return std::chrono::duration<double, std::milli>(
             std::chrono::steady_clock::now().time_since_epoch())
      .count();
}

void check(cudaError_t e, const char* what) {
  if (e != cudaSuccess) {
    std::fprintf(stderr, "%s: %s\n", what, cudaGetErrorString(e));
    std::exit(1);
  }
}

// Fresh anonymous memory (no page touched yet), optionally advised to use huge pages.
char* fresh(std::size_t bytes, bool huge) {
  void* p = mmap(nullptr, bytes, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
  if (p == MAP_FAILED) {
    std::perror("mmap");
    std::exit(1);
  }
#ifdef MADV_HUGEPAGE
  if (huge) madvise(p, bytes, MADV_HUGEPAGE);
#endif
  return static_cast<char*>(p);
}

template <class F>
void on_threads(int threads, std::size_t bytes, F f) {
  std::vector<std::thread> t;
  const std::size_t part = (bytes / threads + 4095) & ~std::size_t(4095);
  for (int i = 0; i < threads; ++i) {
    const std::size_t a = std::min(bytes, part * i), b = std::min(bytes, part * (i + 1));
    t.emplace_back([=] { f(a, b); });
  }
  for (auto& x : t) x.join();
}

template <class F>
double median_ms(int reps, F f) {
  std::vector<double> t;
  for (int i = 0; i < reps; ++i) {
    const double t0 = now_ms();
    f();
    t.push_back(now_ms() - t0);
  }
  std::sort(t.begin(), t.end());
  return t[t.size() / 2];
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<std::size_t> mbs;
  for (int i = 1; i < argc; ++i) mbs.push_back(std::size_t(std::atoll(argv[i])));
  if (mbs.empty()) mbs = {64, 256, 1024};
  cudaDeviceProp prop;
  check(cudaGetDeviceProperties(&prop, 0), "device");
  const int T = int(std::max(1u, std::thread::hardware_concurrency()));
  std::printf("# device: %s, host threads %d\n", prop.name, T);
  check(cudaFree(nullptr), "context");
  std::printf("%-44s %10s %10s\n", "what", "ms", "GB/s");
  for (std::size_t mb : mbs) {
    const std::size_t bytes = mb << 20;
    auto row = [&](const char* what, double ms) {
      std::printf("%-36s %5zu MB %10.2f %10.2f\n", what, mb, ms, bytes / ms / 1e6);
    };
    void* dev = nullptr;
    check(cudaMalloc(&dev, bytes), "cudaMalloc");
    check(cudaMemset(dev, 1, bytes), "memset");
    void* pinned = nullptr;
    double t0 = now_ms();
    check(cudaMallocHost(&pinned, bytes), "cudaMallocHost");
    row("cudaMallocHost", now_ms() - t0);
    t0 = now_ms();
    check(cudaFreeHost(pinned), "cudaFreeHost");
    row("cudaFreeHost", now_ms() - t0);
    check(cudaMallocHost(&pinned, bytes), "cudaMallocHost");
    std::memset(pinned, 0, bytes);
    row("D2H pinned", median_ms(3, [&] {
          check(cudaMemcpy(pinned, dev, bytes, cudaMemcpyDeviceToHost), "d2h");
        }));
    row("H2D pinned", median_ms(3, [&] {
          check(cudaMemcpy(dev, pinned, bytes, cudaMemcpyHostToDevice), "h2d");
        }));
    {  // pageable, touched
      char* p = fresh(bytes, true);
      std::memset(p, 0, bytes);
      row("D2H pageable (touched)",
          median_ms(3, [&] { check(cudaMemcpy(p, dev, bytes, cudaMemcpyDeviceToHost), "d2h"); }));
      row("H2D pageable",
          median_ms(3, [&] { check(cudaMemcpy(dev, p, bytes, cudaMemcpyHostToDevice), "h2d"); }));
      row("memcpy pinned->touched, all threads", median_ms(3, [&] {
            on_threads(T, bytes, [&](std::size_t a, std::size_t b) {
              std::memcpy(p + a, static_cast<char*>(pinned) + a, b - a);
            });
          }));
      row("memcpy touched->pinned, all threads", median_ms(3, [&] {
            on_threads(T, bytes, [&](std::size_t a, std::size_t b) {
              std::memcpy(static_cast<char*>(pinned) + a, p + a, b - a);
            });
          }));
      t0 = now_ms();
      check(cudaHostRegister(p, bytes, cudaHostRegisterDefault), "register");
      row("cudaHostRegister (touched)", now_ms() - t0);
      row("D2H registered",
          median_ms(3, [&] { check(cudaMemcpy(p, dev, bytes, cudaMemcpyDeviceToHost), "d2h"); }));
      t0 = now_ms();
      check(cudaHostUnregister(p), "unregister");
      row("cudaHostUnregister", now_ms() - t0);
      munmap(p, bytes);
    }
    for (int huge = 0; huge < 2; ++huge) {
      for (int threads : {1, T}) {
        char* p = fresh(bytes, huge);
        t0 = now_ms();
        on_threads(threads, bytes, [&](std::size_t a, std::size_t b) {
          for (std::size_t i = a; i < b; i += 4096) p[i] = 1;
        });
        char what[64];
        std::snprintf(what, sizeof what, "first touch, %d thr%s", threads, huge ? ", huge" : "");
        row(what, now_ms() - t0);
        munmap(p, bytes);
        p = fresh(bytes, huge);
        t0 = now_ms();
        on_threads(threads, bytes, [&](std::size_t a, std::size_t b) {
          std::memcpy(p + a, static_cast<char*>(pinned) + a, b - a);
        });
        std::snprintf(what, sizeof what, "memcpy pinned->fresh, %d thr%s", threads,
                      huge ? ", huge" : "");
        row(what, now_ms() - t0);
        munmap(p, bytes);
      }
      char* p = fresh(bytes, huge);
      t0 = now_ms();
      check(cudaMemcpy(p, dev, bytes, cudaMemcpyDeviceToHost), "d2h");
      row(huge ? "D2H pageable (fresh, huge)" : "D2H pageable (fresh)", now_ms() - t0);
      munmap(p, bytes);
      p = fresh(bytes, huge);
      t0 = now_ms();
      check(cudaHostRegister(p, bytes, cudaHostRegisterDefault), "register");
      row(huge ? "cudaHostRegister (fresh, huge)" : "cudaHostRegister (fresh)", now_ms() - t0);
      check(cudaHostUnregister(p), "unregister");
      munmap(p, bytes);
    }
    {  // the zero-fill a std::vector<float>(n) does, on one thread
      t0 = now_ms();
      std::vector<float> v(bytes / 4);
      row("std::vector<float>(n), 1 thread", now_ms() - t0);
    }
    check(cudaFreeHost(pinned), "free");
    check(cudaFree(dev), "free");
  }
  return 0;
}
