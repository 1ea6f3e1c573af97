// Annotations that let one function body compile for both executors.
#pragma once

#if defined(__CUDACC__)
#define GG_HD __host__ __device__
#define GG_INLINE __host__ __device__ __forceinline__
// For rare slow paths inside hot loops: kept out of line so they cost no registers there.
#define GG_NOINLINE __host__ __device__ __noinline__
#else
#define GG_HD
#define GG_INLINE inline
#define GG_NOINLINE __attribute__((noinline))
#endif

// A lambda usable by both executors: `GG_LAMBDA(int64_t i) { ... }`. Under nvcc this needs
// --extended-lambda, which the build sets.
#define GG_LAMBDA [=] GG_HD
