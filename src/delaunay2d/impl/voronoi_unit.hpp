// The headers the 2D Voronoi diagram (impl/voronoi.inl) needs: included, before the executor's
// own header, by each executor's unit (voronoi_cpu.cpp, voronoi_cuda.cu).
#pragma once
#include <algorithm>
#include <chrono>
#include <cstdint>
#include <string>
#include <thrust/functional.h>

#include "base/clock.hpp"
#include "delaunay2d/del2d_backend.hpp"
#include "delaunay2d/voronoi_core.hpp"
#include "exec/atomics.hpp"
#include "exec/deliver.hpp"
#include "exec/peak.hpp"
#include "exec/scratch_lease.hpp"
#include "exec/voronoi_upload.hpp"
#include "gpugeom/removed.hpp"
#include "mesh/union_find.hpp"
#include "mesh/vertex_classes.hpp"
#include "predicates/predicates.hpp"
