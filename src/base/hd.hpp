// Annotations that let one function body compile for both executors.
#pragma once

#if defined(__CUDACC__)
#define GG_HD __host__ __device__
#define GG_INLINE __host__ __device__ __forceinline__
#else
#define GG_HD
#define GG_INLINE inline
#endif

// A lambda usable by both executors: `GG_LAMBDA(int64_t i) { ... }`. Under nvcc this needs
// --extended-lambda, which the build sets.
#define GG_LAMBDA [=] GG_HD
