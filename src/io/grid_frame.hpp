// What the grid writer needs of one frame: the real nodes of the grid (no
// ghosts) with plain per-node arrays, no solver types. The simulation fills
// it (src/physics/grid_frame.cpp); src/io writes it.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace sablier {

// GridFrame::regime: the case of the node's stress row after the solve
// (METHOD.md step 5, the local problem's three candidates).
enum GridRegime : std::uint8_t {
  kNoRow = 0,      // no stress row (no grains round the node)
  kSeparated = 1,  // no stress: loose sand, or grains in flight
  kSticking = 2,   // stress inside the cone: the sand there moves rigidly
  kSliding = 3,    // stress on the cone: at yield (flowing where its velocity shears)
};

struct GridFrame {
  int dimension = 2;
  double time = 0.0;                  // s
  std::array<int, 3> nodes{1, 1, 1};  // per axis: cells + 1 (1 on z in 2D)
  double spacing = 1.0;               // cell side h, m; node (i, j, k) sits at h (i, j, k)
  // Per node, x fastest then y then z (VTK's order):
  std::vector<double> phi;       // grain volume / node volume
  std::vector<double> velocity;  // interleaved, `dimension` per node, m/s; 0 where inactive
  std::vector<double> pressure;  // bulk phi Tr(lambda)/d, Pa, compression positive; 0 if inactive
  std::vector<std::uint8_t> active;  // 1 where the node has a stress row
  // How the node's stress row ended the last solve (GridRegime); 0 where
  // the node has none.
  std::vector<std::uint8_t> regime;

  std::size_t node_count() const {
    return static_cast<std::size_t>(nodes[0]) * nodes[1] * nodes[2];
  }
};

}  // namespace sablier
