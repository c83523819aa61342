// Scene files to Worlds. The order of reading follows docs/scenes.md.
#include <algorithm>
#include <cmath>
#include <fstream>
#include <numbers>
#include <optional>
#include <set>
#include <sstream>
#include <stdexcept>
#include <vector>

#include <fmt/format.h>

#include "fabric_readers.hpp"
#include "force_parsers.hpp"
#include "joint_reader.hpp"
#include "json_reader.hpp"
#include "memory_estimate.hpp"
#include "one_line.hpp"
#include "rigid_body_reader.hpp"
#include "room_fit.hpp"
#include "swarm_reader.hpp"
#include "pba/forces.hpp"
#include "pba/swarm.hpp"
#include "pba/scene/scene.hpp"

namespace pba {

SceneError::SceneError(std::string file, std::string field, std::string reason)
    // One line whatever the parts hold: a field's keys and a reason's quoted names are cut where
    // they are put in, and a file's path here.
    : std::runtime_error(fmt::format("{}: {}: {}", scene_detail::oneLine(file, scene_detail::kShownPathLength),
                                     scene_detail::oneLine(field, scene_detail::kWhole),
                                     scene_detail::oneLine(reason, scene_detail::kWhole))),
      m_file(std::move(file)),
      m_field(std::move(field)), m_reason(std::move(reason))
{
}

namespace scene_detail {

Integrator readIntegrator(ObjectReader& reader, const std::string& key, Integrator fallback)
{
    if (!reader.has(key))
        return fallback;
    const std::string name = reader.string(key);
    const auto integrator = integratorFromName(name);
    if (!integrator)
        reader.fail(key, fmt::format("unknown integrator '{}' (expected {})", oneLine(name), integratorNameList()));
    return *integrator;
}

bool insideSurfaces(const World& world, const dvec3& x, double radius)
{
    for (const Plane& plane : world.planes())
        if (plane.distance(x) < radius)
            return false;
    return true;
}

std::string ballOutsideText(const World& world, const dvec3& x, double radius)
{
    if (radius == 0.0)
        return outsideText(world, x);
    return fmt::format("a ball of radius {:g} m at ({:g}, {:g}, {:g}) reaches beyond the ground or room: {}", radius,
                       x.x, x.y, x.z, surfacesText(world));
}

ContactKeys readContactKeys(ObjectReader& reader)
{
    ContactKeys keys;
    keys.radius = reader.nonNegative("radius", 0.0);
    keys.friction = reader.nonNegative("friction", 0.0);
    return keys;
}

std::string surfacesText(const World& world)
{
    if (const auto& room = world.room())
        return fmt::format("the room spans x {:g} to {:g}, y {:g} to {:g}, z {:g} to {:g} m", room->min.x, room->max.x,
                           room->min.y, room->max.y, room->min.z, room->max.z);
    if (const auto& ground = world.ground())
        return fmt::format("the ground is at y = {:g} m", *ground);
    return "no surfaces";
}

std::string outsideText(const World& world, const dvec3& x)
{
    return fmt::format("({:g}, {:g}, {:g}) lies outside the ground or room: {}", x.x, x.y, x.z, surfacesText(world));
}

/// A name (of the scene, a particle, a swarm): it goes into summaries, CSV rows, pictures and
/// titles, so control characters (a newline, a tab, an escape) are refused.
std::string readName(ObjectReader& reader, const std::string& key, const std::optional<std::string>& fallback)
{
    const std::string name = fallback ? reader.string(key, *fallback) : reader.string(key);
    for (const char c : name)
        if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f)
            reader.fail(key, fmt::format("contains a control character (code {}); names are one line of text",
                                         static_cast<int>(static_cast<unsigned char>(c))));
    return name;
}

} // namespace scene_detail

namespace {

using scene_detail::Json;
using scene_detail::ObjectReader;
using scene_detail::insideSurfaces;
using scene_detail::outsideText;
using scene_detail::ballOutsideText;
using scene_detail::ContactKeys;
using scene_detail::readContactKeys;
using scene_detail::readIntegrator;
using scene_detail::oneLine;
using scene_detail::readName;
using scene_detail::fitsFloat;
using scene_detail::kFloatMax;
using scene_detail::readSwarm;
using scene_detail::requireMemoryForBodies;
using scene_detail::swarmFieldsFit;

void readSurfaces(ObjectReader& root, World& world)
{
    if (root.has("ground") && root.has("room"))
        root.fail("room", "a scene has either a ground or a room, not both");
    if (root.has("ground")) {
        ObjectReader ground = root.object("ground");
        ground.expectKeys({"height"});
        world.setGround(ground.number("height", 0.0));
        ground.finish();
    }
    if (root.has("room")) {
        ObjectReader room = root.object("room");
        room.expectKeys({"min", "max"});
        const Aabb box{room.vec3("min"), room.vec3("max")};
        for (int i = 0; i < 3; ++i)
            if (!(box.min[i] < box.max[i]))
                room.fail("min", fmt::format("must be below max on every axis (axis {}: {} >= {})", "xyz"[i],
                                             box.min[i], box.max[i]));
        world.setRoom(box);
        room.finish();
    }
}

void readParticle(const Json& value, const std::string& path, const std::string& file, World& world,
                  std::set<std::string>& names)
{
    ObjectReader reader(value, path, file);
    reader.expectKeys(
        {"name", "position", "velocity", "mass", "restitution", "radius", "friction", "integrator", "fixed"});
    Particle p;
    const std::string name = readName(reader, "name");
    if (name.empty())
        reader.fail("name", "must not be empty");
    if (!names.insert(name).second)
        reader.fail("name", fmt::format("another particle is already named '{}'", oneLine(name)));
    p.setName(name);
    p.setPos(reader.vec3("position"));
    p.setVel(reader.vec3("velocity", dvec3(0.0)));
    const double mass = reader.positive("mass", 1.0);
    p.setMass(mass);
    const double restitution = reader.number("restitution", 1.0);
    if (!(restitution >= 0.0 && restitution <= 1.0))
        reader.fail("restitution", fmt::format("must be in [0, 1], got {}", restitution));
    p.setCor(restitution);
    const ContactKeys contact = readContactKeys(reader);
    p.setRadius(contact.radius);
    p.setFriction(contact.friction);
    p.setIntegrator(readIntegrator(reader, "integrator", Integrator::SemiImplicitEuler));
    p.setFixed(reader.boolean("fixed", false));
    if (!insideSurfaces(world, p.getPos()))
        reader.fail("position", outsideText(world, p.getPos()));
    if (!insideSurfaces(world, p.getPos(), contact.radius))
        reader.fail("radius", ballOutsideText(world, p.getPos(), contact.radius));
    reader.finish();
    world.addParticle(p);
}

/// A force's keys depend on its type; while the type is missing or unknown, any key of any
/// force type is let through so that the type's own error comes first.
void expectForceKeys(ObjectReader& reader, const Json& value)
{
    std::vector<std::string> keys{"type"};
    const auto& types = scene_detail::forceTypes();
    const bool typed = value.contains("type") && value["type"].is_string();
    const auto known = std::find_if(types.begin(), types.end(), [&](const auto& t) {
        return typed && value["type"].get<std::string>() == t.name;
    });
    for (auto t = types.begin(); t != types.end(); ++t)
        if (known == types.end() || t == known)
            keys.insert(keys.end(), t->keys.begin(), t->keys.end());
    std::sort(keys.begin() + 1, keys.end());
    keys.erase(std::unique(keys.begin(), keys.end()), keys.end());
    reader.expectKeys(std::move(keys));
}

void readForce(const Json& value, const std::string& path, const std::string& file, World& world)
{
    ObjectReader reader(value, path, file);
    expectForceKeys(reader, value);
    const std::string type = reader.string("type");
    for (const auto& known : scene_detail::forceTypes()) {
        if (type == known.name) {
            std::unique_ptr<Force> force = known.parse(reader, world);
            try {
                world.addForce(std::move(force));
            } catch (const std::invalid_argument& refused) { // one that cannot act on the scene's swarms
                reader.failHere(refused.what());
            }
            reader.finish();
            if (!swarmFieldsFit(world))
                reader.failHere("its numbers, as the accelerations they give the scene's swarms, cannot be "
                                "represented in single precision (a swarm's numbers are floats)");
            return;
        }
    }
    std::vector<std::string> names;
    for (const auto& known : scene_detail::forceTypes())
        names.emplace_back(known.name);
    if (const auto close = scene_detail::closestName(type, names))
        reader.fail("type", fmt::format("unknown force type '{}' (did you mean \"{}\"?)", oneLine(type),
                                        *close));
    reader.fail("type", fmt::format("unknown force type '{}' (expected one of: {})", oneLine(type),
                                    fmt::join(names, ", ")));
}

/// Every particle's energy must be finite at the start: a velocity of 1e300 m/s is a valid
/// number whose kinetic energy is not, and would fail the first step with no field to blame.
/// The scene key that made body i: particles[i] itself, or the rope or cloth it belongs to.
std::string bodyKey(std::size_t i, const World& world, const FabricLayout& fabric)
{
    if (world.isRigid(i)) {
        std::size_t k = 0;
        for (std::size_t j = 0; j < i; ++j)
            k += world.isRigid(j) ? 1 : 0;
        return fmt::format("rigid_bodies[{}]", k);
    }
    for (std::size_t r = 0; r < fabric.ropes.size(); ++r)
        for (const std::size_t p : fabric.ropes[r].particles)
            if (p == i)
                return fmt::format("ropes[{}]", r);
    for (std::size_t c = 0; c < fabric.cloths.size(); ++c) {
        const ClothLayout& cloth = fabric.cloths[c];
        if (i >= cloth.first && i < cloth.first + cloth.width * cloth.height)
            return fmt::format("cloths[{}]", c);
    }
    return fmt::format("particles[{}]", i);
}

void requireFiniteEnergies(const World& world, const FabricLayout& fabric, const std::string& file)
{
    const std::vector<double> energies = world.energies();
    for (std::size_t i = 0; i < world.bodyCount(); ++i) {
        if (std::isfinite(energies[i]))
            continue;
        const std::string key = bodyKey(i, world, fabric);
        // A particle's or rigid body's own entry has the fields.
        const bool own = key.rfind("particles[", 0) == 0 || key.rfind("rigid_bodies[", 0) == 0;
        const std::string who = own ? "" : fmt::format("its particle '{}': ", oneLine(world.body(i).getName()));
        if (!std::isfinite(world.kineticEnergy(i)))
            throw SceneError(file, own ? key + ".velocity" : key,
                             who + "too large: the kinetic energy m v^2 / 2 is not finite");
        throw SceneError(file, own ? key + ".position" : key, who + "too far: the potential energy is not finite");
    }
}

/// A whole number of sweeps from `least` to 1,000.
int readSweeps(ObjectReader& reader, const std::string& key, int least, int fallback)
{
    if (!reader.has(key))
        return fallback;
    const double sweeps = reader.number(key);
    if (!(sweeps >= least && sweeps <= 1000 && sweeps == std::floor(sweeps)))
        reader.fail(key, fmt::format("a whole number of sweeps from {} to 1000, got {}", least, sweeps));
    return static_cast<int>(sweeps);
}

/// How the rigid bodies' contacts are solved: the velocity pass's sweeps (a fixed count when
/// both are given alike, as an engine compared sweep for sweep), the position pass's, sleep.
void readContactSettings(ObjectReader reader, ContactSettings& settings)
{
    reader.expectKeys({"velocity_iterations", "max_velocity_iterations", "position_iterations", "sleeping"});
    settings.velocityIterations = readSweeps(reader, "velocity_iterations", 1, settings.velocityIterations);
    settings.maxVelocityIterations = readSweeps(reader, "max_velocity_iterations", 1,
                                                std::max(settings.velocityIterations, settings.maxVelocityIterations));
    if (settings.maxVelocityIterations < settings.velocityIterations)
        reader.fail("max_velocity_iterations",
                    fmt::format("{} is fewer than velocity_iterations ({}): the sweeps go on past those, never short",
                                settings.maxVelocityIterations, settings.velocityIterations));
    settings.positionIterations = readSweeps(reader, "position_iterations", 0, settings.positionIterations);
    settings.sleeping = reader.boolean("sleeping", settings.sleeping);
    reader.finish();
}

SceneCamera readCamera(ObjectReader reader)
{
    reader.expectKeys({"position", "target"});
    SceneCamera camera{reader.vec3("position"), reader.vec3("target")};
    const dvec3 offset = camera.position - camera.target;
    const double apart = glm::length(offset);
    if (!(apart >= SceneCamera::kMinDistance && apart <= SceneCamera::kMaxDistance))
        reader.fail("position", fmt::format("must be {:g} to {:g} m from the target, got {:.6g} m",
                                            SceneCamera::kMinDistance, SceneCamera::kMaxDistance, apart));
    const double pitch = std::asin(std::clamp(offset.y / apart, -1.0, 1.0));
    if (std::abs(pitch) > SceneCamera::kMaxPitch)
        reader.fail("position", fmt::format("is straight {} the target ({:.1f} degrees from level, at most {:.1f}): "
                                            "move it sideways",
                                            pitch > 0 ? "above" : "below", std::abs(pitch) * 180.0 / std::numbers::pi,
                                            SceneCamera::kMaxPitch * 180.0 / std::numbers::pi));
    reader.finish();
    return camera;
}

Scene readScene(const Json& document, const std::string& file, const std::filesystem::path& directory)
{
    ObjectReader root(document, "", file);
    root.expectKeys({"name", "summary", "description", "dt", "duration", "gravity", "collision_response", "substeps",
                     "contacts", "ground", "room", "camera", "particles", "ropes", "cloths", "rigid_bodies", "joints",
                     "swarms", "forces"});
    Scene scene;
    scene.source = file;
    scene.name = readName(root, "name", "unnamed");
    scene.summary = readName(root, "summary", "");
    scene.description = root.string("description", "");
    scene.dt = root.positive("dt", 0.01);
    scene.duration = root.positive("duration", 10.0);
    const dvec3 g = root.vec3("gravity", dvec3(0.0, -9.81, 0.0));
    if (root.has("collision_response")) {
        const std::string name = root.string("collision_response");
        const auto response = collisionResponseFromName(name);
        if (!response)
            root.fail("collision_response",
                      fmt::format("unknown collision response '{}' (expected {})", oneLine(name),
                                  collisionResponseNameList()));
        scene.world.setCollisionResponse(*response);
    }
    if (root.has("substeps")) {
        const double substeps = root.number("substeps");
        if (!(substeps >= 1 && substeps <= World::kMaxXpbdSubsteps && substeps == std::floor(substeps)))
            root.fail("substeps", fmt::format("xpbd's substeps a step: a whole number from 1 to {}, got {}",
                                              World::kMaxXpbdSubsteps, substeps));
        scene.world.setXpbdSubsteps(static_cast<int>(substeps));
    }
    if (root.has("contacts"))
        readContactSettings(root.object("contacts"), scene.world.contactSettings());
    if (root.has("camera"))
        scene.camera = readCamera(root.object("camera"));
    readSurfaces(root, scene.world);
    scene.world.addForce(std::make_unique<Gravity>(g));
    if (document.is_object() && document.contains("swarms") && !(fitsFloat(g.x) && fitsFloat(g.y) && fitsFloat(g.z)))
        root.fail("gravity", fmt::format("cannot be represented in single precision, as a swarm's numbers are (at "
                                         "most {:.3g} in size)", kFloatMax));
    requireMemoryForBodies(document, file, directory);
    std::set<std::string> names;
    scene_detail::MeshLibrary meshes;
    root.array("particles", [&](const Json& value, const std::string& path, std::size_t) {
        readParticle(value, path, file, scene.world, names);
    });
    const scene_detail::FabricTarget fabric{scene.world, names, scene.fabric};
    root.array("ropes", [&](const Json& value, const std::string& path, std::size_t) {
        scene_detail::readRope(value, path, file, fabric);
    });
    root.array("cloths", [&](const Json& value, const std::string& path, std::size_t) {
        scene_detail::readCloth(value, path, file, fabric);
    });
    root.array("rigid_bodies", [&](const Json& value, const std::string& path, std::size_t) {
        if (scene_detail::readRigidBody(value, path, file, directory, scene.world, names, meshes))
            scene.dice.push_back(scene.world.bodyCount() - 1);
    });
    std::vector<scene_detail::BodyPair> joinedApart; // may start inside each other
    root.array("joints", [&](const Json& value, const std::string& path, std::size_t) {
        const JointDesc joint = scene_detail::readJoint(value, path, file, scene.world);
        if (joint.bodyB && !joint.collide)
            joinedApart.emplace_back(std::min(joint.bodyA, *joint.bodyB), std::max(joint.bodyA, *joint.bodyB));
    });
    root.array("swarms", [&](const Json& value, const std::string& path, std::size_t) {
        readSwarm(value, path, file, scene.world, names);
    });
    root.array("forces", [&](const Json& value, const std::string& path, std::size_t) {
        readForce(value, path, file, scene.world);
    });
    root.finish();
    scene_detail::requireRigidBodiesInside(scene.world, file);
    std::sort(joinedApart.begin(), joinedApart.end());
    scene_detail::requireRigidBodiesApart(scene.world, file, joinedApart);
    scene_detail::requireParticlesOutsideRigidBodies(scene.world, scene.fabric, file, joinedApart);
    requireFiniteEnergies(scene.world, scene.fabric, file);
    return scene;
}

/// The parser's message quotes the whole token it stopped in, after `opener` and up to `closer`
/// (a string of a megabyte, all of it): only its end is kept, which is where the trouble is.
std::string cutQuotedToken(const std::string& reason, std::string_view opener, std::string_view closer)
{
    const auto at = reason.find(opener);
    if (at == std::string::npos)
        return reason;
    const std::size_t begin = at + opener.size();
    const auto end = closer.empty() ? reason.size() - 1 : reason.rfind(closer);
    if (end == std::string::npos || end < begin || reason[end] != '\'')
        return reason;
    return reason.substr(0, begin) + scene_detail::oneLineTail(std::string_view(reason).substr(begin, end - begin)) +
           reason.substr(end);
}

std::string parseErrorReason(const nlohmann::json::exception& error)
{
    const std::string what = error.what();
    const auto pos = what.find("] ");
    std::string reason = pos == std::string::npos ? what : what.substr(pos + 2);
    const bool expected = reason.find("'; expected ") != std::string::npos;
    reason = cutQuotedToken(reason, "; last read: '", expected ? "'; expected " : "");
    reason = cutQuotedToken(reason, "number overflow parsing '", "");
    return "malformed JSON: " + reason;
}

} // namespace

namespace {

/// A first pass over a scene's text, as the parser's SAX events: where the parser is in the
/// document, as the JSON path an error names (cloths[0].stiffness), the first key its object
/// already has, and what stops the text being read. nlohmann's parse callback could watch this
/// too, but its parser rescans the enclosing array each time an object in it ends, which made a
/// long array of particles quadratic to load.
class DocumentCheck {
public:
    /// Far beyond any scene's nesting (a few levels). Without a limit a text of '[' alone is
    /// read to its end, a level of nesting for each byte, before any check of the scene sees it.
    static constexpr std::size_t kMaxDepth = 64;

    struct Problem {
        std::string field;
        std::string reason;
    };

    bool null() { return value(); }
    bool boolean(bool) { return value(); }
    bool number_integer(Json::number_integer_t) { return value(); }
    bool number_unsigned(Json::number_unsigned_t) { return value(); }
    bool number_float(Json::number_float_t, const Json::string_t&) { return value(); }
    bool string(Json::string_t&) { return value(); }
    bool binary(Json::binary_t&) { return value(); }
    bool start_object(std::size_t) { return open(false); }
    bool start_array(std::size_t) { return open(true); }
    bool end_object() { return close(); }
    bool end_array() { return close(); }

    bool key(Json::string_t& key)
    {
        Frame& object = m_frames.back();
        object.key = key;
        if (!object.keys.insert(object.key).second && !m_duplicate)
            m_duplicate = path();
        return true;
    }

    bool parse_error(std::size_t, const std::string&, const Json::exception& error)
    {
        // A number too large (out_of_range) is the value being read; a syntax error is the
        // document's, and the parser's line and column say where.
        const bool number = dynamic_cast<const Json::out_of_range*>(&error) != nullptr;
        m_failure = Problem{number ? path(true) : "(document)", parseErrorReason(error)};
        return false;
    }

    /// What stopped the text being read: a syntax error, a number too large, a nesting too deep.
    const std::optional<Problem>& failure() const { return m_failure; }
    /// The path of the first key that its object already had.
    const std::optional<std::string>& duplicate() const { return m_duplicate; }

private:
    struct Frame {
        bool array = false;
        long index = -1;            ///< an array's element being read
        std::string key;            ///< an object's key being read
        std::set<std::string> keys; ///< an object's keys so far
    };

    /// An element of an array begins (a scalar: and ends).
    void countElement()
    {
        if (!m_frames.empty() && m_frames.back().array)
            ++m_frames.back().index;
    }

    bool value()
    {
        countElement();
        return true;
    }

    bool open(bool array)
    {
        countElement();
        if (m_frames.size() == kMaxDepth) {
            m_failure = Problem{"(document)", fmt::format("nested deeper than {} levels of objects and arrays",
                                                          kMaxDepth)};
            return false;
        }
        m_frames.emplace_back();
        m_frames.back().array = array;
        return true;
    }

    bool close()
    {
        m_frames.pop_back();
        return true;
    }

    /// The path to the value being read; "(document)" outside every object. `unfinished`: the
    /// innermost value's parse failed (a number too large), so no event counted it as an
    /// element of its array yet: it is the one after the last counted.
    std::string path(bool unfinished = false) const
    {
        std::string out;
        for (std::size_t k = 0; k < m_frames.size(); ++k) {
            const Frame& frame = m_frames[k];
            const long index = frame.index + (unfinished && k + 1 == m_frames.size() ? 1 : 0);
            if (frame.array && index >= 0)
                out += fmt::format("[{}]", index);
            else if (!frame.array && !frame.key.empty())
                out.append(out.empty() ? "" : ".").append(oneLine(frame.key));
        }
        return out.empty() ? "(document)" : out;
    }

    std::vector<Frame> m_frames;
    std::optional<Problem> m_failure;
    std::optional<std::string> m_duplicate;
};

Scene parseScene(std::string_view json, const std::string& source, const std::filesystem::path& directory)
{
    // A NUL byte would end the document early, silently dropping what follows it.
    if (const auto nul = json.find('\0'); nul != std::string_view::npos)
        throw SceneError(source, "(document)", fmt::format("contains a NUL byte at offset {}: not a text file", nul));
    DocumentCheck check;
    Json::sax_parse(json.begin(), json.end(), &check);
    if (const auto& failure = check.failure())
        throw SceneError(source, failure->field, failure->reason);
    // Duplicate keys: JSON leaves them undefined and the parser keeps the last; a scene refuses
    // them, as it refuses unknown keys (both are usually mistakes).
    if (const auto& duplicate = check.duplicate())
        throw SceneError(source, *duplicate, "duplicate key (each key may appear once in an object)");
    Json document;
    try {
        document = Json::parse(json.begin(), json.end());
    } catch (const nlohmann::json::exception& error) { // the first pass read this text, so only in theory
        throw SceneError(source, "(document)", parseErrorReason(error));
    }
    return readScene(document, source, directory);
}

} // namespace

Scene parseScene(std::string_view json, const std::string& source) { return parseScene(json, source, {}); }

Scene loadSceneFile(const std::filesystem::path& path)
{
    std::error_code ec;
    if (!std::filesystem::is_regular_file(path, ec))
        throw SceneError(path.string(), "(file)", std::filesystem::exists(path, ec) ? "is not a regular file"
                                                                                     : "no such file");
    std::ifstream in(path, std::ios::binary);
    if (!in)
        throw SceneError(path.string(), "(file)", "cannot be opened for reading");
    std::ostringstream text;
    text << in.rdbuf();
    const std::filesystem::path directory = path.has_parent_path() ? path.parent_path() : std::filesystem::path(".");
    return parseScene(text.str(), path.string(), directory);
}

Scene loadScene(std::string_view nameOrPath)
{
    if (const std::string_view text = builtinSceneText(nameOrPath); !text.empty()) {
        Scene scene = parseScene(text, fmt::format("builtin:{}", nameOrPath));
        return scene;
    }
    const std::filesystem::path path{std::string(nameOrPath)};
    if (path.has_parent_path() || path.extension() == ".json" || std::filesystem::exists(path))
        return loadSceneFile(path);
    const std::vector<std::string> names = builtinSceneNames();
    if (const auto close = scene_detail::closestName(nameOrPath, names))
        throw SceneError(std::string(nameOrPath), "(scene)",
                         fmt::format("neither a built-in scene nor a file (did you mean \"{}\"?)", *close));
    throw SceneError(std::string(nameOrPath), "(scene)",
                     fmt::format("neither a built-in scene ({}) nor a file", fmt::join(names, ", ")));
}

} // namespace pba
