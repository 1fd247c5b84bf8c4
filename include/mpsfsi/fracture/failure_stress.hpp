// SPDX-License-Identifier: BSD-3-Clause
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <type_traits>
#include <vector>

#include "mpsfsi/core/abi.hpp"
#include "mpsfsi/core/error.hpp"
#include "mpsfsi/core/parallel.hpp"
#include "mpsfsi/core/types.hpp"
#include "mpsfsi/solid/bonds.hpp"
#include "mpsfsi/solid/deformation.hpp"
#include "mpsfsi/solid/structure_surface.hpp"

namespace mpsfsi {
inline namespace MPSFSI_ABI {

// The stress tensor the failure criterion (eq 27) reads, per particle (ElasticSolver keeps one).
// - Averaged (average_failure_stress) over the particle and its intact bonds, weights w0 and the
//   particle itself with the weight of a nearest neighbour: the stress of the material around
//   the particle rather than its own sample. A bond cut since the first read gives its weight to
//   the particle's own stress (the sum of weights stays that of the first read): where material
//   is gone nothing else stands for it, and a particle that has lost most of its bonds is not
//   averaged down by the relaxed neighbours left in its piece (in the 3D bending beam one such
//   particle pair, 0.8 of their bonds cut, held the broken halves together by a 2 l0 bond
//   stretched 48 %: sigma_1 3.6-3.8 MPa at the particles, sigma_f 1.14 MPa, and neither
//   failed). Bonds already cut at the first read (an imposed notch) are not material and stay
//   out.
//   A particle cut out of the solid (failed with CrackSide::slab, crack_plane.hpp) has lost its
//   bonds across both faces of its slab: its stress is that of a loose strip, not of material
//   that holds the solid together, and averaged in it would lower the read of the particle ahead
//   of the crack (three beams of the bending study then stay in one piece). Its bonds,
//   intact or not, give their weight to the reading particle's own stress, as cut bonds do.
// - At the surface (given a second-order fit, i.e. failure_stress_at_surface with the default
//   stress model): a particle on the body's outer surface (outward normal n_i from the bonds at
//   the first read, so imposed notches count and crack faces do not) reads its fitted field at
//   X_i + (l0/2) n_i, on the continuum's surface, instead of at its centre l0/2 inside it (the
//   first-order error in l0/h that made the bending study's peak load depend on l0). The caller
//   may let it read the other end of its cell, X_i - (l0/2) n_i, instead (`inner_end(outer,
//   inner)`, given both tensors; FractureProcess: where the criterion's value is larger there):
//   the criterion applies to all of the particle's material, the fitted gradient is linear
//   across the cell, and a convex criterion is largest at one of its two ends. A face in
//   bending tension reads its outer end; the last particle of a ligament, which a crack has
//   reached from the opposite face, reads the end toward the crack tip (docs/theory.md, 5.4).
//   Only where the face is whole and free around the particle (face_whole); with averaging,
//   the end is chosen on the two ends' averages (read_inner_ends). Averaged,
//   it is averaged only along its face (bonded surface particles with normals within 25
//   degrees, each read at its own surface point), so the read-out does not move inwards; and
//   twice (a filter over +-4 l0 on a flat face): with one pass, the grid-scale release wave of
//   the first cut started second cracks 3-4 l0 beside the first in three of the five bending
//   cases. Once, as the interior is, where it lies in the slab of a cut-out bonded neighbour
//   (|(x_i - x_k) . n_k| < l0/2, crack_plane.hpp) whose crack crosses the face (|n_i . n_k| <
//   1/2): on that crack's plane, ahead of it along the face. A crack crossing a 3D face has such
//   particles at the ends of its front, where the field has the crack's own concentration, one
//   spacing wide; the second pass spreads it over the relaxed face beside the crack, and the
//   front then steps from column to column instead of running along its plane. (In 2D a crack
//   meets its face at one particle: a face neighbour lies in its slab only where the crack runs
//   within 30 degrees of the face, and then it does not cross it.) Crack faces are
//   not read outside: at a crack tip the field is singular, and a fit extrapolated into the
//   crack reads noise (it branched the crack of the bending study at mid-height). Nor are
//   loaded particles (`loaded(i)`; ElasticSolver: in contact, or having carried an external
//   force such as the FSI load at any step so far, unless the solver was told that it is a
//   distributed traction, mark_distributed_load): a fit extrapolated to a face under point loads
//   reads their spikes (it cracked the top beside the indenter), and the spikes stay in the field
//   after the load is gone. A droplet's impact loads the ice beam's top
//   for one fluid step and then leaves it at zero pressure: read outside from then on, that face
//   fails one solid step later and the failures run along the whole beam (docs/validation/fsi.md).
//   The read-out is meant for faces that stay traction-free or carry a traction smooth along
//   them (the foundation under ice on water: its bottom fibre, read at the centres, reads
//   1 - l0/h of the surface stress before averaging, less after; docs/validation/fracture.md).
template <int Dim>
class FailureStressReadout {
 public:
  using mat_type = Mat<Dim, double>;
  using fit_type = DeformationFit<Dim, double>;

  struct Settings {
    double l0 = 0;
    double n0 = 0;           // number density of a full neighbourhood (surface detection)
    double self_weight = 0;  // the particle's own weight in the average
    LameConstants<double> lame;
    bool average = true;
  };

  // Reads at the outer end of a surface particle's cell, whatever the inner end holds.
  struct OuterEnd {
    bool operator()(const mat_type&, const mat_type&) const { return false; }
  };

  // `point`: the stress at the particle centres; `fit`: the stress model's fit, or nullptr to
  // read every particle at its centre; `loaded(i)`: whether particle i carries a load;
  // `inner_end(outer, inner)`: whether a particle read at the surface reads the inner end of its
  // cell (see above).
  template <class Loaded, class InnerEnd = OuterEnd>
  const MatArray<Dim, double>& read(const MatArray<Dim, double>& point, const VecArray<Dim, double>& x,
                                    const VecArray<Dim, double>& reference, const BondList<Dim, double>& bonds,
                                    const fit_type* fit, Loaded&& loaded, const Settings& s,
                                    InnerEnd&& inner_end = InnerEnd{}) {
    const auto& sampled = sample(point, x, reference, bonds, fit, loaded, s, inner_end, !s.average);
    if (!s.average) return sampled;
    average_pass(point, bonds, sampled, false, averaged_, nullptr);
    if (at_surface_) average_pass(point, bonds, averaged_, true, smoothed_, nullptr);
    read_inner_ends(point, bonds, inner_end, nullptr, nullptr, false);
    return at_surface_ ? smoothed_ : averaged_;
  }

  // The same read, averaged only where a particle may need it: `bound(sigma)`, a convex upper
  // bound of the criterion's value (a weighted average of tensors then bounds no higher than the
  // highest of them), and `may_fail(i, b)`, whether particle i can fail when b bounds the value of
  // its read tensor, false for every b below `floor` (the lowest strength). An average (and the
  // second, along the face) is a convex combination of the particle's and its bonded neighbours'
  // samples, so the largest bound over the particle's neighbourhood (its neighbours' for the
  // second pass) bounds its read. Where that rules failure out, the read is left for complete():
  // evaluated(i) says where the returned tensors hold. complete(), given the same `point` and
  // `bonds` as they were at this call (FractureProcess completes before anything changes them),
  // gives to the bit the tensors read() would have (given the same `inner_end`). A surface
  // sample with both ends is bounded by the higher of its two ends' bounds: both ends' averages
  // are convex combinations of the two ends' samples.
  template <class Loaded, class Bound, class MayFail, class InnerEnd = OuterEnd>
  const MatArray<Dim, double>& read_screened(const MatArray<Dim, double>& point, const VecArray<Dim, double>& x,
                                             const VecArray<Dim, double>& reference,
                                             const BondList<Dim, double>& bonds, const fit_type* fit, Loaded&& loaded,
                                             const Settings& s, Bound&& bound, MayFail&& may_fail, double floor,
                                             InnerEnd&& inner_end = InnerEnd{}) {
    const auto& sampled = sample(point, x, reference, bonds, fit, loaded, s, inner_end, !s.average);
    if (!s.average) return sampled;
    const std::size_t n = point.size();
    sample_bound_.resize(n);
    reach_bound_.resize(n);
    needed_.resize(n);
    // The bounds of both samples of every particle (interior averages read the centre stress,
    // face averages the surface one), and the largest magnitude among them: the averages'
    // round-off, a few ulps of it, is covered by a margin of 1e-9 of that (the bound's own
    // slack covers only its own evaluation; docs/theory.md, 5.1). A sample whose bound or norm is
    // NaN screens nothing out.
    double largest_norm = 0;
    int not_a_number = 0;
    MPSFSI_OMP(parallel for schedule(static) reduction(max : largest_norm) reduction(| : not_a_number))
    for (std::int64_t kk = 0; kk < static_cast<std::int64_t>(n); ++kk) {
      const auto k = static_cast<std::size_t>(kk);
      const bool outside = at_surface_ && read_outside_[k];
      const bool both_ends = outside && !two_ended_.empty() && two_ended_[k];
      const double centre_bound = bound(point[k]), centre_norm = point[k].norm();
      double surface_bound = outside ? bound(sampled[k]) : centre_bound;
      double surface_norm = outside ? sampled[k].norm() : centre_norm;
      if (both_ends) {
        const double inner_bound = bound(inner_stress_[k]), inner_norm = inner_stress_[k].norm();
        // NaN stays NaN (std::max keeps its first argument when either is NaN).
        surface_bound = std::isnan(inner_bound) ? inner_bound : std::max(surface_bound, inner_bound);
        surface_norm = std::isnan(inner_norm) ? inner_norm : std::max(surface_norm, inner_norm);
      }
      // NaN if any of them is (or if infinities of both signs meet: screened off as well).
      not_a_number |= std::isnan(centre_bound + surface_bound + centre_norm + surface_norm) ? 1 : 0;
      sample_bound_[k] = std::max(centre_bound, surface_bound);
      largest_norm = std::max(largest_norm, std::max(centre_norm, surface_norm));
    }
    const double margin = 1e-9 * largest_norm;
    // Only a sample whose bound reaches the floor can let a neighbourhood's reach it. Where such
    // samples are few (a loading phase), the screen follows them through the bonds; otherwise it
    // takes the highest bound over every particle's neighbourhood. Both give the same needed_.
    hot_.clear();
    if (!not_a_number)
      for (std::size_t k = 0; k < n && hot_.size() * kSparseScreen <= n; ++k)
        if (!(sample_bound_[k] + margin < floor)) hot_.push_back(k);
    if (not_a_number) {
      std::fill(needed_.begin(), needed_.end(), std::uint8_t(1));
      if (at_surface_) first_pass_needed_.assign(n, 1);
    } else if (hot_.size() * kSparseScreen <= n) {
      screen_from_hot(bonds, may_fail, margin);
    } else {
      neighbourhood_highest(bonds, sample_bound_, reach_bound_, nullptr);  // bounds the first pass
      if (at_surface_) {  // bounds the second, along the face
        neighbourhood_highest(bonds, reach_bound_, sample_bound_, &read_outside_);
        reach_bound_.swap(sample_bound_);
      }
      MPSFSI_OMP(parallel for schedule(static))
      for (std::int64_t ii = 0; ii < static_cast<std::int64_t>(n); ++ii) {
        const auto i = static_cast<std::size_t>(ii);
        needed_[i] = may_fail(i, reach_bound_[i] + margin) ? 1 : 0;
      }
      // The second pass of a needed particle reads the first of its face neighbours: bonds are
      // symmetric, so a particle's first pass is needed where it or a bonded neighbour is.
      // Without the second pass, the first is needed where the read is.
      if (at_surface_) {
        first_pass_needed_.resize(n);
        MPSFSI_OMP(parallel for schedule(static))
        for (std::int64_t kk = 0; kk < static_cast<std::int64_t>(n); ++kk) {
          const auto k = static_cast<std::size_t>(kk);
          std::uint8_t need = needed_[k];
          for (Offset b = bonds.begin(k); b < bonds.end(k) && !need; ++b)
            need = needed_[static_cast<std::size_t>(bonds.neighbor(b))];
          first_pass_needed_[k] = need;
        }
      }
    }
    average_pass(point, bonds, sampled, false, averaged_, &first_pass_needed());
    if (at_surface_) average_pass(point, bonds, averaged_, true, smoothed_, &needed_);
    read_inner_ends(point, bonds, inner_end, &first_pass_needed(), &needed_, false);
    pending_ = true;
    cuts_at_read_ = bonds.num_cut();
    return at_surface_ ? smoothed_ : averaged_;
  }

  // Whether the last read_screened() computed particle i's tensor (always true after read() and
  // complete()).
  bool evaluated(std::size_t i) const { return !pending_ || needed_[i] != 0; }

  // Fills the tensors read_screened() left out, from the same `point` and `bonds` it was given,
  // and with the same `inner_end`. Throws InvalidInput if a bond has been cut since: the read
  // would then mix two states (a caller that cuts bonds completes the read first). The read
  // stays pending until the next.
  template <class InnerEnd = OuterEnd>
  void complete(const MatArray<Dim, double>& point, const BondList<Dim, double>& bonds,
                InnerEnd&& inner_end = InnerEnd{}) {
    if (!pending_) return;
    if (bonds.num_cut() != cuts_at_read_)
      detail::throw_invalid("FailureStressReadout::complete", "bonds were cut after the read it completes");
    if (!two_ended_.empty() && std::is_same_v<std::decay_t<InnerEnd>, OuterEnd>)
      detail::throw_invalid("FailureStressReadout::complete", "the read it completes was given an inner_end; pass it");
    average_pass(point, bonds, at_surface_ ? surface_stress_ : point, false, averaged_, &first_pass_needed(), true);
    if (at_surface_) average_pass(point, bonds, averaged_, true, smoothed_, &needed_, true);
    read_inner_ends(point, bonds, inner_end, &first_pass_needed(), &needed_, true);
    pending_ = false;
  }

  // The number of particles whose read the last read_screened() left out.
  std::size_t screened_out() const {
    if (!pending_) return 0;
    std::size_t count = 0;
    for (const auto need : needed_) count += need ? 0 : 1;
    return count;
  }

  // The tensors the last read() returned, when they are the read-out's own (kept until the next
  // read), or nullptr when it returned `point` itself.
  const MatArray<Dim, double>* last_read() const {
    switch (last_) {
      case Last::surface: return &surface_stress_;
      case Last::averaged: return &averaged_;
      case Last::smoothed: return &smoothed_;
      default: return nullptr;
    }
  }

  // Checkpoints (io/checkpoint.hpp): what the first read fixed (normals, surface flags, bond
  // weights); the rest is recomputed at every read.
  template <class Archive>
  void checkpoint_state(Archive& a) {
    a.array(normal_);
    a.array(initial_weight_);
    a.array(on_surface_);
    cut_out_.clear();  // FractureProcess marks them again from its record
    cut_out_normal_.clear();
    pending_ = false;
  }

  // Particle i has been cut out (see above) with the crack normal `normal`; n: the particle count.
  void mark_cut_out(std::size_t i, std::size_t n, const Vec<Dim, double>& normal) {
    cut_out_.resize(n, 0);
    cut_out_normal_.resize(n, Vec<Dim, double>::Zero());
    cut_out_[i] = 1;
    cut_out_normal_[i] = normal;
  }
  std::size_t cut_out_marks() const { return cut_out_.size(); }

  // The particles at the surface (marked at the first read; empty before it): those a read at
  // the surface fits, unless they carry a load.
  const std::vector<std::uint8_t>& surface_particles() const { return on_surface_; }

  // The next reads take each surface particle's fitted A_i from `fitted` (the stress model's fit
  // at the same positions and bonds, every surface particle's entry current) instead of fitting
  // it again; nullptr: they fit it.
  void use_fitted(const std::vector<typename fit_type::affine_type>* fitted) { fitted_ = fitted; }

 private:
  // Surface detection threshold of structure_normals, and the cosine within which two surface
  // particles are on the same face (a narrow 3D beam's bottom face is within 2 l0 of its edges,
  // whose samples lie on the side faces).
  static constexpr double kSurfaceThreshold = 0.1;
  static constexpr double kSameFace = 0.9;
  // A crack crosses a face where its plane is within 30 degrees of the face's normal: |n_i . n| <
  // sin 30 degrees, as the slab's half-width l0/2 is 30 degrees at one spacing (crack_plane.hpp).
  static constexpr double kCrossesFace = 0.5;
  // read_screened() follows the samples that reach the floor through the bonds while they are at
  // most 1/16 of the particles (a loading phase has few or none): the bonds of their
  // neighbourhoods are read a few times, against three passes over all bonds.
  static constexpr std::size_t kSparseScreen = 16;

  bool same_face(std::size_t i, std::size_t k) const {
    return read_outside_[k] != 0 && normal_[i].dot(normal_[k]) >= kSameFace;
  }

  // Whether particle i's face is whole and free around it: every bonded particle of its face is
  // read outside as well (not loaded), its bond not cut since the first read, and not cut out.
  // Beside a crack's mouth the inner end of the cell reads the field beside the crack tip, and
  // beside a loaded particle the spikes of its load (see above), not the face's: only the outer
  // end is read there.
  bool face_whole(const BondList<Dim, double>& bonds, std::size_t i) const {
    for (Offset b = bonds.begin(i); b < bonds.end(i); ++b) {
      const auto k = static_cast<std::size_t>(bonds.neighbor(b));
      if (!on_surface_[k] || normal_[i].dot(normal_[k]) < kSameFace) continue;
      const bool cut_since = bonds.beta(b) == 0 && initial_weight_[static_cast<std::size_t>(b)] != 0;
      if (!read_outside_[k] || cut_since || (k < cut_out_.size() && cut_out_[k] != 0)) return false;
    }
    return true;
  }

  // The surface samples (at the centre where not read outside), and what every read starts from.
  // With an `inner_end`, the inner end's tensor too where the face is whole (elsewhere the outer
  // one stands in for it), the end chosen now (`choose`, without averaging) or after the
  // averaging (two_ended_, read_inner_ends()).
  template <class Loaded, class InnerEnd>
  const MatArray<Dim, double>& sample(const MatArray<Dim, double>& point, const VecArray<Dim, double>& x,
                                      const VecArray<Dim, double>& reference, const BondList<Dim, double>& bonds,
                                      const fit_type* fit, Loaded&& loaded, const Settings& s, InnerEnd&& inner_end,
                                      bool choose) {
    constexpr bool two_ends = !std::is_same_v<std::decay_t<InnerEnd>, OuterEnd>;
    const std::size_t n = x.size();
    const bool at_surface = fit != nullptr;
    pending_ = false;
    two_ended_.clear();
    // The settings complete() averages with again, and what the read returns.
    self_weight_ = s.self_weight;
    at_surface_ = at_surface;
    if (s.average)
      last_ = at_surface ? Last::smoothed : Last::averaged;
    else
      last_ = at_surface ? Last::surface : Last::point;
    if (initial_weight_.size() != bonds.num_bonds()) {
      initial_weight_.resize(bonds.num_bonds());
      for (std::size_t b = 0; b < initial_weight_.size(); ++b) initial_weight_[b] = bonds.weight(static_cast<Offset>(b));
    }
    if (at_surface) {
      if (normal_.size() != n) structure_normals(bonds, reference, s.n0, kSurfaceThreshold, normal_, on_surface_);
      read_outside_.resize(n);
      surface_stress_.resize(n);
      if (two_ends) inner_stress_.resize(n);
      if (two_ends && !choose) two_ended_.resize(n);
      MPSFSI_OMP(parallel for schedule(static))
      for (std::int64_t ii = 0; ii < static_cast<std::int64_t>(n); ++ii) {
        const auto i = static_cast<std::size_t>(ii);
        read_outside_[i] = on_surface_[i] && !loaded(i) ? 1 : 0;
      }
      // A particle in the slab of a cut-out bonded neighbour whose crack crosses its face lies on
      // that crack's plane, ahead of it along the face (see above).
      crack_ahead_.assign(n, 0);
      if (!cut_out_.empty()) {
        MPSFSI_OMP(parallel for schedule(static))
        for (std::int64_t ii = 0; ii < static_cast<std::int64_t>(n); ++ii) {
          const auto i = static_cast<std::size_t>(ii);
          if (!read_outside_[i]) continue;
          for (Offset b = bonds.begin(i); b < bonds.end(i); ++b) {
            const auto k = static_cast<std::size_t>(bonds.neighbor(b));
            if (cut_out_[k] != 0 && std::abs(normal_[i].dot(cut_out_normal_[k])) < kCrossesFace &&
                std::abs((x[i] - x[k]).dot(cut_out_normal_[k])) < 0.5 * s.l0) {
              crack_ahead_[i] = 1;
              break;
            }
          }
        }
      }
      MPSFSI_OMP(parallel for schedule(static))
      for (std::int64_t ii = 0; ii < static_cast<std::int64_t>(n); ++ii) {
        const auto i = static_cast<std::size_t>(ii);
        if (!two_ended_.empty()) two_ended_[i] = 0;
        if (!read_outside_[i]) {
          surface_stress_[i] = point[i];
          continue;
        }
        const auto affine = fitted_ ? (*fitted_)[i] : fit->affine(x, bonds, i);
        const Vec<Dim, double> half_cell = 0.5 * s.l0 * normal_[i];
        surface_stress_[i] = detail::cauchy_from_svk(fit->gradient_at(affine, half_cell), s.lame);
        if constexpr (two_ends) {
          if (!face_whole(bonds, i)) {
            inner_stress_[i] = surface_stress_[i];
            continue;
          }
          inner_stress_[i] = detail::cauchy_from_svk(fit->gradient_at(affine, -half_cell), s.lame);
          if (!choose)
            two_ended_[i] = 1;
          else if (inner_end(surface_stress_[i], inner_stress_[i]))
            surface_stress_[i] = inner_stress_[i];
        }
      }
    }
    return at_surface ? surface_stress_ : point;
  }

  // The inner ends' samples averaged along the face as the outer ones were (the same two passes,
  // over the particles read outside that `first_only` and `second_only` mark, or, with `rest`,
  // that they do not), and the end chosen on the averages for every particle whose face is whole:
  // its read becomes the inner average where `inner_end` says so. Choosing sample by sample
  // before the averaging would average the larger of two values at every particle, which lifts
  // the average wherever the field is rough at the scale of the spacing (docs/theory.md, 5.4).
  template <class InnerEnd>
  void read_inner_ends(const MatArray<Dim, double>& point, const BondList<Dim, double>& bonds, InnerEnd&& inner_end,
                       const std::vector<std::uint8_t>* first_only, const std::vector<std::uint8_t>* second_only,
                       bool rest) {
    if constexpr (!std::is_same_v<std::decay_t<InnerEnd>, OuterEnd>) {
      if (two_ended_.empty()) return;
      average_pass(point, bonds, inner_stress_, false, averaged_inner_, first_only, rest, true);
      average_pass(point, bonds, averaged_inner_, true, smoothed_inner_, second_only, rest, true);
      MPSFSI_OMP(parallel for schedule(static))
      for (std::int64_t ii = 0; ii < static_cast<std::int64_t>(two_ended_.size()); ++ii) {
        const auto i = static_cast<std::size_t>(ii);
        if (!two_ended_[i] || (second_only && ((*second_only)[i] != 0) == rest)) continue;
        if (inner_end(smoothed_[i], smoothed_inner_[i])) smoothed_[i] = smoothed_inner_[i];
      }
    }
  }

  // Which particles' first averaging pass read_screened() computed.
  const std::vector<std::uint8_t>& first_pass_needed() const { return at_surface_ ? first_pass_needed_ : needed_; }

  // needed_ (and first_pass_needed_) from the few particles in hot_: the same values as the
  // highest bounds over every neighbourhood give, computed only where a hot sample reaches. A
  // particle with no hot sample in its neighbourhood (first pass) or, read outside, in its bonded
  // neighbours' (second) has every bound below the floor, where may_fail is false. Relies on
  // symmetric bonds (BondList), cut or not, as neighbourhood_highest reads them.
  template <class MayFail>
  void screen_from_hot(const BondList<Dim, double>& bonds, MayFail&& may_fail, double margin) {
    const std::size_t n = sample_bound_.size();
    level_.assign(n, 0);
    std::fill(needed_.begin(), needed_.end(), std::uint8_t(0));
    // Level 1: the hot particles and their bonded neighbours, cut or not, with the highest sample
    // bound over their neighbourhoods (the first pass's bound, as neighbourhood_highest gives it).
    reached_.clear();
    const auto reach = [&](std::size_t i, std::uint8_t level) {
      if (level_[i] != 0) return;
      level_[i] = level;
      reached_.push_back(i);
    };
    for (const std::size_t k : hot_) {
      reach(k, 1);
      for (Offset b = bonds.begin(k); b < bonds.end(k); ++b) reach(static_cast<std::size_t>(bonds.neighbor(b)), 1);
    }
    const auto reached = static_cast<std::int64_t>(reached_.size());
    MPSFSI_OMP(parallel for schedule(static))
    for (std::int64_t r = 0; r < reached; ++r) {
      const std::size_t i = reached_[static_cast<std::size_t>(r)];
      double h = sample_bound_[i];
      for (Offset b = bonds.begin(i); b < bonds.end(i); ++b)
        h = std::max(h, sample_bound_[static_cast<std::size_t>(bonds.neighbor(b))]);
      reach_bound_[i] = h;
    }
    if (at_surface_) {
      // Level 2: particles read outside with a level-1 neighbour. A particle read outside takes
      // the highest first-pass bound over its bonded neighbours; only level-1 ones can reach the
      // floor.
      for (std::int64_t r = 0; r < reached; ++r) {
        const std::size_t k = reached_[static_cast<std::size_t>(r)];
        for (Offset b = bonds.begin(k); b < bonds.end(k); ++b) {
          const auto i = static_cast<std::size_t>(bonds.neighbor(b));
          if (read_outside_[i]) reach(i, 2);
        }
      }
      const auto all = static_cast<std::int64_t>(reached_.size());
      MPSFSI_OMP(parallel for schedule(static))
      for (std::int64_t r = 0; r < all; ++r) {
        const std::size_t i = reached_[static_cast<std::size_t>(r)];
        double h = level_[i] == 1 ? reach_bound_[i] : -std::numeric_limits<double>::infinity();
        if (read_outside_[i])
          for (Offset b = bonds.begin(i); b < bonds.end(i); ++b) {
            const auto k = static_cast<std::size_t>(bonds.neighbor(b));
            if (level_[k] == 1) h = std::max(h, reach_bound_[k]);
          }
        sample_bound_[i] = h;  // the bound of i's read (reach_bound_ keeps the first pass's)
      }
      MPSFSI_OMP(parallel for schedule(static))
      for (std::int64_t r = 0; r < all; ++r) {
        const std::size_t i = reached_[static_cast<std::size_t>(r)];
        needed_[i] = may_fail(i, sample_bound_[i] + margin) ? 1 : 0;
      }
      // A needed particle's second pass reads its bonded neighbours' first.
      first_pass_needed_.assign(n, 0);
      for (const std::size_t i : reached_) {
        if (!needed_[i]) continue;
        first_pass_needed_[i] = 1;
        for (Offset b = bonds.begin(i); b < bonds.end(i); ++b) first_pass_needed_[static_cast<std::size_t>(bonds.neighbor(b))] = 1;
      }
    } else {
      MPSFSI_OMP(parallel for schedule(static))
      for (std::int64_t r = 0; r < reached; ++r) {
        const std::size_t i = reached_[static_cast<std::size_t>(r)];
        needed_[i] = may_fail(i, reach_bound_[i] + margin) ? 1 : 0;
      }
    }
  }

  // out[i]: the highest of in[] over particle i and its bonded neighbours, cut or not; with
  // `only`, just where it is set (elsewhere in[i]).
  static void neighbourhood_highest(const BondList<Dim, double>& bonds, const std::vector<double>& in,
                                    std::vector<double>& out, const std::vector<std::uint8_t>* only) {
    const Offset* const offsets = bonds.offsets().data();
    const Index* const neighbor = bonds.neighbors().data();
    MPSFSI_OMP(parallel for schedule(static))
    for (std::int64_t ii = 0; ii < static_cast<std::int64_t>(in.size()); ++ii) {
      const auto i = static_cast<std::size_t>(ii);
      double h = in[i];
      if (!only || (*only)[i])
        for (Offset b = offsets[i]; b < offsets[i + 1]; ++b) h = std::max(h, in[static_cast<std::size_t>(neighbor[b])]);
      out[i] = h;
    }
  }

  // One averaging pass into `out`: particles read outside average `in` along their face; the
  // others (all of them without surface reading) average the centre stresses over all bonds,
  // or, with `surface_only`, keep `in`, or, with `faces_only`, are left as they are. With
  // `only`, just the particles it marks (or, with `rest`, just the others).
  void average_pass(const MatArray<Dim, double>& point, const BondList<Dim, double>& bonds,
                    const MatArray<Dim, double>& in, bool surface_only, MatArray<Dim, double>& out,
                    const std::vector<std::uint8_t>* only, bool rest = false, bool faces_only = false) {
    const std::size_t n = point.size();
    out.resize(n);
    MPSFSI_OMP(parallel for schedule(static))
    for (std::int64_t ii = 0; ii < static_cast<std::int64_t>(n); ++ii) {
      const auto i = static_cast<std::size_t>(ii);
      if (only && ((*only)[i] != 0) == rest) continue;
      const bool along_face = at_surface_ && read_outside_[i] != 0;
      if (faces_only && !along_face) continue;
      if (surface_only && (!along_face || crack_ahead_[i])) {
        out[i] = in[i];
        continue;
      }
      double own = self_weight_;
      mat_type sum = mat_type::Zero();
      double weight = 0;
      for (Offset b = bonds.begin(i); b < bonds.end(i); ++b) {
        // A bond's weight is its first read's until it is cut (BondList::weight, without
        // recomputing it from r0).
        const double w = bonds.beta(b) == 0 ? 0.0 : initial_weight_[static_cast<std::size_t>(b)];
        const auto k = static_cast<std::size_t>(bonds.neighbor(b));
        if (along_face && !same_face(i, k)) continue;
        if (w == 0 || (k < cut_out_.size() && cut_out_[k] != 0)) {
          own += initial_weight_[static_cast<std::size_t>(b)];  // cut since the first read, or cut out
          continue;
        }
        sum += w * (along_face ? in[k] : point[k]);
        weight += w;
      }
      out[i] = (sum + own * in[i]) / (weight + own);
    }
  }

  enum class Last { point, surface, averaged, smoothed };
  Last last_ = Last::point;  // what the last read() returned
  VecArray<Dim, double> normal_;  // outward normals at the first read (zero inside)
  std::vector<double> initial_weight_;  // w of every bond at the first read (0 if already cut)
  std::vector<std::uint8_t> on_surface_, read_outside_;
  const std::vector<typename fit_type::affine_type>* fitted_ = nullptr;  // use_fitted()
  MatArray<Dim, double> surface_stress_, averaged_, smoothed_;
  // At the inner end of the cell, for a caller's inner_end (the outer end's where the face is not
  // whole), and its two averaging passes along the face.
  MatArray<Dim, double> inner_stress_, averaged_inner_, smoothed_inner_;
  std::vector<std::uint8_t> two_ended_;  // read outside with both ends, the end chosen after the averaging (or empty)
  std::vector<std::uint8_t> cut_out_;  // empty until the first CrackSide::slab failure
  VecArray<Dim, double> cut_out_normal_;  // their crack normals
  std::vector<std::uint8_t> crack_ahead_;  // read outside, on the plane of a crack across its face (sample())
  // The settings of the last read (complete() averages with them again).
  double self_weight_ = 0;
  bool at_surface_ = false;
  // read_screened(): the bounds, which particles' reads (and, with the second pass, first
  // passes) it computed, whether it left some out, and the bonds cut when it read.
  std::vector<double> sample_bound_, reach_bound_;
  std::vector<std::uint8_t> needed_, first_pass_needed_;
  std::vector<std::size_t> hot_, reached_;  // samples that reach the floor; the particles they reach
  std::vector<std::uint8_t> level_;         // 1: reached by a hot sample's bonds, 2: on its face beyond
  bool pending_ = false;
  std::size_t cuts_at_read_ = 0;
};

}  // namespace MPSFSI_ABI
}  // namespace mpsfsi
