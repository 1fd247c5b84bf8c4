// SPDX-License-Identifier: BSD-3-Clause
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <optional>
#include <string>
#include <type_traits>
#include <utility>

#include "mpsfsi/core/abi.hpp"
#include "mpsfsi/fsi/interface_quasi_newton.hpp"

namespace mpsfsi {
inline namespace MPSFSI_ABI {

// Coupling-scheme policies of FsiCoupler. A scheme owns the advance of one coupled step from t^n
// to t^n + dt: `template <class Step> void advance(Step& step)`, where the coupler's Step
// (FsiCoupler::Step, fsi_coupler.hpp) offers
//   step.solve_fluid()           the fluid's step from t^n, the structure as its moving wall
//   step.fluid_load(F)           the fluid's load on the structure after the last solve (eqs 18-19)
//   step.advance_structure(F)    the structure from t^n to t^n + dt under F plus applied_force()
//   step.load()                  the interface load the coupler keeps across steps and reports
//   step.workspace(k)            interface-sized arrays kept by the coupler (no allocation per step)
//   step.fail(what)              a SimulationError naming the step and time
// and dt(), step_number() and fluid_solves(). A scheme that solves the fluid or advances the
// structure more than once in a step declares `static constexpr bool iterative = true`: the
// coupler then keeps both solvers' state at t^n, returns to it on each repeat, and moves the
// wall of a repeated fluid solve at the structure's mean velocity over the step,
// (x_s^{n+1,k} - x_s^n) / dt. The coupler runs advance() once per step, on one thread; the
// solvers parallelise inside.

// ExplicitPartitioned, the paper's scheme (its Fig 1 and docs/theory.md, section 4.2): the fluid steps
// with the structure at t^n as its moving wall, the interface pressure P^{n+1} becomes the load,
// and the structure sub-steps to t^n + dt under it. One fluid solve per step. Like every
// loosely coupled scheme it is subject to the added-mass instability when the structure is light
// against the fluid it moves.
struct ExplicitPartitioned {
  static constexpr bool iterative = false;
  static constexpr const char* name = "explicit";

  template <class Step>
  void advance(Step& step) const {
    step.solve_fluid();
    step.fluid_load(step.load());
    step.advance_structure(step.load());
  }
};

namespace detail {

// r = F~ - F over the structure's particles; true when |r| <= tolerance |F~| (2-norms), the
// convergence test of the iterated schemes.
template <class VecArrayT>
bool interface_residual(const VecArrayT& trial, const VecArrayT& load, VecArrayT& residual, double tolerance) {
  residual.resize(trial.size());
  double r2 = 0, f2 = 0;
  for (std::size_t s = 0; s < trial.size(); ++s) {
    residual[s] = trial[s] - load[s];
    r2 += residual[s].squaredNorm();
    f2 += trial[s].squaredNorm();
  }
  return std::sqrt(r2) <= tolerance * std::sqrt(f2);
}

template <class S, class Step, class = void>
struct can_advance : std::false_type {};
template <class S, class Step>
struct can_advance<S, Step, std::void_t<decltype(std::declval<S&>().advance(std::declval<Step&>()))>> : std::true_type {};

template <class S, class = void>
struct has_scheme_basics : std::false_type {};
template <class S>
struct has_scheme_basics<S, std::void_t<decltype(bool(S::iterative)), decltype(static_cast<const char*>(S::name))>>
    : std::true_type {};

}  // namespace detail

// SubIterated: strong (implicit) coupling by fixed-point iteration on the interface load with
// Aitken's dynamic relaxation (Kuettler & Wall 2008). Iteration 0 is the explicit step. Then,
// repeatedly: the fluid redoes the step from t^n with the wall moving at the structure's mean
// velocity over the step, the new interface load F~ gives the residual r_k = F~ - F_k, the load
// is relaxed, F_{k+1} = F_k + omega_k r_k,
//   omega_k = -omega_{k-1} r_{k-1}.(r_k - r_{k-1}) / |r_k - r_{k-1}|^2,
// and the structure redoes the step from t^n under F_{k+1}. Converged when
// |r_k| <= tolerance |F~| (2-norms over the structure's particles); a step that does not converge
// within max_iterations throws SimulationError. Costs one fluid solve per iteration.
struct SubIterated {
  static constexpr bool iterative = true;
  static constexpr const char* name = "sub-iterated";
  int max_iterations = 50;
  double tolerance = 1e-3;
  double initial_relaxation = 0.5;  // omega_0, also the bound of |omega| at the first iteration

  template <class Step>
  void advance(Step& step) {
    auto& load = step.load();
    auto& trial = step.workspace(0);
    auto& residual = step.workspace(1);
    auto& previous_residual = step.workspace(2);
    step.solve_fluid();
    step.fluid_load(load);
    step.advance_structure(load);
    // Start from the relaxation the last step converged with (bounded): the added-mass ratio
    // that sets it changes slowly.
    double omega = std::clamp(std::isnan(last_relaxation_) ? initial_relaxation : last_relaxation_, 0.05, 1.0);
    for (int it = 1; it <= max_iterations; ++it) {
      step.solve_fluid();
      step.fluid_load(trial);
      if (detail::interface_residual(trial, load, residual, tolerance)) {
        last_relaxation_ = omega;
        return;
      }
      if (it > 1) {
        double num = 0, den = 0;
        for (std::size_t s = 0; s < residual.size(); ++s) {
          const auto d = (residual[s] - previous_residual[s]).eval();
          num += previous_residual[s].dot(d);
          den += d.squaredNorm();
        }
        if (den > 0) omega = -omega * num / den;
      }
      for (std::size_t s = 0; s < load.size(); ++s) load[s] += omega * residual[s];
      previous_residual = residual;
      step.advance_structure(load);
    }
    step.fail("the sub-iterated coupling did not converge in " + std::to_string(max_iterations) + " iterations");
  }

  // Checkpoints (io/checkpoint.hpp): the relaxation the next step starts from.
  template <class Archive>
  void checkpoint_state(Archive& a) {
    a.value(last_relaxation_);
  }

 private:
  double last_relaxation_ = std::numeric_limits<double>::quiet_NaN();  // none yet: initial_relaxation
};

// InterfaceQuasiNewton: strong coupling by IQN-ILS (Degroote, Bathe & Vierendeels 2009), the
// iterations of SubIterated with the load updated from a least-squares model of how the fluid's
// load answers the structure (interface_quasi_newton.hpp), kept over `reuse_steps` steps. Where
// the fluid's added mass dwarfs the structure's mass over a long wave (a floating ice sheet: the
// water under it weighs tens of times the ice), Aitken's single factor has to damp every mode
// by the strongest one's gain and converges slowly or not at all; the model fits the few strong
// modes and leaves the rest to the fixed point. Same convergence test and failure as SubIterated.
struct InterfaceQuasiNewton {
  static constexpr bool iterative = true;
  static constexpr const char* name = "IQN-ILS";
  int max_iterations = 50;
  double tolerance = 1e-3;
  double initial_relaxation = 0.5;  // omega of the first iteration when the model has no column
  int reuse_steps = 8;              // steps whose columns are kept (read at the first step)
  int max_columns = 64;             // read at the first step

  template <class Step>
  void advance(Step& step) {
    static_assert(std::is_same_v<typename Step::scalar_type, double>, "InterfaceQuasiNewton: the model works in double");
    auto& load = step.load();
    auto& trial = step.workspace(0);
    auto& residual = step.workspace(1);
    step.solve_fluid();
    // From the second step on, start from the last step's converged load: where the fluid's
    // added mass dwarfs the structure's, the explicit step's load (the wall moving on at its
    // velocity at t^n) is off by more than the load itself, and a first iterate that far sends
    // the next fluid solve into suction and the clamp to zero pressure, where the model learns
    // nothing.
    if (step.step_number() == 1) step.fluid_load(load);
    step.advance_structure(load);
    model().begin_step();
    for (int it = 1; it <= max_iterations; ++it) {
      step.solve_fluid();
      step.fluid_load(trial);
      if (detail::interface_residual(trial, load, residual, tolerance)) return;
      model().next_load(load, trial, residual, initial_relaxation);
      step.advance_structure(load);
    }
    step.fail("the IQN-ILS coupling did not converge in " + std::to_string(max_iterations) + " iterations");
  }

  // Checkpoints (io/checkpoint.hpp): the model's columns kept for the next steps.
  template <class Archive>
  void checkpoint_state(Archive& a) {
    model().checkpoint_state(a);
  }

  // The least-squares model, built from reuse_steps and max_columns at its first use.
  InterfaceQuasiNewtonModel<double>& model() {
    if (!model_) model_.emplace(reuse_steps, max_columns);
    return *model_;
  }

 private:
  std::optional<InterfaceQuasiNewtonModel<double>> model_;
};

// Compile-time check of a scheme for the coupler's Step (FsiCoupler static_asserts it).
template <class S, class Step>
constexpr bool check_coupling_scheme() {
  static_assert(detail::has_scheme_basics<S>::value,
                "coupling scheme lacks `static constexpr bool iterative` or `static constexpr const char* name`");
  static_assert(detail::can_advance<S, Step>::value,
                "coupling scheme lacks `template <class Step> void advance(Step& step)` (one coupled step; "
                "fsi/coupling_schemes.hpp lists what Step offers)");
  return true;
}

}  // namespace MPSFSI_ABI
}  // namespace mpsfsi
