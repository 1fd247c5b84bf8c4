// SPDX-License-Identifier: BSD-3-Clause
// What an example's output loop has done so far, saved with the solver in each checkpoint so that
// a restarted run writes the same files as one run straight through. An example with more to
// carry over derives from it and adds its own fields after these.
#pragma once

#include <cstdint>
#include <vector>

namespace mpsfsi_examples {

struct OutputRecord {
  long long frames = 0;             // snapshots written
  double next_output = 0;           // simulated time of the next one
  std::vector<double> frame_times;  // simulated time of each snapshot (the PVD index)
  std::uint64_t csv_rows = 0;       // rows of the example's time-history CSV

  template <class Archive>
  void checkpoint_state(Archive& a) {
    a.value(frames);
    a.value(next_output);
    a.array(frame_times);
    a.value(csv_rows);
  }
};

}  // namespace mpsfsi_examples
