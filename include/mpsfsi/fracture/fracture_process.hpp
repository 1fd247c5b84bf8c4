// SPDX-License-Identifier: BSD-3-Clause
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "mpsfsi/core/abi.hpp"
#include "mpsfsi/core/error.hpp"
#include "mpsfsi/core/parallel.hpp"
#include "mpsfsi/core/particle_set.hpp"
#include "mpsfsi/core/types.hpp"
#include "mpsfsi/fracture/failure_criteria.hpp"
#include "mpsfsi/fracture/failure_stress.hpp"
#include "mpsfsi/fracture/policy_checks.hpp"
#include "mpsfsi/fracture/strength.hpp"
#include "mpsfsi/solid/bonds.hpp"
#include "mpsfsi/solid/crack_plane.hpp"
#include "mpsfsi/solid/deformation.hpp"
#include "mpsfsi/solid/elastic_solver.hpp"
#include "mpsfsi/solid/failure_slot.hpp"
#include "mpsfsi/solid/solid_parameters.hpp"

namespace mpsfsi {
inline namespace MPSFSI_ABI {

// Brittle solid: the default models with the maximum principal stress criterion (eq 27).
template <int Dim>
struct BrittleSolidPolicies : SolidDefaults<Dim> {
  using failure = MaxPrincipalStress;
};

// Brittle fracture of an ElasticSolver whose failure model has `enabled = true` (docs/theory.md,
// section 5): after each step, the stress the criterion reads (failure_stress.hpp) at every
// particle, eq 27 against the particle's strength, and for each failing particle, strongest first,
// the bonds cut across its crack plane (crack_plane.hpp); the failures are logged. With
// CrackSide::slab (default) a failing particle loses its bonds across both faces of its slab and
// is cut out: it leaves the failure read-out of its neighbours. With CrackSide::attachment the
// side of its plane each failing particle keeps is decided for all of them from the bonds before
// any is cut (orient_toward_attachment), so the cuts of one check do not depend on their order
// and a mirror image of the solid cracks as the mirror image. The solver
// holds one and calls it; it owns the model object, the per-particle strengths (the `strength`
// and `failure_stress` output fields) and the record.
template <int Dim, class Failure>
class FractureProcess {
  static_assert(check_failure_model<Failure, Dim>());

 public:
  using readout_settings = typename FailureStressReadout<Dim>::Settings;

  explicit FractureProcess(Failure failure) : failure_(std::move(failure)) {}

  // Adds the `strength` and `failure_stress` fields and gives each particle its strength:
  // sigma_f, or what the failure model assigns (strength.hpp), checked for count and sign.
  void initialize(ParticleSet<Dim>& set, const SolidParameters<Dim>& p, double particle_volume) {
    strength_ = set.template add_field<double>("strength");
    failure_stress_ = set.template add_field<double>("failure_stress");
    auto& strength = set.field(strength_);
    if constexpr (detail::has_assign_strengths<Failure>::value) {
      const StrengthSetup setup{p.tensile_strength, p.youngs_modulus, p.poisson_ratio, p.l0, particle_volume,
                                &set.ids()};
      failure_.assign_strengths(setup, strength);
      if (strength.size() != set.size())
        detail::throw_invalid("ElasticSolver", "the failure model assigned " + std::to_string(strength.size()) +
                                                   " strengths for " + std::to_string(set.size()) + " particles");
      for (std::size_t i = 0; i < strength.size(); ++i)
        if (!(strength[i] > 0) || std::isnan(strength[i]))
          detail::throw_invalid("ElasticSolver", "the failure model assigned particle " + std::to_string(i) +
                                                     " a strength that is not positive");
    } else {
      std::fill(strength.begin(), strength.end(), p.tensile_strength);
    }
  }

  // Where and how the solid is now, for one check.
  struct State {
    ParticleSet<Dim>& set;
    BondList<Dim, double>& bonds;
    const MatArray<Dim, double>& stresses;    // at the particle centres
    const VecArray<Dim, double>& reference;   // reference positions
    const VecArray<Dim, double>& external;    // external forces (mark a face as loaded)
    const DeformationFit<Dim, double>* fit;   // the stress model's fit for surface reads, or nullptr
    readout_settings readout;
    double crack_half_width, re, time;
    CrackSide crack_side = CrackSide::slab;
    // The fit's A_i at these positions and bonds, current at every surface particle
    // (surface_particles()), or nullptr: the read-out fits them itself.
    const std::vector<typename DeformationFit<Dim, double>::affine_type>* fitted = nullptr;
  };

  // Eq 27 at every particle that `fixed(i)` does not hold and that has an intact bond; each
  // failing particle, strongest first, cuts the bonds across its crack plane. `touching(i)`:
  // whether particle i is in contact (a loaded face, for the surface read-out). The particles
  // whose bonds changed are appended to `touched`. Returns whether any bond was cut.
  template <class Fixed, class Touching>
  bool apply(const State& s, Fixed&& fixed, Touching&& touching, std::vector<std::size_t>& touched,
             std::vector<std::size_t>& scratch) {
    const auto& x = s.set.positions();
    const std::size_t n = s.set.size();
    // An external force marks its particle as loaded from then on (failure_stress.hpp: why),
    // unless it was declared a distributed traction.
    if (s.fit) {
      carried_external_.resize(n, kNoExternal);
      MPSFSI_OMP(parallel for schedule(static))
      for (std::int64_t ii = 0; ii < static_cast<std::int64_t>(n); ++ii) {
        const auto i = static_cast<std::size_t>(ii);
        if (carried_external_[i] == kNoExternal && !s.external[i].isZero(0.0)) carried_external_[i] = kPointLoad;
      }
    }
    const auto loaded = [&](std::size_t i) { return touching(i) || carried_external_[i] == kPointLoad; };
    const bool slab = s.crack_side == CrackSide::slab;
    if (slab && readout_.cut_out_marks() != n)  // after a checkpoint was read: from the record
      for (const auto& e : log_) readout_.mark_cut_out(e.particle, n, e.normal);
    failing_.clear();
    const auto& strength = s.set.field(strength_);
    auto& read = s.set.field(failure_stress_);
    const auto candidate = [&](std::size_t i) { return !fixed(i) && s.bonds.intact_count(i) > 0; };
    // Below it no particle can fail (read_screened's floor); a NaN strength screens nothing out.
    const auto lowest_strength = [&] {
      double lowest = std::numeric_limits<double>::infinity();
      int not_a_number = 0;
      MPSFSI_OMP(parallel for schedule(static) reduction(min : lowest) reduction(| : not_a_number))
      for (std::int64_t ii = 0; ii < static_cast<std::int64_t>(n); ++ii) {
        const double value = strength[static_cast<std::size_t>(ii)];
        not_a_number |= std::isnan(value) ? 1 : 0;
        lowest = std::min(lowest, value);
      }
      return not_a_number ? -std::numeric_limits<double>::infinity() : lowest;
    };
    // With a convex bound, the averages are computed only where the bound of the particle's
    // neighbourhood reaches its strength (FailureStressReadout::read_screened).
    readout_.use_fitted(s.fitted);
    const auto& sigma = [&]() -> const MatArray<Dim, double>& {
      if constexpr (detail::has_convex_failure_bound<Failure, Dim>::value)
        return readout_.read_screened(
            s.stresses, x, s.reference, s.bonds, s.fit, loaded, s.readout,
            [&](const Mat<Dim, double>& t) { return failure_.template upper_bound<Dim, double>(t); },
            [&](std::size_t i, double bound) { return candidate(i) && !(bound < strength[i]); }, lowest_strength(),
            larger_end());
      else
        return readout_.read(s.stresses, x, s.reference, s.bonds, s.fit, loaded, s.readout, larger_end());
    }();
    readout_.use_fitted(nullptr);
    // With the model's upper bound, a particle whose bound is below its strength cannot fail and
    // its principal() is left for refresh_output(). That reads the tensors later, so only when
    // they are the read-out's own: the stress field itself is recomputed after a cut.
    deferred_ = false;
    if constexpr (detail::has_failure_upper_bound<Failure, Dim>::value) deferred_ = readout_.last_read() != nullptr;
    unevaluated_.resize(n);
    MPSFSI_OMP(parallel)
    {
      std::vector<Failing> mine;
      MPSFSI_OMP(for schedule(static) nowait)
      for (std::int64_t ii = 0; ii < static_cast<std::int64_t>(n); ++ii) {
        const auto i = static_cast<std::size_t>(ii);
        read[i] = 0;
        unevaluated_[i] = 0;
        if (!candidate(i)) continue;
        if constexpr (detail::has_failure_upper_bound<Failure, Dim>::value) {
          if (deferred_ &&
              (!readout_.evaluated(i) || failure_.template upper_bound<Dim, double>(sigma[i]) < strength[i])) {
            unevaluated_[i] = 1;
            continue;
          }
        }
        Vec<Dim, double> direction;
        const double s1 = failure_.template principal<Dim, double>(sigma[i], direction);
        read[i] = s1;
        if (s1 < strength[i]) continue;
        if (s.crack_side == CrackSide::attachment) direction = orient_toward_attachment(s.bonds, x, i, direction);
        mine.push_back({s1, i, direction});
      }
      MPSFSI_OMP(critical)
      failing_.insert(failing_.end(), mine.begin(), mine.end());
    }
    if (failing_.empty()) return false;
    readout_.complete(s.stresses, s.bonds, larger_end());  // the read before the cuts, for the output field
    std::sort(failing_.begin(), failing_.end(), [](const Failing& a, const Failing& b) {
      return a.sigma1 > b.sigma1 || (a.sigma1 == b.sigma1 && a.particle < b.particle);
    });
    std::size_t cut = 0;
    for (const auto& f : failing_) {
      const std::size_t cut_here = cut_bonds_across_plane(s.bonds, x, f.particle, f.normal, s.crack_half_width, s.re,
                                                          touched, scratch, slab ? 0.5 * s.readout.l0 : 0.0);
      if (cut_here == 0) continue;  // no intact bond across its plane: nothing breaks, nothing logged
      if (slab) readout_.mark_cut_out(f.particle, n, f.normal);
      cut += cut_here;
      log_.push_back({s.time, f.particle, f.sigma1, f.normal});
      if (first_failure_time_ < 0) first_failure_time_ = s.time;
    }
    return cut > 0;
  }

  const Failure& model() const { return failure_; }
  const std::vector<FailureEvent<Dim>>& log() const { return log_; }
  double first_failure_time() const { return first_failure_time_; }
  // The particles a read at the surface fits (FailureStressReadout::surface_particles; empty
  // before the first check, which marks them). The vector stays where it is.
  const std::vector<std::uint8_t>& surface_particles() const { return readout_.surface_particles(); }
  const std::vector<double>& strengths(const ParticleSet<Dim>& set) const { return set.field(strength_); }
  const std::vector<double>& criterion_stresses(ParticleSet<Dim>& set, const MatArray<Dim, double>& stresses,
                                               const BondList<Dim, double>& bonds) {
    refresh_output(set, stresses, bonds);
    return set.field(failure_stress_);
  }

  // Fills the `failure_stress` field where the last check ruled failure out by the upper bound:
  // principal() of the tensor that check read (ElasticSolver calls it before output and
  // checkpoints). Until the next check, the read-out keeps those tensors.
  void refresh_output(ParticleSet<Dim>& set, const MatArray<Dim, double>& stresses,
                      const BondList<Dim, double>& bonds) {
    if (!deferred_) return;
    readout_.complete(stresses, bonds, larger_end());
    const auto& sigma = *readout_.last_read();
    auto& read = set.field(failure_stress_);
    MPSFSI_OMP(parallel for schedule(static))
    for (std::int64_t ii = 0; ii < static_cast<std::int64_t>(unevaluated_.size()); ++ii) {
      const auto i = static_cast<std::size_t>(ii);
      if (!unevaluated_[i]) continue;
      Vec<Dim, double> direction;
      read[i] = failure_.template principal<Dim, double>(sigma[i], direction);
    }
    deferred_ = false;
  }

  // Particle i's external force is a distributed traction (water pressure, a foundation): smooth
  // along its face, so the read-out extrapolates the face to its surface as it does a free one
  // (failure_stress.hpp), from now on, also if it was marked as loaded before. Contact still
  // marks it as loaded.
  void mark_distributed_load(std::size_t i, std::size_t n) {
    carried_external_.resize(n, kNoExternal);
    carried_external_[i] = kDistributedLoad;
  }

  // Checkpoints (io/checkpoint.hpp): the read-out's first-read data, the particles that have
  // carried an external force (and those whose external force is distributed), and the record.
  // The strengths are fields of the particle set.
  template <class Archive>
  void checkpoint_state(Archive& a) {
    deferred_ = false;  // the field is complete in the archive (refresh_output came first)
    readout_.checkpoint_state(a);
    a.array(carried_external_);
    a.value(first_failure_time_);
    std::uint64_t failures = log_.size();
    a.value(failures);  // overwritten when reading
    log_.resize(static_cast<std::size_t>(failures));
    for (auto& e : log_) {
      a.value(e.time);
      a.value(e.particle);
      a.value(e.sigma1);
      a.value(e.normal);
    }
  }

 private:
  struct Failing {
    double sigma1;
    std::size_t particle;
    Vec<Dim, double> normal;
  };
  Failure failure_;
  FieldHandle<double> strength_, failure_stress_;
  // The end of its cell a particle read at the surface reads (FailureStressReadout;
  // docs/theory.md, 5.4): the inner one where the criterion's value is larger there.
  struct LargerEnd {
    const Failure* failure;
    bool operator()(const Mat<Dim, double>& outer, const Mat<Dim, double>& inner) const {
      Vec<Dim, double> direction;
      const double at_inner = failure->template principal<Dim, double>(inner, direction);
      return at_inner > failure->template principal<Dim, double>(outer, direction);
    }
  };
  LargerEnd larger_end() const { return {&failure_}; }

  FailureStressReadout<Dim> readout_;
  // Per particle, for the surface read-out: whether it has carried an external force, and of
  // which kind.
  static constexpr std::uint8_t kNoExternal = 0, kPointLoad = 1, kDistributedLoad = 2;
  std::vector<std::uint8_t> carried_external_;
  std::vector<Failing> failing_;
  // Whether the last check left some particles' principal() out, and which.
  bool deferred_ = false;
  std::vector<std::uint8_t> unevaluated_;
  std::vector<FailureEvent<Dim>> log_;
  double first_failure_time_ = -1;
};

}  // namespace MPSFSI_ABI
}  // namespace mpsfsi
