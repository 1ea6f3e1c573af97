// One block of the several devices of one host (delaunay_devices.cpp), run where its
// triangulation is made: the block's points go to its device once, are triangulated there, and
// the per-simplex passes (its owned simplices, the simplices to test, the border for the other
// blocks, the output rows and the face requests) run on the same device (block_pass_on.hpp);
// only their compact results come back, and the owned rows stay there for the assembly. The
// modules' tables run it (Assembly::block in del2d_backend.hpp / del3d_backend.hpp), so one source
// serves both executors.
#pragma once
#include <cstdint>
#include <functional>
#include <memory>
#include <utility>
#include <vector>

#include "blocks/simplex_rules.hpp"
#include "gpugeom/blocks.hpp"
#include "gpugeom/host_vector.hpp"

namespace gpugeom::blocks_detail {

// What a block is given (host memory): its local points in increasing global order (so a
// simplex's lowest local vertex is its lowest global one: the owner rule), each one's input
// index (the output's names) and block (its own points are those of `block`). The points come
// either as `points`, or where the block's device can read the prepared points (`source`, the
// first device's memory: peer access, the same device, or the host on the CPU executor) as each
// local point's place there, gathered on the block's device.
struct BlockTask {
  const double* points = nullptr;
  const double* source = nullptr;
  const std::int32_t* places = nullptr;
  std::int64_t n = 0;
  const std::int32_t* ids = nullptr;
  const std::int32_t* blk = nullptr;
  std::int64_t block = 0;
  // The first round's border and first finality test: the blocks' grid (null in the second
  // round, which has neither), the largest coordinate magnitude of the bounds, the boxes.
  const BorderCells* cells = nullptr;
  double scale = 0;
  const BlockBoxes* boxes = nullptr;
};

// What comes back (host memory).
struct BlockRows {
  // First round: the simplices whose stars the host tests against every point (stars_final),
  // as their D + 1 local vertex indices each, in the triangulation's order; and per other block
  // (increasing) the local indices of the own points it is sent, increasing.
  HostVector<std::int32_t> test;
  std::vector<std::pair<std::int64_t, HostVector<std::int32_t>>> borders;
  // Whether the output below was made (the first round's only where the host's test passed).
  bool final = false;
  // The `count` owned simplices (those whose lowest vertex is an own point), in the
  // triangulation's order, in input indices; per face the neighbour's row here, -1 (the global
  // hull) or -2 (another block's): left where they were made (the block's device; the host on
  // the CPU executor), for the assembly to copy (owned_on.hpp). And, in host memory, the -2
  // faces as requests (block_output's rules, in row-major order): the block that matches each,
  // its D input indices sorted, its position row * (D + 1) + face, and whether it is open (a
  // local hull face that may lie on the global hull).
  std::shared_ptr<std::int32_t> simplices, neighbors;
  std::int64_t count = 0;
  int device = -1;  // (-1: host memory)
  HostVector<std::int32_t> request_owner, request_key, request_pos;
  HostVector<std::uint8_t> request_open;
  // Milliseconds: the triangulation (with the points' copy), the passes before the test, the
  // host's test, and the output (with the copies back).
  double ms_triangulate = 0, ms_passes = 0, ms_final = 0, ms_output = 0;
};

// The host's finality test of the first round's rows (true: the block's stars are final).
using FinalTest = std::function<bool(const BlockRows&)>;

}  // namespace gpugeom::blocks_detail
