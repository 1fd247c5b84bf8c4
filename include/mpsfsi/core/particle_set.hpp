// SPDX-License-Identifier: BSD-3-Clause
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <limits>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "mpsfsi/core/abi.hpp"
#include "mpsfsi/core/error.hpp"
#include "mpsfsi/core/types.hpp"

namespace mpsfsi {
inline namespace MPSFSI_ABI {

// What a particle is. Fluid particles carry the flow; wall particles take part in the pressure
// Poisson equation with a prescribed velocity; dummy particles only fill the number density
// behind walls; solid particles belong to an elastic body.
enum class ParticleKind : std::uint8_t { fluid = 0, wall = 1, dummy = 2, solid = 3 };

// Typed handle to an extra per-particle field. Fields are looked up by handle (an array slot),
// never by name; the name is only what output files call it.
template <class T>
struct FieldHandle {
  std::size_t slot = static_cast<std::size_t>(-1);
};

namespace detail {

template <class T>
struct FieldStore {
  std::vector<std::string> names;
  std::vector<std::vector<T>> data;
};

// Reorders v so that v_new[k] = v_old[new_to_old[k]].
template <class T, class Alloc>
void apply_permutation(std::vector<T, Alloc>& v, const std::vector<Index>& new_to_old) {
  std::vector<T, Alloc> out(v.size());
  for (std::size_t k = 0; k < v.size(); ++k) out[k] = v[static_cast<std::size_t>(new_to_old[k])];
  v.swap(out);
}

}  // namespace detail

// Particles as a structure of arrays. Built-in fields: position, velocity, kind and a stable id
// (the index at creation, which survives reordering). Extra typed fields are added with
// add_field<T>() for T = Scalar, Vec, Mat or std::int32_t; every field is resized and permuted
// together, so no array can fall out of step with the others.
template <int Dim, class Scalar = double>
class ParticleSet {
  static_assert(detail::is_supported_dim<Dim>, "mpsfsi::ParticleSet: Dim must be 2 or 3");

 public:
  static constexpr int dim = Dim;
  using scalar_type = Scalar;
  using vec_type = Vec<Dim, Scalar>;
  using mat_type = Mat<Dim, Scalar>;

  ParticleSet() = default;
  explicit ParticleSet(std::size_t n) { resize(n); }

  std::size_t size() const { return position_.size(); }
  bool empty() const { return position_.empty(); }

  // Appends one particle; extra fields get zero. Returns its index.
  Index add(const vec_type& position, ParticleKind kind = ParticleKind::fluid,
            const vec_type& velocity = vec_type::Zero()) {
    // Copied first: the arguments may refer into this set's own arrays, which resize() moves.
    const vec_type p = position, v = velocity;
    const std::size_t n = size();
    resize(n + 1);
    position_[n] = p;
    velocity_[n] = v;
    kind_[n] = kind;
    return static_cast<Index>(n);
  }

  // Resizes every field; new particles sit at the origin, at rest, as fluid, with new ids.
  void resize(std::size_t n) {
    const std::size_t old = id_.size();
    if (n > static_cast<std::size_t>(std::numeric_limits<Index>::max()))
      detail::throw_invalid("ParticleSet::resize", "more than 2^31 - 1 particles");
    position_.resize(n, vec_type::Zero());
    velocity_.resize(n, vec_type::Zero());
    kind_.resize(n, ParticleKind::fluid);
    id_.resize(n);
    // Ids are never reused, even after a permute and a shrink.
    for (std::size_t k = old; k < n; ++k) id_[k] = next_id_++;
    for_each_store([n](auto& store) {
      using T = typename std::decay_t<decltype(store.data)>::value_type::value_type;
      for (auto& f : store.data) f.resize(n, zero_of<T>());
    });
  }

  void reserve(std::size_t n) {
    position_.reserve(n);
    velocity_.reserve(n);
    kind_.reserve(n);
    id_.reserve(n);
    for_each_store([n](auto& store) {
      for (auto& f : store.data) f.reserve(n);
    });
  }

  VecArray<Dim, Scalar>& positions() { return position_; }
  const VecArray<Dim, Scalar>& positions() const { return position_; }
  VecArray<Dim, Scalar>& velocities() { return velocity_; }
  const VecArray<Dim, Scalar>& velocities() const { return velocity_; }
  std::vector<ParticleKind>& kinds() { return kind_; }
  const std::vector<ParticleKind>& kinds() const { return kind_; }
  const std::vector<Index>& ids() const { return id_; }

  // Adds a zero-initialised field of type T named `name` (the name output files use).
  template <class T>
  FieldHandle<T> add_field(std::string name) {
    auto& store = store_for<T>();
    store.names.push_back(std::move(name));
    store.data.emplace_back(size(), zero_of<T>());
    return FieldHandle<T>{store.data.size() - 1};
  }

  template <class T>
  std::vector<T>& field(FieldHandle<T> h) {
    return store_for<T>().data.at(h.slot);
  }
  template <class T>
  const std::vector<T>& field(FieldHandle<T> h) const {
    return const_cast<ParticleSet*>(this)->store_for<T>().data.at(h.slot);
  }
  template <class T>
  const std::string& field_name(FieldHandle<T> h) const {
    return const_cast<ParticleSet*>(this)->store_for<T>().names.at(h.slot);
  }

  // Calls f(name, array) for every extra field of each type, for writers.
  template <class F>
  void for_each_scalar_field(F&& f) const { visit(scalars_, f); }
  template <class F>
  void for_each_vector_field(F&& f) const { visit(vectors_, f); }
  template <class F>
  void for_each_tensor_field(F&& f) const { visit(tensors_, f); }
  template <class F>
  void for_each_int_field(F&& f) const { visit(ints_, f); }

  // Passes every array and the id counter to a checkpoint archive (io/checkpoint.hpp), which
  // writes or overwrites them; the extra fields' names are labels that must match on reading.
  template <class Archive>
  void checkpoint_state(Archive& a) {
    a.array(position_);
    a.array(velocity_);
    a.array(kind_);
    a.array(id_);
    a.value(next_id_);
    for_each_store([&a](auto& store) {
      std::uint64_t count = store.data.size();
      a.value(count);  // overwritten when reading
      if (count != store.data.size())
        detail::throw_invalid("ParticleSet::checkpoint_state", "the checkpoint has " + std::to_string(count) +
                                                                   " fields of a type of which this set has " +
                                                                   std::to_string(store.data.size()));
      for (std::size_t s = 0; s < store.data.size(); ++s) {
        a.label(store.names[s]);
        a.array(store.data[s]);
      }
    });
    validate();
  }

  // Gives the particles the ids first, first + 1, ... in their order, and later additions the ids
  // after them. A set split over processes (mpi/) numbers each part from its offset, so that
  // ids are unique over all parts.
  void number_ids_from(Index first) {
    if (first < 0 || static_cast<std::size_t>(std::numeric_limits<Index>::max() - first) < size())
      detail::throw_invalid("ParticleSet::number_ids_from", "ids from " + std::to_string(first) + " for " +
                                                                std::to_string(size()) + " particles exceed 2^31 - 1");
    for (std::size_t k = 0; k < size(); ++k) id_[k] = first + static_cast<Index>(k);
    next_id_ = first + static_cast<Index>(size());
  }

  // Bytes that pack() writes per particle: every built-in and extra field.
  std::size_t packed_size() const {
    return 2 * sizeof(vec_type) + sizeof(ParticleKind) + sizeof(Index) + scalars_.data.size() * sizeof(Scalar) +
           vectors_.data.size() * sizeof(vec_type) + tensors_.data.size() * sizeof(mat_type) +
           ints_.data.size() * sizeof(std::int32_t);
  }

  // Writes particle i, every field, to out[0 .. packed_size()) (to move it to another process).
  void pack(std::size_t i, unsigned char* out) const {
    auto put = [&out](const auto& value) {
      std::memcpy(out, static_cast<const void*>(&value), sizeof value);
      out += sizeof value;
    };
    put(position_[i]);
    put(velocity_[i]);
    put(kind_[i]);
    put(id_[i]);
    for_each_store_const([&](const auto& store) {
      for (const auto& f : store.data) put(f[i]);
    });
  }

  // Appends the particle that pack() wrote from a set with the same fields, with its id.
  void unpack(const unsigned char* in) {
    auto get = [&in](auto& value) {
      std::memcpy(static_cast<void*>(&value), in, sizeof value);  // Eigen's fixed-size types are plain arrays
      in += sizeof value;
    };
    vec_type p, v;
    ParticleKind kind;
    Index id;
    get(p);
    get(v);
    get(kind);
    get(id);
    position_.push_back(p);
    velocity_.push_back(v);
    kind_.push_back(kind);
    id_.push_back(id);
    next_id_ = std::max(next_id_, id + 1);
    for_each_store([&](auto& store) {
      using T = typename std::decay_t<decltype(store.data)>::value_type::value_type;
      for (auto& f : store.data) {
        T value;
        get(value);
        f.push_back(value);
      }
    });
  }

  // Overwrites particle i with what pack() wrote (the same particle, moved on).
  void unpack_into(std::size_t i, const unsigned char* in) {
    auto get = [&in](auto& value) {
      std::memcpy(static_cast<void*>(&value), in, sizeof value);  // Eigen's fixed-size types are plain arrays
      in += sizeof value;
    };
    get(position_[i]);
    get(velocity_[i]);
    get(kind_[i]);
    get(id_[i]);
    for_each_store([&](auto& store) {
      for (auto& f : store.data) get(f[i]);
    });
  }

  // Reorders every field: particle k after the call is particle new_to_old[k] before it.
  void permute(const std::vector<Index>& new_to_old) {
    if (new_to_old.size() != size())
      detail::throw_invalid("ParticleSet::permute", "permutation has " +
                                                        std::to_string(new_to_old.size()) +
                                                        " entries for " + std::to_string(size()) +
                                                        " particles");
    for (Index k : new_to_old)
      if (k < 0 || static_cast<std::size_t>(k) >= size())
        detail::throw_invalid("ParticleSet::permute", "index " + std::to_string(k) + " out of range");
    detail::apply_permutation(position_, new_to_old);
    detail::apply_permutation(velocity_, new_to_old);
    detail::apply_permutation(kind_, new_to_old);
    detail::apply_permutation(id_, new_to_old);
    for_each_store([&](auto& store) {
      for (auto& f : store.data) detail::apply_permutation(f, new_to_old);
    });
  }

  // Throws InvalidInput naming the problem: a field whose size differs from the particle count,
  // or a non-finite position or velocity (with the particle's index and id).
  void validate() const {
    const std::size_t n = size();
    auto check_size = [n](std::size_t got, const std::string& what) {
      if (got != n)
        detail::throw_invalid("ParticleSet::validate", "field '" + what + "' has " +
                                                           std::to_string(got) + " entries for " +
                                                           std::to_string(n) + " particles");
    };
    check_size(velocity_.size(), "velocity");
    check_size(kind_.size(), "kind");
    check_size(id_.size(), "id");
    for_each_store_const([&](const auto& store) {
      for (std::size_t s = 0; s < store.data.size(); ++s) check_size(store.data[s].size(), store.names[s]);
    });
    for (std::size_t i = 0; i < n; ++i) {
      if (!position_[i].allFinite())
        detail::throw_invalid("ParticleSet::validate", "position of particle " + std::to_string(i) +
                                                           " (id " + std::to_string(id_[i]) +
                                                           ") is not finite");
      if (!velocity_[i].allFinite())
        detail::throw_invalid("ParticleSet::validate", "velocity of particle " + std::to_string(i) +
                                                           " (id " + std::to_string(id_[i]) +
                                                           ") is not finite");
    }
  }

 private:
  template <class T>
  static T zero_of() {
    if constexpr (std::is_arithmetic_v<T>) {
      return T(0);
    } else {
      return T::Zero();
    }
  }

  template <class T>
  detail::FieldStore<T>& store_for() {
    if constexpr (std::is_same_v<T, Scalar>) {
      return scalars_;
    } else if constexpr (std::is_same_v<T, vec_type>) {
      return vectors_;
    } else if constexpr (std::is_same_v<T, mat_type>) {
      return tensors_;
    } else {
      static_assert(std::is_same_v<T, std::int32_t>,
                    "mpsfsi::ParticleSet fields are Scalar, Vec<Dim>, Mat<Dim> or std::int32_t");
      return ints_;
    }
  }

  template <class F>
  void for_each_store(F&& f) {
    f(scalars_);
    f(vectors_);
    f(tensors_);
    f(ints_);
  }
  template <class F>
  void for_each_store_const(F&& f) const {
    f(scalars_);
    f(vectors_);
    f(tensors_);
    f(ints_);
  }
  template <class Store, class F>
  static void visit(const Store& store, F& f) {
    for (std::size_t s = 0; s < store.data.size(); ++s) f(store.names[s], store.data[s]);
  }

  VecArray<Dim, Scalar> position_;
  VecArray<Dim, Scalar> velocity_;
  std::vector<ParticleKind> kind_;
  std::vector<Index> id_;
  Index next_id_ = 0;
  detail::FieldStore<Scalar> scalars_;
  detail::FieldStore<vec_type> vectors_;
  detail::FieldStore<mat_type> tensors_;
  detail::FieldStore<std::int32_t> ints_;
};

}  // namespace MPSFSI_ABI
}  // namespace mpsfsi
