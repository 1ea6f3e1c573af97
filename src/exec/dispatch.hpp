// A module's entries on the executor a run resolved to (internal).
//
// A module's algorithm is one source, written over a type named `Exec` (its impl/*.inl files),
// and compiled once per executor: the executor's unit (NS/*_cpu.cpp, NS/*_cuda.cu, a few lines
// each) names `Exec` inside NS::cpu_impl or NS::cuda_impl (the latter only in CUDA builds),
// includes the algorithm, and then fills the module's table of entries as `entries` in that
// namespace (impl/entries.inl, or one line in the unit where the table is short). The table is a
// struct of function pointers, declared once, in the module's backend header; the public entries
// pick a table with GG_ENTRIES(backend, NS) and call through it, and one module reaches another's
// entries the same way.
//
// Why a table of functions and not function templates over Exec instantiated per executor:
// a CUDA unit compiles its algorithm over a type of its own (exec/tu_exec.hpp says why), which
// no other unit can name, and the host code that calls it (built by the host compiler) cannot
// construct a CudaExec. The unit boundary therefore has to be plain functions; inside a unit
// everything is written over `Exec` once.
#pragma once
#include "gpugeom/common.hpp"

// GG_TABLE(backend, NS, name) picks another table of the module's (one per unit where a
// module has two, as Delaunay and its Voronoi diagram do).
#ifdef GPUGEOM_HAVE_CUDA
#define GG_TABLE(backend, ns, name) \
  ((backend) == ::gpugeom::Backend::Cuda ? ns::cuda_impl::name : ns::cpu_impl::name)
#else
#define GG_TABLE(backend, ns, name) ((void)(backend), ns::cpu_impl::name)
#endif
#define GG_ENTRIES(backend, ns) GG_TABLE(backend, ns, entries)

// Declares the module's table `name` of type `type` once for each executor, in the module's
// namespace (the backend header's one line; each executor's unit defines it).
#define GG_DECLARE_TABLE(type, name) \
  namespace cpu_impl {               \
  extern const type name;            \
  }                                  \
  namespace cuda_impl {              \
  extern const type name;            \
  }
