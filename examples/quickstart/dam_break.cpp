// Quick start: a 2D dam break with FluidSolver, written for ParaView.
#include <cstdio>
#include <mpsfsi/mpsfsi.hpp>
using namespace mpsfsi;

int main() {
  const double l0 = 0.01;  // particle spacing, m
  // A water column 0.25 m x 0.5 m against the left wall of a tank 1 m long and 0.6 m high
  // (the scene adds the wall and dummy particles).
  FluidParameters<2> p;
  p.l0 = l0;  // time step: automatic (Courant 0.2); gravity: -9.81 m/s2 along y
  FluidSolver<2> water(scenes::dam_break<2>(0.25, 0.5, 1.0, 0.6, l0), p);
  PvdWriter series("dam_break.pvd");
  for (int frame = 0; frame <= 10; ++frame) {
    water.advance_to(0.02 * frame);  // s
    const std::string file = numbered_file_name("dam_break", frame);
    write_vtu(file, water.particles());  // position, velocity, pressure, ...
    series.add(water.time(), file);
  }
  std::printf("t = %.2f s: surge front at x = %.3f m after %lld steps\n", water.time(),
              scenes::surge_front(water.particles(), l0), water.step_count());
}
