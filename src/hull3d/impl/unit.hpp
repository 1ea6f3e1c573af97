// The headers the 3D hull's algorithm (unit.inl) needs: included, before the executor's own
// header, by each executor's unit (hull3d_cpu.cpp, hull3d_cuda.cu).
#pragma once
#include <algorithm>
#include <array>
#include <cmath>
#include <chrono>
#include <cstdint>
#include <cstring>
#include <functional>
#include <limits>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "base/clock.hpp"
#include "exec/atomics.hpp"
#include "exec/deliver.hpp"
#include "exec/peak.hpp"
#include "hull3d/hull3d_backend.hpp"
#include "exec/scratch_slots.hpp"
#include "mesh/adjacency.hpp"
#include "mesh/cavity_schedule.hpp"
#include "mesh/visibility_walk.hpp"
#include "mesh/compact.hpp"
#include "mesh/decision.hpp"
#include "mesh/flip_fix.hpp"
#include "mesh/flip_schedule.hpp"
#include "mesh/first_tetrahedron.hpp"
#include "mesh/kept_points.hpp"
#include "mesh/prepare.hpp"
#include "mesh/priority.hpp"
#include "mesh/simplex_changes.hpp"
#include "mesh/work_list.hpp"
#include "predicates/predicates.hpp"
