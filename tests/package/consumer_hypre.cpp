// SPDX-License-Identifier: BSD-3-Clause
// Downstream use of the optional BoomerAMG solver: solves a 2x2 SPD system.
#include <cstdio>

#include <mpsfsi/fluid/hypre_amg.hpp>

int main() {
  mpsfsi::PpeMatrix a(2, 2);
  a.insert(0, 0) = 2;
  a.insert(0, 1) = -1;
  a.insert(1, 0) = -1;
  a.insert(1, 1) = 2;
  a.makeCompressed();
  mpsfsi::PpeVector b(2), x = mpsfsi::PpeVector::Zero(2);
  b << 1, 0;
  const auto r = mpsfsi::HypreAmgCg{}.solve(a, b, x, 1e-12, 50);
  std::printf("x = (%g, %g), %d iterations\n", x[0], x[1], r.iterations);
  return r.converged ? 0 : 1;
}
