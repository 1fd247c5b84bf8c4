// SPDX-License-Identifier: BSD-3-Clause
#pragma once

#include <type_traits>
#include <utility>
#include <vector>

#include "mpsfsi/core/abi.hpp"
#include "mpsfsi/core/types.hpp"
#include "mpsfsi/fracture/strength.hpp"

namespace mpsfsi {
inline namespace MPSFSI_ABI {

// Compile-time check of ElasticSolver's failure-model slot (failure_criteria.hpp states the
// contract). FractureProcess static_asserts it, so a model written wrong fails with a message
// naming the member rather than with an error deep in the solver, or, for a direction taken by
// value, instead of compiling and leaving the crack normal unset.
namespace detail {

// principal(sigma, direction) with `direction` an lvalue (Direction = Vec&) or an rvalue
// (Direction = Vec): a model that accepts the rvalue takes the direction by value or by const
// reference and cannot return the crack normal through it.
template <class F, int Dim, class Direction, class = void>
struct has_failure_principal : std::false_type {};
template <class F, int Dim, class Direction>
struct has_failure_principal<F, Dim, Direction,
                             std::void_t<decltype(double(std::declval<const F&>().template principal<Dim, double>(
                                 std::declval<const Mat<Dim, double>&>(), std::declval<Direction>())))>>
    : std::true_type {};

template <class F, class = void>
struct has_convexity_flag : std::false_type {};
template <class F>
struct has_convexity_flag<F, std::void_t<decltype(bool(F::upper_bound_is_convex))>> : std::true_type {};

// The optional upper_bound(sigma) (failure_criteria.hpp).
template <class F, int Dim, class = void>
struct has_failure_upper_bound : std::false_type {};
template <class F, int Dim>
struct has_failure_upper_bound<F, Dim,
                               std::void_t<decltype(double(std::declval<const F&>().template upper_bound<Dim, double>(
                                   std::declval<const Mat<Dim, double>&>())))>> : std::true_type {};

// An upper bound the model declares convex (upper_bound_is_convex = true): the bound of a weighted
// average of tensors is then at most the largest of theirs, so the averaged read-out can be
// screened before it is averaged (FailureStressReadout::read_screened).
template <class F, int Dim>
struct has_convex_failure_bound {
  static constexpr bool value = [] {
    if constexpr (has_failure_upper_bound<F, Dim>::value && has_convexity_flag<F>::value)
      return bool(F::upper_bound_is_convex);
    else
      return false;
  }();
};

template <class F, class = void>
struct names_assign_strengths : std::false_type {};
template <class F>
struct names_assign_strengths<F, std::void_t<decltype(&F::assign_strengths)>> : std::true_type {};

}  // namespace detail

template <class F, int Dim>
constexpr bool check_failure_model() {
  static_assert(detail::has_failure_enabled<F>::value, "failure model lacks `static constexpr bool enabled`");
  static_assert(detail::has_failure_principal<F, Dim, Vec<Dim, double>&>::value,
                "failure model lacks `template <int Dim, class Scalar> Scalar principal(const Mat<Dim, Scalar>& sigma, "
                "Vec<Dim, Scalar>& direction) const` (or static)");
  static_assert(!detail::has_failure_principal<F, Dim, Vec<Dim, double>>::value,
                "failure model's principal() must take the direction as `Vec<Dim, Scalar>&`: it returns the crack "
                "normal through it");
  static_assert(!detail::names_assign_strengths<F>::value || detail::has_assign_strengths<F>::value,
                "failure model's assign_strengths must be `void assign_strengths(const StrengthSetup&, "
                "std::vector<double>& strength) const`");
  static_assert(!detail::has_convexity_flag<F>::value || detail::has_failure_upper_bound<F, Dim>::value,
                "failure model declares `upper_bound_is_convex` but has no `template <int Dim, class Scalar> Scalar "
                "upper_bound(const Mat<Dim, Scalar>& sigma) const` (or static)");
  return true;
}

}  // namespace MPSFSI_ABI
}  // namespace mpsfsi
