// A capability's typed statistics (a struct of std::int64_t counters deriving from RunStats,
// common.hpp) given their names once (internal): GG_COUNTER_MAP(TYPE, LIST) defines
// TYPE::counter_map() from LIST, an X-macro naming every counter field, and checks at compile
// time that LIST names as many fields as TYPE adds to RunStats, so a new field cannot be left
// out of the printed map.
#pragma once
#include <cstdint>
#include <map>
#include <string>

#include "gpugeom/common.hpp"

#define GG_PUT_COUNTER_(f) m[#f] = f;
#define GG_COUNT_ONE_(f) +1
#define GG_COUNTER_MAP(TYPE, LIST)                                                                 \
  std::map<std::string, std::int64_t> TYPE::counter_map() const {                                  \
    auto m = RunStats::counter_map();                                                              \
    LIST(GG_PUT_COUNTER_)                                                                          \
    return m;                                                                                      \
  }                                                                                                \
  static_assert(sizeof(TYPE) == sizeof(RunStats) + (0 LIST(GG_COUNT_ONE_)) * sizeof(std::int64_t), \
                #TYPE "'s counter fields and its list in counter_map differ")
