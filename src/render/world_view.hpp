#pragma once
// The World as a picture: the room or ground, each body at its interpolated state in a colour
// of its own (body_groups.hpp), a particle's fading trail and a line at its start height, ropes
// and cloths, rigid bodies and their joints (rigid_view.hpp), and the blow dryer's cone and field
// arrows. Reads the world; never writes it.
#include <deque>
#include <functional>
#include <optional>
#include <vector>

#include "body_groups.hpp"
#include "camera.hpp"
#include "draw_list.hpp"
#include "pba/fabric.hpp"
#include "pba/world.hpp"

namespace pba::render {

struct ViewSettings {
    bool interpolate = true;      ///< blend previous and current state with the clock's alpha
    bool trails = true;
    bool referenceLines = true;   ///< a horizontal line at each particle's start height
    bool cone = true;             ///< the blow dryer's region, translucent
    bool fieldArrows = false;     ///< arrows on a grid inside the cone, scaled by magnitude
    float particleRadius = 0.08f; ///< drawn radius, m (particles are points)
    bool contacts = false;        ///< each contact point of the last step and its normal, on top
    bool joints = false;          ///< each joint's frame: a dot at its point on each body, a hinge's axis
    bool axes = false;            ///< each rigid body's axes, with its omega and L arrows
    /// Integrator lanes: where the exact solution puts body i at time t, drawn as a translucent
    /// ghost beside the body (nothing where there is no exact solution). Set by the program,
    /// which knows the oracles; the renderer only draws.
    std::function<std::optional<glm::vec3>(std::size_t, double)> ghost;
    /// Which particles form ropes (drawn as a line of beads) and cloths (a lit surface) rather
    /// than balls with trails: the scene's layout, set by the program that loaded it.
    FabricLayout fabric;
    /// The rigid bodies drawn as dice, pips on their faces (the scene's `"die": true`), ascending.
    std::vector<std::size_t> dice;
};

/// Recent drawn positions of each body, for fading trails.
class Trails {
public:
    explicit Trails(std::size_t length = 90) : m_length(length) {}
    /// Each body's drawn centre (drawnCentre), so a trail runs through the balls as drawn.
    void record(const World& world, double alpha, const ViewSettings& settings);
    void clear() { m_points.clear(); }
    const std::vector<std::deque<glm::vec3>>& points() const { return m_points; }

private:
    std::size_t m_length;
    std::vector<std::deque<glm::vec3>> m_points;
};

/// A body of this mass is drawn at ViewSettings::particleRadius; others scale with the cube root
/// of their mass (one density), so the blow dryer's light and heavy balls can be told apart.
inline constexpr double kDrawnReferenceMass = 1.0;
float drawnRadius(const Body& body, const ViewSettings& settings);

/// The time of the state drawn: between the last two steps with the clock's alpha.
double drawnTime(const World& world, double alpha, bool interpolate);

/// The position of body i in the state drawn (the particle's point).
glm::vec3 drawnPosition(const World& world, std::size_t i, double alpha, bool interpolate);

/// Where a ball of `radius` around a particle at `point` is drawn: pushed out of each surface
/// (the world's planes) that the point lies within `radius` of, so that at impact and at rest,
/// when the particle is a point on the floor, its ball rests on the floor instead of sinking
/// half into it. Away from surfaces, and over the floor's hole, it is the point itself.
glm::vec3 restingCentre(const World& world, glm::vec3 point, float radius);

/// The centre of body i's drawn ball: its drawn position resting on the surfaces it touches.
glm::vec3 drawnCentre(const World& world, std::size_t i, double alpha, const ViewSettings& settings);

/// Whether each body belongs to a rope or cloth (drawn as such, not as a ball with a trail).
std::vector<bool> fabricMembers(const World& world, const FabricLayout& fabric);

/// Fills `out` with the world. `initial` (the scene at t = 0) gives the start heights.
void buildDrawList(const World& world, const World& initial, double alpha, const ViewSettings& settings,
                   const Trails* trails, DrawList& out);

/// What a picture frames: the room, or the bodies above the ground with room around them.
struct FramedBox {
    glm::vec3 lo, hi;
};
FramedBox framedBox(const World& world);

/// A camera that frames the room, or the ground and the particles.
OrbitCamera frameWorld(const World& world);

} // namespace pba::render
