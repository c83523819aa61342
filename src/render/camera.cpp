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
    pitch = std::clamp(pitch + dPitch, -1.5f, 1.5f);
}

void OrbitCamera::zoom(float factor) { distance = std::clamp(distance * factor, 0.1f, 1000.0f); }

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

} // namespace pba::render
