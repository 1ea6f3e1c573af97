// GG_TU_EXECUTOR(Base): the executor type of one CUDA translation unit, its own (internal).
//
// Why not `using Exec = CudaExec`: nvcc hands a __host__ __device__ lambda to host code inside a
// wrapper whose copy and call go through function pointers that the translation unit creating
// the lambda sets when it creates it. A shared template (mesh::, exec::) instantiated with the
// same executor in two translation units is merged by the linker, which may keep the function
// that creates the lambda from one unit and the one that copies it (a CudaExec member
// instantiated for the wrapper) from the other, whose pointers were never set: a call to
// address 0 (seen: DynamicDelaunay3d::remove from Python, mesh::gather_live's compaction).
// Instantiated with a type that belongs to the unit, every such template is the unit's own.
#pragma once
#include "exec/exec_context.hpp"
#include "gpugeom/common.hpp"

#define GG_TU_EXECUTOR(Base)                                                                       \
  namespace {                                                                                      \
  struct Exec : Base {                                                                             \
    explicit Exec(const RunOptions& run = {}) : Base(run) {}                                       \
    Exec(const RunOptions& run, const ::gpugeom::detail::ExecContext* outer) : Base(run, outer) {} \
  };                                                                                               \
  }
