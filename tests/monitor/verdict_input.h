#pragma once
// A run the verdict passes (swa/run_record/verdict.h), for tests that change one thing of it: completed, truth seen,
// d_NB within the band of r = 10 m ± 10 %, no collision, one group.

#include "swa/run_record/verdict.h"

namespace swa::record::testing {

inline VerdictInput passingRun() {
  VerdictInput in;
  in.completed = true;
  in.end_reason = "completed";
  in.saw_truth = true;
  in.summary.mean_neighbor_distance_m = 10.3;
  in.summary.collisions = 0;
  in.summary.groups = 1;
  in.scoring.formation.radius_m = 10.0;
  in.scoring.radius_tolerance = 0.10;
  return in;
}

}  // namespace swa::record::testing
