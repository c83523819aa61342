#include "world_view.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include "pba/blow_dryer.hpp"
#include "pba/forces.hpp"
#include "pba/spring_network.hpp"
#include "rigid_view.hpp"

namespace pba::render {

namespace {

/// A particle's `radius` (where it touches), or 0 for a point or any other body.
float ballRadius(const Body& body)
{
    const auto* particle = dynamic_cast<const Particle*>(&body);
    return particle ? float(particle->getRadius()) : 0.0f;
}

} // namespace

float drawnRadius(const Body& body, const ViewSettings& settings)
{
    // A ball with a radius is drawn at its size: that is where it touches.
    if (const float radius = ballRadius(body); radius > 0.0f)
        return radius;
    // Balls of one density: the radius grows as the cube root of the mass, so masses that differ
    // tenfold still differ visibly (2.15x) without hiding the light ones.
    const double scale = std::clamp(std::cbrt(body.getMass() / kDrawnReferenceMass), 0.4, 2.5);
    return settings.particleRadius * float(scale);
}

double drawnTime(const World& world, double alpha, bool interpolate)
{
    return interpolate ? world.previousTime() + alpha * (world.time() - world.previousTime()) : world.time();
}

glm::vec3 drawnPosition(const World& world, std::size_t i, double alpha, bool interpolate)
{
    return glm::vec3(interpolate ? world.interpolatedState(i, alpha).pos : world.body(i).getPos());
}

glm::vec3 restingCentre(const World& world, glm::vec3 point, float radius)
{
    for (const Plane& plane : world.planes()) {
        const double d = plane.distance(dvec3(point));
        // Beyond -radius the point is not touching this plane (it left the room, or fell into
        // the hole's shaft): drawn where it is.
        if (d < radius && d > -radius && !plane.overHole(dvec3(point)))
            point += float(radius - d) * glm::vec3(plane.normal);
    }
    return point;
}

glm::vec3 drawnCentre(const World& world, std::size_t i, double alpha, const ViewSettings& settings)
{
    return restingCentre(world, drawnPosition(world, i, alpha, settings.interpolate),
                         drawnRadius(world.body(i), settings));
}

void Trails::record(const World& world, double alpha, const ViewSettings& settings)
{
    m_points.resize(world.bodyCount());
    for (std::size_t i = 0; i < world.bodyCount(); ++i) {
        auto& trail = m_points[i];
        trail.push_back(drawnCentre(world, i, alpha, settings));
        while (trail.size() > m_length)
            trail.pop_front();
    }
}

std::vector<bool> fabricMembers(const World& world, const FabricLayout& fabric)
{
    std::vector<bool> member(world.bodyCount(), false);
    auto mark = [&](std::size_t i) {
        if (i < member.size())
            member[i] = true;
    };
    for (const RopeLayout& rope : fabric.ropes)
        for (const std::size_t i : rope.particles)
            mark(i);
    for (const ClothLayout& cloth : fabric.cloths)
        for (std::size_t k = 0; k < cloth.width * cloth.height; ++k)
            mark(cloth.first + k);
    return member;
}

namespace {

/// The world's springs, drawn as coils: anchored ones (kept in the camera's frame) and those
/// between two bodies.
struct Springs final : ForceVisitor {
    std::vector<const Spring*> anchored;
    std::vector<std::pair<std::size_t, std::size_t>> between; ///< the two bodies of each
    void visit(const Spring& spring) override { anchored.push_back(&spring); }
    void visit(const TwoBodySpring& spring) override { between.emplace_back(spring.first(), spring.second()); }
    void visit(const SpringNetwork& springs) override
    {
        for (std::size_t s = 0; s < springs.size(); ++s)
            between.emplace_back(springs.link(s).a, springs.link(s).b);
    }
};

Springs springs(const World& world)
{
    Springs finder;
    for (std::size_t i = 0; i < world.forceCount(); ++i)
        world.force(i).accept(finder);
    return finder;
}

void addSurfaces(const World& world, DrawList& out)
{
    const glm::vec4 edge(0.55f, 0.60f, 0.70f, 1.0f);
    Floor floor;
    if (world.room()) {
        const glm::vec3 lo(world.room()->min), hi(world.room()->max);
        out.addBoxEdges(lo, hi, edge);
        floor.min = {lo.x, lo.z};
        floor.max = {hi.x, hi.z};
        floor.height = lo.y;
        floor.cell = std::max(hi.x - lo.x, hi.z - lo.z) / 8.0f;
    } else if (world.ground()) {
        glm::vec3 centre(0.0f);
        for (std::size_t i = 0; i < world.bodyCount(); ++i)
            centre += glm::vec3(world.body(i).getPos()) / float(world.bodyCount());
        floor.min = {centre.x - 3.0f, centre.z - 3.0f};
        floor.max = {centre.x + 3.0f, centre.z + 3.0f};
        floor.height = float(*world.ground());
        floor.cell = 0.5f;
    } else {
        return;
    }
    if (const auto& hole = world.floorHole()) {
        floor.holeCentre = {float(hole->centre.x), float(hole->centre.z)};
        floor.holeRadius = float(hole->radius);
    }
    out.floor = floor;
}

/// Arrows on a grid in two vertical planes through the axis. The scale is the push on the axis
/// at the nozzle (the dryer's strength), which spans most of a cell, and a length grows as the
/// square root of the force: the push fades to a few newtons at the top, where lengths in
/// proportion were a few pixels. The air's pull toward the axis near the nozzle is many times
/// the strength: those arrows stop at a cell, drawn white, so they do not cross the room. The
/// colour, from orange to yellow, gives the magnitude in proportion.
void addFieldArrows(const BlowDryerField& f, const glm::vec3& u, const glm::vec3& w, DrawList& out)
{
    const glm::vec3 axis(f.axis), nozzle(f.nozzle);
    const float cell = float(std::max(f.topRadius, f.height) / 10.0);
    const float reference = float(std::max(std::abs(f.strength), 1e-9));
    for (const glm::vec3& across : {u, w})
        for (float h = 0.5f * cell; h < float(f.height); h += cell)
            for (float s = -float(f.topRadius); s <= float(f.topRadius); s += cell) {
                const glm::vec3 x = nozzle + h * axis + s * across;
                const glm::vec3 force(blowDryerForce(f, dvec3(x)));
                const float m = glm::length(force) / reference;
                if (m <= 0.0f)
                    continue;
                const glm::vec3 along = (0.9f * cell * std::sqrt(std::min(m, 1.0f))) * glm::normalize(force);
                const glm::vec4 colour =
                    m > 1.0f ? glm::vec4(1.0f, 1.0f, 1.0f, 0.9f) : glm::vec4(1.0f, 0.55f + 0.45f * m, 0.2f, 0.9f);
                out.addArrow(x, x + along, colour);
            }
}

void addCone(const BlowDryerField& f, bool arrows, DrawList& out)
{
    const glm::vec3 axis(f.axis), nozzle(f.nozzle);
    glm::vec3 u = glm::cross(axis, glm::vec3(0, 0, 1));
    if (glm::length(u) < 1e-4f)
        u = glm::cross(axis, glm::vec3(1, 0, 0));
    u = glm::normalize(u);
    const glm::vec3 w = glm::cross(axis, u);
    const glm::vec3 top = nozzle + float(f.height) * axis;
    const int segments = 48;
    const glm::vec4 fill(0.35f, 0.75f, 1.0f, 0.10f), rim(0.45f, 0.80f, 1.0f, 0.8f);
    for (int k = 0; k < segments; ++k) {
        const float a0 = 2.0f * std::numbers::pi_v<float> * float(k) / segments;
        const float a1 = 2.0f * std::numbers::pi_v<float> * float(k + 1) / segments;
        const glm::vec3 d0 = std::cos(a0) * u + std::sin(a0) * w, d1 = std::cos(a1) * u + std::sin(a1) * w;
        const glm::vec3 b0 = nozzle + float(f.nozzleRadius) * d0, b1 = nozzle + float(f.nozzleRadius) * d1;
        const glm::vec3 t0 = top + float(f.topRadius) * d0, t1 = top + float(f.topRadius) * d1;
        out.addTriangle(b0, t0, t1, fill);
        out.addTriangle(b0, t1, b1, fill);
        out.addLine(t0, t1, rim);
        out.addLine(b0, b1, rim);
        if (k % 12 == 0)
            out.addLine(b0, t0, glm::vec4(rim.r, rim.g, rim.b, 0.5f));
    }
    if (arrows)
        addFieldArrows(f, u, w, out);
}

/// A rope: a line through its particles with a small bead on each; pins drawn grey.
void addRope(const World& world, const RopeLayout& rope, double alpha, const ViewSettings& settings,
             const BodyGroups& groups, DrawList& out)
{
    if (rope.particles.empty() || rope.particles.front() >= world.bodyCount())
        return;
    const glm::vec4 colour = groups[groups.groupOf(rope.particles.front())].colour;
    glm::vec3 before(0.0f);
    for (std::size_t k = 0; k < rope.particles.size(); ++k) {
        const std::size_t i = rope.particles[k];
        if (i >= world.bodyCount())
            return;
        const bool pinned = world.body(i).isFixed();
        // A bead with a radius is drawn at its size: that is where it touches.
        const float ball = ballRadius(world.body(i));
        const float radius = ball > 0.0f ? ball : settings.particleRadius * (pinned ? 0.8f : 0.45f);
        // A bead on the floor lies on it, as a lone particle's ball does, not half sunk in.
        const glm::vec3 at = restingCentre(world, drawnPosition(world, i, alpha, settings.interpolate), radius);
        if (k > 0)
            out.addLine(before, at, colour);
        out.sprites.push_back({at, radius, pinned ? groups.bodyColour(i) : colour});
        before = at;
    }
}

/// A cloth: two triangles a grid cell, each vertex with the normal of the faces around it
/// (area-weighted by the unnormalised cross products), so the sheet is shaded smoothly.
void addCloth(const World& world, const ClothLayout& cloth, double alpha, const ViewSettings& settings,
              const BodyGroups& groups, DrawList& out)
{
    const std::size_t w = cloth.width, h = cloth.height;
    if (w < 2 || h < 2 || cloth.first + w * h > world.bodyCount())
        return;
    std::vector<glm::vec3> x(w * h), n(w * h, glm::vec3(0.0f));
    for (std::size_t k = 0; k < w * h; ++k)
        x[k] = drawnPosition(world, cloth.first + k, alpha, settings.interpolate);
    for (std::size_t j = 0; j + 1 < h; ++j)
        for (std::size_t i = 0; i + 1 < w; ++i) {
            const std::size_t a = j * w + i, b = a + 1, c = a + w, d = c + 1;
            const glm::vec3 face = glm::cross(x[b] - x[a], x[c] - x[a]) + glm::cross(x[c] - x[d], x[b] - x[d]);
            for (const std::size_t v : {a, b, c, d})
                n[v] += face;
        }
    const glm::vec4 front = groups[groups.groupOf(cloth.first)].colour, back = glm::mix(front, glm::vec4(1.0f), 0.4f);
    for (std::size_t j = 0; j + 1 < h; ++j)
        for (std::size_t i = 0; i + 1 < w; ++i) {
            const std::size_t a = j * w + i, b = a + 1, c = a + w, d = c + 1;
            // A checkered weave, so that the folds can be followed.
            const glm::vec4 colour = (i / 2 + j / 2) % 2 ? front : glm::mix(front, back, 0.35f);
            for (const std::size_t v : {a, b, d, a, d, c})
                out.surfaces.push_back({x[v], n[v], colour});
        }
    // A cloth given a radius touches as a net of balls (docs/scenes.md): its balls are drawn too,
    // so that what rests on it rests on them, and an edge it drapes over stays under them.
    for (std::size_t k = 0; k < w * h; ++k) {
        const Body& body = world.body(cloth.first + k);
        if (const float ball = ballRadius(body); ball > 0.0f)
            out.sprites.push_back({x[k], ball, body.isFixed() ? groups.bodyColour(cloth.first + k) : front});
        else if (body.isFixed())
            out.sprites.push_back({x[k], settings.particleRadius * 0.8f, groups.bodyColour(cloth.first + k)});
    }
}

void addFabric(const World& world, double alpha, const ViewSettings& settings, const BodyGroups& groups, DrawList& out)
{
    for (const RopeLayout& rope : settings.fabric.ropes)
        addRope(world, rope, alpha, settings, groups, out);
    for (const ClothLayout& cloth : settings.fabric.cloths)
        addCloth(world, cloth, alpha, settings, groups, out);
}

void addBodies(const World& world, const World& initial, double alpha, const ViewSettings& settings,
               const Trails* trails, const BodyGroups& groups, DrawList& out)
{
    for (std::size_t i = 0; i < world.bodyCount(); ++i) {
        if (groups.inFabric(i))
            continue;
        const glm::vec4 colour = groups.bodyColour(i);
        if (world.isRigid(i)) {
            addRigidBody(world, i, alpha, settings, colour, out);
            continue;
        }
        const glm::vec3 at = drawnCentre(world, i, alpha, settings);
        out.sprites.push_back({at, drawnRadius(world.body(i), settings), colour});
        if (settings.ghost) {
            // The exact solution at the drawn time, one lane behind the body (+z).
            const double t = drawnTime(world, alpha, settings.interpolate);
            if (const auto exact = settings.ghost(i, t)) {
                const glm::vec3 lane(0.0f, 0.0f, -3.0f * settings.particleRadius);
                const glm::vec3 ghost = restingCentre(world, *exact + lane, settings.particleRadius);
                // Its body's colour, paler and half seen through: not a grey a fixed ball has.
                const glm::vec3 pale = glm::mix(glm::vec3(colour), glm::vec3(1.0f), 0.5f);
                out.sprites.push_back({ghost, settings.particleRadius, glm::vec4(pale, 0.55f)});
                out.addLine(at, ghost, glm::vec4(0.85f, 0.85f, 0.95f, 0.25f));
            }
        }
        if (settings.referenceLines && i < initial.bodyCount()) {
            const glm::vec3 start(initial.body(i).getPos());
            const glm::vec4 faint(colour.r, colour.g, colour.b, 0.8f);
            out.addLine(start - glm::vec3(0.25f, 0, 0), start + glm::vec3(0.25f, 0, 0), faint);
        }
        if (settings.trails && trails && i < trails->points().size()) {
            const auto& trail = trails->points()[i];
            for (std::size_t k = 1; k < trail.size(); ++k) {
                const float fade = float(k) / float(trail.size());
                out.addLine(trail[k - 1], trail[k], glm::vec4(glm::vec3(colour) * (0.25f + 0.75f * fade), 1.0f));
            }
        }
    }
}

/// A spring as a zigzag from one end to the other.
void addCoil(const glm::vec3& from, const glm::vec3& to, DrawList& out)
{
    const glm::vec3 along = to - from;
    glm::vec3 side = glm::cross(along, glm::vec3(0, 0, 1));
    if (glm::length(side) < 1e-6f)
        side = glm::vec3(1, 0, 0);
    side = 0.08f * glm::normalize(side);
    const int coils = 16;
    const glm::vec4 colour(0.85f, 0.85f, 0.9f, 1.0f);
    glm::vec3 previous = from;
    for (int k = 1; k <= coils; ++k) {
        const float t = float(k) / float(coils + 1);
        const glm::vec3 next = from + t * along + (k % 2 ? side : -side);
        out.addLine(previous, next, colour);
        previous = next;
    }
    out.addLine(previous, to, colour);
}

void addSprings(const World& world, double alpha, const ViewSettings& settings, DrawList& out)
{
    const Springs found = springs(world);
    const std::size_t n = world.bodyCount();
    for (const Spring* spring : found.anchored) {
        if (spring->particle() >= n)
            continue;
        const glm::vec3 anchor(spring->anchor());
        addCoil(anchor, drawnCentre(world, spring->particle(), alpha, settings), out);
        out.sprites.push_back({anchor, 0.05f, glm::vec4(0.6f, 0.6f, 0.65f, 1.0f)}); // the anchor, a small ball
    }
    // A rope's or cloth's own springs are its line or surface, not coils.
    const std::vector<bool> fabric = fabricMembers(world, settings.fabric);
    for (const auto& [a, b] : found.between)
        if (a < n && b < n && !(fabric[a] && fabric[b]))
            addCoil(drawnCentre(world, a, alpha, settings), drawnCentre(world, b, alpha, settings), out);
}

} // namespace

void buildDrawList(const World& world, const World& initial, double alpha, const ViewSettings& settings,
                   const Trails* trails, DrawList& out)
{
    out.clear();
    addSurfaces(world, out);
    if (settings.cone)
        for (const WorldDryer& dryer : blowDryers(world))
            addCone(dryer.field, settings.fieldArrows, out);
    const BodyGroups groups(world, settings.fabric);
    addSprings(world, alpha, settings, out);
    addFabric(world, alpha, settings, groups, out);
    addBodies(world, initial, alpha, settings, trails, groups, out);
    addJoints(world, alpha, settings, groups, out);
    addContacts(world, alpha, settings, out);
    addBodyAxes(world, alpha, settings, out);
    // Swarms keep no previous state (24 bytes a particle is the budget): drawn where they are.
    for (std::size_t s = 0; s < world.swarmCount(); ++s) {
        const Swarm& swarm = world.swarm(s);
        out.addPoints(swarm.px().data(), swarm.py().data(), swarm.pz().data(), swarm.size(),
                      swarm.radius() > 0.0f ? swarm.radius() : settings.particleRadius * 0.3f,
                      groups.swarmColour(s));
    }
}

FramedBox framedBox(const World& world)
{
    if (world.room())
        return {glm::vec3(world.room()->min), glm::vec3(world.room()->max)};
    glm::vec3 lo(1e30f), hi(-1e30f);
    for (std::size_t i = 0; i < world.bodyCount(); ++i) {
        lo = glm::min(lo, glm::vec3(world.body(i).getPos()));
        hi = glm::max(hi, glm::vec3(world.body(i).getPos()));
    }
    for (const Spring* spring : springs(world).anchored) {
        lo = glm::min(lo, glm::vec3(spring->anchor()));
        hi = glm::max(hi, glm::vec3(spring->anchor()));
    }
    if (world.bodyCount() == 0)
        lo = hi = glm::vec3(0.0f);
    if (world.ground()) {
        lo.y = std::min(lo.y, float(*world.ground()));
        // Headroom above the start: a bounce may rise above where it fell from (forward Euler's
        // gains half its height again in the integrators scene's 10 s).
        hi.y += 0.5f * (hi.y - lo.y);
    }
    // A dryer's cone, where what it catches hovers (the first scene's ball, 2.3 m above a throw
    // from 0.5 m, flew out of the picture's top): its nozzle and its top's disc.
    for (const WorldDryer& dryer : blowDryers(world)) {
        const BlowDryerField& f = dryer.field;
        const glm::vec3 axis(f.axis), top(f.nozzle + f.height * f.axis);
        const glm::vec3 across = float(f.topRadius) * glm::sqrt(glm::max(glm::vec3(1.0f) - axis * axis, glm::vec3(0.0f)));
        lo = glm::min(lo, glm::min(glm::vec3(f.nozzle), top - across));
        hi = glm::max(hi, glm::max(glm::vec3(f.nozzle), top + across));
    }
    return {lo - glm::vec3(0.5f), hi + glm::vec3(0.5f)};
}

OrbitCamera frameWorld(const World& world)
{
    const FramedBox box = framedBox(world);
    OrbitCamera camera = OrbitCamera::framing(box.lo, box.hi);
    if (!world.room())
        camera.pitch = 0.2f;
    return camera;
}

} // namespace pba::render
