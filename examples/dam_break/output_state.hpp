// SPDX-License-Identifier: BSD-3-Clause
// What the dam break's output loop has done so far (dam_break and dam_break_mpi), saved with the
// solver in each checkpoint. In dam_break_mpi every process saves it; the CSV rows are process
// 0's, the rest is the same on every process.
#pragma once

#include "common/output_record.hpp"

namespace dam_break_example {

struct OutputState : mpsfsi_examples::OutputRecord {
  double wall = 0;  // wall seconds in the solver so far (the CSV's wall_s)

  template <class Archive>
  void checkpoint_state(Archive& a) {
    OutputRecord::checkpoint_state(a);
    a.value(wall);
  }
};

}  // namespace dam_break_example
