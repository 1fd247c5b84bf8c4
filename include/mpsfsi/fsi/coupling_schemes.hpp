// SPDX-License-Identifier: BSD-3-Clause
#pragma once

#include <type_traits>
#include <utility>

#include "mpsfsi/core/abi.hpp"

namespace mpsfsi {
inline namespace MPSFSI_ABI {

// Coupling-scheme policies of FsiCoupler. One coupled step from t^n to t^n + dt:
//
// ExplicitPartitioned, the paper's scheme (its Fig 1 and docs/theory.md, section 4.2): the fluid steps
// with the structure at t^n as its moving wall, the interface pressure P^{n+1} becomes the load,
// and the structure sub-steps to t^n + dt under it. One fluid solve per step. Like every
// loosely coupled scheme it is subject to the added-mass instability when the structure is light
// against the fluid it moves.
struct ExplicitPartitioned {
  static constexpr bool iterative = false;
  static constexpr const char* name = "explicit";
};

// SubIterated: strong (implicit) coupling by fixed-point iteration on the interface load with
// Aitken's dynamic relaxation (Kuettler & Wall 2008). Iteration 0 is the explicit step. Then,
// repeatedly: the fluid redoes the step from t^n with the wall moving at the structure's mean
// velocity over the step, (x_s^{n+1,k} - x_s^n)/dt, the new interface load F~ gives the residual
// r_k = F~ - F_k, the load is relaxed, F_{k+1} = F_k + omega_k r_k,
//   omega_k = -omega_{k-1} r_{k-1}.(r_k - r_{k-1}) / |r_k - r_{k-1}|^2,
// and the structure redoes the step from t^n under F_{k+1}. Converged when
// |r_k| <= tolerance |F~| (2-norms over the structure's particles); a step that does not converge
// within max_iterations throws SimulationError. Costs one fluid solve per iteration.
struct SubIterated {
  static constexpr bool iterative = true;
  static constexpr bool quasi_newton = false;
  static constexpr const char* name = "sub-iterated";
  int max_iterations = 50;
  double tolerance = 1e-3;
  double initial_relaxation = 0.5;  // omega_0, also the bound of |omega| at the first iteration
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
  static constexpr bool quasi_newton = true;
  static constexpr const char* name = "IQN-ILS";
  int max_iterations = 50;
  double tolerance = 1e-3;
  double initial_relaxation = 0.5;  // omega of the first iteration when the model has no column
  int reuse_steps = 8;              // steps whose columns are kept
  int max_columns = 64;
};

// Compile-time check of a scheme (FsiCoupler static_asserts it): the members above, by kind.
namespace detail {

template <class S, class = void>
struct has_scheme_basics : std::false_type {};
template <class S>
struct has_scheme_basics<S, std::void_t<decltype(bool(S::iterative)), decltype(static_cast<const char*>(S::name))>>
    : std::true_type {};

template <class S, class = void>
struct has_iteration_controls : std::false_type {};
template <class S>
struct has_iteration_controls<S, std::void_t<decltype(int(std::declval<const S&>().max_iterations)),
                                             decltype(double(std::declval<const S&>().tolerance)),
                                             decltype(double(std::declval<const S&>().initial_relaxation))>>
    : std::true_type {};

template <class S, class = void>
struct has_quasi_newton_flag : std::false_type {};
template <class S>
struct has_quasi_newton_flag<S, std::void_t<decltype(bool(S::quasi_newton))>> : std::true_type {};

template <class S, class = void>
struct has_quasi_newton_controls : std::false_type {};
template <class S>
struct has_quasi_newton_controls<S, std::void_t<decltype(int(std::declval<const S&>().reuse_steps)),
                                                decltype(int(std::declval<const S&>().max_columns))>>
    : std::true_type {};

}  // namespace detail

template <class S>
constexpr bool check_coupling_scheme() {
  static_assert(detail::has_scheme_basics<S>::value,
                "coupling scheme lacks `static constexpr bool iterative` or `static constexpr const char* name`");
  if constexpr (detail::has_scheme_basics<S>::value && S::iterative) {
    static_assert(detail::has_iteration_controls<S>::value,
                  "iterative coupling scheme lacks `max_iterations`, `tolerance` or `initial_relaxation`");
    if constexpr (detail::has_quasi_newton_flag<S>::value) {
      if constexpr (S::quasi_newton)
        static_assert(detail::has_quasi_newton_controls<S>::value,
                      "quasi-Newton coupling scheme lacks `reuse_steps` or `max_columns`");
    }
  }
  return true;
}

}  // namespace MPSFSI_ABI
}  // namespace mpsfsi
