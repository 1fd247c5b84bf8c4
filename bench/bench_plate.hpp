// SPDX-License-Identifier: BSD-3-Clause
// The plate of the solid benchmarks: the plate of Gray, Monaghan & Swift scaled to L/H = 10 with
// `length` particles along it (its width equal to its thickness in 3D), clamped by 4 columns,
// started in its first mode (every bond stretched).
#pragma once

#include <cstddef>
#include <vector>

#include "mpsfsi/scenes/oscillating_plate.hpp"
#include "mpsfsi/solid/solid_parameters.hpp"

namespace mpsfsi::bench {

template <int Dim>
struct BenchPlate {
  ParticleSet<Dim> particles;
  SolidParameters<Dim> params;
  std::vector<std::size_t> clamped;

  explicit BenchPlate(long length) {
    scenes::OscillatingPlate plate;
    const double l0 = plate.length / static_cast<double>(length);
    plate.thickness = plate.width = plate.length / 10;
    std::size_t tip = 0;
    params.l0 = l0;
    plate.set_material(params);
    particles = plate.particles<Dim>(l0, 4, clamped, tip);
  }
};

}  // namespace mpsfsi::bench
