// gpugeom._core: the extension module. The Python package (python/gpugeom) gives it SciPy's
// names and shapes; this file holds what every binding shares: errors, devices, options.
#include <nanobind/stl/string.h>

#include "arrays.hpp"
#include "gpugeom/gpugeom.hpp"

#ifndef GPUGEOM_VERSION
#error "GPUGEOM_VERSION must be defined by the build"
#endif

namespace gpugeom::py {

// points: float64 (n, dim), C order.
Input points_input(const AnyArray& a, int dim) {
  Input in = inspect(a, "points");
  if (in.shape.size() != 2 || in.shape[1] != dim)
    throw nb::value_error(("points must have shape (n, " + std::to_string(dim) + ")").c_str());
  if (!holds<double>(in)) throw nb::type_error("points must be float64");
  return in;
}

Input inspect(const AnyArray& a, const char* name) {
  Input in;
  in.data = a.data();
  in.dtype = a.dtype();
  in.shape.resize(a.ndim());
  std::int64_t expect = 1;
  bool empty = false;
  for (std::size_t k = 0; k < a.ndim(); ++k) empty = empty || a.shape(k) == 0;
  for (std::size_t k = a.ndim(); k-- > 0;) {
    in.shape[k] = std::int64_t(a.shape(k));
    if (!empty && a.shape(k) > 1 && a.stride(k) != expect)  // (an empty array has no layout)
      throw nb::value_error((std::string(name) +
                             " must be C-contiguous (np.ascontiguousarray / cupy.ascontiguousarray "
                             "/ tensor.contiguous() make it so)")
                                .c_str());
    expect *= std::int64_t(a.shape(k));
  }
  const int dt = a.device_type();
  if (dt == nb::device::cuda::value) {
    in.on_device = true;
    in.device_id = a.device_id();
  } else if (dt != nb::device::cpu::value) {
    throw nb::type_error((std::string(name) +
                          " is in memory gpugeom cannot read (DLPack device type " +
                          std::to_string(dt) + "); give a NumPy array or a CUDA device array")
                             .c_str());
  }
  return in;
}

RunOptions run_options(const std::string& backend, nb::handle stream, int threads,
                       const Input& in) {
  RunOptions o;
  o.backend = parse_backend(backend);
  set_stream(o, stream);
  o.threads = threads;
  o.device = in.on_device ? in.device_id : -1;
  if (in.on_device && o.backend == Backend::Cpu)
    throw nb::value_error(
        "backend='cpu' with an array in GPU memory: move it to the host first (e.g. "
        "cupy.asnumpy / tensor.cpu()) or use backend='cuda'");
  return o;
}

int device_of(const RunOptions& o) {
  if (o.device >= 0) return o.device;
  const DeviceInfo d = query_device(-1);
  return d.device < 0 ? 0 : d.device;
}

nb::dict stats_dict(const RunStats& s) {
  nb::dict d, phases, counters;
  for (const auto& [k, v] : s.phase_ms) phases[k.c_str()] = v;
  for (const auto& [k, v] : s.counter_map()) counters[k.c_str()] = v;
  d["backend"] = backend_name(s.backend);
  d["phase_ms"] = phases;
  d["counters"] = counters;
  d["total_ms"] = s.total_ms();
  return d;
}

// Host int32 (rows, k) array, C order.
const std::int32_t* cells_of(const AnyArray& a, const char* name, int k, std::int64_t* rows) {
  Input in = inspect(a, name);
  if (in.on_device) throw nb::value_error((std::string(name) + " must be in host memory").c_str());
  if (!holds<std::int32_t>(in))
    throw nb::type_error((std::string(name) + " must be int32").c_str());
  if (in.shape.size() != 2 || in.shape[1] != k)
    throw nb::value_error(
        (std::string(name) + " must have shape (m, " + std::to_string(k) + ")").c_str());
  *rows = in.shape[0];
  return static_cast<const std::int32_t*>(in.data);
}

// Host float64 (rows, k) array, C order.
const double* reals_of(const AnyArray& a, const char* name, int k, std::int64_t* rows) {
  Input in = inspect(a, name);
  if (in.on_device || !holds<double>(in) || in.shape.size() != 2 || in.shape[1] != k)
    throw nb::value_error((std::string(name) + " must be a host float64 array of shape (m, " +
                           std::to_string(k) + ")")
                              .c_str());
  *rows = in.shape[0];
  return static_cast<const double*>(in.data);
}

}  // namespace gpugeom::py

using namespace gpugeom;
using namespace gpugeom::py;

NB_MODULE(_core, m) {
  m.doc() = "gpugeom's extension module; use the gpugeom package, which wraps it.";
  m.attr("__version__") = GPUGEOM_VERSION;

  // The library's errors by kind: bad input is a ValueError (degenerate input a subclass, so a
  // caller can tell it apart), an impossible request a RuntimeError subclass.
  // (Raw references kept for the life of the process: the translator may run until the end.)
  static PyObject* degenerate = PyErr_NewExceptionWithDoc(
      "gpugeom._core.DegenerateInputError",
      "The input has no result of the kind asked for: too few distinct points, or all of them "
      "on one line (2D) or one plane (3D). The message names the case. A ValueError.",
      PyExc_ValueError, nullptr);
  static PyObject* unsupported = PyErr_NewExceptionWithDoc(
      "gpugeom._core.UnsupportedError",
      "Asked for what this build or machine cannot do, e.g. backend=\"cuda\" where no GPU can "
      "be used (gpugeom.device_info() says why), or an option a device entry cannot honour. "
      "A RuntimeError.",
      PyExc_RuntimeError, nullptr);
  static PyObject* cuda_error = PyErr_NewExceptionWithDoc(
      "gpugeom._core.CudaError",
      "A failure of the CUDA runtime other than running out of memory (which raises "
      "MemoryError). A RuntimeError.",
      PyExc_RuntimeError, nullptr);
  m.attr("DegenerateInputError") = nb::borrow(degenerate);
  m.attr("UnsupportedError") = nb::borrow(unsupported);
  m.attr("CudaError") = nb::borrow(cuda_error);
  nb::register_exception_translator([](const std::exception_ptr& p, void*) {
    try {
      std::rethrow_exception(p);
    } catch (const Error& e) {
      PyObject* type = PyExc_RuntimeError;
      switch (e.code()) {
        case ErrorCode::InvalidArgument:
        case ErrorCode::InvalidInput:
        case ErrorCode::Parse:
          type = PyExc_ValueError;
          break;
        case ErrorCode::DegenerateInput:
          type = degenerate;
          break;
        case ErrorCode::Io:
          type = PyExc_OSError;
          break;
        case ErrorCode::Unsupported:
          type = unsupported;
          break;
        case ErrorCode::OutOfMemory:
          type = PyExc_MemoryError;
          break;
        case ErrorCode::Cuda:
          type = cuda_error;
          break;
        case ErrorCode::Internal:
          type = PyExc_RuntimeError;
          break;
      }
      PyErr_SetString(type, e.what());
    }
  });

  m.def("built_with_cuda", &built_with_cuda, "True when this build has the CUDA executor.");
  m.def("built_cuda_architectures", &built_cuda_architectures);
  m.def(
      "device_info",
      [](int device) {
        const DeviceInfo d = query_device(device);
        nb::dict r;
        r["available"] = d.available;
        r["device"] = d.device;
        r["device_count"] = d.device_count;
        r["name"] = d.name;
        r["compute_capability"] = nb::make_tuple(d.compute_major, d.compute_minor);
        r["multiprocessors"] = d.multiprocessors;
        r["total_memory"] = d.total_memory;
        r["free_memory"] = d.free_memory;
        r["reason"] = d.reason;
        r["built_with_cuda"] = built_with_cuda();
        r["architectures"] = built_cuda_architectures();
        return r;
      },
      nb::arg("device") = -1);
  m.def("resolve_backend",
        [](const std::string& b) { return backend_name(resolve_backend(parse_backend(b))); });
  m.def("release_cached_device_memory", &release_cached_device_memory);
  m.def("prepare_device", &prepare_device, nb::arg("device") = -1);

  bind_spatial(m);
  bind_cells(m);
  bind_mesh(m);
  bind_grid(m);
}
