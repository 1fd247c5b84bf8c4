// SPDX-License-Identifier: BSD-3-Clause
#pragma once

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <deque>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "mpsfsi/core/abi.hpp"
#include "mpsfsi/core/cell_list_search.hpp"
#include "mpsfsi/core/detail/format.hpp"
#include "mpsfsi/core/detail/state_archive.hpp"
#include "mpsfsi/core/error.hpp"
#include "mpsfsi/core/particle_set.hpp"
#include "mpsfsi/fsi/coupling_parameters.hpp"
#include "mpsfsi/fsi/coupling_schemes.hpp"
#include "mpsfsi/fsi/interface_acceleration.hpp"
#include "mpsfsi/fsi/interface_load.hpp"
#include "mpsfsi/fsi/structure_surface.hpp"
#include "mpsfsi/kernels/lattice_constants.hpp"
#include "mpsfsi/kernels/weight.hpp"

namespace mpsfsi {
inline namespace MPSFSI_ABI {

// Fully Lagrangian fluid-structure interaction (the paper's eqs 9-10, 18-19, Fig 1;
// docs/theory.md, section 4), for a FluidSolver and an ElasticSolver of the same dimension:
// - The structure's particles join the fluid's particle set: its surface particles (structure
//   normals from the number-density gradient of its intact bonds) as moving wall particles in
//   the PPE, the rest as dummy particles. Positions, velocities and the surface are refreshed
//   from the structure before every fluid step, so deformation and cracks reach the fluid; fluid
//   may enter a crack once it opens.
// - A surface particle whose outward lattice site x_i + l0 n_i lies inside the tank's fixed walls
//   (a wall or dummy particle of the fluid's own set within 0.25 l0 of it) is covered, not wetted:
//   it joins the fluid as a dummy particle and takes no load (CouplingParameters::
//   covered_surface_as_dummy). A structure clamped into a tank wall would otherwise put a strip
//   of wall particles under that wall, ending in the structure's end face, a P = 0 row of the
//   PPE; the pressure drains along it and draws the water in the corner (hydrostatic plate at
//   h/l0 = 8: peak corner speed 0.28 m/s without the option, 0.06 with it; docs/validation/fsi.md).
//   0.25 l0: on a structure lying on the walls' lattice, the site of a covered flat face is within
//   0.07 l0 of a wall particle (normals tilt by up to 0.03 near an end), while the diagonal site of
//   a corner particle, wetted on its other side (a crack's foot on the tank floor), is 0.39-0.44 l0
//   from one. Off the walls' lattice a covered face may be missed: it stays a wall, as without
//   the option.
// - The interface pressure at x_i + 0.5 l0 n_i (eqs 18-19) becomes the structure's load.
// - The structure sub-steps through each fluid step (dt_f / dt_s steps of its own stable dt).
// - The interface acceleration enters the fluid predictor (eq 10), unless switched off.
// The Scheme policy (coupling_schemes.hpp) advances the two within a step, through Step.
template <class Fluid, class Solid, class Scheme = ExplicitPartitioned>
class FsiCoupler {
  static_assert(Fluid::dimension == Solid::dimension,
                "FsiCoupler: the fluid and the solid solver have different dimensions (FluidSolver<Dim> and "
                "ElasticSolver<Dim> must use the same Dim)");
  static_assert(std::is_same_v<typename Fluid::scalar_type, typename Solid::scalar_type>,
                "FsiCoupler: the fluid and the solid solver use different scalar types");

 public:
  static constexpr int dimension = Fluid::dimension;
  using scalar_type = typename Fluid::scalar_type;
  using vec_type = Vec<dimension, scalar_type>;
  using fluid_type = Fluid;
  using solid_type = Solid;
  using scheme_type = Scheme;
  using vec_array = VecArray<dimension, scalar_type>;

  // What a coupling scheme advances one step through (coupling_schemes.hpp lists the calls).
  class Step {
   public:
    static constexpr int dimension = FsiCoupler::dimension;
    using scalar_type = FsiCoupler::scalar_type;
    using vec_array = FsiCoupler::vec_array;

    // The fluid's step from t^n with the structure as its moving wall: at its velocity at t^n on
    // the first solve of the step; on a repeat (iterative schemes) the fluid first returns to t^n
    // and the wall moves at the structure's mean velocity over the step, if it has advanced.
    void solve_fluid() { c_.solve_fluid(); }
    // The fluid's load on each structure particle after the last solve (eqs 18-19).
    void fluid_load(vec_array& load) {
      c_.require_fluid_solved("fluid_load");
      c_.compute_loads(load);
    }
    // The structure from t^n (returned to it on a repeat) to t^n + dt under `load` plus the
    // user's applied_force(), in sub-steps of its own stable step.
    void advance_structure(const vec_array& load) { c_.advance_structure_in_step(load); }
    // The interface load kept across steps; what the step leaves here is interface_force().
    vec_array& load() { return c_.load_; }
    // Scratch array k, one entry per structure particle, kept by the coupler across steps (its
    // content at the start of a step is unspecified).
    vec_array& workspace(std::size_t k) {
      while (c_.workspace_.size() <= k) c_.workspace_.emplace_back();
      c_.workspace_[k].resize(c_.load_.size());
      return c_.workspace_[k];
    }
    // The fluid's time step of this step (after the first solve_fluid), the step's number
    // (1 for the first step of the run) and the fluid solves so far in this step.
    double dt() const {
      c_.require_fluid_solved("dt");
      return c_.dt_;
    }
    long long step_number() const { return c_.step_count_ + 1; }
    int fluid_solves() const { return c_.fluid_solves_; }
    // Throws SimulationError: "FsiCoupler: <what> at step N (t = T s)".
    [[noreturn]] void fail(const std::string& what) const {
      throw SimulationError("FsiCoupler: " + what + " at step " + std::to_string(c_.step_count_ + 1) +
                                " (t = " + detail::format_number(c_.fluid_.time()) + " s)",
                            c_.step_count_ + 1, c_.fluid_.time(), -1);
    }

    Step(const Step&) = delete;  // valid for the one step it was handed for
    Step& operator=(const Step&) = delete;

   private:
    friend class FsiCoupler;
    explicit Step(FsiCoupler& coupler) : c_(coupler) {}
    FsiCoupler& c_;
  };
  static_assert(check_coupling_scheme<Scheme, Step>());

 private:
  template <class P, class = void>
  struct has_checkpoint_member : std::false_type {};
  template <class P>
  struct has_checkpoint_member<P, std::void_t<decltype(std::declval<P&>().checkpoint_state(
                                      std::declval<detail::CheckpointWriter&>()))>> : std::true_type {};
  // An iterative scheme returns the structure to t^n through its checkpoint state.
  static_assert(!Scheme::iterative || (has_checkpoint_member<typename Solid::stress_model_type>::value &&
                                       has_checkpoint_member<typename Solid::contact_type>::value),
                "FsiCoupler: an iterative coupling scheme returns the structure to the start of each step through "
                "its checkpoint state: the stress model and the contact policy need "
                "`template <class Archive> void checkpoint_state(Archive&)` (docs/extending.md)");

 public:

  // Takes the fluid's particles (fluid, wall, dummy: the tank without the structure), its
  // parameters, the structure (with its boundary conditions already set) and the coupling
  // settings. Throws InvalidInput if the two spacings differ, the parameters are invalid, or a
  // fluid particle overlaps the structure.
  FsiCoupler(ParticleSet<dimension, scalar_type> fluid_particles, typename Fluid::parameters_type fluid_parameters,
             Solid solid, CouplingParameters coupling = {}, Scheme scheme = {})
      : c_(coupling),
        scheme_(scheme),
        solid_(std::move(solid)),
        offset_(fluid_particles.size()),
        fluid_(with_structure(std::move(fluid_particles), fluid_parameters, solid_, c_, normal_, on_surface_),
               fluid_parameters),
        search_(c_.interface_radius_ratio * fluid_parameters.l0 + 0.5 * fluid_parameters.l0),
        tank_search_(0.25 * fluid_parameters.l0),
        structure_n0_(structure_n0(solid_)) {
    if (c_.covered_surface_as_dummy) {
      // The tank's fixed walls: the fluid set's own wall and dummy particles, which do not move.
      const auto& set = fluid_.particles();
      VecArray<dimension, scalar_type> tank;
      for (std::size_t i = 0; i < offset_; ++i)
        if (set.kinds()[i] != ParticleKind::fluid) tank.push_back(set.positions()[i]);
      tank_search_.build(tank);
      sync_walls();
    }
    if (c_.partial_wetting_correction)
      full_weight_ = c_.interface_pressure == InterfacePressure::linear_fit
                         ? least_full_wetting_weight<Weight, dimension, scalar_type>(fluid_.parameters().l0, re())
                         : full_wetting_weight<Weight, dimension, scalar_type>(fluid_.parameters().l0, re());
    structure_acceleration_.assign(solid_.particles().size(), vec_type::Zero());
    load_.assign(solid_.particles().size(), vec_type::Zero());
    applied_force_.assign(solid_.particles().size(), vec_type::Zero());
    interface_pressure_.assign(solid_.particles().size(), 0);
  }

  // One coupled step of the fluid's time step, advanced by the scheme. Throws SimulationError
  // (from either solver, or from the scheme, such as an iterated step that does not converge)
  // with the step and time.
  void step() {
    sync_walls();
    if (c_.interface_acceleration) {
      find_candidates();
      interface_accelerations<Weight>(solid_.particles().positions(), structure_acceleration_, on_surface_,
                                      fluid_.particles(), candidates_, re(), fluid_.external_acceleration(),
                                      weight_sum_);
    }
    velocity_start_ = solid_.particles().velocities();
    position_start_ = solid_.particles().positions();
    if constexpr (Scheme::iterative) {
      fluid_start_.take(fluid_);
      solid_start_.take(solid_);
    }
    fluid_solves_ = 0;
    structure_advances_ = 0;
    Step handle(*this);
    try {
      scheme_.advance(handle);
    } catch (...) {
      iterations_ = fluid_solves_;  // last_iterations() reports the failed step's solves
      throw;
    }
    if (fluid_solves_ == 0 || structure_advances_ == 0)
      detail::throw_invalid("FsiCoupler", std::string("the coupling scheme '") + Scheme::name + "' ended a step without " +
                                              (fluid_solves_ == 0 ? "solving the fluid" : "advancing the structure"));
    iterations_ = fluid_solves_;
    const auto& v = solid_.particles().velocities();
    for (std::size_t s = 0; s < v.size(); ++s) structure_acceleration_[s] = (v[s] - velocity_start_[s]) / dt_;
    ++step_count_;
  }

  // Steps until the fluid's time reaches end_time.
  void advance_to(double end_time) {
    while (time() < end_time - 1e-12 * std::max(1.0, std::abs(end_time))) step();
  }

  double time() const { return fluid_.time(); }

  // Checkpoints (io/checkpoint.hpp): both solvers, the user's applied force, the last load (the
  // quasi-Newton step starts from it), the structure's acceleration (eq 10 reads it), the step
  // count and the scheme's own state, if it has a checkpoint_state (the Aitken relaxation, the
  // quasi-Newton columns kept across steps).
  static constexpr const char* checkpoint_kind = "FsiCoupler";
  std::size_t checkpoint_particle_count() const { return fluid_.particles().size(); }
  template <class Archive>
  void checkpoint_state(Archive& a) {
    fluid_.checkpoint_state(a);
    solid_.checkpoint_state(a);
    a.array(applied_force_);
    a.array(load_);
    a.array(structure_acceleration_);
    a.value(step_count_);
    if constexpr (has_checkpoint_state<Scheme, Archive>::value) scheme_.checkpoint_state(a);
    a.value(substeps_);  // the last step's report (last_substeps, last_iterations), which outputs show
    a.value(iterations_);
  }
  void checkpoint_restored() {
    fluid_.checkpoint_restored();
    solid_.checkpoint_restored();
  }
  long long step_count() const { return step_count_; }
  Fluid& fluid() { return fluid_; }
  const Fluid& fluid() const { return fluid_; }
  Solid& solid() { return solid_; }
  const Solid& solid() const { return solid_; }
  const CouplingParameters& parameters() const { return c_; }
  Scheme& scheme() { return scheme_; }
  const Scheme& scheme() const { return scheme_; }

  // Structure particle s is particle structure_offset() + s of the fluid's set.
  std::size_t structure_offset() const { return offset_; }
  // Per structure particle: the fluid's load (N, per unit thickness in 2D), the interface
  // pressure of eq 18, the outward normal and whether it is on the wetted surface (on the
  // structure's surface and not covered by the tank's fixed walls).
  const VecArray<dimension, scalar_type>& interface_force() const { return load_; }
  // Forces on structure particles besides the fluid's (N, per unit thickness in 2D): a load the
  // user applies, such as a force on an edge. Added to the interface load at every advance of
  // the structure and never relaxed by a sub-iterated scheme; zero unless set. The structure's
  // own external_force() is overwritten by the coupler, so loads go here.
  VecArray<dimension, scalar_type>& applied_force() { return applied_force_; }
  const VecArray<dimension, scalar_type>& applied_force() const { return applied_force_; }
  const std::vector<scalar_type>& interface_pressure() const { return interface_pressure_; }
  const VecArray<dimension, scalar_type>& normals() const { return normal_; }
  const std::vector<std::uint8_t>& on_surface() const { return on_surface_; }
  vec_type total_interface_force() const {
    vec_type sum = vec_type::Zero();
    for (const auto& f : load_) sum += f;
    return sum;
  }

  // Structure sub-steps and coupling iterations (fluid solves) of the last step; wall-clock
  // seconds spent in the fluid and in the structure so far.
  int last_substeps() const { return substeps_; }
  int last_iterations() const { return iterations_; }
  double fluid_seconds() const { return fluid_seconds_; }
  double solid_seconds() const { return solid_seconds_; }

 private:
  using Weight = typename Fluid::weight_type;

  double re() const { return c_.interface_radius_ratio * fluid_.parameters().l0; }

  // The fluid's particle set with the structure appended (wall on its surface, dummy inside).
  static ParticleSet<dimension, scalar_type> with_structure(ParticleSet<dimension, scalar_type> set,
                                                            const typename Fluid::parameters_type& fp,
                                                            const Solid& solid, const CouplingParameters& c,
                                                            VecArray<dimension, scalar_type>& normal,
                                                            std::vector<std::uint8_t>& on_surface) {
    c.validate();
    fp.validate();
    const double l0_f = fp.l0, l0_s = solid.parameters().l0;
    if (std::abs(l0_f - l0_s) > 1e-9 * l0_f)
      detail::throw_invalid("FsiCoupler", "the fluid and the structure have different particle spacings (l0 = " +
                                              detail::format_number(l0_f) + " and " + detail::format_number(l0_s) + " m)");
    const auto& sp = solid.particles();
    structure_normals(solid.bonds(), sp.positions(), structure_n0(solid), c.surface_threshold, normal, on_surface);
    const std::size_t start = set.size();
    set.resize(start + sp.size());
    for (std::size_t s = 0; s < sp.size(); ++s) {
      set.positions()[start + s] = sp.positions()[s];
      set.velocities()[start + s] = sp.velocities()[s];
      set.kinds()[start + s] = on_surface[s] ? ParticleKind::wall : ParticleKind::dummy;
    }
    return set;
  }

  // Number density of a full neighbourhood of the structure's lattice: the scale of the surface test.
  static scalar_type structure_n0(const Solid& solid) {
    const auto& p = solid.parameters();
    return ideal_lattice_constants<dimension, typename Solid::weight_type>(p.l0, p.re()).n0;
  }

  // The structure as the fluid's moving wall: positions, velocities, surface.
  void sync_walls() {
    structure_normals(solid_.bonds(), solid_.particles().positions(), structure_n0_, c_.surface_threshold, normal_,
                      on_surface_);
    if (c_.covered_surface_as_dummy) uncover_buried_surface();
    auto& set = fluid_.particles();
    const auto& sp = solid_.particles();
    for (std::size_t s = 0; s < sp.size(); ++s) {
      set.positions()[offset_ + s] = sp.positions()[s];
      set.velocities()[offset_ + s] = sp.velocities()[s];
      set.kinds()[offset_ + s] = on_surface_[s] ? ParticleKind::wall : ParticleKind::dummy;
    }
  }

  // Clears on_surface_ where the outward site x + l0 n lies inside the tank's fixed walls.
  void uncover_buried_surface() {
    if (tank_search_.num_points() == 0) return;
    const auto& x = solid_.particles().positions();
    const scalar_type l0 = fluid_.parameters().l0;
    sites_.resize(x.size());
    for (std::size_t s = 0; s < x.size(); ++s) sites_[s] = on_surface_[s] ? vec_type(x[s] + l0 * normal_[s]) : x[s];
    tank_search_.query(sites_, covering_);
    for (std::size_t s = 0; s < x.size(); ++s)
      if (on_surface_[s] && covering_.count(s) > 0) on_surface_[s] = 0;
  }

  void find_candidates() {
    QueryOptions opt;
    search_.build(fluid_.particles().positions());
    search_.query(solid_.particles().positions(), candidates_, opt);
  }

  void compute_loads(VecArray<dimension, scalar_type>& load) {
    find_candidates();
    interface_loads<Weight>(solid_.particles().positions(), normal_, on_surface_, fluid_.particles(),
                            fluid_.pressure(), candidates_, fluid_.parameters().l0, re(), full_weight_, load,
                            interface_pressure_, c_.interface_pressure);
  }

  template <class S, class Archive, class = void>
  struct has_checkpoint_state : std::false_type {};
  template <class S, class Archive>
  struct has_checkpoint_state<S, Archive, std::void_t<decltype(std::declval<S&>().checkpoint_state(std::declval<Archive&>()))>>
      : std::true_type {};

  void require_fluid_solved(const char* call) const {
    if (fluid_solves_ == 0)
      detail::throw_invalid("FsiCoupler", std::string("the coupling scheme '") + Scheme::name + "' called Step::" + call +
                                              " before the step's first solve_fluid");
  }

  [[noreturn]] void throw_repeat(const char* what) const {
    detail::throw_invalid("FsiCoupler", std::string("the coupling scheme '") + Scheme::name + "' " + what +
                                            " twice in one step but declares `iterative = false`, so the coupler "
                                            "kept no state at t^n to return to");
  }

  void solve_fluid() {
    if (fluid_solves_ > 0) {
      if constexpr (!Scheme::iterative) throw_repeat("solved the fluid");
      fluid_start_.restore(fluid_);
      if (structure_advances_ > 0) {
        const auto& x_end = solid_.particles().positions();
        auto& wall_velocity = fluid_.particles().velocities();
        for (std::size_t s = 0; s < x_end.size(); ++s)
          wall_velocity[offset_ + s] = (x_end[s] - position_start_[s]) / dt_;
      }
    }
    const auto t0 = std::chrono::steady_clock::now();
    fluid_.step();
    fluid_seconds_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    dt_ = fluid_.last_dt();
    ++fluid_solves_;
  }

  void advance_structure_in_step(const vec_array& load) {
    require_fluid_solved("advance_structure");
    if (structure_advances_ > 0) {
      if constexpr (!Scheme::iterative) throw_repeat("advanced the structure");
      solid_start_.restore(solid_);
    }
    substeps_ = advance_structure(dt_, load);
    ++structure_advances_;
  }

  int advance_structure(double dt, const vec_array& load) {
    const auto t0 = std::chrono::steady_clock::now();
    const std::size_t n = solid_.particles().size();
    if (load.size() != n)
      detail::throw_invalid("FsiCoupler", "the coupling scheme's load has " + std::to_string(load.size()) +
                                              " entries for " + std::to_string(n) + " structure particles");
    if (applied_force_.size() != n)
      detail::throw_invalid("FsiCoupler", "applied_force() must keep one entry per structure particle (" +
                                              std::to_string(n) + ")");
    auto& f = solid_.external_force();
    f.resize(load.size());
    for (std::size_t s = 0; s < load.size(); ++s) {
      if (!applied_force_[s].allFinite())
        detail::throw_invalid("FsiCoupler", "applied_force() of structure particle " + std::to_string(s) +
                                                " is not finite");
      f[s] = load[s] + applied_force_[s];
    }
    const int substeps = solid_.advance_by(dt);
    solid_seconds_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    return substeps;
  }

  CouplingParameters c_;
  Scheme scheme_;
  Solid solid_;
  std::size_t offset_;
  VecArray<dimension, scalar_type> normal_;
  std::vector<std::uint8_t> on_surface_;
  Fluid fluid_;
  CellListSearch<dimension, scalar_type> search_;
  CellListSearch<dimension, scalar_type> tank_search_;  // the tank's fixed walls, radius 0.25 l0
  scalar_type structure_n0_;
  BasicNeighborList<scalar_type> candidates_, covering_;
  VecArray<dimension, scalar_type> sites_;
  VecArray<dimension, scalar_type> applied_force_;  // the user's load on the structure
  VecArray<dimension, scalar_type> load_;
  std::deque<vec_array> workspace_;  // Step::workspace; a deque keeps earlier arrays in place as it grows
  VecArray<dimension, scalar_type> structure_acceleration_, velocity_start_, position_start_;
  std::vector<scalar_type> interface_pressure_, weight_sum_;
  detail::StateSnapshot fluid_start_, solid_start_;  // iterative schemes: the state at t^n
  long long step_count_ = 0;
  int substeps_ = 0, iterations_ = 0;
  int fluid_solves_ = 0, structure_advances_ = 0;  // within the current step
  double dt_ = 0;
  double fluid_seconds_ = 0, solid_seconds_ = 0;
  scalar_type full_weight_ = 0;
};

}  // namespace MPSFSI_ABI
}  // namespace mpsfsi
