// SPDX-License-Identifier: BSD-3-Clause
#pragma once

#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "mpsfsi/core/abi.hpp"
#include "mpsfsi/core/detail/csr_builder.hpp"
#include "mpsfsi/core/detail/format.hpp"
#include "mpsfsi/core/detail/nanoflann_compat.hpp"
#include "mpsfsi/core/error.hpp"
#include "mpsfsi/core/neighbor_list.hpp"
#include "mpsfsi/core/types.hpp"

namespace mpsfsi {
inline namespace MPSFSI_ABI {

// Fixed-radius neighbour search on a nanoflann kd-tree: the alternative to CellListSearch, with
// the same interface and the same results. It needs no grid, so it suits very uneven particle
// distributions; on the near-uniform sets of MPS the cell list is faster (see bench/).
template <int Dim, class Scalar = double>
class KdTreeSearch {
  static_assert(detail::is_supported_dim<Dim>, "mpsfsi::KdTreeSearch: Dim must be 2 or 3");

  // nanoflann's dataset adaptor over a copy of the source points.
  struct Dataset {
    VecArray<Dim, Scalar> points;
    std::size_t kdtree_get_point_count() const { return points.size(); }
    Scalar kdtree_get_pt(std::size_t i, std::size_t k) const { return points[i][static_cast<int>(k)]; }
    template <class Box>
    bool kdtree_get_bbox(Box&) const { return false; }
  };
  using Tree = nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<Scalar, Dataset>,
                                                   Dataset, Dim, Index>;

 public:
  static constexpr int dim = Dim;
  using scalar_type = Scalar;
  using vec_type = Vec<Dim, Scalar>;

  explicit KdTreeSearch(Scalar radius, std::size_t leaf_max_size = 16) : radius_(radius), leaf_(leaf_max_size) {
    if (!(radius > 0) || !std::isfinite(radius))
      detail::throw_invalid("KdTreeSearch", "search radius must be positive and finite, got " +
                                                detail::format_number(radius));
    if (leaf_max_size == 0) detail::throw_invalid("KdTreeSearch", "leaf size must be positive");
  }

  Scalar radius() const { return radius_; }
  std::size_t num_points() const { return data_->points.size(); }

  void build(const VecArray<Dim, Scalar>& points) {
    check_finite(points);
    data_->points = points;  // reuses the copy's capacity from the last build
    tree_ = std::make_unique<Tree>(Dim, *data_, detail::nanoflann_compat::tree_parameters(leaf_));
    built_ = true;
  }

  void query(const VecArray<Dim, Scalar>& queries, BasicNeighborList<Scalar>& out,
             const QueryOptions& options = {}) const {
    check_finite(queries);
    run(queries, out, options, false);
  }

  void self_query(const VecArray<Dim, Scalar>& points, BasicNeighborList<Scalar>& out,
                  const QueryOptions& options = {}) const {
    if (points.size() != num_points())
      detail::throw_invalid("KdTreeSearch::self_query",
                            "got " + std::to_string(points.size()) + " points but build() saw " +
                                std::to_string(num_points()) + "; rebuild first");
    run(points, out, options, true);
  }

 private:
  static void check_finite(const VecArray<Dim, Scalar>& points) {
    for (std::size_t i = 0; i < points.size(); ++i)
      if (!points[i].allFinite())
        detail::throw_invalid("KdTreeSearch", "position of point " + std::to_string(i) +
                                                  " is not finite (NaN or inf)");
  }

  void run(const VecArray<Dim, Scalar>& queries, BasicNeighborList<Scalar>& out,
           const QueryOptions& options, bool exclude_self) const {
    if (!built_ || num_points() == 0) {
      out.offsets.assign(queries.size() + 1, 0);
      out.indices.clear();
      out.distances.clear();
      return;
    }
    const Scalar r2 = radius_ * radius_;
    const Scalar worst = r2 * (Scalar(1) + 4 * std::numeric_limits<Scalar>::epsilon()) +
                         std::numeric_limits<Scalar>::min();
    const auto params = detail::nanoflann_compat::unsorted_search();
    detail::build_csr(queries.size(), options, scratch_, out, [&](std::size_t i, detail::CsrSink<Scalar>& sink) {
      const vec_type& x = queries[i];
      auto on_point = [&](Index j) {
        const Scalar d2 = detail::squared_distance<Dim, Scalar>(x, data_->points[static_cast<std::size_t>(j)]);
        sink.reserve(1);
        sink.put(j, d2, d2 <= r2 && !(exclude_self && static_cast<std::size_t>(j) == i));
      };
      detail::nanoflann_compat::CallbackResultSet<Scalar, Index, decltype(on_point)> result(worst, on_point);
      tree_->findNeighbors(result, x.data(), params);
    });
  }

  Scalar radius_;
  std::size_t leaf_;
  bool built_ = false;
  // Behind a pointer: the tree keeps a reference to the dataset, which must survive a move.
  std::unique_ptr<Dataset> data_ = std::make_unique<Dataset>();
  std::unique_ptr<Tree> tree_;
  mutable detail::CsrScratch<Scalar> scratch_;
};

}  // namespace MPSFSI_ABI
}  // namespace mpsfsi
