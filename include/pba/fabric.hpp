#pragma once
// Which particles of a World form a rope or a cloth. The World holds them as ordinary
// particles joined by two-body springs and needs nothing more; this record is what a scene
// keeps beside it so that a reader of the state (the renderer) can draw a rope as a line
// and a cloth as a surface. Plain indices: no physics and no drawing here.
#include <cstddef>
#include <string>
#include <utility>
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
    /// The edges they are drawn with, as pairs of particles: a rope's links; a cloth's rows,
    /// columns and each cell's diagonal from its first corner to its last.
    std::vector<std::pair<std::size_t, std::size_t>> edges() const
    {
        std::vector<std::pair<std::size_t, std::size_t>> out;
        for (const RopeLayout& rope : ropes)
            for (std::size_t k = 0; k + 1 < rope.particles.size(); ++k)
                out.emplace_back(rope.particles[k], rope.particles[k + 1]);
        for (const ClothLayout& c : cloths)
            for (std::size_t j = 0; j < c.height; ++j)
                for (std::size_t i = 0; i < c.width; ++i) {
                    if (i + 1 < c.width)
                        out.emplace_back(c.at(i, j), c.at(i + 1, j));
                    if (j + 1 < c.height)
                        out.emplace_back(c.at(i, j), c.at(i, j + 1));
                    if (i + 1 < c.width && j + 1 < c.height)
                        out.emplace_back(c.at(i, j), c.at(i + 1, j + 1));
                }
        return out;
    }
};

} // namespace pba
