// What the scene parser needs of the seeding (seeding.cpp): how many
// particles each [[sand]] block seeds, so that a block seeding none is an
// error of the scene rather than a silent no-op.
#pragma once

#include <cstddef>
#include <vector>

#include "scene/scene.hpp"

namespace sablier {

// Particles seeded per [[sand]] block, in block order (overlaps counted for
// the first block only, as seeded).
std::vector<std::size_t> seeded_per_region(const SceneConfig& scene);

}  // namespace sablier
