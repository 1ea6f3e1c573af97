// The library's knobs for one call (RunOptions::tuning, src/exec/tuning.hpp): the tests' way to
// send small inputs through the paths only large ones take. Carried in the options, so tests with
// different knobs may run calls at once.
#pragma once
#include <memory>

#include "exec/tuning.hpp"

namespace gg_test {
// set(t) adjusts a default detail::Tuning t; the result goes in RunOptions::tuning.
template <class Set>
std::shared_ptr<const gpugeom::detail::Tuning> tuning(Set set) {
  auto t = std::make_shared<gpugeom::detail::Tuning>();
  set(*t);
  return t;
}
// o with the knobs set(t) makes.
template <class Options, class Set>
Options tuned(Options o, Set set) {
  o.tuning = tuning(set);
  return o;
}
}  // namespace gg_test
