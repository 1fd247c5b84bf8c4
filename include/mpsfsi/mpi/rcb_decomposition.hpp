// SPDX-License-Identifier: BSD-3-Clause
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

#include "mpsfsi/core/abi.hpp"
#include "mpsfsi/core/error.hpp"
#include "mpsfsi/core/types.hpp"
#include "mpsfsi/mpi/communicator.hpp"

namespace mpsfsi {
inline namespace MPSFSI_ABI {

// Recursive coordinate bisection (Berger & Bokhari 1987): space is cut by planes normal to the
// axes into one box per process, each holding an equal share of the particles. A box of k
// processes is cut across its longest extent (of the particles in it) so that floor(k/2)
// processes' share lies below the cut, and each side is cut again until every box has one
// process. Every process holds the whole tree (2P - 1 nodes): which process owns a point, and
// which boxes lie within a radius of it, are answered locally in O(log P). The particles
// themselves stay where they are; particle_exchange.hpp moves them.
template <int Dim>
class RcbDecomposition {
 public:
  using vec_type = Vec<Dim, double>;
  // A process's box: lower <= x < upper per axis (infinite on the outer sides).
  struct Box {
    vec_type lower = vec_type::Zero(), upper = vec_type::Zero();
    double squared_distance(const vec_type& p) const {
      double d2 = 0;
      for (int a = 0; a < Dim; ++a) {
        const double d = std::max({lower[a] - p[a], p[a] - upper[a], 0.0});
        d2 += d * d;
      }
      return d2;
    }
  };

  // Collective: cuts space for the particles positions[0 .. count) of every process. Each cut
  // is found by bisection on its coordinate with a global count per trial (one reduction of
  // every box of a level together, at most 64 per level); particles that share the coordinate
  // of a cut stay on one side, so a lattice's shares can differ by a row.
  void build(const Communicator& comm, const VecArray<Dim, double>& positions, std::size_t count) {
    nodes_.assign(1, Node{0, comm.size(), 0, 0.0, -1, -1});
    std::vector<int> node_of(count, 0);
    std::vector<int> splitting;  // the boxes to cut at this level: those of several processes
    if (comm.size() > 1) splitting.push_back(0);
    while (!splitting.empty()) {
      const std::size_t s_count = splitting.size();
      std::vector<int> slot_of_node(nodes_.size(), -1);
      for (std::size_t s = 0; s < s_count; ++s) slot_of_node[static_cast<std::size_t>(splitting[s])] = static_cast<int>(s);
      // Bounding box and particle count of each box being cut.
      std::vector<double> lower(s_count * Dim, std::numeric_limits<double>::infinity());
      std::vector<double> upper(s_count * Dim, -std::numeric_limits<double>::infinity());
      std::vector<std::int64_t> total(s_count, 0);
      for (std::size_t i = 0; i < count; ++i) {
        const int s = slot_of_node[static_cast<std::size_t>(node_of[i])];
        if (s < 0) continue;
        for (int a = 0; a < Dim; ++a) {
          lower[static_cast<std::size_t>(s) * Dim + a] = std::min(lower[static_cast<std::size_t>(s) * Dim + a], positions[i][a]);
          upper[static_cast<std::size_t>(s) * Dim + a] = std::max(upper[static_cast<std::size_t>(s) * Dim + a], positions[i][a]);
        }
        ++total[static_cast<std::size_t>(s)];
      }
      comm.min_in_place(lower);
      comm.max_in_place(upper);
      comm.sum_in_place(total);
      // Bisection on the cut: c(t) = particles of the box with x[axis] < t, and
      // c(below) <= target <= c(above) throughout.
      std::vector<double> below(s_count), above(s_count);
      std::vector<std::int64_t> target(s_count), count_below(s_count, 0), count_above(s_count);
      for (std::size_t s = 0; s < s_count; ++s) {
        Node& node = nodes_[static_cast<std::size_t>(splitting[s])];
        int axis = 0;
        for (int a = 1; a < Dim; ++a)
          if (upper[s * Dim + a] - lower[s * Dim + a] > upper[s * Dim + axis] - lower[s * Dim + axis]) axis = a;
        node.axis = axis;
        const int left_ranks = node.ranks / 2;
        target[s] = (total[s] * left_ranks + node.ranks / 2) / node.ranks;
        if (total[s] == 0) {
          below[s] = above[s] = 0;  // an empty box: any cut will do
          count_above[s] = 0;
          continue;
        }
        below[s] = lower[s * Dim + axis];
        above[s] = std::nextafter(upper[s * Dim + axis], std::numeric_limits<double>::infinity());
        count_above[s] = total[s];
      }
      std::vector<std::int64_t> trial(s_count);
      for (int iteration = 0; iteration < 64; ++iteration) {
        bool settled = true;
        for (std::size_t s = 0; s < s_count; ++s) settled = settled && (count_below[s] == target[s] || total[s] == 0);
        if (settled) break;
        std::fill(trial.begin(), trial.end(), 0);
        for (std::size_t i = 0; i < count; ++i) {
          const int s = slot_of_node[static_cast<std::size_t>(node_of[i])];
          if (s < 0) continue;
          const auto su = static_cast<std::size_t>(s);
          const int axis = nodes_[static_cast<std::size_t>(splitting[su])].axis;
          if (positions[i][axis] < 0.5 * (below[su] + above[su])) ++trial[su];
        }
        comm.sum_in_place(trial);
        for (std::size_t s = 0; s < s_count; ++s) {
          if (count_below[s] == target[s] || total[s] == 0) continue;
          const double middle = 0.5 * (below[s] + above[s]);
          if (trial[s] <= target[s]) {
            below[s] = middle;
            count_below[s] = trial[s];
          } else {
            above[s] = middle;
            count_above[s] = trial[s];
          }
        }
      }
      // The children; the particles of this process follow them down.
      std::vector<int> next;
      for (std::size_t s = 0; s < s_count; ++s) {
        const auto parent = static_cast<std::size_t>(splitting[s]);
        const bool take_below = target[s] - count_below[s] <= count_above[s] - target[s];
        nodes_[parent].cut = take_below ? below[s] : above[s];
        const Node n = nodes_[parent];
        const int left_ranks = n.ranks / 2;
        nodes_[parent].left = static_cast<int>(nodes_.size());
        nodes_.push_back(Node{n.first_rank, left_ranks, 0, 0.0, -1, -1});
        nodes_[parent].right = static_cast<int>(nodes_.size());
        nodes_.push_back(Node{n.first_rank + left_ranks, n.ranks - left_ranks, 0, 0.0, -1, -1});
        for (const int child : {nodes_[parent].left, nodes_[parent].right})
          if (nodes_[static_cast<std::size_t>(child)].ranks > 1) next.push_back(child);
      }
      for (std::size_t i = 0; i < count; ++i) {
        const Node& n = nodes_[static_cast<std::size_t>(node_of[i])];
        if (n.left < 0) continue;
        node_of[i] = positions[i][n.axis] < n.cut ? n.left : n.right;
      }
      splitting.swap(next);
    }
    make_boxes();
  }

  // Checkpoints (io/checkpoint.hpp): the tree of cuts, from which the boxes follow. A tree read
  // back must be one with a box per process of `processes`, or it throws InvalidInput.
  template <class Archive>
  void checkpoint_state(Archive& a, int processes) {
    std::vector<int> ints;  // first_rank, ranks, axis, left, right of each node
    std::vector<double> cuts;
    for (const Node& n : nodes_) {
      ints.insert(ints.end(), {n.first_rank, n.ranks, n.axis, n.left, n.right});
      cuts.push_back(n.cut);
    }
    a.array(ints);
    a.array(cuts);
    if (ints.size() != 5 * cuts.size())
      detail::throw_invalid("RcbDecomposition", "the checkpoint's decomposition is not a tree of cuts");
    nodes_.resize(cuts.size());
    for (std::size_t k = 0; k < cuts.size(); ++k)
      nodes_[k] = Node{ints[5 * k], ints[5 * k + 1], ints[5 * k + 2], cuts[k], ints[5 * k + 3], ints[5 * k + 4]};
    if (nodes_.empty() || nodes_[0].ranks != processes ||
        nodes_.size() != 2 * static_cast<std::size_t>(processes) - 1)
      detail::throw_invalid("RcbDecomposition", "the checkpoint's decomposition is for " +
                                                    std::to_string(nodes_.empty() ? 0 : nodes_[0].ranks) +
                                                    " processes, this run has " + std::to_string(processes));
    // The tree build() makes: node 0 holds every process; an inner node's two children come after
    // it, have no other parent, split its processes in order, and its cut is finite; a leaf holds
    // one process. Anything else (a crafted or mis-written file) is refused before it is used.
    std::vector<int> parents(nodes_.size(), 0);
    bool valid = nodes_[0].first_rank == 0;
    for (std::size_t k = 0; k < nodes_.size() && valid; ++k) {
      const Node& n = nodes_[k];
      const auto child = [&](int c) { return c > static_cast<int>(k) && c < static_cast<int>(nodes_.size()); };
      valid = n.first_rank >= 0 && n.ranks >= 1 && n.ranks <= processes - n.first_rank;
      if (!valid) break;
      if (n.left < 0) {
        valid = n.right < 0 && n.ranks == 1;
        continue;
      }
      valid = n.ranks >= 2 && child(n.left) && child(n.right) && n.left != n.right && n.axis >= 0 && n.axis < Dim &&
              std::isfinite(n.cut);
      if (!valid) break;
      const Node& low = nodes_[static_cast<std::size_t>(n.left)];
      const Node& high = nodes_[static_cast<std::size_t>(n.right)];
      valid = ++parents[static_cast<std::size_t>(n.left)] == 1 && ++parents[static_cast<std::size_t>(n.right)] == 1 &&
              low.first_rank == n.first_rank && low.ranks >= 1 && low.ranks < n.ranks &&
              high.first_rank == n.first_rank + low.ranks && high.ranks == n.ranks - low.ranks;
    }
    if (!valid) detail::throw_invalid("RcbDecomposition", "the checkpoint's decomposition is not a tree of cuts");
    make_boxes();
  }

  // A hash of the tree (FNV-1a over every node's numbers and cut), equal on every process that
  // holds the same tree: checkpoint pieces are compared by it.
  std::uint64_t fingerprint() const {
    std::uint64_t h = 14695981039346656037ull;
    const auto mix = [&h](std::uint64_t v) {
      for (int b = 0; b < 8; ++b) h = (h ^ ((v >> (8 * b)) & 0xFFu)) * 1099511628211ull;
    };
    for (const Node& n : nodes_) {
      for (const int v : {n.first_rank, n.ranks, n.axis, n.left, n.right}) mix(static_cast<std::uint64_t>(static_cast<std::int64_t>(v)));
      std::uint64_t cut_bits = 0;
      std::memcpy(&cut_bits, &n.cut, sizeof cut_bits);
      mix(cut_bits);
    }
    return h;
  }

  int ranks() const { return static_cast<int>(boxes_.size()); }
  const Box& box(int rank) const { return boxes_[static_cast<std::size_t>(rank)]; }

  // The process whose box holds p (not collective).
  int owner(const vec_type& p) const {
    std::size_t k = 0;
    while (nodes_[k].left >= 0) k = static_cast<std::size_t>(p[nodes_[k].axis] < nodes_[k].cut ? nodes_[k].left : nodes_[k].right);
    return nodes_[k].first_rank;
  }

  // Calls f(rank) for every process whose box lies within `radius` of p, p's own box included
  // (not collective).
  template <class F>
  void for_each_rank_within(const vec_type& p, double radius, F&& f) const {
    visit_within(0, p, radius, f);
  }

 private:
  struct Node {
    int first_rank, ranks;  // the processes of this box
    int axis;
    double cut;             // below: x[axis] < cut
    int left, right;        // children, -1 for a leaf
  };

  void make_boxes() {
    boxes_.assign(static_cast<std::size_t>(nodes_[0].ranks), Box{});
    Box all;
    all.lower.setConstant(-std::numeric_limits<double>::infinity());
    all.upper.setConstant(std::numeric_limits<double>::infinity());
    assign_boxes(0, all);
  }

  void assign_boxes(std::size_t k, const Box& b) {
    const Node& n = nodes_[k];
    if (n.left < 0) {
      boxes_[static_cast<std::size_t>(n.first_rank)] = b;
      return;
    }
    Box low = b, high = b;
    low.upper[n.axis] = n.cut;
    high.lower[n.axis] = n.cut;
    assign_boxes(static_cast<std::size_t>(n.left), low);
    assign_boxes(static_cast<std::size_t>(n.right), high);
  }

  template <class F>
  void visit_within(std::size_t k, const vec_type& p, double radius, F& f) const {
    const Node& n = nodes_[k];
    if (n.left < 0) {
      if (boxes_[static_cast<std::size_t>(n.first_rank)].squared_distance(p) <= radius * radius) f(n.first_rank);
      return;
    }
    if (p[n.axis] - radius < n.cut) visit_within(static_cast<std::size_t>(n.left), p, radius, f);
    if (p[n.axis] + radius >= n.cut) visit_within(static_cast<std::size_t>(n.right), p, radius, f);
  }

  std::vector<Node> nodes_;
  std::vector<Box> boxes_;
};

// The load imbalance max_p n_p / mean_p n_p - 1 of `local` particles per process (collective):
// the decomposition is rebuilt when it exceeds a threshold.
inline double load_imbalance(const Communicator& comm, std::size_t local) {
  const auto n = static_cast<std::int64_t>(local);
  const std::int64_t total = comm.sum(n), largest = comm.max(n);
  if (total == 0) return 0;
  return static_cast<double>(largest) * comm.size() / static_cast<double>(total) - 1;
}

}  // namespace MPSFSI_ABI
}  // namespace mpsfsi
