// Annotations that let one function body compile for both executors.
#pragma once

#if defined(__CUDACC__)
#define GG_HD __host__ __device__
#define GG_INLINE __host__ __device__ __forceinline__
// A rarely taken, long path: kept out of line on the device so that it does not raise the
// register count of the kernels that call it.
#define GG_COLD __host__ __device__ __noinline__ inline
#else
#define GG_HD
#define GG_INLINE inline
#define GG_COLD inline
#endif
// A small test on a CPU executor's hot path: inlined on the host too, where the compiler's own
// choice varies with what surrounds the call (2D's orientation test stayed a call from the
// cavity insertion's walk in one build and not in the next, 10-15 % of its time).
#if defined(__CUDACC__)
#define GG_ALWAYS_INLINE __host__ __device__ __forceinline__
#elif defined(__GNUC__)
#define GG_ALWAYS_INLINE inline __attribute__((always_inline))
#else
#define GG_ALWAYS_INLINE inline
#endif

// A lambda usable by both executors: `GG_LAMBDA(int64_t i) { ... }`. Under nvcc this needs
// --extended-lambda, which the build sets.
#define GG_LAMBDA [=] GG_HD

// A hint that the host will soon read (or, write = true, write) p: for the CPU executor's
// passes that gather through an index (their misses overlap instead of following one another).
// Nothing on the device, whose warps hide the latency.
template <bool Write = false>
GG_INLINE void prefetch_on_host(const void* p) {
#if !defined(__CUDA_ARCH__) && defined(__GNUC__)
  __builtin_prefetch(p, Write ? 1 : 0);
#else
  (void)p;
#endif
}
