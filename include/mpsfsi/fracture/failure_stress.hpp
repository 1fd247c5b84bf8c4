// SPDX-License-Identifier: BSD-3-Clause
#pragma once

#include <cstdint>
#include <vector>

#include "mpsfsi/core/abi.hpp"
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
//   first-order error in l0/h that made the bending study's peak load depend on l0). Averaged,
//   it is averaged only along its face (bonded surface particles with normals within 25
//   degrees, each read at its own surface point), so the read-out does not move inwards; and
//   twice (a filter over +-4 l0 on a flat face): with one pass, the grid-scale release wave of
//   the first cut started second cracks 3-4 l0 beside the first in three of the five bending
//   cases. Crack faces are not read outside: at a crack tip the field is singular, and a fit
//   extrapolated into the crack reads noise (it branched the crack of the bending study at
//   mid-height). Nor are loaded particles (`loaded(i)`; ElasticSolver: in contact, or having
//   carried an external force such as the FSI load at any step so far): a fit extrapolated to a
//   face under point loads reads their spikes (it cracked the top beside the indenter), and the
//   spikes stay in the field after the load is gone. A droplet's impact loads the ice beam's top
//   for one fluid step and then leaves it at zero pressure: read outside from then on, that face
//   fails one solid step later and the failures run along the whole beam (docs/validation/fsi.md).
//   The read-out is meant for faces that stay traction-free.
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

  // `point`: the stress at the particle centres; `fit`: the stress model's fit, or nullptr to
  // read every particle at its centre; `loaded(i)`: whether particle i carries a load.
  template <class Loaded>
  const MatArray<Dim, double>& read(const MatArray<Dim, double>& point, const VecArray<Dim, double>& x,
                                    const VecArray<Dim, double>& reference, const BondList<Dim, double>& bonds,
                                    const fit_type* fit, Loaded&& loaded, const Settings& s) {
    const std::size_t n = x.size();
    const bool at_surface = fit != nullptr;
    if (initial_weight_.size() != bonds.num_bonds()) {
      initial_weight_.resize(bonds.num_bonds());
      for (std::size_t b = 0; b < initial_weight_.size(); ++b) initial_weight_[b] = bonds.weight(static_cast<Offset>(b));
    }
    if (at_surface) {
      if (normal_.size() != n) structure_normals(bonds, reference, s.n0, kSurfaceThreshold, normal_, on_surface_);
      read_outside_.resize(n);
      surface_stress_.resize(n);
      MPSFSI_OMP(parallel for schedule(static))
      for (std::int64_t ii = 0; ii < static_cast<std::int64_t>(n); ++ii) {
        const auto i = static_cast<std::size_t>(ii);
        read_outside_[i] = on_surface_[i] && !loaded(i) ? 1 : 0;
        surface_stress_[i] = read_outside_[i] ? detail::cauchy_from_svk(
                                                    fit->gradient_at(fit->affine(x, bonds, i), 0.5 * s.l0 * normal_[i]), s.lame)
                                              : point[i];
      }
    }
    const auto& sampled = at_surface ? surface_stress_ : point;
    if (!s.average) {
      last_ = at_surface ? Last::surface : Last::point;
      return sampled;
    }
    average_pass(point, sampled, bonds, s.self_weight, at_surface, false, averaged_);
    last_ = at_surface ? Last::smoothed : Last::averaged;
    if (!at_surface) return averaged_;
    average_pass(point, averaged_, bonds, s.self_weight, true, true, smoothed_);
    return smoothed_;
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
  }

  // Particle i has been cut out (see above); n: the particle count.
  void mark_cut_out(std::size_t i, std::size_t n) {
    cut_out_.resize(n, 0);
    cut_out_[i] = 1;
  }
  std::size_t cut_out_marks() const { return cut_out_.size(); }

 private:
  // Surface detection threshold of structure_normals, and the cosine within which two surface
  // particles are on the same face (a narrow 3D beam's bottom face is within 2 l0 of its edges,
  // whose samples lie on the side faces).
  static constexpr double kSurfaceThreshold = 0.1;
  static constexpr double kSameFace = 0.9;

  bool same_face(std::size_t i, std::size_t k) const {
    return read_outside_[k] != 0 && normal_[i].dot(normal_[k]) >= kSameFace;
  }

  // One averaging pass into `out`: particles read outside average `in` along their face; the
  // others (all of them without surface reading) average the centre stresses over all bonds,
  // or, with `surface_only`, keep `in`.
  void average_pass(const MatArray<Dim, double>& point, const MatArray<Dim, double>& in,
                    const BondList<Dim, double>& bonds, double self_weight, bool at_surface, bool surface_only,
                    MatArray<Dim, double>& out) const {
    const std::size_t n = point.size();
    out.resize(n);
    MPSFSI_OMP(parallel for schedule(static))
    for (std::int64_t ii = 0; ii < static_cast<std::int64_t>(n); ++ii) {
      const auto i = static_cast<std::size_t>(ii);
      const bool along_face = at_surface && read_outside_[i] != 0;
      if (surface_only && !along_face) {
        out[i] = in[i];
        continue;
      }
      double own = self_weight;
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
  MatArray<Dim, double> surface_stress_, averaged_, smoothed_;
  std::vector<std::uint8_t> cut_out_;  // empty until the first CrackSide::slab failure
};

}  // namespace MPSFSI_ABI
}  // namespace mpsfsi
