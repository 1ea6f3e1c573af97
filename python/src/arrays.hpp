// The bridge between Python arrays and the library's (internal to the extension): inputs as the
// caller's memory (NumPy on the host; CuPy, PyTorch or any DLPack producer on a CUDA device),
// outputs handed to Python without a copy (the library's host vectors and device arrays become
// the arrays' owners), run options from the Python keywords, and the library's errors as Python
// exceptions.
#pragma once
#include <nanobind/nanobind.h>
#include <nanobind/ndarray.h>

#include <cstdint>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "gpugeom/common.hpp"
#include "gpugeom/host_vector.hpp"

namespace gpugeom::py {

namespace nb = nanobind;

// A read-only array of any kind, as nanobind receives it through DLPack or the buffer protocol.
using AnyArray = nb::ndarray<nb::ro>;

// Where an input lives and what it holds; checked for C order (the Python layer makes inputs
// contiguous, so a non-contiguous one here is a bug of the caller's own extension use).
struct Input {
  const void* data = nullptr;
  std::vector<std::int64_t> shape;
  bool on_device = false;  // CUDA device memory
  int device_id = -1;
  nb::dlpack::dtype dtype;
};
Input inspect(const AnyArray& a, const char* name);

template <class T>
bool holds(const Input& in) {
  return in.dtype == nb::dtype<T>();
}

// The run options every binding takes: backend name, the caller's CUDA stream, CPU threads; the
// device is the input's. The stream is an integer handle (0: the per-thread default stream), or
// a pair (handle, allocator) where the caller's array framework lends its allocator: an object
// with allocate(nbytes, stream) -> pointer, deallocate(pointer, nbytes, stream) and
// cached_bytes(device), through which the call takes all its device memory (memory.cpp).
RunOptions run_options(const std::string& backend, nb::handle stream, int threads, const Input& in);
void set_stream(RunOptions& o, nb::handle stream);

// Host results: the vector moves into the array's owner (no copy).
template <class T>
nb::object host_array(HostVector<T>&& v, std::vector<std::size_t> shape) {
  static T empty_storage[1] = {};
  auto* owner = new HostVector<T>(std::move(v));
  nb::capsule cap(owner, [](void* p) noexcept { delete static_cast<HostVector<T>*>(p); });
  T* data = owner->empty() ? empty_storage : owner->data();
  return nb::cast(nb::ndarray<nb::numpy, T>(data, shape.size(), shape.data(), cap));
}

// Device results: the shared pointer moves into the array's owner. On the CUDA executor the
// array is a DLPack producer on that device (the Python layer makes it a CuPy array or a PyTorch
// tensor); on the CPU executor a NumPy array.
template <class T>
nb::object device_array(std::shared_ptr<T> p, std::vector<std::size_t> shape, Backend where,
                        int device_id) {
  static T empty_storage[1] = {};
  auto* owner = new std::shared_ptr<T>(std::move(p));
  nb::capsule cap(owner, [](void* q) noexcept { delete static_cast<std::shared_ptr<T>*>(q); });
  T* data = owner->get();
  if (where != Backend::Cuda) {
    if (!data) data = empty_storage;
    return nb::cast(nb::ndarray<nb::numpy, T>(data, shape.size(), shape.data(), cap));
  }
  return nb::cast(nb::ndarray<nb::array_api, T>(data, shape.size(), shape.data(), cap, nullptr,
                                                nb::dtype<T>(), nb::device::cuda::value,
                                                device_id < 0 ? 0 : device_id));
}

// Options of type Opt (a RunOptions) from the Python keywords and the input.
template <class Opt>
Opt options_for(const std::string& backend, nb::handle stream, int threads, const Input& in) {
  return options_from<Opt>(run_options(backend, stream, threads, in));
}

// f() with the interpreter unlocked (the library's work never touches Python objects).
template <class F>
auto unlocked(F&& f) -> decltype(f()) {
  nb::gil_scoped_release released;
  return f();
}

// Device results of one run: where they are (device_array) fixed once.
struct DeviceOut {
  Backend where;
  int device;
  template <class T>
  nb::object operator()(std::shared_ptr<T> p, std::vector<std::size_t> shape) const {
    return device_array(std::move(p), std::move(shape), where, device);
  }
};

nb::dict stats_dict(const RunStats& s);

// The device a CUDA run used (the input's, else the calling thread's current one).
int device_of(const RunOptions& o);

// Points: float64 (n, dim), C order (ValueError, TypeError otherwise); their coordinates.
Input points_input(const AnyArray& a, int dim);
inline const double* pts(const Input& in) {
  return static_cast<const double*>(in.data);
}

// Host int32 / float64 arrays of shape (rows, k), C order (rows returned), or a ValueError.
const std::int32_t* cells_of(const AnyArray& a, const char* name, int k, std::int64_t* rows);
const double* reals_of(const AnyArray& a, const char* name, int k, std::int64_t* rows);

void bind_spatial(nb::module_& m);
void bind_mesh(nb::module_& m);
void bind_cells(nb::module_& m);
void bind_grid(nb::module_& m);

}  // namespace gpugeom::py
