// SPDX-License-Identifier: BSD-3-Clause
// What the dam break's output loop has done so far (dam_break and dam_break_mpi), saved with the
// solver in each checkpoint so that a restarted run writes the same files as one run straight
// through. In dam_break_mpi every process saves it; the CSV rows are process 0's, the rest is
// the same on every process.
#pragma once

#include <cstdint>
#include <vector>

namespace dam_break_example {

struct OutputState {
  long long frames = 0;             // snapshots written
  double next_output = 0;           // simulated time of the next one
  double wall = 0;                  // wall seconds in the solver so far (the CSV's wall_s)
  std::vector<double> frame_times;  // simulated time of each snapshot (the PVD index)
  std::uint64_t csv_rows = 0;       // rows of dam_break.csv

  template <class Archive>
  void checkpoint_state(Archive& a) {
    a.value(frames);
    a.value(next_output);
    a.value(wall);
    a.array(frame_times);
    a.value(csv_rows);
  }
};

}  // namespace dam_break_example
