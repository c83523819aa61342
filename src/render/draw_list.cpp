#include "draw_list.hpp"

namespace pba::render {

void DrawList::clear()
{
    sprites.clear();
    lines.clear();
    triangles.clear();
    surfaces.clear();
    floor.reset();
    overlayLines.clear();
    overlaySprites.clear();
}

void DrawList::addLine(const glm::vec3& a, const glm::vec3& b, const glm::vec4& colour)
{
    lines.push_back({a, colour});
    lines.push_back({b, colour});
}

void DrawList::addBoxEdges(const glm::vec3& lo, const glm::vec3& hi, const glm::vec4& colour)
{
    auto corner = [&](int i) { return glm::vec3(i & 1 ? hi.x : lo.x, i & 2 ? hi.y : lo.y, i & 4 ? hi.z : lo.z); };
    for (int i = 0; i < 8; ++i)
        for (int bit : {1, 2, 4})
            if (!(i & bit))
                addLine(corner(i), corner(i | bit), colour);
}

void DrawList::addTriangle(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c, const glm::vec4& colour)
{
    triangles.push_back({a, colour});
    triangles.push_back({b, colour});
    triangles.push_back({c, colour});
}

namespace {

/// An arrow's shaft and two barbs, in the plane of the arrow and the horizontal, a quarter of
/// its length.
void arrowInto(std::vector<ColouredVertex>& lines, const glm::vec3& from, const glm::vec3& to, const glm::vec4& colour)
{
    const glm::vec3 d = to - from;
    const float length = glm::length(d);
    if (length <= 0.0f)
        return;
    glm::vec3 side = glm::cross(d, glm::vec3(0, 0, 1));
    if (glm::length(side) < 1e-6f * length)
        side = glm::cross(d, glm::vec3(1, 0, 0));
    side = glm::normalize(side) * (0.12f * length);
    const glm::vec3 back = to - 0.25f * d;
    for (const glm::vec3& end : {from, back + side, back - side}) {
        lines.push_back({to, colour});
        lines.push_back({end, colour});
    }
}

} // namespace

void DrawList::addArrow(const glm::vec3& from, const glm::vec3& to, const glm::vec4& colour)
{
    arrowInto(lines, from, to, colour);
}

void DrawList::addOverlayLine(const glm::vec3& a, const glm::vec3& b, const glm::vec4& colour)
{
    overlayLines.push_back({a, colour});
    overlayLines.push_back({b, colour});
}

void DrawList::addOverlayArrow(const glm::vec3& from, const glm::vec3& to, const glm::vec4& colour)
{
    arrowInto(overlayLines, from, to, colour);
}

void DrawList::addPoints(const float* xyz, std::size_t n, float radius, const glm::vec4& colour)
{
    sprites.reserve(sprites.size() + n);
    for (std::size_t i = 0; i < n; ++i)
        sprites.push_back({glm::vec3(xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2]), radius, colour});
}

} // namespace pba::render

namespace pba::render {

void DrawList::addPoints(const float* x, const float* y, const float* z, std::size_t n, float radius,
                         const glm::vec4& colour)
{
    sprites.reserve(sprites.size() + n);
    for (std::size_t i = 0; i < n; ++i)
        sprites.push_back({glm::vec3(x[i], y[i], z[i]), radius, colour});
}

} // namespace pba::render
