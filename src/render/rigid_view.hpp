#pragma once
// Rigid bodies as pictures: each body's mesh at its drawn pose, its faces told apart (shaded by
// the renderer, see LitVertex), a die's with pips; the rods
// and strings of its joints; and, on request, what the contact pipeline and the joints work with
// (contact points and normals, joint frames) and each body's axes with its omega and L arrows.
// Reads the world; never writes it.
#include <cstddef>

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

#include "body_groups.hpp"
#include "draw_list.hpp"
#include "pba/world.hpp"

namespace pba::render {

struct ViewSettings;

/// Where body i is drawn: its position and orientation blended between the last two steps.
struct DrawnPose {
    glm::vec3 at{0.0f};
    glm::quat turn{1.0f, 0.0f, 0.0f, 0.0f};
    glm::vec3 apply(const glm::vec3& local) const { return at + turn * local; }
};
DrawnPose drawnPose(const World& world, std::size_t i, double alpha, bool interpolate);

/// A point that moves with body i, given where it is now: where it is in the drawn pose.
glm::vec3 followBody(const World& world, std::size_t i, double alpha, bool interpolate, const dvec3& now);

/// The lengths of body i's arrows, in metres: omega's grows linearly (one turn a second spans
/// kArrowPerTurn of the body's reach), L's as L / I_mean on the same scale, so they coincide
/// for a sphere and part where the inertia is not isotropic. Capped at kLongestArrow reaches.
inline constexpr float kArrowPerTurn = 1.5f;
inline constexpr float kLongestArrow = 4.0f;
float spinArrowLength(const RigidBody& body);
float momentumArrowLength(const RigidBody& body);

/// The length of a contact's normal line: growing with the square root of the force it
/// carried (its impulse over the step) over the body's weight, between 2 and 30 cm.
float contactLineLength(const World& world, const World::ContactPointView& contact);

void addRigidBody(const World& world, std::size_t i, double alpha, const ViewSettings& settings,
                  const glm::vec4& colour, DrawList& out);
/// Each joint's rods (from a body's centre to its joint point) and a distance joint's string;
/// with settings.joints, its frame on top: a dot at the point on each body, a hinge's axis.
void addJoints(const World& world, double alpha, const ViewSettings& settings, const BodyGroups& groups, DrawList& out);
/// settings.contacts: each touching contact point of the last step, on top.
void addContacts(const World& world, double alpha, const ViewSettings& settings, DrawList& out);
/// settings.axes: each rigid body's axes (x red, y green, z blue), omega (yellow) and L (magenta).
void addBodyAxes(const World& world, double alpha, const ViewSettings& settings, DrawList& out);

/// The colours of the marks, shared by the legend of the panel.
inline constexpr glm::vec4 kContactColour{1.0f, 0.96f, 0.5f, 1.0f};
inline constexpr glm::vec4 kHingeAxisColour{0.3f, 0.95f, 1.0f, 1.0f};
inline constexpr glm::vec4 kSpinColour{1.0f, 0.68f, 0.05f, 1.0f};
inline constexpr glm::vec4 kMomentumColour{1.0f, 0.35f, 0.9f, 1.0f};
inline constexpr glm::vec4 kAxisColours[3] = {{0.95f, 0.3f, 0.3f, 1.0f}, {0.35f, 0.9f, 0.35f, 1.0f},
                                              {0.35f, 0.55f, 1.0f, 1.0f}};

} // namespace pba::render
