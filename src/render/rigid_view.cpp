#include "rigid_view.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "world_view.hpp"

namespace pba::render {

DrawnPose drawnPose(const World& world, std::size_t i, double alpha, bool interpolate)
{
    return {drawnPosition(world, i, alpha, interpolate),
            glm::quat(world.interpolatedOrientation(i, interpolate ? alpha : 1.0))};
}

glm::vec3 followBody(const World& world, std::size_t i, double alpha, bool interpolate, const dvec3& now)
{
    const Body& body = world.body(i);
    const dquat turn = world.isRigid(i) ? static_cast<const RigidBody&>(body).getOrientation() : dquat(1, 0, 0, 0);
    const glm::vec3 local(glm::conjugate(turn) * (now - body.getPos()));
    return drawnPose(world, i, alpha, interpolate).apply(local);
}

namespace {

/// How far the body reaches: the scale of its axes and arrows.
float reach(const RigidBody& body) { return float(std::max(body.getBoundingRadius(), 0.02)); }

/// The mean of the principal moments: L over it is an angular velocity, drawn on omega's scale.
double meanInertia(const RigidBody& body)
{
    const dmat3& I = body.getInertiaBody();
    return (I[0][0] + I[1][1] + I[2][2]) / 3.0;
}

float arrowLength(const RigidBody& body, double radiansPerSecond)
{
    const double turns = radiansPerSecond / (2.0 * std::numbers::pi);
    return reach(body) * float(std::min(kArrowPerTurn * turns, double(kLongestArrow)));
}

const glm::vec4 kRodColour(0.78f, 0.78f, 0.84f, 1.0f);
const glm::vec4 kAnchorColour(0.6f, 0.6f, 0.65f, 1.0f);

} // namespace

float spinArrowLength(const RigidBody& body) { return arrowLength(body, glm::length(body.getAngularVelocity())); }

float momentumArrowLength(const RigidBody& body)
{
    return arrowLength(body, glm::length(body.getAngularMomentum()) / meanInertia(body));
}

float contactLineLength(const World& world, const World::ContactPointView& contact)
{
    const double dt = world.time() - world.previousTime();
    const double g = glm::length(world.gravity());
    const double weight = world.body(contact.bodyA).getMass() * (g > 0.0 ? g : 9.81);
    const double share = dt > 0.0 && weight > 0.0 ? contact.impulse / dt / weight : 0.0;
    return float(std::clamp(0.06 * std::sqrt(std::max(share, 0.0)), 0.02, 0.3));
}

void addRigidBody(const World& world, std::size_t i, double alpha, const ViewSettings& settings,
                  const glm::vec4& colour, DrawList& out)
{
    const Mesh& mesh = world.body(i).getMesh();
    const DrawnPose pose = drawnPose(world, i, alpha, settings.interpolate);
    const glm::mat4 local = mesh.getLocal(); // the mesh in the body's frame
    const glm::mat3 localNormals = glm::transpose(glm::inverse(glm::mat3(local)));
    const glm::mat3 turn = glm::mat3_cast(pose.turn);
    const auto& vertices = mesh.vertices();
    const auto& normals = mesh.normals();
    const auto& indices = mesh.indices();
    const bool die = std::binary_search(settings.dice.begin(), settings.dice.end(), i);
    float halfSide = 0.0f; // a die's: its faces at +-1 in the pips' coordinates
    if (die)
        for (const glm::vec3& v : vertices) {
            const glm::vec3 p(local * glm::vec4(v, 1.0f));
            halfSide = std::max({halfSide, std::abs(p.x), std::abs(p.y), std::abs(p.z)});
        }
    for (const unsigned index : indices) {
        const glm::vec3 p(local * glm::vec4(vertices[index], 1.0f));
        const glm::vec3 n = glm::normalize(localNormals * normals[index]);
        out.surfaces.push_back({pose.at + turn * p, turn * n, colour, n, die ? p / halfSide : glm::vec3(0.0f),
                              die ? 1.0f : 0.0f});
    }
}

void addJoints(const World& world, double alpha, const ViewSettings& settings, const BodyGroups& groups, DrawList& out)
{
    const bool interpolate = settings.interpolate;
    for (std::size_t j = 0; j < world.jointCount(); ++j) {
        const JointFrame frame = world.jointFrame(j);
        const glm::vec3 onA = followBody(world, frame.bodyA, alpha, interpolate, frame.onA);
        const glm::vec3 onB = frame.bodyB ? followBody(world, *frame.bodyB, alpha, interpolate, frame.onB)
                                          : glm::vec3(frame.onB);
        // The rods: from each body's centre to its point of the joint (a pendulum's massless
        // rod), and a distance joint's string between the two points.
        out.addLine(drawnPosition(world, frame.bodyA, alpha, interpolate), onA, kRodColour);
        if (frame.bodyB)
            out.addLine(drawnPosition(world, *frame.bodyB, alpha, interpolate), onB, kRodColour);
        else
            // The point on the world, a ball large enough to be seen from across the room (a chain
            // seemed to hang from nothing at 3 cm).
            out.sprites.push_back({onB, 0.05f, kAnchorColour});
        if (frame.type == JointType::Distance)
            out.addLine(onA, onB, kRodColour);
        if (!settings.joints)
            continue;
        out.overlaySprites.push_back({onA, 0.025f, groups.bodyColour(frame.bodyA)});
        out.overlaySprites.push_back({onB, 0.018f, frame.bodyB ? groups.bodyColour(*frame.bodyB) : kAnchorColour});
        if (frame.type == JointType::Hinge) {
            const glm::vec3 axis = 0.18f * glm::normalize(glm::vec3(frame.axis));
            out.addOverlayLine(onA - axis, onA + axis, kHingeAxisColour);
        }
    }
}

void addContacts(const World& world, double alpha, const ViewSettings& settings, DrawList& out)
{
    if (!settings.contacts)
        return;
    for (const World::ContactPointView& c : world.contactPoints()) {
        const glm::vec3 at = followBody(world, c.bodyA, alpha, settings.interpolate, c.point);
        // The normal runs from the first body into the second (or the room's surface): the line
        // goes the other way, the way the contact pushes the first body, out of the floor.
        const glm::vec3 push = -glm::normalize(glm::vec3(c.normal));
        out.overlaySprites.push_back({at, 0.015f, kContactColour});
        out.addOverlayLine(at, at + contactLineLength(world, c) * push, kContactColour);
    }
}

void addBodyAxes(const World& world, double alpha, const ViewSettings& settings, DrawList& out)
{
    if (!settings.axes)
        return;
    for (std::size_t i = 0; i < world.bodyCount(); ++i) {
        if (!world.isRigid(i))
            continue;
        const auto& body = static_cast<const RigidBody&>(world.body(i));
        const DrawnPose pose = drawnPose(world, i, alpha, settings.interpolate);
        const float r = 1.3f * reach(body);
        for (int k = 0; k < 3; ++k) {
            glm::vec3 e(0.0f);
            e[k] = r;
            out.addOverlayLine(pose.at, pose.apply(e), kAxisColours[k]);
        }
        const dvec3 w = body.getAngularVelocity(), L = body.getAngularMomentum();
        if (glm::length(w) > 0.0)
            out.addOverlayArrow(pose.at, pose.at + spinArrowLength(body) * glm::normalize(glm::vec3(w)), kSpinColour);
        if (glm::length(L) > 0.0)
            out.addOverlayArrow(pose.at, pose.at + momentumArrowLength(body) * glm::normalize(glm::vec3(L)),
                                kMomentumColour);
    }
}

} // namespace pba::render
