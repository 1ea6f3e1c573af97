// A capability's typed statistics (a struct of std::int64_t counters deriving from RunStats,
// common.hpp) given their names once (internal): GG_COUNTER_MAP(TYPE, LIST) defines
// TYPE::counter_map() from LIST, an X-macro naming every counter field, and checks at compile
// time that LIST names as many fields as TYPE adds to RunStats, so a new field cannot be left
// out of the printed map. GG_COUNTER_MAP_OVER(TYPE, BASE, LIST) likewise over another base.
#pragma once
#include <cstdint>
#include <map>
#include <string>

#include "gpugeom/common.hpp"

#define GG_PUT_COUNTER_(f) m[#f] = f;
#define GG_COUNT_ONE_(f) +1
// TYPE derives from BASE (RunStats, or another capability's statistics whose counters it carries
// beside its own, as the CDT's carry its Delaunay triangulation's).
#define GG_COUNTER_MAP_OVER(TYPE, BASE, LIST)                                                  \
  std::map<std::string, std::int64_t> TYPE::counter_map() const {                              \
    auto m = BASE::counter_map();                                                              \
    LIST(GG_PUT_COUNTER_)                                                                      \
    return m;                                                                                  \
  }                                                                                            \
  static_assert(sizeof(TYPE) == sizeof(BASE) + (0 LIST(GG_COUNT_ONE_)) * sizeof(std::int64_t), \
                #TYPE "'s counter fields and its list in counter_map differ")
#define GG_COUNTER_MAP(TYPE, LIST) GG_COUNTER_MAP_OVER(TYPE, RunStats, LIST)
