// The schedule of a mesh module's flip rounds, one for the 2D and 3D triangulations and the
// hull's Flip-Flop (design notes, "One schedule for the flip rounds").
//
// A round works through one work list (mesh/work_list.hpp) whose length stays on the executor,
// so rounds are launched without the host waiting on each: while the list is long, a chunk of
// rounds runs as kernels and the host reads the counters once after it; once the list is short
// (the tail of a batch, when a round costs its launches rather than its work), the rounds run
// in one team (Exec::team: one block on CUDA, one OpenMP region on the CPU) with barriers
// between the steps, until the list grows past the team's length, empties, or the round's room
// runs out. The host then reads the counters once and goes on.
//
// What differs is the module's, through a phase object (its rounds.inl):
//   std::int64_t pending()                 entries on the next round's list (the last read)
//   std::int64_t team_max()                the longest list a team takes
//   bool team_fits()                       the room rule for a team, on the host
//   std::int64_t plan()                    rounds in the next chunk of kernels (at least 1);
//                                          also where the module makes room before a chunk
//   void team(std::int64_t limit)          a team of at most `limit` rounds (team_rounds below)
//   void kernels(std::int64_t rounds)      `rounds` rounds as kernels
//   ChunkEnd end_chunk(bool team)          the counters read once, the host's state updated
//   void out_of_rounds()                   the round budget spent: throw, or leave pending()
//                                          at 0 (a test's cut)
// Room is where the modules differ most: 2D's store never grows, and its host checks a round
// that could overflow the flip log or the exact list (plan, kernels); 3D's rounds halt
// themselves on the device and the host grows the store (end_chunk).
#pragma once
#include <algorithm>
#include <cstdint>

#include "base/clock.hpp"
#include "base/hd.hpp"

namespace gpugeom::mesh {

// What one read of the counters after a chunk says.
struct ChunkEnd {
  std::int64_t rounds = 0;  // rounds the chunk ran (a team that ran none: the kernels go next)
  bool stop = false;        // the phase is done for now (3D: the list carried to the next batch)
};

// How the rounds ran, for the modules' statistics.
struct ScheduleCounts {
  std::int64_t chunks = 0;          // chunks of rounds as kernels
  std::int64_t team_calls = 0;      // teams launched
  std::int64_t team_rounds = 0;     // rounds a team ran
  double wide_ms = 0, team_ms = 0;  // host time of each way's chunks, launch to end_chunk
};

// Rounds until the phase's list is empty (or end_chunk says stop), at most max_rounds in all.
template <class Phase>
void run_rounds(Phase& p, std::int64_t max_rounds, ScheduleCounts& counts) {
  std::int64_t ran = 0;
  bool team_ran_none = false;  // (only at the round limit: then the kernels take the round)
  while (p.pending() > 0) {
    if (ran >= max_rounds) {
      p.out_of_rounds();
      break;
    }
    const std::int64_t chunk = std::min(p.plan(), max_rounds - ran);
    const bool team = !team_ran_none && p.pending() <= p.team_max() && p.team_fits();
    const auto t0 = Clock::now();
    if (team)
      p.team(max_rounds - ran);
    else
      p.kernels(chunk);
    const ChunkEnd e = p.end_chunk(team);
    (team ? counts.team_ms : counts.wide_ms) += ms_since(t0);
    ++(team ? counts.team_calls : counts.chunks);
    if (team) counts.team_rounds += e.rounds;
    team_ran_none = team && e.rounds == 0;
    ran += e.rounds;
    if (e.stop) break;
  }
}

// The rounds of one team, from the round R is at (called by every thread of the team t):
// each round, every thread reads the list's length (R.count()); the team stops when it is 0 or
// over `max`, at round `stop`, or where room(R, n) says the round does not fit. Otherwise a
// barrier (every thread has read the length before the round's first write), body(R, n) (the
// round's steps with barriers between them, ending with one), and R.advance() to the next
// round. Rank 0 leaves the round it stopped at (not run) in *end.
template <class Team, class Round, class Room, class Body>
GG_HD void team_rounds(const Team& t, Round R, std::int64_t max, std::int32_t stop,
                       std::int64_t* end, Room room, Body body) {
  for (;;) {
    const std::int64_t n = *R.count();
    if (n == 0 || n > max || R.round >= stop || !room(R, n)) break;
    t.barrier();
    body(R, n);
    R.advance();
  }
  if (t.rank == 0) *end = R.round;
}

// The last round a team may start from `round` with a budget of `limit` rounds.
inline std::int32_t team_stop(std::int32_t round, std::int64_t limit) {
  return std::int32_t(std::min<std::int64_t>(std::int64_t(round) + limit, INT32_MAX));
}

}  // namespace gpugeom::mesh
