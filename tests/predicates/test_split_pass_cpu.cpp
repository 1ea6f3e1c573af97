#include "exec/cpu_exec.hpp"
#define EXEC gpugeom::CpuExec
#define SUITE CpuSplitPass
#include "split_pass_suite.inl"
