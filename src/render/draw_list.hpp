#pragma once
// What one frame shows, as plain data: shaded sprites, coloured lines, translucent triangles
// and an optional checkered floor. Scene drawing fills it from the World; the Renderer turns
// it into GL calls. Keeping the two apart lets tests and later features (the blow dryer's
// cone, swarms) add shapes without touching OpenGL.
#include <optional>
#include <vector>

#include <glm/glm.hpp>

namespace pba::render {

struct Sprite {
    glm::vec3 position;
    float radius; ///< world units
    glm::vec4 colour;
};

struct ColouredVertex {
    glm::vec3 position;
    glm::vec4 colour;
};

/// A vertex of a lit surface (a cloth, a rigid body's faces), shaded from its normal on both
/// sides. A rigid body's also carries the direction it faces in the body's own frame: its shade
/// is chosen from that per pixel (a ball's six patches have round borders, not a triangle's
/// steps), and a die's pips are drawn from where on the die it is.
struct LitVertex {
    glm::vec3 position;
    glm::vec3 normal;                ///< in the world
    glm::vec4 colour;
    glm::vec3 bodyNormal{0.0f};      ///< in the body's frame; zero for no shade (a cloth)
    glm::vec3 onDie{0.0f};           ///< a die's point in its frame over its half side (faces at +-1)
    float die = 0.0f;                ///< 1 on a die: pips
};

/// A checkered rectangle in the plane y = height, with an optional round hole.
struct Floor {
    glm::vec2 min{-1.0f}; ///< x, z
    glm::vec2 max{1.0f};
    float height = 0.0f;
    float cell = 0.5f;
    glm::vec2 holeCentre{0.0f};
    float holeRadius = 0.0f;
};

struct DrawList {
    std::vector<Sprite> sprites;
    std::vector<ColouredVertex> lines;     ///< pairs of vertices
    std::vector<ColouredVertex> triangles; ///< triples, drawn blended after everything opaque
    std::vector<LitVertex> surfaces;       ///< triples, opaque and lit, both sides
    std::optional<Floor> floor;
    /// Marks drawn last, over everything, with no depth test: contact points, joint frames and
    /// body axes, which lie inside or under the bodies they describe.
    std::vector<ColouredVertex> overlayLines;
    std::vector<Sprite> overlaySprites;

    void clear();
    void addLine(const glm::vec3& a, const glm::vec3& b, const glm::vec4& colour);
    void addBoxEdges(const glm::vec3& lo, const glm::vec3& hi, const glm::vec4& colour);
    void addTriangle(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c, const glm::vec4& colour);
    void addArrow(const glm::vec3& from, const glm::vec3& to, const glm::vec4& colour);
    void addOverlayLine(const glm::vec3& a, const glm::vec3& b, const glm::vec4& colour);
    void addOverlayArrow(const glm::vec3& from, const glm::vec3& to, const glm::vec4& colour);
    /// n sprites from a packed float array x0 y0 z0 x1 y1 z1 ... (swarms).
    void addPoints(const float* xyz, std::size_t n, float radius, const glm::vec4& colour);
    /// n sprites from structure-of-arrays coordinates (swarms).
    void addPoints(const float* x, const float* y, const float* z, std::size_t n, float radius, const glm::vec4& colour);
};

} // namespace pba::render
