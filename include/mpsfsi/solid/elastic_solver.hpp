// SPDX-License-Identifier: BSD-3-Clause
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <iostream>
#include <limits>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "mpsfsi/core/abi.hpp"
#include "mpsfsi/core/detail/format.hpp"
#include "mpsfsi/core/error.hpp"
#include "mpsfsi/core/parallel.hpp"
#include "mpsfsi/core/particle_set.hpp"
#include "mpsfsi/kernels/lattice_constants.hpp"
#include "mpsfsi/kernels/weight.hpp"
#include "mpsfsi/solid/bond_viscosity.hpp"
#include "mpsfsi/solid/bonds.hpp"
#include "mpsfsi/solid/contact.hpp"
#include "mpsfsi/solid/corrected_total_lagrangian.hpp"
#include "mpsfsi/solid/crack_plane.hpp"
#include "mpsfsi/solid/deformation.hpp"
#include "mpsfsi/solid/detail/blowup_check.hpp"
#include "mpsfsi/solid/detail/held_particles.hpp"
#include "mpsfsi/solid/detail/spacing_check.hpp"
#include "mpsfsi/solid/failure_slot.hpp"
#include "mpsfsi/solid/fragments.hpp"
#include "mpsfsi/solid/hwang_model.hpp"
#include "mpsfsi/solid/particle_constraints.hpp"
#include "mpsfsi/solid/policy_checks.hpp"
#include "mpsfsi/solid/principal_stress.hpp"
#include "mpsfsi/solid/rigid_obstacle.hpp"
#include "mpsfsi/solid/solid_parameters.hpp"

namespace mpsfsi {
inline namespace MPSFSI_ABI {

// The policy bundle of ElasticSolver. Override one entry by deriving:
//   struct MyPolicies : SolidDefaults<2> { using contact = NoContact; };
template <int Dim>
struct SolidDefaults {
  using weight = KoshizukaWeight;
  using stress_model = CorrectedTotalLagrangian<Dim, double>;
  using contact = PenaltyContact<Dim, double>;
  using failure = NoFailure;
};

// BrittleSolidPolicies (failure = MaxPrincipalStress) is in fracture/fracture_process.hpp.

// The paper's own structure model (eqs 16-17 and rotation, eq 8) in place of the default.
template <int Dim>
struct PaperSolidPolicies : SolidDefaults<Dim> {
  using stress_model = HwangModel<Dim, double>;
};

// Elastic solid on fixed initial bonds (total Lagrangian, docs/theory.md, section 3), integrated
// explicitly with velocity Verlet (kick-drift-kick, symplectic):
//   v^{n+1/2} = v^n + dt/2 a^n,   x^{n+1} = x^n + dt v^{n+1/2},   v^{n+1} = v^{n+1/2} + dt/2 a^{n+1},
//   m a = f_internal(x) + f_contact(x) + f_external + m g   (eq 16 with f_FtoS = f_external / m).
// The stress model (default: corrected total-Lagrangian SVK; PaperSolidPolicies: the paper's
// eqs 16-17 with rotation) and the contact model are policies. Particles with different body ids
// never share bonds and interact through contact only (supports, indenters, fragments). A failure
// model with `enabled = true` breaks bonds after each step through FractureProcess
// (fracture/fracture_process.hpp, which the program then includes).
template <int Dim, class Policies = SolidDefaults<Dim>>
class ElasticSolver {
  using Weight = typename Policies::weight;
  static_assert(check_weight<Weight>());
  static_assert(check_stress_model<typename Policies::stress_model, Dim>());
  static_assert(check_contact<typename Policies::contact, Dim>());
  static_assert(detail::has_failure_enabled<typename Policies::failure>::value,
                "failure model lacks `static constexpr bool enabled`");
  static constexpr bool can_fail = Policies::failure::enabled;
  using fracture_type = std::conditional_t<can_fail, FractureProcess<Dim, typename Policies::failure>,
                                           NoFractureProcess<Dim, typename Policies::failure>>;
  static_assert(!can_fail || detail::is_complete<fracture_type>::value,
                "ElasticSolver: a failure model with `enabled = true` needs FractureProcess: include "
                "\"mpsfsi/fracture/fracture_process.hpp\" (or \"mpsfsi/mpsfsi.hpp\")");

 public:
  using vec_type = Vec<Dim, double>;
  using mat_type = Mat<Dim, double>;
  using parameters_type = SolidParameters<Dim, double>;
  using stress_model_type = typename Policies::stress_model;
  using contact_type = typename Policies::contact;
  using failure_type = typename Policies::failure;
  using scalar_type = double;
  using weight_type = Weight;
  static constexpr int dimension = Dim;

  // Takes the particles (all become ParticleKind::solid; their positions are the reference
  // configuration, their velocities the initial ones), the parameters, optionally a body id per
  // particle (default: one body) and the failure model object (default: built from no
  // parameters; WeibullStrength and CrackBandStrength take theirs here). Throws InvalidInput on an
  // empty set, non-finite values, overlapping particles (closer than l0/2), a spacing that
  // disagrees with l0 (see check_spacing) or missing/invalid parameters.
  ElasticSolver(ParticleSet<Dim> particles, parameters_type params, std::vector<std::int32_t> body = {},
                failure_type failure = failure_type{})
      : p_(std::move(params)), set_(std::move(particles)), fracture_(std::move(failure)) {
    p_.validate();
    if (set_.empty()) detail::throw_invalid("ElasticSolver", "the particle set is empty");
    set_.validate();
    const std::size_t n = set_.size();
    if (body.empty()) body.assign(n, 0);
    if (body.size() != n)
      detail::throw_invalid("ElasticSolver", "got " + std::to_string(body.size()) + " body ids for " +
                                                 std::to_string(n) + " particles");
    if (p_.bond_viscosity < 0) p_.bond_viscosity = failure_type::enabled ? p_.fracture_bond_viscosity : 0;
    if (failure_type::enabled && std::isinf(p_.tensile_strength))
      detail::throw_invalid("ElasticSolver", "the failure criterion needs tensile_strength (sigma_f), which is not set");
    std::fill(set_.kinds().begin(), set_.kinds().end(), ParticleKind::solid);
    check_spacing();
    if (p_.dt > p_.max_stable_dt()) {
      const std::string what = "dt = " + detail::format_number(p_.dt) + " s exceeds the stability limit " +
                               detail::format_number(p_.max_stable_dt()) + " s (max_courant l0 / c, c = " +
                               detail::format_number(p_.signal_speed()) + " m/s)";
      if (!p_.warn_only_on_unstable_dt) detail::throw_invalid("ElasticSolver", what);
      std::cerr << "warning: ElasticSolver: " << what << '\n';
    }
    reference_ = set_.positions();
    body_ = set_.template add_field<std::int32_t>("body");
    set_.field(body_) = body;
    blowup_check_ = detail::BodyBlowupCheck<Dim>(body);
    constraint_field_ = set_.template add_field<std::int32_t>("constraint");
    displacement_ = set_.template add_field<vec_type>("displacement");
    stress_field_ = set_.template add_field<mat_type>("stress");
    damage_ = set_.template add_field<double>("damage");
    principal_ = set_.template add_field<double>("max_principal_stress");
    fragment_ = set_.template add_field<std::int32_t>("fragment");
    bonds_.template build<Weight>(reference_, body, p_.re());
    const auto lattice = ideal_lattice_constants<Dim, Weight>(p_.l0, p_.re());
    context_.lame = p_.lame();
    context_.density = p_.density;
    context_.l0 = p_.l0;
    context_.volume = std::pow(p_.l0, Dim);
    context_.n0 = lattice.n0;
    context_.lap_lambda = lattice.lambda;
    mass_ = p_.density * context_.volume;
    if constexpr (can_fail) fracture_.initialize(set_, p_, context_.volume);
    model_.initialize(bonds_, context_);
    if (p_.bond_viscosity > 0 && !model_adds_viscosity) viscosity_.initialize(bonds_);
    contact_.initialize(n, p_.contact_distance(), p_.contact_stiffness(), contact_damping());
    if (p_.contact_friction > 0) {
      if constexpr (detail::has_contact_friction<contact_type>::value)
        contact_.set_friction(p_.contact_friction);
      else
        detail::throw_invalid("ElasticSolver", "contact_friction is set, but the contact policy has no friction "
                                               "(no set_friction(mu))");
    }
    constraints_.reset(n);
    external_.assign(n, vec_type::Zero());
    compute_forces(set_.positions(), set_.velocities(), force_);
  }

  // --- Boundary conditions (may be changed between steps) ---

  // Fixes particle i where it is (prescribed velocity zero).
  void clamp(std::size_t i) {
    check_index(i, "clamp");
    constraints_.prescribe(i, vec_type::Zero());
    constraint_changed(i);
  }

  // Particle i moves with velocity v from now on (an indenter, a moving clamp).
  void prescribe_velocity(std::size_t i, const vec_type& v) {
    check_index(i, "prescribe_velocity");
    if (!v.allFinite()) detail::throw_invalid("ElasticSolver::prescribe_velocity", "velocity is not finite");
    constraints_.prescribe(i, v);
    constraint_changed(i);
  }

  // Particle i cannot move along `normal` (a simple support: only a reaction along normal).
  void support(std::size_t i, const vec_type& normal) {
    check_index(i, "support");
    if (!(normal.norm() > 0) || !normal.allFinite())
      detail::throw_invalid("ElasticSolver::support", "the support normal must be a finite non-zero vector");
    constraints_.support(i, normal);
    constraint_changed(i);
  }

  void release(std::size_t i) {
    check_index(i, "release");
    constraints_.release(i);
    constraint_changed(i);
  }

  Constraint constraint(std::size_t i) const { return constraints_.at(i); }

  // Gives the solver a rigid body its particles touch (a structure, a moving wall, a floor;
  // solid/rigid_obstacle.hpp) with the particle pairs' contact law, from now on; the solver moves
  // it by its velocity at every step. Returns its index for obstacle(). A checkpoint holds the
  // obstacles' motion and friction anchors: add the same obstacles before reading one.
  std::size_t add_obstacle(RigidObstacle<Dim, double> obstacle) {
    const std::size_t k = obstacles_.add(std::move(obstacle), set_.size(), 0.5 * p_.contact_distance(),
                                         p_.contact_stiffness(), contact_damping(), p_.contact_friction);
    compute_forces(set_.positions(), set_.velocities(), force_);
    stresses_current_ = false;
    return k;
  }
  std::size_t num_obstacles() const { return obstacles_.size(); }
  // Obstacle k: its load() and displacement(); set_velocity() between steps.
  RigidObstacle<Dim, double>& obstacle(std::size_t k) { return obstacles_.at(k); }
  const RigidObstacle<Dim, double>& obstacle(std::size_t k) const { return obstacles_.at(k); }

  // External force per particle (N, per unit thickness in 2D); kept until changed. The FSI load.
  VecArray<Dim, double>& external_force() { return external_; }

  // Particle i's external force is a distributed traction, smooth along its face (the water
  // under floating ice, a foundation), not a concentrated load: the failure read-out takes its
  // face's stress on the surface as it does on a free face, instead of at the particle centres
  // as it does under loads (failure_stress.hpp: why). From now on; kept in checkpoints.
  void mark_distributed_load(std::size_t i) {
    check_index(i, "mark_distributed_load");
    fracture_.mark_distributed_load(i, set_.size());
  }

  // --- Time stepping ---

  // One step of the automatic or fixed dt.
  void step() { step(choose_dt()); }

  // One step of the given dt (sub-stepping inside a fluid step). Throws InvalidInput if dt is
  // above the stability limit and SimulationError (step, time, particle) on a blow-up, leaving
  // positions and velocities as they were before the step.
  void step(double dt) {
    if (!(dt > 0) || !std::isfinite(dt)) detail::throw_invalid("ElasticSolver::step", "dt must be positive");
    if (dt > p_.max_stable_dt() * (1 + 1e-12) && !p_.warn_only_on_unstable_dt)
      detail::throw_invalid("ElasticSolver::step", "dt = " + detail::format_number(dt) + " s exceeds the stability limit " +
                                                       detail::format_number(p_.max_stable_dt()) + " s");
    const std::size_t n = set_.size();
    if (external_.size() != n)
      detail::throw_invalid("ElasticSolver::step", "external_force() has " + std::to_string(external_.size()) +
                                                       " entries for " + std::to_string(n) + " particles");
    if (const auto i = detail::first_non_finite(external_); i < n)
      detail::throw_invalid("ElasticSolver::step", "external force on particle " + std::to_string(i) + " (id " +
                                                       std::to_string(set_.ids()[i]) + ") is not finite");
    const auto& x = set_.positions();
    const auto& v = set_.velocities();
    const double decay = std::exp(-0.5 * p_.damping * dt);
    x_next_.resize(n);
    v_next_.resize(n);
    MPSFSI_OMP(parallel for schedule(static))
    for (std::int64_t ii = 0; ii < static_cast<std::int64_t>(n); ++ii) {
      const auto i = static_cast<std::size_t>(ii);
      // The acceleration of the current state, with the external force as it is now (a coupler
      // changes it between steps).
      const vec_type a = (force_[i] + external_[i]) / mass_ + p_.gravity;
      v_next_[i] = constraints_.constrained(i, decay * v[i] + 0.5 * dt * a);
      x_next_[i] = x[i] + dt * v_next_[i];
    }
    model_.kick(0.5 * dt);
    model_.drift(dt);
    obstacles_.move(dt);
    // With fracture the stresses are read after every step: the stress model computes them with
    // the forces when it can, into stress_next_, which becomes the stress field when the step is
    // committed.
    const bool with_stresses = compute_forces(x_next_, v_next_, force_next_, can_fail ? &stress_next_ : nullptr);
    const double inv_m = 1 / mass_;
    MPSFSI_OMP(parallel for schedule(static))
    for (std::int64_t ii = 0; ii < static_cast<std::int64_t>(n); ++ii) {
      const auto i = static_cast<std::size_t>(ii);
      const vec_type a = inv_m * (force_next_[i] + external_[i]) + p_.gravity;  // at the new positions
      v_next_[i] = constraints_.constrained(i, decay * (v_next_[i] + 0.5 * dt * a));
    }
    // Throws, before anything is committed, if the step blows up.
    try {
      blowup_check_.check(x_next_, v_next_, set_.ids(), p_.blowup_speed_factor * p_.p_wave_speed(), step_count_ + 1,
                          time_ + dt);
    } catch (...) {
      obstacles_.move(-dt);
      throw;
    }
    model_.kick(0.5 * dt);
    set_.positions().swap(x_next_);
    set_.velocities().swap(v_next_);
    force_.swap(force_next_);
    if (with_stresses) set_.field(stress_field_).swap(stress_next_);
    time_ += dt;
    last_dt_ = dt;
    ++step_count_;
    stresses_current_ = with_stresses;
    kept_fits_current_ = loop_kept_fits_;
    if constexpr (can_fail) {
      if (apply_failure()) {
        stresses_current_ = compute_forces(set_.positions(), set_.velocities(), force_, &set_.field(stress_field_));
        kept_fits_current_ = loop_kept_fits_;
      }
    }
  }

  // Cuts the bonds across a crack plane through particle c with the given normal (eqs 34-35, see
  // cut_bonds_across_plane): a notch or pre-crack. c keeps its bonds on the side the normal points
  // to, whatever SolidParameters::crack_side says. Returns the number of bonds (pairs) cut.
  std::size_t impose_crack(std::size_t c, const vec_type& normal) {
    check_index(c, "impose_crack");
    if (!(normal.norm() > 0) || !normal.allFinite())
      detail::throw_invalid("ElasticSolver::impose_crack", "the crack normal must be a finite non-zero vector");
    // The last check's read-out completed from the bonds it read, before they change.
    fracture_.refresh_output(set_, set_.field(stress_field_), bonds_);
    touched_.clear();
    const std::size_t cut = cut_bonds_across_plane(bonds_, set_.positions(), c, vec_type(normal.normalized()),
                                                   p_.crack_half_width(), p_.re(), touched_, scratch_);
    if (cut > 0) {
      bonds_changed();
      compute_forces(set_.positions(), set_.velocities(), force_);
    }
    return cut;
  }

  // Steps until the simulated time reaches end_time.
  void advance_to(double end_time) {
    while (time_ < end_time - 1e-12 * std::max(1.0, std::abs(end_time))) step();
  }

  // Advances by `duration` in the fewest equal sub-steps no longer than the solver's dt (FSI:
  // one fluid step of the structure). Returns the number of sub-steps.
  int advance_by(double duration) {
    if (!(duration > 0)) detail::throw_invalid("ElasticSolver::advance_by", "duration must be positive");
    const int substeps = std::max(1, static_cast<int>(std::ceil(duration / choose_dt() - 1e-9)));
    for (int k = 0; k < substeps; ++k) step(duration / substeps);
    return substeps;
  }

  double dt() const { return choose_dt(); }
  double last_dt() const { return last_dt_; }
  double time() const { return time_; }
  long long step_count() const { return step_count_; }

  // --- State and diagnostics ---

  const ParticleSet<Dim>& particles() const { return set_; }
  ParticleSet<Dim>& particles() { return set_; }
  const VecArray<Dim, double>& reference_positions() const { return reference_; }
  const parameters_type& parameters() const { return p_; }
  const BondList<Dim, double>& bonds() const { return bonds_; }
  stress_model_type& stress_model() { return model_; }
  const contact_type& contact() const { return contact_; }
  double particle_mass() const { return mass_; }
  double particle_volume() const { return context_.volume; }

  // Cauchy stress per particle at the current positions (computed once per step on demand).
  const MatArray<Dim, double>& stresses() {
    if (!stresses_current_) {
      prepare_loop(set_.positions());
      model_.stresses(set_.positions(), bonds_, set_.field(stress_field_));
      stresses_current_ = true;
      kept_fits_current_ = loop_kept_fits_;
    }
    return set_.field(stress_field_);
  }

  // The particle set with its output fields (displacement, stress, damage, max_principal_stress,
  // fragment, body, constraint) brought up to date, ready for write_vtu. `fragment` labels the
  // connected pieces of the intact-bond graph (find_fragments): after fracture, colour by it to
  // see the pieces. With a failure model there are two more: `strength`, each particle's, and
  // `failure_stress`, the criterion's value of the stress the last step's check read (from the
  // failure read-out's stress, not from `stress`; 0 where it was not checked: prescribed
  // particles and particles with no intact bond). Where the model's upper bound ruled failure
  // out, that value is computed here (FractureProcess::refresh_output).
  const ParticleSet<Dim>& output() {
    stresses();
    auto& u = set_.field(displacement_);
    auto& damage = set_.field(damage_);
    auto& principal = set_.field(principal_);
    const auto& sigma = set_.field(stress_field_);
    for (std::size_t i = 0; i < set_.size(); ++i) {
      u[i] = set_.positions()[i] - reference_[i];
      damage[i] = bonds_.damage(i);
      vec_type direction;
      principal[i] = max_principal_stress<Dim, double>(sigma[i], direction);
    }
    set_.field(fragment_) = find_fragments(bonds_).label;
    fracture_.refresh_output(set_, set_.field(stress_field_), bonds_);
    return set_;
  }

  // Internal (elastic + contact) force on particle i at the current positions.
  const vec_type& internal_force(std::size_t i) const { return force_[i]; }

  // Force the constraint exerts on particle i: what keeps a prescribed particle at its velocity
  // or a supported one off its normal (zero for free particles). The sum over an indenter's
  // particles, negated, is the load it applies.
  vec_type reaction(std::size_t i) const { return constraints_.reaction(i, force_[i] + external_[i] + mass_ * p_.gravity); }

  double kinetic_energy() const {
    double e = 0;
    for (const auto& v : set_.velocities()) e += 0.5 * mass_ * v.squaredNorm();
    return e;
  }
  // Elastic energy of the stress model plus the contact springs (particle pairs and obstacles).
  double strain_energy() const {
    return model_.strain_energy(set_.positions(), bonds_) + contact_.energy(set_.positions(), bonds_) +
           obstacles_.energy(set_.positions());
  }
  double gravity_energy() const {
    double e = 0;
    for (const auto& x : set_.positions()) e -= mass_ * p_.gravity.dot(x);
    return e;
  }
  double total_energy() const { return kinetic_energy() + strain_energy() + gravity_energy(); }

  // Fracture record: bonds (pairs) cut so far, particle failures so far (a failure is a particle
  // at sigma_1 >= sigma_f that cut at least one bond; it counts each step it does), and the time
  // of the first failure (negative if none yet).
  std::size_t cut_bonds() const { return bonds_.num_cut(); }
  std::size_t failure_events() const { return fracture_.log().size(); }
  double first_failure_time() const { return fracture_.first_failure_time(); }
  // Every failure in order: the crack path (reference_positions()[event.particle]) and history.
  const std::vector<FailureEvent<Dim>>& failure_log() const { return fracture_.log(); }
  // The failure model object; each particle's strength and the criterion's value of the stress
  // the last step's check read (the output fields `strength` and `failure_stress`; Pa; empty
  // without a failure model).
  const failure_type& failure_model() const { return fracture_.model(); }
  const std::vector<double>& strengths() const { return fracture_.strengths(set_); }
  const std::vector<double>& criterion_stresses() {
    return fracture_.criterion_stresses(set_, set_.field(stress_field_), bonds_);
  }

  // Directed bonds evaluated per force evaluation (the benchmark's unit of work).
  std::size_t bond_evaluations_per_step() const { return bonds_.num_bonds(); }

  // Checkpoints (io/checkpoint.hpp: write_checkpoint, read_checkpoint). The state a step depends
  // on: the particles with every field, the cut bonds, the stress model's fits (and frames), the
  // contact list, the failure read-out's first-read data, the constraints and loads, the forces
  // of the current positions, the failure log and the clock. The stress model and the contact
  // policy provide checkpoint_state() for this.
  static constexpr const char* checkpoint_kind = "ElasticSolver";
  std::size_t checkpoint_particle_count() const { return set_.size(); }
  template <class Archive>
  void checkpoint_state(Archive& a) {
    // The `failure_stress` field complete before it is written.
    fracture_.refresh_output(set_, set_.field(stress_field_), bonds_);
    set_.checkpoint_state(a);
    a.array(reference_);
    bonds_.checkpoint_state(a);
    model_.checkpoint_state(a);
    contact_.checkpoint_state(a);
    obstacles_.checkpoint_state(a);
    constraints_.checkpoint_state(a);
    a.array(external_);
    a.array(force_);
    a.value(time_);
    a.value(last_dt_);
    a.value(step_count_);
    fracture_.checkpoint_state(a);
  }
  void checkpoint_restored() {
    const std::size_t n = set_.size();
    if (reference_.size() != n || !constraints_.sized_for(n) ||
        external_.size() != n || force_.size() != n || !obstacles_.sized_for(n))
      detail::throw_invalid("ElasticSolver", "the checkpoint's arrays do not match its particle count");
    model_.checkpoint_restored(bonds_);
    if (p_.bond_viscosity > 0 && !model_adds_viscosity) viscosity_.initialize(bonds_);
    stresses_current_ = kept_fits_current_ = false;
  }

 private:
  double choose_dt() const { return p_.dt > 0 ? p_.dt : p_.stable_dt(); }

  // The contact dashpot c = 2 zeta sqrt(k m/2) (docs/theory.md, section 3.5).
  double contact_damping() const {
    return 2 * p_.contact_damping_ratio * std::sqrt(p_.contact_stiffness() * 0.5 * mass_);
  }

  void check_index(std::size_t i, const char* what) const {
    if (i >= set_.size())
      detail::throw_invalid(std::string("ElasticSolver::") + what,
                            "particle " + std::to_string(i) + " out of range (" + std::to_string(set_.size()) + ")");
  }

  // Particle i's velocity and `constraint` output field follow its new constraint at once.
  void constraint_changed(std::size_t i) {
    set_.velocities()[i] = constraints_.constrained(i, set_.velocities()[i]);
    set_.field(constraint_field_)[i] = static_cast<std::int32_t>(constraints_.at(i));
  }

  // The forces on the particles at positions x, all but the external one and gravity:
  // f_internal + f_contact + f_viscous (m a adds f_external + m g, in step()). The bond viscosity
  // uses the velocities it is given (the half-step ones inside step()). Given `stresses`, a
  // stress model that computes the Cauchy stresses with its forces writes those of x there;
  // returns whether it did.
  bool compute_forces(const VecArray<Dim, double>& x, const VecArray<Dim, double>& v, VecArray<Dim, double>& force,
                      MatArray<Dim, double>* stresses = nullptr) {
    prepare_loop(x);
    const double viscosity =
        p_.bond_viscosity * p_.density * p_.p_wave_speed() * context_.volume * Dim / context_.n0;
    if constexpr (model_adds_viscosity) {
      // The stress model adds the bond viscosity in its own pass over the bonds.
      if (p_.bond_viscosity > 0) {
        const bool with_stresses = stresses && detail::has_model_forces_with_stresses<stress_model_type, Dim>::value;
        model_.internal_forces(x, v, bonds_, force, with_stresses ? stresses : nullptr, viscosity);
        contact_.add_forces(x, v, bonds_, force);
        obstacles_.add_forces(x, v, force);
        return with_stresses;
      }
    }
    bool with_stresses = false;
    if constexpr (detail::has_model_forces_with_stresses<stress_model_type, Dim>::value) {
      if (stresses) {
        model_.internal_forces(x, bonds_, force, *stresses);
        with_stresses = true;
      }
    }
    if (!with_stresses) model_.internal_forces(x, bonds_, force);
    contact_.add_forces(x, v, bonds_, force);
    obstacles_.add_forces(x, v, force);
    if (p_.bond_viscosity > 0) viscosity_.add(bonds_, x, v, viscosity, force);
    return with_stresses;
  }

  // Eq 27 at every particle, and the cuts of the failing ones (FractureProcess). The stress is
  // read on traction-free outer faces at the surface when the stress model has a second-order
  // fit (failure_stress.hpp). Returns whether any bond was cut (the forces are then recomputed).
  bool apply_failure() {
    const DeformationFit<Dim, double>* fit = nullptr;
    if constexpr (detail::has_deformation_fit<stress_model_type>::value)
      if (p_.failure_stress_at_surface) fit = &model_.fit();
    const auto& x = set_.positions();
    touched_.clear();
    const auto& sigma = stresses();
    typename fracture_type::State state{
        set_, bonds_, sigma, reference_, external_, fit,
        {p_.l0, context_.n0, Weight::value(p_.l0, p_.re()), context_.lame, p_.average_failure_stress},
        p_.crack_half_width(), p_.re(), time_, p_.crack_side};
    if constexpr (detail::keeps_affine<stress_model_type>::value)
      if (fit && kept_fits_current_) state.fitted = &model_.kept_affine();
    const bool cut = fracture_.apply(
        state, [this](std::size_t i) { return constraints_.at(i) == Constraint::prescribed; },
        [&](std::size_t i) {
          return contact_.touching(x, i) || obstacles_.touching(x[i]);
        },
        touched_, scratch_);
    if (cut) bonds_changed();
    return cut;
  }

  // Tells the stress model's loop about to run on x which particles it may skip (held) and asks
  // it to keep the A_i of the check's surface particles (marked at its first read); the kept fits
  // become current only where the caller says so.
  void prepare_loop(const VecArray<Dim, double>& x) {
    if constexpr (detail::skips_held<stress_model_type>::value) model_.skip_held(held_.mark(constraints_, bonds_, x));
    kept_fits_current_ = loop_kept_fits_ = false;
    if constexpr (can_fail && detail::keeps_affine<stress_model_type>::value) {
      const auto& wanted = fracture_.surface_particles();
      loop_kept_fits_ = p_.failure_stress_at_surface && wanted.size() == x.size();
      model_.keep_affine(loop_kept_fits_ ? &wanted : nullptr);
    }
  }

  void bonds_changed() {
    kept_fits_current_ = false;
    std::sort(touched_.begin(), touched_.end());
    touched_.erase(std::unique(touched_.begin(), touched_.end()), touched_.end());
    model_.bonds_changed(bonds_, touched_);
    viscosity_.bonds_changed(bonds_, touched_);
    stresses_current_ = false;
  }

  // Overlapping particles (closer than l0/2) and a spacing that disagrees with l0
  // (detail::check_solid_spacing) are errors.
  void check_spacing() const { detail::check_solid_spacing(set_.positions(), p_.l0); }

  parameters_type p_;
  ParticleSet<Dim> set_;
  VecArray<Dim, double> reference_;
  BondList<Dim, double> bonds_;
  SolidModelContext<Dim, double> context_;
  stress_model_type model_;
  contact_type contact_;
  RigidObstacles<Dim, double> obstacles_;
  // Whether the stress model adds the bond viscosity in its force pass (then viscosity_ stays empty).
  static constexpr bool model_adds_viscosity = detail::has_model_forces_with_viscosity<stress_model_type, Dim>::value;
  BondViscosity<Dim> viscosity_;
  fracture_type fracture_;
  double mass_ = 0;
  FieldHandle<std::int32_t> body_, constraint_field_, fragment_;
  FieldHandle<vec_type> displacement_;
  FieldHandle<mat_type> stress_field_;
  FieldHandle<double> damage_, principal_;
  ParticleConstraints<Dim> constraints_;
  detail::HeldParticles<Dim> held_;  // the particles the stress model may skip
  VecArray<Dim, double> external_, force_;
  VecArray<Dim, double> x_next_, v_next_, force_next_;
  MatArray<Dim, double> stress_next_;  // the stresses of x_next_, when the stress model gives them
  detail::BodyBlowupCheck<Dim> blowup_check_;
  double time_ = 0, last_dt_ = 0;
  long long step_count_ = 0;
  bool stresses_current_ = false;
  // Whether the last force loop kept the surface particles' A_i, and whether those are of the
  // current positions and bonds (the last loop ran on them and they have not changed since).
  bool loop_kept_fits_ = false, kept_fits_current_ = false;
  std::vector<std::size_t> touched_, scratch_;  // particles whose bonds a cut changed
};

}  // namespace MPSFSI_ABI
}  // namespace mpsfsi
