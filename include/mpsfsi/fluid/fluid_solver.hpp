// SPDX-License-Identifier: BSD-3-Clause
#pragma once

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <iostream>
#include <limits>
#include <string>
#include <vector>

#include "mpsfsi/core/abi.hpp"
#include "mpsfsi/core/cell_list_search.hpp"
#include "mpsfsi/core/detail/format.hpp"
#include "mpsfsi/core/detail/spacing.hpp"
#include "mpsfsi/core/error.hpp"
#include "mpsfsi/core/filter_neighbors.hpp"
#include "mpsfsi/core/neighbor_search.hpp"
#include "mpsfsi/core/particle_set.hpp"
#include "mpsfsi/fluid/collision.hpp"
#include "mpsfsi/fluid/fluid_parameters.hpp"
#include "mpsfsi/fluid/free_surface.hpp"
#include "mpsfsi/fluid/linear_solver.hpp"
#include "mpsfsi/fluid/policy_checks.hpp"
#include "mpsfsi/fluid/ssor_cg.hpp"
#include "mpsfsi/fluid/ppe.hpp"
#include "mpsfsi/kernels/detail/pair.hpp"
#include "mpsfsi/kernels/divergence.hpp"
#include "mpsfsi/kernels/gradient.hpp"
#include "mpsfsi/kernels/gradient_correction.hpp"
#include "mpsfsi/kernels/laplacian.hpp"
#include "mpsfsi/kernels/lattice_constants.hpp"
#include "mpsfsi/kernels/number_density.hpp"
#include "mpsfsi/kernels/weight.hpp"

namespace mpsfsi {
inline namespace MPSFSI_ABI {

// The policy bundle of FluidSolver. Override one entry by deriving:
//   struct MyPolicies : FluidDefaults<2> { using linear_solver = JacobiCg; };
template <int Dim>
struct FluidDefaults {
  using weight = KoshizukaWeight;
  using gradient_correction = KhayyerGotohCorrection<Dim, double>;
  // SSOR-CG: 1.5-3.8x faster than Jacobi-CG on PPEs of 1e4 and 1e5 unknowns, 2D and 3D
  // (docs/performance.md). DeflatedSsorCg is faster on large 2D PPEs.
  using linear_solver = SsorCg;
  using free_surface = NumberDensitySurface;
  using collision = KoshizukaCollision;
  using neighbor_search = CellListSearch<Dim, double>;
  // Koshizuka's min-reference pressure gradient keeps every pair repulsive.
  static constexpr GradientReference pressure_gradient_reference = GradientReference::neighbour_minimum;
};

namespace detail {

// The lists of one step, cut from the search's at the Laplacian's radius. The number density,
// collision, divergence, gradient correction and pressure gradient run over lists cut to their
// radius re_short (2.1 l0 by default, against the Laplacian's 3.1 l0): less than half the pairs.
// The pairs dropped have zero weight and the rest keep their order, so the sums are the same to
// the bit. (Cut a little beyond the radius so that a pair at the radius within round-off is
// kept; its weight is zero anyway.) The last three see no dummy particles (without_dummies);
// the PPE assembly takes the whole list and skips them itself. Returns whether short_all was
// filled (re_short < re_laplacian); otherwise the whole list serves as it.
inline bool cut_step_lists(const NeighborList& all, const std::vector<ParticleKind>& kind, double re_short,
                           double re_laplacian, NeighborList& short_all, NeighborList& without_dummies) {
  auto in_ppe = [&](Index j) { return kind[static_cast<std::size_t>(j)] != ParticleKind::dummy; };
  if (!(re_short < re_laplacian)) {
    filter_neighbors(all, in_ppe, without_dummies);
    return false;
  }
  const double cut = re_short * (1 + 1e-9);
  const double* const d = all.distances.data();
  filter_neighbors(all, [d, cut](std::size_t, Index, Offset k) { return d[k] <= cut; }, short_all);
  filter_neighbors(short_all, in_ppe, without_dummies);
  return true;
}

}  // namespace detail

// Wall-clock seconds spent in each phase of the last step.
struct FluidStepTimings {
  double search = 0, predictor = 0, ppe_assembly = 0, ppe_solve = 0, corrector = 0;
  double total() const { return search + predictor + ppe_assembly + ppe_solve + corrector; }
};

// Incompressible free-surface flow by PNU-MPS (Lee et al. 2011), the paper's eqs 9-15:
//   predictor   u* = u^k + dt (nu lap u^k + f + g)                                    (eq 9)
//   PPE         lap P = (rho/dt) div u* + gamma (rho/dt^2) (n0 - n^k)/n0              (eq 11)
//   corrector   u^{k+1} = u* - (dt/rho) grad P  (gradient-corrected, Khayyer & Gotoh) (eq 14)
//   positions   r^{k+1} = r^k + dt u^{k+1}                                            (eq 15)
// Particle kinds: fluid; wall (in the PPE, moves with the velocity the user gives it); dummy
// (counts in the number density only). One neighbour search per step serves every operator.
template <int Dim, class Policies = FluidDefaults<Dim>>
class FluidSolver {
  using Weight = typename Policies::weight;
  using Search = typename Policies::neighbor_search;
  static_assert(check_weight<Weight>());
  static_assert(check_neighbor_search<Search>());
  static_assert(check_gradient_correction<typename Policies::gradient_correction, Weight, Dim>());
  static_assert(check_linear_solver<typename Policies::linear_solver>());
  static_assert(check_free_surface<typename Policies::free_surface, Dim>());
  static_assert(check_collision<typename Policies::collision, Dim>());

 public:
  using vec_type = Vec<Dim, double>;
  using parameters_type = FluidParameters<Dim, double>;
  using scalar_type = double;
  using weight_type = Weight;
  static constexpr int dimension = Dim;

  // Takes the particles (fluid, wall and dummy), the parameters and, optionally, the gradient
  // correction and linear solver objects with their own settings (default-constructed
  // otherwise); throws InvalidInput on an empty set, a set without fluid, non-finite values,
  // overlapping particles, fluid spaced otherwise than l0 or bad parameters.
  FluidSolver(ParticleSet<Dim> particles, parameters_type params,
              typename Policies::gradient_correction correction = typename Policies::gradient_correction(),
              typename Policies::linear_solver linear_solver = typename Policies::linear_solver())
      : p_(std::move(params)),
        set_(std::move(particles)),
        search_(radius_of(p_)),
        correction_(std::move(correction)),
        solver_(std::move(linear_solver)) {
    p_.validate();
    if (set_.empty()) detail::throw_invalid("FluidSolver", "the particle set is empty");
    set_.validate();
    if (std::none_of(set_.kinds().begin(), set_.kinds().end(), [](ParticleKind k) { return k == ParticleKind::fluid; }))
      detail::throw_invalid("FluidSolver", "the particle set has no fluid particles");
    pressure_ = set_.template add_field<double>("pressure");
    density_ = set_.template add_field<double>("number_density");
    surface_field_ = set_.template add_field<std::int32_t>("free_surface");
    c_n_ = ideal_lattice_constants<Dim, Weight>(p_.l0, p_.re_density());
    c_grad_ = ideal_lattice_constants<Dim, Weight>(p_.l0, p_.re_gradient());
    c_lap_ = ideal_lattice_constants<Dim, Weight>(p_.l0, p_.re_laplacian());
    external_.assign(set_.size(), vec_type::Zero());
    // The particles' extent along gravity (along the last axis without gravity).
    vec_type down = vec_type::Zero();
    down[Dim - 1] = -1;
    if (p_.gravity.norm() > 0) down = p_.gravity.normalized();
    double lo = std::numeric_limits<double>::max(), hi = -lo;
    for (std::size_t i = 0; i < set_.size(); ++i) {
      lo = std::min(lo, set_.positions()[i].dot(down));
      hi = std::max(hi, set_.positions()[i].dot(down));
    }
    reference_speed_ = std::sqrt(2 * p_.gravity.norm() * std::max(hi - lo, p_.l0));
    update_neighbors();
    check_spacing();
  }

  // Advances one time step. Throws SimulationError (step, time, particle) if the step would
  // produce non-finite or runaway velocities or the PPE does not converge; the state is then
  // the one before the step.
  void step() {
    check_external_acceleration();
    auto tick = clock::now();
    // A step repeated from the positions its neighbour lists were built for (snapshot_restored)
    // reuses them, and with them the PPE's matrix and the gradient correction.
    repeated_setup_ = returned_ && set_up_lists_ == lists_version_ && listed_positions_ == set_.positions() &&
                      listed_kinds_ == set_.kinds();
    returned_ = false;
    if (step_count_ > 0 && !repeated_setup_) update_neighbors();
    timings_.search = lap_time(tick);
    const double dt = choose_dt();
    auto& x = set_.positions();
    auto& u = set_.velocities();
    const auto& kind = set_.kinds();
    const std::size_t n = set_.size();

    // Number density n^k, free surface, and the predictor (eq 9) with the viscous term.
    auto& nd = set_.field(density_);
    number_density<Weight>(x, short_all(), p_.re_density(), nd);
    Policies::free_surface::detect(x, kind, list_all_, nd, c_n_.n0, p_.surface_beta, p_.l0, p_.re_density(), surface_);
    laplacian<Weight>(x, list_all_, u, c_lap_, lap_u_);
    u_star_.resize(n);
    MPSFSI_OMP(parallel for schedule(static))
    for (std::int64_t ii = 0; ii < static_cast<std::int64_t>(n); ++ii) {
      const auto i = static_cast<std::size_t>(ii);
      u_star_[i] = kind[i] == ParticleKind::fluid
                       ? vec_type(u[i] + dt * (p_.kinematic_viscosity * lap_u_[i] + p_.gravity + external_[i]))
                       : u[i];
      set_.field(surface_field_)[i] = surface_[i];
    }
    collision_.apply(x, kind, short_all(), p_.l0, u_star_, scratch_);
    timings_.predictor = lap_time(tick);

    // PPE source (eq 11) over fluid and wall particles, assembled and solved.
    const bool neumann = p_.wall_condition == WallCondition::neumann;
    divergence<Weight>(x, neumann ? list_ff_ : list_pw_, u_star_, c_grad_, NoGradientCorrection<Dim, double>{}, div_);
    const double rho = p_.density;
    if (neumann) neumann_ghost_gradients(dt);
    source_.resize(n);
    MPSFSI_OMP(parallel for schedule(static))
    for (std::int64_t i = 0; i < static_cast<std::int64_t>(n); ++i) {
      const double deficit = p_.density_term_compression_only ? std::min(c_n_.n0 - nd[i], 0.0) : c_n_.n0 - nd[i];
      const double divergence_term = neumann && kind[i] != ParticleKind::fluid ? 0.0 : rho / dt * div_[i];
      source_[i] = divergence_term + p_.gamma * rho / (dt * dt) * deficit / c_n_.n0;
    }
    const bool leave_out = p_.enclosed_region == EnclosedRegion::zero_pressure;
    // Skips dummy neighbours, or takes them as ghosts (WallCondition::neumann).
    const auto* ghosts = neumann ? &ghost_gradient_ : nullptr;
    if (repeated_setup_) {
      ppe_.update_right_hand_side(x, kind, list_all_, c_lap_, source_, b_, ghosts);
    } else {
      ppe_.assemble(x, kind, surface_, list_all_, c_lap_, source_, a_, b_, leave_out, ghosts);
    }
    if (ppe_.enclosed_fluid() > 0) {  // wall-only enclosed regions are left out silently
      if (!leave_out) {
        const auto i = static_cast<std::size_t>(*std::find_if(
            ppe_.enclosed().begin(), ppe_.enclosed().end(),
            [&](Index k) { return kind[static_cast<std::size_t>(k)] == ParticleKind::fluid; }));
        throw SimulationError("FluidSolver: at step " + std::to_string(step_count_ + 1) + " (t = " +
                                  detail::format_number(time_ + dt) + " s) " + std::to_string(ppe_.enclosed().size()) +
                                  " particles, among them particle " + std::to_string(i) + " (id " +
                                  std::to_string(set_.ids()[i]) + ") at " + format_position(x[i]) +
                                  ", form a region that touches no free surface: its pressure is undetermined "
                                  "(a closed container filled to the top?). Set FluidParameters::enclosed_region "
                                  "= EnclosedRegion::zero_pressure to leave such regions out with P = 0.",
                              step_count_ + 1, time_ + dt, static_cast<long long>(i));
      }
      enclosed_steps_ += 1;
    }
    timings_.ppe_assembly = lap_time(tick);
    auto& pressure = set_.field(pressure_);
    solution_.resize(static_cast<Eigen::Index>(ppe_.num_unknowns()));
    for (std::size_t r = 0; r < ppe_.num_unknowns(); ++r)
      solution_[static_cast<Eigen::Index>(r)] = pressure[static_cast<std::size_t>(ppe_.particle_of_row()[r])];
    using LinearSolver = typename Policies::linear_solver;
    if constexpr (detail::has_solve_same_matrix<LinearSolver>::value) {
      if (repeated_setup_)
        report_ = solver_.solve_same_matrix(a_, b_, solution_, p_.ppe_tolerance, p_.ppe_max_iterations);
      else
        report_ = solver_.solve(a_, b_, solution_, p_.ppe_tolerance, p_.ppe_max_iterations);
    } else {
      report_ = solver_.solve(a_, b_, solution_, p_.ppe_tolerance, p_.ppe_max_iterations);
    }
    timings_.ppe_solve = lap_time(tick);
    if (!report_.converged || !solution_.allFinite())
      throw SimulationError("FluidSolver: PPE did not converge at step " + std::to_string(step_count_ + 1) +
                                " (t = " + detail::format_number(time_ + dt) + " s): " + std::to_string(report_.iterations) +
                                " iterations, relative residual " + detail::format_number(report_.relative_residual),
                            step_count_ + 1, time_ + dt, -1);
    new_pressure_.assign(n, 0.0);
    for (std::size_t r = 0; r < ppe_.num_unknowns(); ++r) {
      double value = solution_[static_cast<Eigen::Index>(r)];
      if (p_.negative_pressure == NegativePressure::clamp_to_zero) value = std::max(value, 0.0);
      new_pressure_[static_cast<std::size_t>(ppe_.particle_of_row()[r])] = value;
    }

    // Corrector (eq 14) with the corrected pressure gradient, checked before it is committed.
    if (!repeated_setup_) correction_.template update<Weight>(x, list_pw_, c_grad_);
    set_up_lists_ = lists_version_;
    gradient<Weight>(x, list_pw_, new_pressure_, c_grad_, correction_, grad_p_, Policies::pressure_gradient_reference);
    const double speed_limit = p_.blowup_speed_factor * std::max(reference_speed_, p_.l0 / dt);
    for (std::size_t i = 0; i < n; ++i) {
      if (kind[i] != ParticleKind::fluid) continue;
      const vec_type v = u_star_[i] - (dt / rho) * grad_p_[i];
      if (!v.allFinite() || v.norm() > speed_limit)
        throw SimulationError("FluidSolver: blow-up at step " + std::to_string(step_count_ + 1) + " (t = " +
                                  detail::format_number(time_ + dt) + " s): particle " + std::to_string(i) + " (id " +
                                  std::to_string(set_.ids()[i]) + ") would move at " + detail::format_number(v.norm()) +
                                  " m/s, limit " + detail::format_number(speed_limit) + " m/s",
                              step_count_ + 1, time_ + dt, static_cast<long long>(i));
    }
    MPSFSI_OMP(parallel for schedule(static))
    for (std::int64_t ii = 0; ii < static_cast<std::int64_t>(n); ++ii) {
      const auto i = static_cast<std::size_t>(ii);
      if (kind[i] == ParticleKind::fluid) u[i] = u_star_[i] - (dt / rho) * grad_p_[i];
      x[i] += dt * u[i];  // eq 15; walls and dummies move with their prescribed velocity
      pressure[i] = new_pressure_[i];
    }
    time_ += dt;
    last_dt_ = dt;
    ++step_count_;
    timings_.corrector = lap_time(tick);
  }

  // Steps until the simulated time reaches end_time (the last step is shortened to land on it
  // only when the time step is automatic).
  void advance_to(double end_time) {
    while (time_ < end_time - 1e-12 * std::max(1.0, end_time)) step();
  }

  // The largest stable step for the current velocities: Courant and viscous limits.
  double stable_dt() const {
    double umax = fastest_fluid_speed();
    // Before anything moves, the speed gravity gives over one spacing bounds the Courant limit.
    umax = std::max(umax, std::sqrt(p_.gravity.norm() * p_.l0));
    double dt = umax > 0 ? p_.courant * p_.l0 / umax : std::numeric_limits<double>::max();
    if (p_.kinematic_viscosity > 0) dt = std::min(dt, p_.viscous_number * p_.l0 * p_.l0 / p_.kinematic_viscosity);
    return dt;
  }

  // The largest speed of a fluid particle (the Courant limit's speed).
  double fastest_fluid_speed() const {
    double umax = 0;
    for (std::size_t i = 0; i < set_.size(); ++i)
      if (set_.kinds()[i] == ParticleKind::fluid) umax = std::max(umax, set_.velocities()[i].norm());
    return umax;
  }

  double time() const { return time_; }
  long long step_count() const { return step_count_; }
  double last_dt() const { return last_dt_; }
  ParticleSet<Dim>& particles() { return set_; }
  const ParticleSet<Dim>& particles() const { return set_; }
  const std::vector<double>& pressure() const { return set_.field(pressure_); }
  const std::vector<double>& number_density_field() const { return set_.field(density_); }
  const std::vector<std::uint8_t>& free_surface() const { return surface_; }
  // Acceleration added to fluid particles in the predictor (eq 9's coupling term f_S->F).
  VecArray<Dim>& external_acceleration() { return external_; }
  const SolveReport& last_solve() const { return report_; }
  // Particles of the last step's enclosed regions (EnclosedRegion; after a successful step they
  // were left out of the PPE with P = 0), and the number of steps so far that left out a region
  // with fluid in it.
  const std::vector<Index>& enclosed_particles() const { return ppe_.enclosed(); }
  long long steps_with_enclosed_regions() const { return enclosed_steps_; }
  // The collision policy object, to change its settings (KoshizukaCollision: distance_ratio,
  // restitution) after construction.
  typename Policies::collision& collision() { return collision_; }
  const typename Policies::collision& collision() const { return collision_; }
  const FluidStepTimings& last_timings() const { return timings_; }
  const parameters_type& parameters() const { return p_; }
  const MpsConstants<double>& density_constants() const { return c_n_; }
  const MpsConstants<double>& laplacian_constants() const { return c_lap_; }
  const NeighborList& neighbors() const { return list_all_; }

  // Checkpoints (io/checkpoint.hpp: write_checkpoint, read_checkpoint). The state a step depends
  // on: the particles with every field (pressure is the PPE's warm start), the external
  // acceleration, the clock and the counters. Neighbour lists are rebuilt from the positions
  // (checkpoint_restored); everything else is recomputed within each step.
  static constexpr const char* checkpoint_kind = "FluidSolver";
  std::size_t checkpoint_particle_count() const { return set_.size(); }
  template <class Archive>
  void checkpoint_state(Archive& a) {
    set_.checkpoint_state(a);
    a.array(external_);
    a.value(time_);
    a.value(last_dt_);
    a.value(reference_speed_);
    a.value(step_count_);
    a.value(enclosed_steps_);
  }
  void checkpoint_restored() {
    check_external_acceleration();
    update_neighbors();
  }
  // After a return to a state this solver held earlier in the run (an iterative coupling
  // scheme's start of step, core/detail/state_archive.hpp): nothing is rebuilt here. If the next
  // step starts with the particles where they were when the neighbour lists were last built (a
  // step repeated from its start), it reuses those lists, the PPE's matrix and the gradient
  // correction, which depend on the positions and kinds alone (last_step_reused_setup); otherwise
  // it rebuilds them. The positions the lists were built for are kept from the first return on, so
  // runs without returns copy nothing.
  void snapshot_restored() {
    check_external_acceleration();
    returned_ = true;
    keep_listed_state_ = true;
  }
  // Whether the last step reused the neighbour lists, PPE matrix and gradient correction of an
  // earlier attempt at the same step (snapshot_restored); the results are the same to the bit.
  bool last_step_reused_setup() const { return repeated_setup_; }

 private:
  using clock = std::chrono::steady_clock;
  static double lap_time(clock::time_point& t) {
    const auto now = clock::now();
    const double s = std::chrono::duration<double>(now - t).count();
    t = now;
    return s;
  }
  static std::string format_position(const vec_type& v) {
    std::string s = "(";
    for (int k = 0; k < Dim; ++k) s += (k ? ", " : "") + detail::format_number(v[k]);
    return s + ")";
  }
  static double radius_of(const parameters_type& p) {
    p.validate();
    return std::max({p.re_density(), p.re_gradient(), p.re_laplacian()});
  }

  void update_neighbors() {
    ++lists_version_;
    if (keep_listed_state_) {
      listed_positions_ = set_.positions();
      listed_kinds_ = set_.kinds();
    }
    QueryOptions opt;
    opt.store_distances = true;
    search_.build(set_.positions());
    search_.self_query(set_.positions(), list_all_, opt);
    const auto& kind = set_.kinds();
    short_lists_ = detail::cut_step_lists(list_all_, kind, std::max(p_.re_density(), p_.re_gradient()), p_.re_laplacian(),
                                          short_all_, list_pw_);
    if (p_.wall_condition == WallCondition::neumann)
      filter_neighbors(list_pw_, [&](Index j) { return kind[static_cast<std::size_t>(j)] == ParticleKind::fluid; },
                       list_ff_);
  }
  const NeighborList& short_all() const { return short_lists_ ? short_all_ : list_all_; }

  // WallCondition::neumann (fluid_parameters.hpp): for each fluid or wall particle with dummy
  // neighbours, the pressure gradient its ghosts follow, G = rho g_t + (rho/dt) ((u*_f - u_w) . n) n,
  // the wall's Neumann condition: n points to the dummies (the weighted sum of their offsets),
  // u_w is their weighted mean velocity, u*_f the particle's own u* (fluid) or the weighted mean
  // u* of its fluid neighbours (wall), and g_t gravity along the wall, so that the ghosts of a
  // fluid at rest are hydrostatic.
  void neumann_ghost_gradients(double dt) {
    const auto& x = set_.positions();
    const auto& u = set_.velocities();
    const auto& kind = set_.kinds();
    const double rho = p_.density;
    ghost_gradient_.resize(x.size());
    MPSFSI_OMP(parallel for schedule(static))
    for (std::int64_t ii = 0; ii < static_cast<std::int64_t>(x.size()); ++ii) {
      const auto i = static_cast<std::size_t>(ii);
      vec_type towards = vec_type::Zero(), u_wall = vec_type::Zero(), u_fluid = vec_type::Zero();
      double w_wall = 0, w_fluid = 0;
      if (kind[i] != ParticleKind::dummy)
        for (Offset k = list_all_.begin(i); k < list_all_.end(i); ++k) {
          const auto j = static_cast<std::size_t>(list_all_.indices[k]);
          const vec_type r = x[j] - x[i];
          const double w = Weight::value(detail::pair_distance(list_all_, k, r), c_lap_.re);
          if (!(w > 0)) continue;
          if (kind[j] == ParticleKind::dummy) {
            towards += w * r;
            u_wall += w * u[j];
            w_wall += w;
          } else if (kind[j] == ParticleKind::fluid) {
            u_fluid += w * u_star_[j];
            w_fluid += w;
          }
        }
      if (!(w_wall > 0) || !(towards.norm() > 0)) {
        ghost_gradient_[i] = vec_type::Zero();
        continue;
      }
      const vec_type nrm = towards.normalized();
      u_wall /= w_wall;
      const vec_type uf = kind[i] == ParticleKind::fluid ? u_star_[i] : (w_fluid > 0 ? vec_type(u_fluid / w_fluid) : u_wall);
      const vec_type g_t = p_.gravity - p_.gravity.dot(nrm) * nrm;
      ghost_gradient_[i] = rho * g_t + (rho / dt) * (uf - u_wall).dot(nrm) * nrm;
    }
  }

  // external_acceleration() is written by the caller between steps: a wrong size or a non-finite
  // entry is bad input, named here rather than surfacing later as a PPE that does not converge.
  void check_external_acceleration() const {
    if (external_.size() != set_.size())
      detail::throw_invalid("FluidSolver::step", "external_acceleration() has " + std::to_string(external_.size()) +
                                                     " entries for " + std::to_string(set_.size()) + " particles");
    const auto i = detail::first_non_finite(external_);
    if (i < external_.size())
      detail::throw_invalid("FluidSolver::step", "external acceleration of particle " + std::to_string(i) + " (id " +
                                                     std::to_string(set_.ids()[i]) + ") is not finite");
  }

  // Overlapping particles (closer than 1e-3 l0) and fluid spaced otherwise than l0 are errors.
  // The spacing (detail::check_median_spacing) is taken between fluid particles only: walls may
  // be laid out otherwise, and a fluid particle may be set close to a wall on purpose.
  void check_spacing() const {
    const double min_distance = 1e-3 * p_.l0;
    const auto& kind = set_.kinds();
    std::vector<double> nearest;
    for (std::size_t i = 0; i < set_.size(); ++i) {
      double d = std::numeric_limits<double>::max();
      for (Offset k = list_all_.begin(i); k < list_all_.end(i); ++k) {
        const double dk = list_all_.distances[static_cast<std::size_t>(k)];
        const Index j = list_all_.indices[static_cast<std::size_t>(k)];
        if (dk < min_distance)
          detail::throw_invalid("FluidSolver", "particles " + std::to_string(i) + " and " + std::to_string(j) +
                                                   " overlap (closer than 1e-3 l0)");
        if (kind[static_cast<std::size_t>(j)] == ParticleKind::fluid) d = std::min(d, dk);
      }
      if (kind[i] == ParticleKind::fluid && d < std::numeric_limits<double>::max()) nearest.push_back(d);
    }
    detail::check_median_spacing(nearest, p_.l0, "FluidSolver");
  }

  double choose_dt() {
    const double limit = stable_dt();
    if (p_.dt <= 0) return p_.max_dt > 0 ? std::min(limit, p_.max_dt) : limit;
    if (p_.dt > limit) {
      const std::string msg = "FluidSolver: time step " + detail::format_number(p_.dt) + " s exceeds the stability limit " +
                              detail::format_number(limit) + " s (Courant " + detail::format_number(p_.courant) +
                              ", viscous " + detail::format_number(p_.viscous_number) + ") at step " +
                              std::to_string(step_count_ + 1);
      if (!p_.warn_only_on_unstable_dt) {
        if (step_count_ == 0) detail::throw_invalid("FluidSolver", msg);
        throw SimulationError(msg, step_count_ + 1, time_, -1);
      }
      if (!warned_dt_) std::cerr << "warning: " << msg << '\n';
      warned_dt_ = true;
    }
    return p_.dt;
  }

  parameters_type p_;
  ParticleSet<Dim> set_;
  Search search_;
  NeighborList list_all_;
  NeighborList short_all_;  // pairs within max(re_density, re_gradient), if shorter than re_laplacian
  NeighborList list_pw_;    // the pairs of short_all() without dummy particles
  NeighborList list_ff_;    // WallCondition::neumann: the pairs of list_pw_ with a fluid neighbour
  bool short_lists_ = false;
  MpsConstants<double> c_n_, c_grad_, c_lap_;
  FieldHandle<double> pressure_, density_;
  FieldHandle<std::int32_t> surface_field_;
  typename Policies::gradient_correction correction_;
  typename Policies::linear_solver solver_;
  typename Policies::collision collision_;
  PpeAssembler<Weight, Dim, double> ppe_;
  PpeMatrix a_;
  PpeVector b_, solution_;
  std::vector<std::uint8_t> surface_;
  VecArray<Dim> external_, u_star_, lap_u_, grad_p_, scratch_, ghost_gradient_;
  std::vector<double> div_, source_, new_pressure_;
  SolveReport report_;
  FluidStepTimings timings_;
  double time_ = 0, last_dt_ = 0, reference_speed_ = 0;
  long long step_count_ = 0, enclosed_steps_ = 0;
  bool warned_dt_ = false;
  // The neighbour lists' build count, and the build from which a step last made its whole set-up
  // (the PPE matrix, the solve, the gradient correction); the positions and kinds of the last
  // build, kept once a step has been repeated (snapshot_restored).
  long long lists_version_ = 0, set_up_lists_ = -1;
  bool keep_listed_state_ = false, returned_ = false, repeated_setup_ = false;
  VecArray<Dim> listed_positions_;
  std::vector<ParticleKind> listed_kinds_;
};

}  // namespace MPSFSI_ABI
}  // namespace mpsfsi
