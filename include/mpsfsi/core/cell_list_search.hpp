// SPDX-License-Identifier: BSD-3-Clause
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "mpsfsi/core/abi.hpp"
#include "mpsfsi/core/detail/candidate_run.hpp"
#include "mpsfsi/core/detail/csr_builder.hpp"
#include "mpsfsi/core/detail/format.hpp"
#include "mpsfsi/core/error.hpp"
#include "mpsfsi/core/neighbor_list.hpp"
#include "mpsfsi/core/parallel.hpp"
#include "mpsfsi/core/types.hpp"

namespace mpsfsi {
inline namespace MPSFSI_ABI {

// Fixed-radius neighbour search on a uniform grid of cells no smaller than the radius (the
// default search). build() bins the source points by a counting sort and keeps a copy of them
// in cell order, so a query streams through memory; query() lists, for every query point, the
// source points within the radius (|r_j - r_i| <= radius, pairs at exactly the radius included).
//
// The grid covers the bounding box of the source points. A point far outside the others only
// makes the cells larger (the cell count is capped near the point count), so results stay exact
// and only speed degrades. One query at a time per object: the scratch buffers are members.
template <int Dim, class Scalar = double>
class CellListSearch {
  static_assert(detail::is_supported_dim<Dim>, "mpsfsi::CellListSearch: Dim must be 2 or 3");

 public:
  static constexpr int dim = Dim;
  using scalar_type = Scalar;
  using vec_type = Vec<Dim, Scalar>;

  explicit CellListSearch(Scalar radius) : radius_(radius) {
    if (!(radius > 0) || !std::isfinite(radius))
      detail::throw_invalid("CellListSearch", "search radius must be positive and finite, got " +
                                                  detail::format_number(radius));
  }

  Scalar radius() const { return radius_; }
  std::size_t num_points() const { return order_.size(); }

  // Bins the source points. Throws InvalidInput on a non-finite position (naming the index).
  void build(const VecArray<Dim, Scalar>& points) {
    const std::size_t n = points.size();
    if (n > static_cast<std::size_t>(std::numeric_limits<Index>::max()))
      detail::throw_invalid("CellListSearch", "more than 2^31 - 1 points");
    check_finite(points);
    for (auto& coordinate : sorted_) coordinate.resize(n);
    order_.resize(n);
    cell_of_.resize(n);
    if (n == 0) {
      cell_start_.assign(2, 0);
      dims_.fill(1);
      return;
    }
    choose_grid(points);
    bin_points(points);
  }

  // Neighbours among the source points of each query point (another particle set, e.g. fluid
  // looking at solid). A query point is not excluded even if it coincides with a source point.
  void query(const VecArray<Dim, Scalar>& queries, BasicNeighborList<Scalar>& out,
             const QueryOptions& options = {}) const {
    check_finite(queries);
    run(queries, out, options, false);
  }

  // Neighbours of each source point among the source points, itself excluded. `points` must be
  // the array given to build(), unchanged.
  void self_query(const VecArray<Dim, Scalar>& points, BasicNeighborList<Scalar>& out,
                  const QueryOptions& options = {}) const {
    if (points.size() != num_points())
      detail::throw_invalid("CellListSearch::self_query",
                            "got " + std::to_string(points.size()) + " points but build() saw " +
                                std::to_string(num_points()) + "; rebuild first");
    run(points, out, options, true);
  }

  // Source indices in cell order: permuting a particle set by it (ParticleSet::permute) puts
  // neighbours close together in memory. Valid after build().
  const std::vector<Index>& cell_order() const { return order_; }

  Scalar cell_size() const { return cell_size_; }
  std::int64_t num_cells() const {
    std::int64_t c = 1;
    for (int k = 0; k < Dim; ++k) c *= dims_[k];
    return c;
  }

 private:
  static void check_finite(const VecArray<Dim, Scalar>& points) {
    bool ok = true;
    MPSFSI_OMP(parallel for reduction(&& : ok))
    for (std::int64_t i = 0; i < static_cast<std::int64_t>(points.size()); ++i)
      ok = ok && points[static_cast<std::size_t>(i)].allFinite();
    if (ok) return;
    for (std::size_t i = 0; i < points.size(); ++i)
      if (!points[i].allFinite())
        detail::throw_invalid("CellListSearch", "position of point " + std::to_string(i) +
                                                    " is not finite (NaN or inf)");
  }

  // Cell of every point, then a stable parallel counting sort: thread t counts its block of
  // points per cell, an exclusive scan in (cell, thread) order gives each thread its slots, and
  // each thread scatters its block. The order equals that of a serial stable sort.
  void bin_points(const VecArray<Dim, Scalar>& points) {
    const std::size_t n = points.size();
    const Scalar inv_h = Scalar(1) / cell_size_;
    const std::int64_t cells = num_cells();
    const int threads = parallel::max_threads();
    histogram_.assign(static_cast<std::size_t>(threads) * static_cast<std::size_t>(cells), 0);
    cell_start_.resize(static_cast<std::size_t>(cells) + 1);
    int team = 1;
    MPSFSI_OMP(parallel num_threads(threads)) {
      const int t = parallel::thread_id();
      const int nt = parallel::team_size();
      MPSFSI_OMP(single) team = nt;
      const std::size_t lo = detail::block_begin(n, t, nt), hi = detail::block_begin(n, t + 1, nt);
      Index* count = histogram_.data() + static_cast<std::size_t>(t) * static_cast<std::size_t>(cells);
      for (std::size_t i = lo; i < hi; ++i) {
        std::int64_t lin = 0;
        for (int k = Dim - 1; k >= 0; --k) {
          auto c = static_cast<std::int64_t>(std::floor((points[i][k] - lower_[k]) * inv_h));
          c = std::clamp<std::int64_t>(c, 0, dims_[k] - 1);
          lin = lin * dims_[k] + c;
        }
        cell_of_[i] = lin;
        ++count[lin];
      }
      MPSFSI_OMP(barrier)
      MPSFSI_OMP(single) {
        Index run = 0;
        for (std::int64_t c = 0; c < cells; ++c) {
          cell_start_[static_cast<std::size_t>(c)] = run;
          for (int tt = 0; tt < team; ++tt) {
            Index& slot = histogram_[static_cast<std::size_t>(tt) * static_cast<std::size_t>(cells) + static_cast<std::size_t>(c)];
            const Index cnt = slot;
            slot = run;
            run += cnt;
          }
        }
        cell_start_[static_cast<std::size_t>(cells)] = run;
      }
      for (std::size_t i = lo; i < hi; ++i) {
        const Index k = count[cell_of_[i]]++;
        order_[static_cast<std::size_t>(k)] = static_cast<Index>(i);
      }
      MPSFSI_OMP(barrier)
      const std::size_t klo = detail::block_begin(n, t, nt), khi = detail::block_begin(n, t + 1, nt);
      for (std::size_t k = klo; k < khi; ++k) {
        const auto& p = points[static_cast<std::size_t>(order_[k])];
        for (int d = 0; d < Dim; ++d) sorted_[static_cast<std::size_t>(d)][k] = p[d];
      }
    }
  }

  void choose_grid(const VecArray<Dim, Scalar>& points) {
    vec_type lo = points[0], hi = points[0];
    for (const auto& p : points) {
      lo = lo.cwiseMin(p);
      hi = hi.cwiseMax(p);
    }
    const vec_type extent = hi - lo;
    if (!extent.allFinite())
      detail::throw_invalid("CellListSearch", "the points span more than a double can hold");
    // A margin over the radius keeps a pair at exactly the radius in adjacent cells despite the
    // rounding of (x - lower) / h.
    Scalar h = radius_ * Scalar(1 + 1e-6);
    const double cap = 2.0 * static_cast<double>(points.size()) + 64.0;
    auto cells_for = [&](Scalar hh) {
      double c = 1;
      for (int k = 0; k < Dim; ++k) c *= std::floor(static_cast<double>(extent[k] / hh)) + 1;
      return c;
    };
    while (cells_for(h) > cap) h *= Scalar(1.5);
    cell_size_ = h;
    lower_ = lo;
    for (int k = 0; k < Dim; ++k) dims_[k] = static_cast<std::int64_t>(std::floor(extent[k] / h)) + 1;
  }

  void run(const VecArray<Dim, Scalar>& queries, BasicNeighborList<Scalar>& out,
           const QueryOptions& options, bool exclude_self) const {
    const Scalar r2 = radius_ * radius_;
    const Scalar inv_h = Scalar(1) / cell_size_;
    if (num_points() == 0) {
      out.offsets.assign(queries.size() + 1, 0);
      out.indices.clear();
      out.distances.clear();
      return;
    }
    const Index none = -1;
    detail::build_csr(queries.size(), options, scratch_, out, [&](std::size_t i, detail::CsrSink<Scalar>& sink) {
      const vec_type& x = queries[i];
      std::array<std::int64_t, 3> c0{0, 0, 0}, c1{0, 0, 0};
      for (int k = 0; k < Dim; ++k) {
        const Scalar u = std::floor((x[k] - lower_[k]) * inv_h);
        // Cells more than one away from the grid hold nothing within the radius.
        if (u < Scalar(-1) || u > static_cast<Scalar>(dims_[k])) return;
        const auto c = static_cast<std::int64_t>(u);
        c0[k] = std::max<std::int64_t>(c - 1, 0);
        c1[k] = std::min<std::int64_t>(c + 1, dims_[k] - 1);
      }
      const Index self = exclude_self ? static_cast<Index>(i) : none;
      const Scalar* const coordinates[3] = {sorted_[0].data(), sorted_[1].data(), sorted_[Dim - 1].data()};
      // Rows along x are contiguous in the cell order: one run of sorted points per (y, z).
      const std::int64_t zlo = (Dim == 3) ? c0[2] : 0, zhi = (Dim == 3) ? c1[2] : 0;
      for (std::int64_t cz = zlo; cz <= zhi; ++cz) {
        for (std::int64_t cy = c0[1]; cy <= c1[1]; ++cy) {
          const std::int64_t row = (Dim == 3 ? cz * dims_[1] + cy : cy) * dims_[0];
          const Index kb = cell_start_[static_cast<std::size_t>(row + c0[0])];
          const Index ke = cell_start_[static_cast<std::size_t>(row + c1[0] + 1)];
          sink.reserve(static_cast<std::size_t>(ke - kb) + detail::candidate_run_slack);
          detail::append_within<Dim, Scalar>(coordinates, order_.data(), kb, ke, x, r2, self, sink);
        }
      }
    });
  }

  Scalar radius_;
  Scalar cell_size_ = 0;
  vec_type lower_ = vec_type::Zero();
  std::array<std::int64_t, Dim> dims_{};
  std::vector<Index> cell_start_;
  std::vector<Index> histogram_;
  std::vector<std::int64_t> cell_of_;
  std::vector<Index> order_;
  // Source coordinates in cell order, one array per axis, so the distance loop streams.
  std::array<std::vector<Scalar>, Dim> sorted_;
  mutable detail::CsrScratch<Scalar> scratch_;
};

}  // namespace MPSFSI_ABI
}  // namespace mpsfsi
