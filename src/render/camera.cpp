#include "camera.hpp"

#include <algorithm>
#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

namespace pba::render {

glm::vec3 OrbitCamera::eye() const
{
    const glm::vec3 offset(std::cos(pitch) * std::sin(yaw), std::sin(pitch), std::cos(pitch) * std::cos(yaw));
    return target + distance * offset;
}

glm::mat4 OrbitCamera::view() const { return glm::lookAt(eye(), target, glm::vec3(0, 1, 0)); }

glm::mat4 OrbitCamera::projection(float aspect) const
{
    return glm::perspective(fovY, aspect, 0.02f * distance, 50.0f * distance);
}

glm::vec3 OrbitCamera::project(const glm::vec3& world, int width, int height) const
{
    const glm::vec4 clip = projection(float(width) / float(height)) * view() * glm::vec4(world, 1.0f);
    const glm::vec3 ndc = glm::vec3(clip) / clip.w;
    return {(ndc.x * 0.5f + 0.5f) * float(width), (0.5f - ndc.y * 0.5f) * float(height), ndc.z * 0.5f + 0.5f};
}

void OrbitCamera::orbit(float dYaw, float dPitch)
{
    yaw += dYaw;
    pitch = std::clamp(pitch + dPitch, -kMaxPitch, kMaxPitch);
}

void OrbitCamera::zoom(float factor) { distance = std::clamp(distance * factor, kMinDistance, kMaxDistance); }

void OrbitCamera::pan(float dx, float dy)
{
    const glm::vec3 forward = glm::normalize(target - eye());
    const glm::vec3 right = glm::normalize(glm::cross(forward, glm::vec3(0, 1, 0)));
    const glm::vec3 up = glm::cross(right, forward);
    target += (right * dx + up * dy) * distance;
}

OrbitCamera OrbitCamera::framing(const glm::vec3& lo, const glm::vec3& hi)
{
    OrbitCamera camera;
    camera.target = 0.5f * (lo + hi);
    const float radius = 0.5f * glm::length(hi - lo);
    camera.distance = std::max(radius / std::sin(0.5f * camera.fovY), 1.0f) * 1.05f;
    return camera;
}

float OrbitCamera::pitchOf(const glm::vec3& eye, const glm::vec3& target)
{
    const glm::vec3 offset = eye - target;
    const float length = glm::length(offset);
    return length > 0.0f ? std::asin(std::clamp(offset.y / length, -1.0f, 1.0f)) : 0.0f;
}

OrbitCamera OrbitCamera::lookingFrom(const glm::vec3& eye, const glm::vec3& target)
{
    // eye() is target + distance (cos p sin y, sin p, cos p cos y): read p and y back.
    const glm::vec3 offset = eye - target;
    OrbitCamera camera;
    camera.target = target;
    camera.distance = std::clamp(glm::length(offset), kMinDistance, kMaxDistance);
    camera.pitch = std::clamp(pitchOf(eye, target), -kMaxPitch, kMaxPitch);
    camera.yaw = std::atan2(offset.x, offset.z);
    return camera;
}

OrbitCamera namedView(NamedView view, const OrbitCamera& framing)
{
    OrbitCamera camera = framing;
    switch (view) {
    case NamedView::Front: camera.yaw = 0.0f, camera.pitch = 0.12f; break;
    case NamedView::Side: camera.yaw = 1.5707963f, camera.pitch = 0.12f; break;
    case NamedView::Top: camera.yaw = 0.0f, camera.pitch = OrbitCamera::kMaxPitch; break;
    case NamedView::Corner: camera.yaw = 0.7853982f, camera.pitch = 0.6f; break;
    }
    return camera;
}

namespace {

/// How far (pixels) the picture of the box reaches down into the corner [0, cx] x [height - cy, height],
/// and how far its top stays below the picture's top edge. The box's picture is the convex hull of its
/// corners', so the lowest point of it left of x = cx is a corner there or a crossing of that line by
/// a segment between two corners.
struct Reach {
    float into = 0.0f, above = 0.0f;
};

Reach reachInto(const OrbitCamera& camera, const glm::vec3& lo, const glm::vec3& hi, int width, int height,
                const glm::vec2& corner)
{
    glm::vec2 p[8];
    float top = float(height), lowest = -1e30f;
    for (int k = 0; k < 8; ++k) {
        const glm::vec3 c((k & 1) ? hi.x : lo.x, (k & 2) ? hi.y : lo.y, (k & 4) ? hi.z : lo.z);
        p[k] = glm::vec2(camera.project(c, width, height));
        top = std::min(top, p[k].y);
        if (p[k].x <= corner.x)
            lowest = std::max(lowest, p[k].y);
    }
    for (int a = 0; a < 8; ++a)
        for (int b = a + 1; b < 8; ++b)
            if ((p[a].x - corner.x) * (p[b].x - corner.x) < 0.0f) {
                const float s = (corner.x - p[a].x) / (p[b].x - p[a].x);
                lowest = std::max(lowest, p[a].y + s * (p[b].y - p[a].y));
            }
    return {lowest - (float(height) - corner.y), top};
}

} // namespace

OrbitCamera clearOfCorner(OrbitCamera camera, const glm::vec3& lo, const glm::vec3& hi, int width, int height,
                          const glm::vec2& corner)
{
    // A picture too small for the legend and the room both (a thumbnail) keeps its framing.
    if (corner.y > 0.4f * float(height))
        return camera;
    const float gap = 6.0f; // pixels left between the box's picture and the corner's edge
    // A few rounds: a pixel at the box's near floor moves further than one at the target's depth.
    for (int round = 0; round < 12; ++round) {
        const Reach reach = reachInto(camera, lo, hi, width, height, corner);
        const float into = reach.into + gap;
        if (into <= 0.0f)
            break;
        // Up into the space above the box, a pixel being the target's world height over its depth
        // (look lower by that much); what that space lacks, by drawing back.
        const float up = std::clamp(reach.above - gap, 0.0f, into);
        camera.pan(0.0f, -up * 2.0f * std::tan(0.5f * camera.fovY) / float(height));
        if (up < into)
            camera.zoom(1.0f + (into - up) / float(height));
    }
    return camera;
}

} // namespace pba::render
