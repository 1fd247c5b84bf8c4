// Quick start: a notched ice bar pulled until it breaks, with ElasticSolver and brittle fracture.
#include <cstdio>
#include <mpsfsi/mpsfsi.hpp>
using namespace mpsfsi;

int main() {
  const double l0 = 0.002;  // m
  ParticleSet<2> ice = scenes::material_block<2>(Vec<2>(-0.05, 0), Vec<2>(0.05, 0.02), l0);  // 0.1 m x 0.02 m
  SolidParameters<2> p;
  p.l0 = l0;
  p.density = 917;              // kg/m3
  p.youngs_modulus = 270e6;     // Pa
  p.poisson_ratio = 0.3;
  p.tensile_strength = 1.14e6;  // Pa: sigma_f of the maximum principal stress criterion
  p.plane_model = PlaneModel::plane_stress;
  ElasticSolver<2, BrittleSolidPolicies<2>> bar(ice, p);
  for (auto i : scenes::select(ice, [](const Vec<2>& x) { return x[0] < -0.044; })) bar.clamp(i);
  for (auto i : scenes::select(ice, [](const Vec<2>& x) { return x[0] > 0.044; }))
    bar.prescribe_velocity(i, Vec<2>(0.05, 0));  // pull the right end at 0.05 m/s
  // A notch: cut the bonds across x = 0 at the bottom particle next to the origin.
  bar.impose_crack(scenes::select(ice, [](const Vec<2>& x) { return x.norm() < 0.002; })[0], Vec<2>(1, 0));
  while (bar.first_failure_time() < 0 && bar.time() < 0.1) bar.step();
  bar.advance_to(bar.time() + 1e-3);  // let the crack run
  std::printf("first failure at t = %.2f ms; %zu bonds cut; %zu pieces\n", 1e3 * bar.first_failure_time(),
              bar.cut_bonds(), find_fragments(bar.bonds()).count_larger_than(10));
  write_vtu("brittle_bar.vtu", bar.output());  // displacement, stress, damage, fragment
}
