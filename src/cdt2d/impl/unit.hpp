// The headers the constrained triangulation (impl/*.inl) needs: included, before the executor's
// own header, by each executor's unit (cdt2d_cpu.cpp, cdt2d_cuda.cu).
#pragma once
#include <algorithm>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>
#include <climits>
#include <thrust/functional.h>

#include "base/clock.hpp"
#include "cdt2d/cavity.hpp"
#include "cdt2d/cdt2d_backend.hpp"
#include "delaunay2d/del2d_backend.hpp"
#include "gpugeom/delaunay2d.hpp"
#include "exec/atomics.hpp"
#include "exec/deliver.hpp"
#include "exec/peak.hpp"
#include "exec/prefault.hpp"
#include "exec/scratch_slots.hpp"
#include "locate/walk.hpp"
#include "mesh/union_find.hpp"
