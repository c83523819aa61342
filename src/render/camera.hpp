#pragma once
// An orbit camera: it circles a target at a distance, yaw and pitch in radians.
#include <glm/glm.hpp>

namespace pba::render {

struct OrbitCamera {
    glm::vec3 target{0.0f, 1.0f, 0.0f};
    float distance = 8.0f;
    float yaw = 0.5f;    ///< about the vertical axis
    float pitch = 0.35f; ///< above the horizon
    float fovY = 0.75f;  ///< vertical field of view, radians

    glm::vec3 eye() const;
    glm::mat4 view() const;
    glm::mat4 projection(float aspect) const;
    /// Window pixel (x right, y down) where a world point lands; z < 0 or > 1 means clipped.
    glm::vec3 project(const glm::vec3& world, int width, int height) const;

    void orbit(float dYaw, float dPitch);
    void zoom(float factor);
    /// Moves the target in the view plane by a fraction of the distance.
    void pan(float dx, float dy);
    /// Frames an axis-aligned box.
    static OrbitCamera framing(const glm::vec3& lo, const glm::vec3& hi);
    /// The camera at `eye` looking at `target`. Its pitch is kept within kMaxPitch, as orbiting
    /// keeps it (straight down, the view's up is undefined): check with pitchOf first.
    static OrbitCamera lookingFrom(const glm::vec3& eye, const glm::vec3& target);
    /// The pitch a camera at `eye` looking at `target` has, radians above the horizon.
    static float pitchOf(const glm::vec3& eye, const glm::vec3& target);
    static constexpr float kMaxPitch = 1.5f;
    static constexpr float kMinDistance = 0.1f;
    static constexpr float kMaxDistance = 1000.0f;
};

/// The named views of `--camera`: the framing camera's target and distance seen from the front
/// (+z), the side (+x), the top, or a corner (+x, +z, from above).
enum class NamedView { Front, Side, Top, Corner };
OrbitCamera namedView(NamedView view, const OrbitCamera& framing);

/// The camera moved so that the picture of the box [lo, hi] keeps out of the picture's lower-left
/// corner of `corner` pixels (the legend's): it looks lower, so the box rises into the space above,
/// and draws back when that space is not enough. A corner taller than 0.4 of the picture (a
/// thumbnail's legend) leaves the camera as it is.
OrbitCamera clearOfCorner(OrbitCamera camera, const glm::vec3& lo, const glm::vec3& hi, int width, int height,
                          const glm::vec2& corner);

} // namespace pba::render
