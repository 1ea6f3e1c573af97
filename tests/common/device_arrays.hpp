// Helpers for the GPU tests of device entry points: a caller's points in device memory, and a
// device result read back. (CUDA tests only: they link the CUDA runtime.)
#pragma once
#include <cuda_runtime.h>

#include <cstdint>
#include <memory>
#include <vector>

#include <gtest/gtest.h>

namespace gg_test {

// A host vector's bytes in a device allocation of their own, freed with this object.
class DeviceCopy {
 public:
  template <class P>
  explicit DeviceCopy(const std::vector<P>& v) : bytes_(v.size() * sizeof(P)) {
    EXPECT_EQ(cudaMalloc(&p_, bytes_), cudaSuccess);
    EXPECT_EQ(cudaMemcpy(p_, v.data(), bytes_, cudaMemcpyHostToDevice), cudaSuccess);
  }
  ~DeviceCopy() { cudaFree(p_); }
  DeviceCopy(const DeviceCopy&) = delete;
  DeviceCopy& operator=(const DeviceCopy&) = delete;
  const double* doubles() const { return static_cast<const double*>(p_); }
  void* data() const { return p_; }

 private:
  void* p_ = nullptr;
  std::size_t bytes_ = 0;
};

// A non-blocking stream of the test's own, destroyed with this object (after its work is done).
// Declare it before the results of calls on it: a device result gives its memory back on its
// call's stream when it goes, so the stream must outlive it.
class Stream {
 public:
  Stream() { EXPECT_EQ(cudaStreamCreateWithFlags(&s_, cudaStreamNonBlocking), cudaSuccess); }
  ~Stream() {
    cudaStreamSynchronize(s_);
    cudaStreamDestroy(s_);
  }
  Stream(const Stream&) = delete;
  Stream& operator=(const Stream&) = delete;
  operator cudaStream_t() const { return s_; }

 private:
  cudaStream_t s_ = nullptr;
};

// n elements of a device array, on the host.
template <class T>
std::vector<T> from_device(const std::shared_ptr<T>& p, std::int64_t n) {
  std::vector<T> v(static_cast<std::size_t>(n));
  EXPECT_EQ(cudaMemcpy(v.data(), p.get(), v.size() * sizeof(T), cudaMemcpyDeviceToHost),
            cudaSuccess);
  return v;
}

// n elements of device memory at d, on the host.
template <class T>
std::vector<T> back(const T* d, std::int64_t n) {
  std::vector<T> h(static_cast<std::size_t>(n));
  EXPECT_EQ(cudaMemcpy(h.data(), d, sizeof(T) * std::size_t(n), cudaMemcpyDeviceToHost),
            cudaSuccess);
  return h;
}

}  // namespace gg_test

// A CUDA call that must succeed (in a test body).
#define GG_CK(x) ASSERT_EQ((x), cudaSuccess) << #x
