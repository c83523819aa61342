#pragma once
// Which particles of a World form a rope or a cloth. The World holds them as ordinary
// particles joined by two-body springs and needs nothing more; this record is what a scene
// keeps beside it so that a reader of the state (the renderer) can draw a rope as a line
// and a cloth as a surface. Plain indices: no physics and no drawing here.
#include <cstddef>
#include <string>
#include <vector>

namespace pba {

/// A rope: its particles in order from one end to the other.
struct RopeLayout {
    std::string name;
    std::vector<std::size_t> particles;
};

/// A cloth: a width x height grid of consecutive particles, row by row: grid index (i, j),
/// with i < width along a row and j < height, is particle first + j * width + i.
struct ClothLayout {
    std::string name;
    std::size_t first = 0;
    std::size_t width = 0;
    std::size_t height = 0;
    std::size_t at(std::size_t i, std::size_t j) const { return first + j * width + i; }
};

/// The ropes and cloths of a scene.
struct FabricLayout {
    std::vector<RopeLayout> ropes;
    std::vector<ClothLayout> cloths;
    bool empty() const { return ropes.empty() && cloths.empty(); }
};

} // namespace pba
