#include <cuda/atomic>

#include "exec/cpu_exec.hpp"
#define EXEC gpugeom::CpuExec
#define SUITE CpuExecTest
#include "exec_suite.inl"
