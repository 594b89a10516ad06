// The regular grid over the scene's box [0, size] with cubic cells of side h.
// Q1 velocity and stress nodes sit on cell corners. Node storage is dense over
// the box plus one ghost layer on each side, so a node's 3^d stencil is always
// addressable by a constant index offset; ghost nodes carry no mass.
// This is the storage interface the physics uses (node_index, cell_index,
// stencil offsets, counts); a sparse block grid can implement the same.
#pragma once

#include <array>
#include <cstdint>

#include "core/tensor.hpp"

namespace sablier {

template <int D>
class DenseGrid {
 public:
  using IVec = std::array<int, D>;

  DenseGrid() = default;
  DenseGrid(const IVec& cells, double h) : cells_(cells), h_(h) {
    node_count_ = 1;
    cell_count_ = 1;
    for (int a = 0; a < D; ++a) {
      node_stride_[a] = static_cast<std::int64_t>(node_count_);
      node_count_ *= cells[a] + 3;  // nodes -1 .. cells[a] + 1
      cell_stride_[a] = static_cast<std::int64_t>(cell_count_);
      cell_count_ *= cells[a];
    }
  }

  double h() const { return h_; }
  const IVec& cells() const { return cells_; }
  std::int64_t node_count() const { return node_count_; }  // including ghosts
  std::int64_t cell_count() const { return cell_count_; }

  // Node (i_0, ..., i_{d-1}), each coordinate in [-1, cells + 1].
  std::int64_t node_index(const IVec& n) const {
    std::int64_t idx = 0;
    for (int a = 0; a < D; ++a) idx += (n[a] + 1) * node_stride_[a];
    return idx;
  }
  IVec node_coords(std::int64_t idx) const {
    IVec n;
    for (int a = D - 1; a >= 0; --a) {
      n[a] = static_cast<int>(idx / node_stride_[a]) - 1;
      idx %= node_stride_[a];
    }
    return n;
  }
  std::int64_t node_stride(int a) const { return node_stride_[a]; }

  std::int64_t cell_index(const IVec& c) const {
    std::int64_t idx = 0;
    for (int a = 0; a < D; ++a) idx += c[a] * cell_stride_[a];
    return idx;
  }
  IVec cell_coords(std::int64_t idx) const {
    IVec c;
    for (int a = D - 1; a >= 0; --a) {
      c[a] = static_cast<int>(idx / cell_stride_[a]);
      idx %= cell_stride_[a];
    }
    return c;
  }
  // Node index of a cell's lowest corner.
  std::int64_t cell_base_node(const IVec& c) const { return node_index(c); }

  // Cell containing position x (clamped into the box).
  IVec cell_of(const Vec<D>& x) const {
    IVec c;
    for (int a = 0; a < D; ++a) {
      int k = static_cast<int>(std::floor(x[a] / h_));
      c[a] = k < 0 ? 0 : (k >= cells_[a] ? cells_[a] - 1 : k);
    }
    return c;
  }

  // True when n is a real (non-ghost) node.
  bool is_real_node(const IVec& n) const {
    for (int a = 0; a < D; ++a)
      if (n[a] < 0 || n[a] > cells_[a]) return false;
    return true;
  }

  // Integral of the Q1 shape function of a real node over the box: h^d,
  // halved for each axis on which the node lies on the box boundary.
  double node_volume(const IVec& n) const {
    double v = 1.0;
    for (int a = 0; a < D; ++a) v *= (n[a] == 0 || n[a] == cells_[a]) ? 0.5 * h_ : h_;
    return v;
  }

  // Index offsets of the N^d block of nodes starting `first` nodes from a
  // node along each axis: offset k <-> relative coordinates
  // (k % N + first, (k / N) % N + first, ...).
  template <int N>
  std::array<std::int64_t, ipow(N, D)> block_offsets(int first) const {
    std::array<std::int64_t, ipow(N, D)> off{};
    for (int k = 0; k < ipow(N, D); ++k) {
      int r = k;
      std::int64_t o = 0;
      for (int a = 0; a < D; ++a) {
        o += (r % N + first) * node_stride_[a];
        r /= N;
      }
      off[k] = o;
    }
    return off;
  }
  // Index offsets of the 3^d stencil around a node (offset k <-> the
  // neighbour at relative coordinates (k % 3 - 1, (k / 3) % 3 - 1, ...)).
  std::array<std::int64_t, ipow(3, D)> stencil_offsets() const { return block_offsets<3>(-1); }
  // Offsets of a cell's 2^d corner nodes from its base node (corner c <->
  // bits of c select +1 on each axis).
  std::array<std::int64_t, ipow(2, D)> corner_offsets() const { return block_offsets<2>(0); }

 private:
  IVec cells_{};
  double h_ = 1.0;
  std::array<std::int64_t, D> node_stride_{};
  std::array<std::int64_t, D> cell_stride_{};
  std::int64_t node_count_ = 0;
  std::int64_t cell_count_ = 0;
};

// Stencil slot (in the 3^d stencil of node j) of node j + corner_b - corner_a,
// for corners a (the stress node's) and b (the velocity node's) of one cell.
template <int D>
constexpr int corner_pair_slot(int a, int b) {
  int slot = 0, mul = 1;
  for (int ax = 0; ax < D; ++ax) {
    slot += (((b >> ax) & 1) - ((a >> ax) & 1) + 1) * mul;
    mul *= 3;
  }
  return slot;
}

}  // namespace sablier
