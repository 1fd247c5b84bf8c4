// SPDX-License-Identifier: BSD-3-Clause
// Must not compile: a failure model that takes the crack normal by value would compile and leave
// the solver's normal unset.
#include "mpsfsi/fracture/fracture_process.hpp"
#include "mpsfsi/solid/elastic_solver.hpp"

struct DirectionByValue {
  static constexpr bool enabled = true;
  template <int Dim, class Scalar>
  static Scalar principal(const mpsfsi::Mat<Dim, Scalar>& sigma, mpsfsi::Vec<Dim, Scalar> direction) {
    direction = mpsfsi::Vec<Dim, Scalar>::UnitX();
    return sigma(0, 0);
  }
};
struct Policies : mpsfsi::SolidDefaults<2> {
  using failure = DirectionByValue;
};
static_assert(sizeof(mpsfsi::ElasticSolver<2, Policies>) > 0);
