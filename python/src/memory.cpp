// The caller's allocator from Python (issue 48): when CuPy or PyTorch arrays come in, the
// package passes an object whose methods take device memory from that framework's caching
// allocator, so that one pool serves the process (torch.cuda.memory_allocated counts the
// library's arrays) instead of two caches fighting over the device.
#include <nanobind/nanobind.h>

#include <cstdint>
#include <memory>
#include <string>

#include "arrays.hpp"
#include "gpugeom/memory.hpp"

namespace gpugeom::py {

namespace {

// A DeviceMemoryResource over a Python object with allocate(nbytes, stream) -> int pointer,
// deallocate(ptr, nbytes, stream) and cached_bytes(device) -> int. The library calls it with
// the interpreter unlocked (its work runs without the GIL), so each call takes the GIL.
class PythonResource final : public DeviceMemoryResource {
 public:
  // (the bound methods looked up once: a call takes tens to hundreds of blocks)
  explicit PythonResource(nb::handle obj)
      : alloc_(obj.attr("allocate")),
        free_(obj.attr("deallocate")),
        cached_(obj.attr("cached_bytes")) {}
  ~PythonResource() override {
    if (!nb::is_alive()) {  // the interpreter is gone: its objects with it
      (void)alloc_.release(), (void)free_.release(), (void)cached_.release();
      return;
    }
    nb::gil_scoped_acquire gil;
    alloc_.reset(), free_.reset(), cached_.reset();
  }
  void* allocate(std::size_t bytes, std::size_t, void* stream) override {
    nb::gil_scoped_acquire gil;
    try {
      const auto p =
          nb::cast<std::uintptr_t>(alloc_(bytes, reinterpret_cast<std::uintptr_t>(stream)));
      return reinterpret_cast<void*>(p);
    } catch (const nb::python_error& e) {
      throw Error(ErrorCode::OutOfMemory,
                  std::string("the array framework's allocator refused ") + std::to_string(bytes) +
                      " bytes of GPU memory (" + e.what() +
                      "): use a smaller input, free GPU memory the program holds, or the CPU "
                      "backend (backend='cpu')");
    }
  }
  void deallocate(void* p, std::size_t bytes, std::size_t, void* stream) noexcept override {
    if (!nb::is_alive()) return;  // at exit the framework's pool is gone with the process
    nb::gil_scoped_acquire gil;
    try {
      free_(reinterpret_cast<std::uintptr_t>(p), bytes, reinterpret_cast<std::uintptr_t>(stream));
    } catch (nb::python_error& e) {
      e.discard_as_unraisable("gpugeom: freeing device memory through the caller's allocator");
    }
  }
  std::uint64_t cached_bytes(int device) const noexcept override {
    if (!nb::is_alive()) return 0;
    nb::gil_scoped_acquire gil;
    try {
      const auto b = nb::cast<std::int64_t>(cached_(device));
      return b > 0 ? std::uint64_t(b) : 0;
    } catch (nb::python_error& e) {
      e.discard_as_unraisable("gpugeom: reading the caller's allocator's cache");
      return 0;
    }
  }

 private:
  nb::object alloc_, free_, cached_;
};

}  // namespace

void set_stream(RunOptions& o, nb::handle stream) {
  nb::handle handle = stream;
  if (nb::isinstance<nb::tuple>(stream)) {
    const auto t = nb::borrow<nb::tuple>(stream);
    if (t.size() != 2) throw nb::value_error("stream must be an int or (int, allocator)");
    handle = t[0];
    if (!t[1].is_none()) o.memory = std::make_shared<PythonResource>(t[1]);
  }
  o.stream = reinterpret_cast<void*>(nb::cast<std::uintptr_t>(handle));
}

}  // namespace gpugeom::py
