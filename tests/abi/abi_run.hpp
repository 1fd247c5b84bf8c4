// SPDX-License-Identifier: BSD-3-Clause
// The run both translation units make: a clamped ice plate released from a bent shape, 200 steps
// of the default ElasticSolver. In an unnamed namespace, so each unit keeps its own copy.
#pragma once

#include <typeinfo>

#include <mpsfsi/mpsfsi.hpp>

#include "abi/abi_report.hpp"

namespace {

AbiReport run_here() {
  using namespace mpsfsi;
  const double l0 = 0.005;
  ParticleSet<2> set = scenes::material_block<2>(Vec<2>(0, 0), Vec<2>(0.2, 0.02), l0);
  for (std::size_t i = 0; i < set.size(); ++i) set.velocities()[i] = Vec<2>(0, 0.01 * set.positions()[i][0] / 0.2);
  SolidParameters<2> p;
  p.l0 = l0;
  p.density = 917;
  p.youngs_modulus = 5e9;
  p.poisson_ratio = 0.3;
  ElasticSolver<2> plate(set, p);
  for (std::size_t i = 0; i < set.size(); ++i)
    if (set.positions()[i][0] < 2 * l0) plate.clamp(i);
  for (int s = 0; s < 200; ++s) plate.step();
  AbiReport r;
  r.lanes = ElasticSolver<2>::stress_model_type::lanes;
  r.solver_type = typeid(ElasticSolver<2>).name();
  for (const auto& x : plate.particles().positions()) r.positions.insert(r.positions.end(), {x[0], x[1]});
  return r;
}

}  // namespace
