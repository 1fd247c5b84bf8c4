// SPDX-License-Identifier: BSD-3-Clause
#pragma once

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

#include "mpsfsi/core/abi.hpp"
#include "mpsfsi/core/detail/format.hpp"
#include "mpsfsi/core/error.hpp"
#include "mpsfsi/core/filter_neighbors.hpp"
#include "mpsfsi/core/parallel.hpp"
#include "mpsfsi/core/particle_set.hpp"
#include "mpsfsi/fluid/fluid_parameters.hpp"
#include "mpsfsi/fluid/fluid_solver.hpp"
#include "mpsfsi/kernels/detail/pair.hpp"
#include "mpsfsi/kernels/divergence.hpp"
#include "mpsfsi/kernels/gradient.hpp"
#include "mpsfsi/kernels/laplacian.hpp"
#include "mpsfsi/kernels/lattice_constants.hpp"
#include "mpsfsi/kernels/number_density.hpp"
#include "mpsfsi/mpi/communicator.hpp"
#include "mpsfsi/mpi/parallel_amg_cg.hpp"
#include "mpsfsi/mpi/particle_exchange.hpp"
#include "mpsfsi/mpi/rcb_decomposition.hpp"

namespace mpsfsi {
inline namespace MPSFSI_ABI {

// Wall-clock seconds of the last step on this process, by phase.
struct DistributedStepTimings {
  double distribute = 0;  // migration + halo + search:
  double migration = 0;   // the global time step, migration, and a recut and second migration when the load is uneven
  double halo = 0;        // the halo build
  double search = 0;      // the neighbour lists over owned + ghost particles
  double predictor = 0, ppe_assembly = 0, ppe_solve = 0, corrector = 0;
  double total() const { return distribute + predictor + ppe_assembly + ppe_solve + corrector; }
};

// What this process sent to other processes, point to point, in the last step. The reductions
// (time step, load balance, flood fill), the all-to-all exchanges of message counts (one per
// migration and per halo build) and hypre's own messages in the PPE solve are not counted. After
// a step that threw, it holds what that step had counted.
struct DistributedStepTraffic {
  std::size_t migrated = 0, migration_bytes = 0;  // particles sent by migration and rebalancing
  std::size_t ghosts = 0;                         // ghosts this process received
  std::size_t halo_bytes = 0, halo_messages = 0;  // the halo build and every refresh of the step
  bool rebalanced = false;
};

// FluidSolver's step (eqs 9-15, the same operators and policies) over the processes of an MPI
// communicator: each process owns the particles in its box of a recursive coordinate bisection
// (rcb_decomposition.hpp), rebuilt when the load imbalance exceeds rebalance_threshold, and
// holds ghost copies of the particles within the search radius of its box (Halo). The operators
// run unchanged over owned + ghost particles; what the owned particles read of their ghosts
// (positions, velocities, u*, free-surface flags, pressures) is refreshed from the owners before
// each pass that reads it, and the ghosts' own results are ignored. The PPE's rows are the owned
// unknowns, numbered after those of lower ranks, and are solved together by BoomerAMG-PCG
// (ParallelAmgCg). Global decisions stay global: the time step (Courant and viscous limits
// over all processes), enclosed regions (a flood fill from the Dirichlet rows, passed across
// processes until no process changes), blow-up detection and PPE failure, which every process
// reports with the same message.
//
// Not yet distributed: WallCondition::neumann (InvalidInput) and the external acceleration of
// FSI coupling.
template <int Dim, class Policies = FluidDefaults<Dim>>
class DistributedFluidSolver {
  using Weight = typename Policies::weight;
  using Search = typename Policies::neighbor_search;

 public:
  using vec_type = Vec<Dim, double>;
  using parameters_type = FluidParameters<Dim, double>;
  using scalar_type = double;
  static constexpr int dimension = Dim;

  // Collective. `particles`: this process's part of the initial particles (any part: they move
  // to their boxes here), with ids unique over all processes (ParticleSet::number_ids_from with
  // Communicator::exclusive_prefix_sum). Throws InvalidInput on every process when the
  // parameters are bad, the set is empty or has no fluid over all processes, or a value is not
  // finite on any process.
  DistributedFluidSolver(const Communicator& comm, ParticleSet<Dim> particles, parameters_type params)
      : comm_(comm), p_(std::move(params)), set_(std::move(particles)), search_(search_radius(p_)) {
    std::string error;
    try {
      if (p_.wall_condition == WallCondition::neumann)
        detail::throw_invalid("DistributedFluidSolver", "WallCondition::neumann is not distributed yet");
      set_.validate();
    } catch (const Error& e) {
      error = e.what();
    }
    try {
      comm_.throw_if_any_failed(error);
    } catch (const Error& e) {
      throw InvalidInput(e.what());
    }
    const auto fluid = std::count(set_.kinds().begin(), set_.kinds().end(), ParticleKind::fluid);
    total_particles_ = static_cast<std::size_t>(comm_.sum(static_cast<std::int64_t>(set_.size())));
    if (total_particles_ == 0)
      detail::throw_invalid("DistributedFluidSolver", "the particle set is empty on every process");
    if (comm_.sum(static_cast<std::int64_t>(fluid)) == 0)
      detail::throw_invalid("DistributedFluidSolver", "the particle set has no fluid particles");
    pressure_ = set_.template add_field<double>("pressure");
    density_ = set_.template add_field<double>("number_density");
    surface_field_ = set_.template add_field<std::int32_t>("free_surface");
    c_n_ = ideal_lattice_constants<Dim, Weight>(p_.l0, p_.re_density());
    c_grad_ = ideal_lattice_constants<Dim, Weight>(p_.l0, p_.re_gradient());
    c_lap_ = ideal_lattice_constants<Dim, Weight>(p_.l0, p_.re_laplacian());
    double lo = std::numeric_limits<double>::max(), hi = -lo;
    for (const auto& x : set_.positions()) {
      lo = std::min(lo, x[Dim - 1]);
      hi = std::max(hi, x[Dim - 1]);
    }
    lo = comm_.min(lo);
    hi = comm_.max(hi);
    reference_speed_ = std::sqrt(2 * p_.gravity.norm() * std::max(hi - lo, p_.l0));
    rcb_.build(comm_, set_.positions(), set_.size());
    migrate(comm_, rcb_, set_);
    owned_ = set_.size();
  }

  // Collective: one time step. Throws SimulationError on every process (the same message,
  // naming the process, step, time and the particle's id) on a blow-up or a PPE that does not
  // converge; the owned particles are then as before the step.
  void step() {
    auto tick = clock::now();
    traffic_ = DistributedStepTraffic{};
    const std::size_t halo_bytes_before = halo_.total_bytes_sent(), halo_messages_before = halo_.total_messages_sent();
    const double dt = choose_dt();  // from the owned particles, before any ghost exists
    const auto start = tick;
    redistribute(tick);
    update_neighbors();
    timings_.search = lap_time(tick);
    timings_.distribute = std::chrono::duration<double>(tick - start).count();
    const auto& x = set_.positions();
    auto& u = set_.velocities();
    const auto& kind = set_.kinds();
    const std::size_t n = set_.size();

    // Number density, free surface (the ghosts' flags from their owners), predictor (eq 9).
    auto& nd = set_.field(density_);
    number_density<Weight>(x, short_all(), p_.re_density(), nd);
    Policies::free_surface::detect(x, kind, list_all_, nd, c_n_.n0, p_.surface_beta, p_.l0, p_.re_density(), surface_);
    halo_.refresh_array(comm_, surface_);
    laplacian<Weight>(x, list_all_, u, c_lap_, lap_u_);
    u_star_.resize(n);
    MPSFSI_OMP(parallel for schedule(static))
    for (std::int64_t ii = 0; ii < static_cast<std::int64_t>(n); ++ii) {
      const auto i = static_cast<std::size_t>(ii);
      u_star_[i] = kind[i] == ParticleKind::fluid ? vec_type(u[i] + dt * (p_.kinematic_viscosity * lap_u_[i] + p_.gravity))
                                                  : u[i];
      set_.field(surface_field_)[i] = surface_[i];
    }
    halo_.refresh_array(comm_, u_star_);
    collision_.apply(x, kind, short_all(), p_.l0, u_star_, scratch_);
    halo_.refresh_array(comm_, u_star_);
    timings_.predictor = lap_time(tick);

    // PPE (eq 11) over the owned unknowns, with the ghosts' global row numbers from their owners.
    divergence<Weight>(x, list_pw_, u_star_, c_grad_, NoGradientCorrection<Dim, double>{}, div_);
    const double rho = p_.density;
    const std::size_t owned = halo_.owned();
    source_.resize(owned);
    MPSFSI_OMP(parallel for schedule(static))
    for (std::int64_t ii = 0; ii < static_cast<std::int64_t>(owned); ++ii) {
      const auto i = static_cast<std::size_t>(ii);
      const double deficit = p_.density_term_compression_only ? std::min(c_n_.n0 - nd[i], 0.0) : c_n_.n0 - nd[i];
      source_[i] = rho / dt * div_[i] + p_.gamma * rho / (dt * dt) * deficit / c_n_.n0;
    }
    left_out_.assign(n, 0);
    assemble();
    const std::size_t enclosed = find_enclosed();
    std::size_t enclosed_fluid = 0;
    long long first_enclosed_fluid = -1;
    for (std::size_t i = 0; i < owned; ++i)
      if (left_out_[i] && kind[i] == ParticleKind::fluid) {
        if (first_enclosed_fluid < 0) first_enclosed_fluid = set_.ids()[i];
        ++enclosed_fluid;
      }
    const auto enclosed_fluid_total = comm_.sum(static_cast<std::int64_t>(enclosed_fluid));
    if (enclosed_fluid_total > 0) {
      if (p_.enclosed_region != EnclosedRegion::zero_pressure) {
        const std::string mine = first_enclosed_fluid < 0 ? std::string()
                                                          : "particle id " + std::to_string(first_enclosed_fluid) +
                                                                " lies in a region that touches no free surface: its "
                                                                "pressure is undetermined (a closed container filled to "
                                                                "the top?). Set FluidParameters::enclosed_region = "
                                                                "EnclosedRegion::zero_pressure to leave such regions out";
        fail(mine, "DistributedFluidSolver: at step " + std::to_string(step_count_ + 1) + " (t = " + detail::format_number(time_ + dt) +
                       " s) ",
             step_count_ + 1, time_ + dt, first_enclosed_fluid);
      }
      ++enclosed_steps_;
    }
    if (comm_.sum(static_cast<std::int64_t>(enclosed)) > 0) assemble();  // without the enclosed regions
    timings_.ppe_assembly = lap_time(tick);
    auto& pressure = set_.field(pressure_);
    solution_.resize(rows_.rows());
    for (std::size_t r = 0; r < rows_.rows(); ++r) solution_[r] = pressure[particle_of_row_[r]];
    report_ = solver_.solve(comm_, rows_, solution_, p_.ppe_tolerance, p_.ppe_max_iterations);
    timings_.ppe_solve = lap_time(tick);
    bool finite = true;
    for (const double v : solution_) finite = finite && std::isfinite(v);
    if (comm_.min(finite ? 1 : 0) == 0 || !report_.converged)
      fail(comm_.rank() == 0 ? "PPE did not converge: " + std::to_string(report_.iterations) + " iterations, relative residual " +
                                   detail::format_number(report_.relative_residual)
                             : std::string(),
           "DistributedFluidSolver: at step " + std::to_string(step_count_ + 1) + " (t = " + detail::format_number(time_ + dt) + " s) ",
           step_count_ + 1, time_ + dt, -1);
    new_pressure_.assign(n, 0.0);
    for (std::size_t r = 0; r < rows_.rows(); ++r) {
      double value = solution_[r];
      if (p_.negative_pressure == NegativePressure::clamp_to_zero) value = std::max(value, 0.0);
      new_pressure_[particle_of_row_[r]] = value;
    }
    halo_.refresh_array(comm_, new_pressure_);

    // Corrector (eq 14), checked on every process before any commits it.
    correction_.template update<Weight>(x, list_pw_, c_grad_);
    gradient<Weight>(x, list_pw_, new_pressure_, c_grad_, correction_, grad_p_, Policies::pressure_gradient_reference);
    const double speed_limit = p_.blowup_speed_factor * std::max(reference_speed_, p_.l0 / dt);
    std::string blowup;
    long long culprit = -1;
    for (std::size_t i = 0; i < owned && blowup.empty(); ++i) {
      if (kind[i] != ParticleKind::fluid) continue;
      const vec_type v = u_star_[i] - (dt / rho) * grad_p_[i];
      if (!v.allFinite() || v.norm() > speed_limit) {
        culprit = set_.ids()[i];
        blowup = "blow-up: particle id " + std::to_string(culprit) + " would move at " + detail::format_number(v.norm()) +
                 " m/s, limit " + detail::format_number(speed_limit) + " m/s";
      }
    }
    fail(blowup, "DistributedFluidSolver: at step " + std::to_string(step_count_ + 1) + " (t = " + detail::format_number(time_ + dt) + " s) ",
         step_count_ + 1, time_ + dt, culprit);
    auto& xs = set_.positions();
    MPSFSI_OMP(parallel for schedule(static))
    for (std::int64_t ii = 0; ii < static_cast<std::int64_t>(owned); ++ii) {
      const auto i = static_cast<std::size_t>(ii);
      if (kind[i] == ParticleKind::fluid) u[i] = u_star_[i] - (dt / rho) * grad_p_[i];
      xs[i] += dt * u[i];  // eq 15
      pressure[i] = new_pressure_[i];
    }
    traffic_.ghosts = halo_.ghosts();
    traffic_.halo_bytes = halo_.total_bytes_sent() - halo_bytes_before;
    traffic_.halo_messages = halo_.total_messages_sent() - halo_messages_before;
    halo_.drop(set_);  // between steps the set holds the owned particles only
    owned_ = set_.size();
    time_ += dt;
    last_dt_ = dt;
    ++step_count_;
    timings_.corrector = lap_time(tick);
  }

  // Checkpoints (io/checkpoint.hpp), one file per process, each written and read by its process
  // (not collective): the owned particles with every field (pressure is the PPE's warm start),
  // the decomposition's cuts, the clock and the counters. A run continues from the files of a
  // run on as many processes, each process reading the file its rank wrote, and then gives the
  // same bits as the run that wrote them: every process holds the same particles in the same
  // order under the same boxes. The header's particle count is the count over all processes.
  static constexpr const char* checkpoint_kind = "DistributedFluidSolver";
  std::size_t checkpoint_particle_count() const { return total_particles_; }
  template <class Archive>
  void checkpoint_state(Archive& a) {
    set_.checkpoint_state(a);
    rcb_.checkpoint_state(a, comm_.size());
    a.value(time_);
    a.value(last_dt_);
    a.value(reference_speed_);
    a.value(step_count_);
    a.value(enclosed_steps_);
    a.value(rebalances_);
  }
  void checkpoint_restored() { owned_ = set_.size(); }
  // Collective, after every process has read its file (read_checkpoint, with a failure on any
  // process passed to all by Communicator::throw_if_any_failed): throws InvalidInput on every
  // process unless the files are pieces of one checkpoint, with the same step, time and
  // decomposition on every process and the run's particle count between them. Pieces of two
  // checkpoints (a run killed while it wrote over an older one's files) would otherwise send the
  // processes different ways.
  void check_checkpoint_pieces() const {
    std::uint64_t time_bits = 0;
    std::memcpy(&time_bits, &time_, sizeof time_bits);
    std::vector<std::uint64_t> low = {static_cast<std::uint64_t>(step_count_), time_bits, rcb_.fingerprint()}, high = low;
    comm_.min_in_place(low);
    comm_.max_in_place(high);
    const auto held = static_cast<std::size_t>(comm_.sum(static_cast<std::int64_t>(set_.size())));
    if (low != high || held != total_particles_)
      detail::throw_invalid("DistributedFluidSolver",
                            "the checkpoint's files are not pieces of one checkpoint: their steps, times or "
                            "decompositions differ, or they hold " +
                                std::to_string(held) + " particles of " + std::to_string(total_particles_));
  }

  // Collective: steps until the simulated time reaches end_time.
  void advance_to(double end_time) {
    while (time_ < end_time - 1e-12 * std::max(1.0, end_time)) step();
  }

  // Rebuild the bisection when max_p n_p / mean_p n_p - 1 exceeds this (checked every step).
  double rebalance_threshold = 0.1;

  double time() const { return time_; }
  long long step_count() const { return step_count_; }
  double last_dt() const { return last_dt_; }
  long long rebalances() const { return rebalances_; }
  long long steps_with_enclosed_regions() const { return enclosed_steps_; }
  // This process's own particles (between steps the set holds no ghosts).
  const ParticleSet<Dim>& particles() const { return set_; }
  std::size_t owned() const { return owned_; }
  const std::vector<double>& pressure() const { return set_.field(pressure_); }
  const SolveReport& last_solve() const { return report_; }
  std::size_t ppe_rows() const { return rows_.rows(); }  // this process's PPE unknowns in the last step
  // The PPE's solver, to change its BoomerAMG settings.
  ParallelAmgCg& linear_solver() { return solver_; }
  const ParallelAmgCg& linear_solver() const { return solver_; }
  const DistributedStepTimings& last_timings() const { return timings_; }
  const DistributedStepTraffic& last_traffic() const { return traffic_; }
  const Halo<Dim>& halo() const { return halo_; }
  const RcbDecomposition<Dim>& decomposition() const { return rcb_; }
  const Communicator& communicator() const { return comm_; }
  const parameters_type& parameters() const { return p_; }

  // Collective: the largest speed of a fluid particle over all processes.
  double fastest_fluid_speed() const {
    double umax = 0;
    for (std::size_t i = 0; i < owned_; ++i)
      if (set_.kinds()[i] == ParticleKind::fluid) umax = std::max(umax, set_.velocities()[i].norm());
    return comm_.max(umax);
  }

 private:
  using clock = std::chrono::steady_clock;
  static double lap_time(clock::time_point& t) {
    const auto now = clock::now();
    const double s = std::chrono::duration<double>(now - t).count();
    t = now;
    return s;
  }
  static double search_radius(const parameters_type& p) {
    p.validate();
    return std::max({p.re_density(), p.re_gradient(), p.re_laplacian()});
  }

  // Throws SimulationError on every process if any has a message: the lowest such rank's.
  void fail(const std::string& mine, const std::string& prefix, long long step, double time, long long particle) {
    const int failed = comm_.max(mine.empty() ? -1 : comm_.size() - comm_.rank());
    if (failed < 0) return;
    halo_.drop(set_);  // the owned particles as they were before the step
    const int root = comm_.size() - failed;
    long long culprit = comm_.rank() == root ? particle : 0;
    MPI_Bcast(&culprit, 1, MPI_LONG_LONG, root, comm_.get());
    std::string message;
    try {
      comm_.throw_if_any_failed(mine);
    } catch (const Error& e) {
      message = e.what();
    }
    throw SimulationError(prefix + message, step, time, culprit);
  }

  // Particles move to the boxes that hold them; the boxes are recut when the load is uneven.
  // Then the ghosts of this step.
  void redistribute(clock::time_point& tick) {
    traffic_.migrated = migrate(comm_, rcb_, set_);
    if (load_imbalance(comm_, set_.size()) > rebalance_threshold) {
      rcb_.build(comm_, set_.positions(), set_.size());
      traffic_.migrated += migrate(comm_, rcb_, set_);
      traffic_.rebalanced = true;
      ++rebalances_;
    }
    traffic_.migration_bytes = traffic_.migrated * set_.packed_size();
    timings_.migration = lap_time(tick);
    halo_.build(comm_, rcb_, set_, search_.radius());
    owned_ = halo_.owned();
    timings_.halo = lap_time(tick);
  }

  // As FluidSolver::update_neighbors, over owned + ghost particles.
  void update_neighbors() {
    QueryOptions opt;
    opt.store_distances = true;
    search_.build(set_.positions());
    search_.self_query(set_.positions(), list_all_, opt);
    short_lists_ = detail::cut_step_lists(list_all_, set_.kinds(), std::max(p_.re_density(), p_.re_gradient()),
                                          p_.re_laplacian(), short_all_, list_pw_);
  }
  const NeighborList& short_all() const { return short_lists_ ? short_all_ : list_all_; }

  // Global time step: the Courant and viscous limits of FluidSolver::stable_dt over all processes.
  double choose_dt() {
    double umax = std::max(fastest_fluid_speed(), std::sqrt(p_.gravity.norm() * p_.l0));
    double limit = umax > 0 ? p_.courant * p_.l0 / umax : std::numeric_limits<double>::max();
    if (p_.kinematic_viscosity > 0) limit = std::min(limit, p_.viscous_number * p_.l0 * p_.l0 / p_.kinematic_viscosity);
    if (p_.dt <= 0) return p_.max_dt > 0 ? std::min(limit, p_.max_dt) : limit;
    if (p_.dt > limit && !p_.warn_only_on_unstable_dt) {
      const std::string msg = "DistributedFluidSolver: time step " + detail::format_number(p_.dt) +
                              " s exceeds the stability limit " + detail::format_number(limit) + " s at step " +
                              std::to_string(step_count_ + 1);
      if (step_count_ == 0) detail::throw_invalid("DistributedFluidSolver", msg);
      throw SimulationError(msg, step_count_ + 1, time_, -1);
    }
    return p_.dt;
  }

  // The owned unknowns' rows (PpeAssembler's matrix, eq 11) with global column numbers.
  void assemble() {
    const auto& x = set_.positions();
    const auto& kind = set_.kinds();
    const std::size_t n = set_.size(), owned = halo_.owned();
    global_row_.assign(n, -1);
    particle_of_row_.clear();
    for (std::size_t i = 0; i < owned; ++i)
      if (kind[i] != ParticleKind::dummy && kind[i] != ParticleKind::solid && !surface_[i] && !left_out_[i])
        particle_of_row_.push_back(i);
    const std::int64_t first = comm_.exclusive_prefix_sum(static_cast<std::int64_t>(particle_of_row_.size()));
    for (std::size_t r = 0; r < particle_of_row_.size(); ++r)
      global_row_[particle_of_row_[r]] = first + static_cast<std::int64_t>(r);
    halo_.refresh_array(comm_, global_row_);
    rows_.clear();
    rows_.first_row = first;
    anchored_.assign(n, 0);
    const double c = 2.0 * Dim / (c_lap_.lambda * c_lap_.n0);
    for (const std::size_t i : particle_of_row_) {
      const std::size_t diagonal = rows_.columns.size();
      rows_.columns.push_back(global_row_[i]);
      rows_.values.push_back(0);
      double diag = 0;
      for (Offset k = list_all_.begin(i); k < list_all_.end(i); ++k) {
        const auto j = static_cast<std::size_t>(list_all_.indices[static_cast<std::size_t>(k)]);
        if (kind[j] == ParticleKind::dummy) continue;
        const vec_type rij = x[j] - x[i];
        const double w = Weight::value(detail::pair_distance(list_all_, k, rij), c_lap_.re);
        if (!(w > 0)) continue;
        diag += c * w;
        if (global_row_[j] >= 0) {
          rows_.columns.push_back(global_row_[j]);
          rows_.values.push_back(-c * w);
        } else {
          anchored_[i] = 1;  // a Dirichlet neighbour
        }
      }
      rows_.values[diagonal] = diag;
      rows_.offsets.push_back(static_cast<std::int64_t>(rows_.columns.size()));
      rows_.rhs.push_back(-source_[i]);
    }
  }

  // Enclosed regions: the unknowns a flood fill from the anchored rows (those with a Dirichlet
  // neighbour) does not reach along the matrix's couplings. Each process fills from its own
  // anchored rows and from ghosts anchored by their owners, then passes its flags on, until no
  // process changes. Marks them in left_out_ and returns this process's count.
  std::size_t find_enclosed() {
    const auto& kind = set_.kinds();
    const std::size_t owned = halo_.owned();
    halo_.refresh_array(comm_, anchored_);
    for (;;) {
      front_.clear();
      for (const std::size_t i : particle_of_row_)
        if (anchored_[i]) front_.push_back(i);
      for (const std::size_t i : particle_of_row_) {
        if (anchored_[i]) continue;
        for (Offset k = list_all_.begin(i); k < list_all_.end(i); ++k) {
          const auto j = static_cast<std::size_t>(list_all_.indices[static_cast<std::size_t>(k)]);
          if (j >= owned && global_row_[j] >= 0 && anchored_[j] && couples(i, k)) {
            anchored_[i] = 1;
            front_.push_back(i);
            break;
          }
        }
      }
      std::int64_t changed = 0;
      for (std::size_t head = 0; head < front_.size(); ++head) {
        const std::size_t i = front_[head];
        for (Offset k = list_all_.begin(i); k < list_all_.end(i); ++k) {
          const auto j = static_cast<std::size_t>(list_all_.indices[static_cast<std::size_t>(k)]);
          if (j >= owned || global_row_[j] < 0 || anchored_[j] || !couples(i, k)) continue;
          anchored_[j] = 1;
          front_.push_back(j);
          ++changed;
        }
      }
      // Ghosts whose owners anchored them this round restart the fill next round.
      before_.assign(anchored_.begin() + static_cast<std::ptrdiff_t>(owned), anchored_.end());
      halo_.refresh_array(comm_, anchored_);
      for (std::size_t g = owned; g < anchored_.size(); ++g) changed += anchored_[g] != before_[g - owned] ? 1 : 0;
      if (comm_.sum(changed) == 0) break;
    }
    std::size_t enclosed = 0;
    for (const std::size_t i : particle_of_row_)
      if (!anchored_[i]) {
        left_out_[i] = 1;
        ++enclosed;
      }
    (void)kind;
    return enclosed;
  }
  bool couples(std::size_t i, Offset k) const {
    const auto j = static_cast<std::size_t>(list_all_.indices[static_cast<std::size_t>(k)]);
    const vec_type rij = set_.positions()[j] - set_.positions()[i];
    return Weight::value(detail::pair_distance(list_all_, k, rij), c_lap_.re) > 0;
  }

  Communicator comm_;
  parameters_type p_;
  ParticleSet<Dim> set_;
  Search search_;
  RcbDecomposition<Dim> rcb_;
  Halo<Dim> halo_;
  NeighborList list_all_, short_all_, list_pw_;
  bool short_lists_ = false;
  MpsConstants<double> c_n_, c_grad_, c_lap_;
  FieldHandle<double> pressure_, density_;
  FieldHandle<std::int32_t> surface_field_;
  typename Policies::gradient_correction correction_;
  typename Policies::collision collision_;
  ParallelAmgCg solver_;
  DistributedRows rows_;
  std::vector<std::size_t> particle_of_row_, front_;
  std::vector<std::int64_t> global_row_;
  std::vector<std::uint8_t> surface_, anchored_, left_out_, before_;
  VecArray<Dim> u_star_, lap_u_, grad_p_, scratch_;
  std::vector<double> div_, source_, new_pressure_, solution_;
  SolveReport report_;
  DistributedStepTimings timings_;
  DistributedStepTraffic traffic_;
  double time_ = 0, last_dt_ = 0, reference_speed_ = 0;
  std::size_t owned_ = 0, total_particles_ = 0;
  long long step_count_ = 0, enclosed_steps_ = 0, rebalances_ = 0;
};

}  // namespace MPSFSI_ABI
}  // namespace mpsfsi
