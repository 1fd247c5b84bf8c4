// Quick start: water released against a rubber gate (Antoci et al. 2007), with FsiCoupler.
#include <cstdio>
#include <mpsfsi/mpsfsi.hpp>
using namespace mpsfsi;

int main() {
  const double l0 = 0.0025;  // m
  const scenes::ElasticGate scene;  // the gate's material and geometry, the tank and the water
  std::vector<std::size_t> clamped;
  std::size_t tip = 0;
  SolidParameters<2> sp;
  sp.l0 = l0;
  scene.set_material(sp);  // rubber: 1100 kg/m3, E = 10 MPa, nu = 0.4
  sp.gravity = scene.gravity_vector<2>();
  ElasticSolver<2> gate(scene.gate_particles<2>(l0, clamped, tip), sp);
  for (auto i : clamped) gate.clamp(i);  // the gate hangs from its top
  FluidParameters<2> fp;
  fp.l0 = l0;
  fp.gravity = scene.gravity_vector<2>();
  // The gate's surface particles join the fluid as moving walls; sub-iterated (strong) coupling.
  FsiCoupler<FluidSolver<2>, ElasticSolver<2>, SubIterated> fsi(scene.fluid_particles<2>(l0), fp, std::move(gate));
  const Vec<2> tip0 = fsi.solid().particles().positions()[tip];
  fsi.advance_to(0.05);  // s
  std::printf("t = %.3f s: gate tip moved %.2f mm downstream; load on the gate %.1f N/m\n", fsi.time(),
              1e3 * (fsi.solid().particles().positions()[tip] - tip0)[0], fsi.total_interface_force().norm());
  write_vtu("water.vtu", fsi.fluid().particles());
  write_vtu("gate.vtu", fsi.solid().output());
}
