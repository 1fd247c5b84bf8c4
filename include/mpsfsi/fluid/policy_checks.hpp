// SPDX-License-Identifier: BSD-3-Clause
#pragma once

#include <cstddef>
#include <cstdint>
#include <type_traits>
#include <utility>
#include <vector>

#include "mpsfsi/core/abi.hpp"
#include "mpsfsi/core/neighbor_list.hpp"
#include "mpsfsi/core/particle_set.hpp"
#include "mpsfsi/core/types.hpp"
#include "mpsfsi/fluid/linear_solver.hpp"
#include "mpsfsi/kernels/lattice_constants.hpp"

namespace mpsfsi {
inline namespace MPSFSI_ABI {

// Compile-time checks of FluidSolver's policy slots (docs/extending.md lists what each must
// provide). FluidSolver static_asserts them, so a policy that lacks a member fails with a message
// naming it rather than with an error deep in the solver.
namespace detail {

template <int Dim>
using PointArray = VecArray<Dim, double>;

template <class G, class Weight, int Dim, class = void>
struct has_correction_update : std::false_type {};
template <class G, class Weight, int Dim>
struct has_correction_update<G, Weight, Dim,
                             std::void_t<decltype(std::declval<G&>().template update<Weight>(
                                 std::declval<const PointArray<Dim>&>(), std::declval<const BasicNeighborList<double>&>(),
                                 std::declval<const MpsConstants<double>&>()))>> : std::true_type {};

template <class G, int Dim, class = void>
struct has_correction_apply : std::false_type {};
template <class G, int Dim>
struct has_correction_apply<G, Dim,
                            std::void_t<decltype(Vec<Dim, double>(std::declval<const G&>().apply(
                                std::size_t{}, std::declval<const Vec<Dim, double>&>())))>> : std::true_type {};

template <class G, class = void>
struct has_correction_is_corrected : std::false_type {};
template <class G>
struct has_correction_is_corrected<G, std::void_t<decltype(bool(std::declval<const G&>().is_corrected(std::size_t{})))>>
    : std::true_type {};

template <class S, class = void>
struct has_linear_solve : std::false_type {};
template <class S>
struct has_linear_solve<S, std::void_t<decltype(SolveReport(std::declval<S&>().solve(
                               std::declval<const PpeMatrix&>(), std::declval<const PpeVector&>(),
                               std::declval<PpeVector&>(), 0.0, 0)))>> : std::true_type {};

template <class F, int Dim, class = void>
struct has_surface_detect : std::false_type {};
template <class F, int Dim>
struct has_surface_detect<F, Dim,
                          std::void_t<decltype(F::detect(
                              std::declval<const PointArray<Dim>&>(), std::declval<const std::vector<ParticleKind>&>(),
                              std::declval<const BasicNeighborList<double>&>(), std::declval<const std::vector<double>&>(),
                              0.0, 0.0, 0.0, 0.0, std::declval<std::vector<std::uint8_t>&>()))>> : std::true_type {};

template <class C, int Dim, class = void>
struct has_collision_apply : std::false_type {};
template <class C, int Dim>
struct has_collision_apply<C, Dim,
                           std::void_t<decltype(std::declval<C&>().apply(
                               std::declval<const PointArray<Dim>&>(), std::declval<const std::vector<ParticleKind>&>(),
                               std::declval<const BasicNeighborList<double>&>(), 0.0, std::declval<PointArray<Dim>&>(),
                               std::declval<PointArray<Dim>&>()))>> : std::true_type {};

}  // namespace detail

template <class G, class Weight, int Dim>
constexpr bool check_gradient_correction() {
  static_assert(detail::has_correction_update<G, Weight, Dim>::value,
                "gradient correction policy lacks `template <class Weight> void update(const VecArray<Dim>& x, "
                "const BasicNeighborList<double>&, const MpsConstants<double>&)`");
  static_assert(detail::has_correction_apply<G, Dim>::value,
                "gradient correction policy lacks `Vec<Dim> apply(std::size_t i, const Vec<Dim>& r_ij) const`");
  static_assert(detail::has_correction_is_corrected<G>::value,
                "gradient correction policy lacks `bool is_corrected(std::size_t i) const`");
  return true;
}

template <class S>
constexpr bool check_linear_solver() {
  static_assert(std::is_default_constructible_v<S>, "linear solver policy must be default-constructible");
  static_assert(detail::has_linear_solve<S>::value,
                "linear solver policy lacks `SolveReport solve(const PpeMatrix&, const PpeVector& b, PpeVector& x, "
                "double tolerance, int max_iterations)`");
  return true;
}

template <class F, int Dim>
constexpr bool check_free_surface() {
  static_assert(detail::has_surface_detect<F, Dim>::value,
                "free-surface policy lacks `template <int Dim, class Scalar> static void detect(x, kinds, list, n, "
                "n0, beta, l0, re, std::vector<std::uint8_t>& surface)`");
  return true;
}

template <class C, int Dim>
constexpr bool check_collision() {
  static_assert(std::is_default_constructible_v<C>, "collision policy must be default-constructible");
  static_assert(detail::has_collision_apply<C, Dim>::value,
                "collision policy lacks `template <int Dim, class Scalar> void apply(x, kinds, list, l0, "
                "VecArray<Dim>& u_star, VecArray<Dim>& scratch)`");
  return true;
}

}  // namespace MPSFSI_ABI
}  // namespace mpsfsi
