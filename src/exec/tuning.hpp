// The library's internal knobs (RunOptions::tuning; issue 48): switches the tests and the
// benchmarks set to send small inputs through the paths only large inputs take, or to try a
// size other than the library's rule. They are carried in the options of one call, never in
// globals, so calls with different knobs may run at once on several host threads. No knob
// changes a result: each only changes how it is reached.
#pragma once
#include <cstdint>

#include "gpugeom/common.hpp"

namespace gpugeom::detail {

struct Tuning {
  struct Edt {
    // Raster-index packing (edt::LinearLayout) for grids whose coordinates fit 32 bits together.
    bool linear_packing = false;
    // Slice-by-slice requests packed by column (edt::ColumnLayout) whatever the volume's size.
    bool column_packing = false;
  } edt;
  struct Del2d {
    // The flip rounds' capacities in place of those sized from the point count (0 keeps the
    // rule's): points one batch inserts, flip-log records, exact-list entries.
    std::int64_t batch_points = 0, log_records = 0, exact_entries = 0;
    // The first triangle slot's number (clamped so that the last slot is 2^30 - 1): small inputs
    // then run through the top of the wide slot encoding (bit 31 set in neighbour pointers).
    std::int64_t slot_base = 0;
    // The longest work list whose flip rounds run in one team (0: the rule's, twice the team's
    // size; -1: none, every round as kernels).
    std::int64_t team_list = 0;
    // The CPU executor runs the batches and flip rounds (the GPU's schedule) rather than its own
    // (points one by one: delaunay2d/impl/one_by_one.inl), as it does where a knob above is set.
    bool batches = false;
  } del2d;
  struct Hull3d {
    // The facet store's first size in slots (0: the rule's, hull3d::first_facet_slots), so that
    // small hulls grow the store.
    std::int64_t first_facet_slots = 0;
    // The CPU executor runs the rounds (the GPU's schedule: splits, then Flip-Flop) rather than
    // its own (points one by one: hull3d/impl/one_by_one.inl).
    bool rounds = false;
  } hull3d;
  struct Del3d {
    // At most this many flip rounds after each insertion batch (-1: until no flip is left), so
    // that star splaying must repair a tetrahedralisation far from Delaunay (0: none). Only the
    // incremental method has rounds; Method::Digital refuses a value >= 0.
    std::int64_t max_flip_rounds = -1;
    // The CPU executor runs the batches and flip rounds (the GPU's schedule) rather than its own
    // (points one by one: delaunay3d/impl/one_by_one.inl), as it does where max_flip_rounds is
    // set.
    bool batches = false;
    // Slots of the room from which the CPU's split parts take their ranges (mesh/
    // cavity_schedule.hpp, PartPoints), in a stage; -1: a quarter of a slot a point and 1024 a
    // split part. Tests make it small, so that it runs out.
    std::int64_t split_room = -1;
  } del3d;
};

// The knobs a call runs with: the options' own, or the library's rules.
inline constexpr Tuning kDefaultTuning{};
inline const Tuning& tuning_of(const RunOptions& run) {
  return run.tuning ? *run.tuning : kDefaultTuning;
}

}  // namespace gpugeom::detail
