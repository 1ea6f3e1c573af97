// The headers the 3D Voronoi diagram and the Voronoi cells (impl/voronoi.inl, cells*.inl) need:
// included, before the executor's own header, by each executor's unit (voronoi3d_cpu.cpp,
// voronoi3d_cuda.cu).
#pragma once
#include <algorithm>
#include <cfloat>
#include <cmath>
#include <chrono>
#include <cstdint>
#include <string>
#include <type_traits>
#include <thrust/functional.h>

#include "base/clock.hpp"
#include "delaunay3d/convex_cell.hpp"
#include "delaunay3d/del3d_backend.hpp"
#include "delaunay3d/voronoi3d_backend.hpp"
#include "exec/atomics.hpp"
#include "exec/deliver.hpp"
#include "exec/peak.hpp"
#include "exec/scratch_lease.hpp"
#include "exec/voronoi_upload.hpp"
#include "gpugeom/removed.hpp"
#include "gpugeom/voronoi_cells.hpp"
#include "mesh/sum2.hpp"
#include "mesh/union_find.hpp"
#include "mesh/vertex_classes.hpp"
#include "predicates/expansion.hpp"
#include "predicates/predicates.hpp"
#include "spatial/hilbert.hpp"
