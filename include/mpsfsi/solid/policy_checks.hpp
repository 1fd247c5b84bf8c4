// SPDX-License-Identifier: BSD-3-Clause
#pragma once

#include <cstddef>
#include <type_traits>
#include <utility>
#include <vector>

#include "mpsfsi/core/abi.hpp"
#include "mpsfsi/core/types.hpp"
#include "mpsfsi/solid/bonds.hpp"
#include "mpsfsi/solid/deformation.hpp"

namespace mpsfsi {
inline namespace MPSFSI_ABI {

// Compile-time checks of ElasticSolver's stress-model and contact slots (docs/extending.md lists
// what each must provide); the failure model's are in fracture/policy_checks.hpp, which
// FractureProcess static_asserts. ElasticSolver static_asserts these, so a policy that lacks a member fails with a message naming
// it rather than with an error deep in the solver.
namespace detail {

template <class M, class = void>
struct has_model_name : std::false_type {};
template <class M>
struct has_model_name<M, std::void_t<decltype(static_cast<const char*>(M::name))>> : std::true_type {};

template <class M, int Dim, class = void>
struct has_model_initialize : std::false_type {};
template <class M, int Dim>
struct has_model_initialize<M, Dim,
                            std::void_t<decltype(std::declval<M&>().initialize(
                                std::declval<const BondList<Dim, double>&>(),
                                std::declval<const SolidModelContext<Dim, double>&>()))>> : std::true_type {};

template <class M, int Dim, class = void>
struct has_model_bonds_changed : std::false_type {};
template <class M, int Dim>
struct has_model_bonds_changed<M, Dim,
                               std::void_t<decltype(std::declval<M&>().bonds_changed(
                                   std::declval<const BondList<Dim, double>&>(),
                                   std::declval<const std::vector<std::size_t>&>()))>> : std::true_type {};

template <class M, int Dim, class = void>
struct has_model_internal_forces : std::false_type {};
template <class M, int Dim>
struct has_model_internal_forces<M, Dim,
                                 std::void_t<decltype(std::declval<M&>().internal_forces(
                                     std::declval<const VecArray<Dim, double>&>(),
                                     std::declval<const BondList<Dim, double>&>(),
                                     std::declval<VecArray<Dim, double>&>()))>> : std::true_type {};

// Optional: the forces and the Cauchy stresses in one pass.
template <class M, int Dim, class = void>
struct has_model_forces_with_stresses : std::false_type {};
template <class M, int Dim>
struct has_model_forces_with_stresses<M, Dim,
                                      std::void_t<decltype(std::declval<M&>().internal_forces(
                                          std::declval<const VecArray<Dim, double>&>(),
                                          std::declval<const BondList<Dim, double>&>(),
                                          std::declval<VecArray<Dim, double>&>(), std::declval<MatArray<Dim, double>&>()))>>
    : std::true_type {};

// Optional: the forces, the stresses (when given) and the bond viscosity (BondViscosity's sum with
// the given coefficient) in one pass.
template <class M, int Dim, class = void>
struct has_model_forces_with_viscosity : std::false_type {};
template <class M, int Dim>
struct has_model_forces_with_viscosity<
    M, Dim,
    std::void_t<decltype(std::declval<M&>().internal_forces(
        std::declval<const VecArray<Dim, double>&>(), std::declval<const VecArray<Dim, double>&>(),
        std::declval<const BondList<Dim, double>&>(), std::declval<VecArray<Dim, double>&>(),
        std::declval<MatArray<Dim, double>*>(), std::declval<double>()))>> : std::true_type {};

// Whether a stress model exposes its DeformationFit (fit()), so the failure criterion can read
// the fitted field away from particle centres.
template <class Model, class = void>
struct has_deformation_fit : std::false_type {};
template <class Model>
struct has_deformation_fit<Model, std::void_t<decltype(std::declval<const Model&>().fit())>> : std::true_type {};
// Whether its force loop can keep the fitted A_i of the surface particles (keep_affine(),
// kept_affine()), for the failure check's surface read-out.
template <class Model, class = void>
struct keeps_affine : std::false_type {};
template <class Model>
struct keeps_affine<Model, std::void_t<decltype(std::declval<Model&>().keep_affine(nullptr)),
                                       decltype(std::declval<const Model&>().kept_affine())>> : std::true_type {};
// Whether its force loop can skip particles that are held (skip_held(), detail::HeldParticles).
template <class Model, class = void>
struct skips_held : std::false_type {};
template <class Model>
struct skips_held<Model, std::void_t<decltype(std::declval<Model&>().skip_held(nullptr))>> : std::true_type {};

template <class M, int Dim, class = void>
struct has_model_stresses : std::false_type {};
template <class M, int Dim>
struct has_model_stresses<M, Dim,
                          std::void_t<decltype(std::declval<M&>().stresses(
                              std::declval<const VecArray<Dim, double>&>(), std::declval<const BondList<Dim, double>&>(),
                              std::declval<MatArray<Dim, double>&>()))>> : std::true_type {};

template <class M, int Dim, class = void>
struct has_model_strain_energy : std::false_type {};
template <class M, int Dim>
struct has_model_strain_energy<M, Dim,
                               std::void_t<decltype(double(std::declval<const M&>().strain_energy(
                                   std::declval<const VecArray<Dim, double>&>(),
                                   std::declval<const BondList<Dim, double>&>())))>> : std::true_type {};

template <class M, class = void>
struct has_model_kick_drift : std::false_type {};
template <class M>
struct has_model_kick_drift<M, std::void_t<decltype(std::declval<M&>().kick(0.0)), decltype(std::declval<M&>().drift(0.0))>>
    : std::true_type {};

template <class C, class = void>
struct has_contact_initialize : std::false_type {};
template <class C>
struct has_contact_initialize<C, std::void_t<decltype(std::declval<C&>().initialize(std::size_t{}, 0.0, 0.0, 0.0))>>
    : std::true_type {};

template <class C, int Dim, class = void>
struct has_contact_add_forces : std::false_type {};
template <class C, int Dim>
struct has_contact_add_forces<C, Dim,
                              std::void_t<decltype(std::declval<C&>().add_forces(
                                  std::declval<const VecArray<Dim, double>&>(), std::declval<const VecArray<Dim, double>&>(),
                                  std::declval<const BondList<Dim, double>&>(), std::declval<VecArray<Dim, double>&>()))>>
    : std::true_type {};

template <class C, int Dim, class = void>
struct has_contact_touching : std::false_type {};
template <class C, int Dim>
struct has_contact_touching<C, Dim,
                            std::void_t<decltype(bool(std::declval<const C&>().touching(
                                std::declval<const VecArray<Dim, double>&>(), std::size_t{})))>> : std::true_type {};

template <class C, int Dim, class = void>
struct has_contact_energy : std::false_type {};
template <class C, int Dim>
struct has_contact_energy<C, Dim,
                          std::void_t<decltype(double(std::declval<const C&>().energy(
                              std::declval<const VecArray<Dim, double>&>(), std::declval<const BondList<Dim, double>&>())))>>
    : std::true_type {};

template <class C, class = void>
struct has_contact_active_pairs : std::false_type {};
template <class C>
struct has_contact_active_pairs<C, std::void_t<decltype(std::size_t(std::declval<const C&>().active_pairs()))>>
    : std::true_type {};

// Optional: `void set_friction(double mu)`, Coulomb friction (SolidParameters::contact_friction).
template <class C, class = void>
struct has_contact_friction : std::false_type {};
template <class C>
struct has_contact_friction<C, std::void_t<decltype(std::declval<C&>().set_friction(0.5))>> : std::true_type {};

}  // namespace detail

template <class M, int Dim>
constexpr bool check_stress_model() {
  static_assert(detail::has_model_name<M>::value, "stress model policy lacks `static constexpr const char* name`");
  static_assert(detail::has_model_initialize<M, Dim>::value,
                "stress model policy lacks `void initialize(const BondList<Dim>&, const SolidModelContext<Dim>&)`");
  static_assert(detail::has_model_bonds_changed<M, Dim>::value,
                "stress model policy lacks `void bonds_changed(const BondList<Dim>&, const std::vector<std::size_t>&)`");
  static_assert(detail::has_model_internal_forces<M, Dim>::value,
                "stress model policy lacks `void internal_forces(const VecArray<Dim>& x, const BondList<Dim>&, "
                "VecArray<Dim>& force)`");
  static_assert(detail::has_model_stresses<M, Dim>::value,
                "stress model policy lacks `void stresses(const VecArray<Dim>& x, const BondList<Dim>&, "
                "MatArray<Dim>& sigma)`");
  static_assert(detail::has_model_strain_energy<M, Dim>::value,
                "stress model policy lacks `double strain_energy(const VecArray<Dim>& x, const BondList<Dim>&) const`");
  static_assert(detail::has_model_kick_drift<M>::value,
                "stress model policy lacks `void kick(double dt)` and `void drift(double dt)` (empty for a model "
                "without particle rotation)");
  return true;
}

template <class C, int Dim>
constexpr bool check_contact() {
  static_assert(std::is_default_constructible_v<C>, "contact policy must be default-constructible");
  static_assert(detail::has_contact_initialize<C>::value,
                "contact policy lacks `void initialize(std::size_t n, double distance, double stiffness, double damping)`");
  static_assert(detail::has_contact_add_forces<C, Dim>::value,
                "contact policy lacks `void add_forces(const VecArray<Dim>& x, const VecArray<Dim>& v, "
                "const BondList<Dim>&, VecArray<Dim>& force)`");
  static_assert(detail::has_contact_touching<C, Dim>::value,
                "contact policy lacks `bool touching(const VecArray<Dim>& x, std::size_t i) const`");
  static_assert(detail::has_contact_energy<C, Dim>::value,
                "contact policy lacks `double energy(const VecArray<Dim>& x, const BondList<Dim>&) const`");
  static_assert(detail::has_contact_active_pairs<C>::value, "contact policy lacks `std::size_t active_pairs() const`");
  return true;
}

}  // namespace MPSFSI_ABI
}  // namespace mpsfsi
