#include "rigid_body_reader.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <fmt/format.h>

#include "fabric_readers.hpp"
#include "one_line.hpp"
#include "pba/scene/scene.hpp"

namespace pba::scene_detail {

std::optional<std::string> sizeProblem(const Shape& shape)
{
    std::optional<MassProperties> unit;
    try {
        unit = massPropertiesOf(shape, 1.0);
        const RigidBody probe(*unit); // its checks of a mass and an inertia tensor
        return std::nullopt;
    } catch (const std::invalid_argument& error) {
        if (!unit) // not computed at all: the shape's own reason
            return error.what();
        const bool large = !(unit->mass < 1.0);
        return fmt::format("too {}: at 1 kg/m^3 its mass and inertia {} ({})", large ? "large" : "small",
                           large ? "overflow" : "underflow to zero", error.what());
    }
}

namespace {

constexpr double kDefaultDensity = 1000.0; // kg/m^3, water's

/// What a body's `shape` gave: a box's, sphere's or cylinder's Shape, or the scene's body of an
/// OBJ file (MeshLibrary); and the key that sets its size, to blame for a size no mass fits.
struct ShapeRead {
    Shape shape;
    const RigidBody* mesh = nullptr;
    std::string sizeKey; ///< e.g. rigid_bodies[0].shape.radius
};

const RigidBody& readMesh(ObjectReader& shape, const std::filesystem::path& directory, MeshLibrary& meshes)
{
    const std::string relative = shape.string("path");
    if (directory.empty())
        shape.fail("path", "a scene read from text (a built-in scene) cannot name a mesh file: its path would have no folder to start from");
    // The system ends a path at its first NUL byte: "cube.obj", a NUL and "ignored" would open cube.obj.
    if (const auto nul = relative.find('\0'); nul != std::string::npos)
        shape.fail("path", fmt::format("contains a NUL byte (at offset {}), which no path can hold", nul));
    const std::filesystem::path file = directory / relative;
    try {
        return meshes.body(file);
    } catch (const std::exception& error) {
        shape.fail("path", fmt::format("{}: {}", oneLine(file.string(), kShownPathLength), error.what()));
    }
}

ShapeRead readShape(ObjectReader& body, const std::filesystem::path& directory, MeshLibrary& meshes)
{
    ObjectReader shape = body.object("shape");
    if (!shape.has("type")) // a mistyped "type" is named as one, not as a missing type
        shape.expectKeys({"type", "size", "radius", "height", "path"});
    const std::string type = shape.string("type");
    ShapeRead result;
    if (type == "box") {
        shape.expectKeys({"type", "size"});
        const dvec3 size = shape.vec3("size");
        if (!(size.x > 0.0 && size.y > 0.0 && size.z > 0.0))
            shape.fail("size", fmt::format("every side must be positive, got [{}, {}, {}]", size.x, size.y, size.z));
        result = {Shape::box(size), nullptr, shape.pathOf("size")};
    } else if (type == "sphere") {
        shape.expectKeys({"type", "radius"});
        result = {Shape::sphere(shape.positive("radius")), nullptr, shape.pathOf("radius")};
    } else if (type == "cylinder") {
        shape.expectKeys({"type", "radius", "height"});
        const double radius = shape.positive("radius"), height = shape.positive("height");
        // The one further from 1 m, in orders of magnitude, is the one that makes it extreme.
        const bool byRadius = std::abs(std::log(radius)) >= std::abs(std::log(height));
        result = {Shape::cylinder(radius, height), nullptr, shape.pathOf(byRadius ? "radius" : "height")};
    } else if (type == "mesh") {
        shape.expectKeys({"type", "path"});
        result.mesh = &readMesh(shape, directory, meshes);
        result.sizeKey = shape.pathOf("path");
    } else {
        shape.fail("type", fmt::format("unknown shape '{}' (expected box, sphere, cylinder or mesh)", oneLine(type)));
    }
    shape.finish();
    return result;
}

/// The body's mass properties, from its `density` or `mass`. What no mass fits is blamed on
/// the shape's size when the shape is too large or too small at any density, else on the key
/// that was given.
void giveMass(ObjectReader& reader, const ShapeRead& shape, RigidBody& body)
{
    if (reader.has("density") && reader.has("mass"))
        reader.fail("mass", "give a density or a mass, not both");
    const bool byMass = reader.has("mass");
    const double amount = byMass ? reader.positive("mass") : reader.positive("density", kDefaultDensity);
    try {
        if (shape.mesh) { // the library's body has the mesh's mass properties at 1 kg/m^3
            const MassProperties unit{shape.mesh->getMass(), dvec3(0.0), shape.mesh->getInertiaBody()};
            body.setMassProperties(unit.withMass(byMass ? amount : amount * unit.mass));
        } else if (byMass) {
            body.setShapeWithMass(shape.shape, amount);
        } else {
            body.setShape(shape.shape, amount);
        }
    } catch (const std::invalid_argument& error) { // sizes whose mass or inertia overflow, or underflow to zero
        if (const auto problem = shape.mesh ? std::nullopt : sizeProblem(shape.shape))
            throw SceneError(reader.file(), shape.sizeKey, *problem);
        const std::string key = byMass ? "mass" : "density";
        if (!reader.has(key))
            throw SceneError(reader.file(), shape.sizeKey,
                             fmt::format("at the default density, {} kg/m^3, its mass and inertia cannot be "
                                         "represented ({}): give a density",
                                         kDefaultDensity, error.what()));
        reader.fail(key, fmt::format("gives no usable mass properties with this shape: {}", error.what()));
    }
}

dquat readOrientation(ObjectReader& reader)
{
    if (!reader.has("orientation"))
        return dquat(1.0, 0.0, 0.0, 0.0);
    const Json& value = reader.raw("orientation");
    if (!value.is_array() || value.size() != 4 || !std::all_of(value.begin(), value.end(), [](const Json& x) {
            return x.is_number() && std::isfinite(x.get<double>());
        }))
        reader.fail("orientation", "must be a quaternion [w, x, y, z] of four finite numbers");
    const dquat q = unitOrZero(
        dquat(value[0].get<double>(), value[1].get<double>(), value[2].get<double>(), value[3].get<double>()));
    if (q == dquat(0.0, 0.0, 0.0, 0.0))
        reader.fail("orientation", "must not be zero (it is normalised, and a zero quaternion has no direction)");
    return q;
}

} // namespace

bool readRigidBody(const Json& value, const std::string& path, const std::string& file,
                   const std::filesystem::path& directory, World& world, std::set<std::string>& names,
                   MeshLibrary& meshes)
{
    ObjectReader reader(value, path, file);
    reader.expectKeys({"name", "shape", "density", "mass", "position", "orientation", "velocity", "angular_velocity",
                       "restitution", "friction", "integrator", "fixed", "die"});
    const std::string name = readName(reader, "name");
    if (name.empty())
        reader.fail("name", "must not be empty");
    if (!names.insert(name).second)
        reader.fail("name", fmt::format("another body is already named '{}'", oneLine(name)));
    const ShapeRead shape = readShape(reader, directory, meshes);
    // A mesh's body is a copy of the library's: it shares the mesh and what is made from it.
    auto body = shape.mesh ? std::make_unique<RigidBody>(*shape.mesh) : std::make_unique<RigidBody>();
    body->setName(name);
    giveMass(reader, shape, *body);
    body->setPos(reader.vec3("position"));
    body->setOrientation(readOrientation(reader));
    body->setVel(reader.vec3("velocity", dvec3(0.0)));
    body->setAngularVelocity(reader.vec3("angular_velocity", dvec3(0.0)));
    const double restitution = reader.number("restitution", 0.5);
    if (!(restitution >= 0.0 && restitution <= 1.0))
        reader.fail("restitution", fmt::format("must be in [0, 1], got {}", restitution));
    body->setCor(restitution);
    body->setFriction(reader.nonNegative("friction", 0.5));
    body->setIntegrator(readIntegrator(reader, "integrator", kDefaultRigidIntegrator));
    if (isSpringSystemMethod(body->getIntegrator()))
        reader.fail("integrator", fmt::format("{} steps particles joined by springs, not rigid bodies: take "
                                              "forward-euler, semi-implicit-euler, velocity-verlet, rk4, "
                                              "implicit-gyroscopic or splitting",
                                              integratorName(body->getIntegrator())));
    body->setFixed(reader.boolean("fixed", false));
    if (body->isFixed()) { // it never moves: its velocities would count in the summary's speed and energy
        body->setVel(dvec3(0.0));
        body->setAngularVelocity(dvec3(0.0));
    }
    if (!std::isfinite(body->getRotationalKineticEnergy()))
        reader.fail("angular_velocity", "too large: the rotational kinetic energy is not finite");
    const bool die = reader.boolean("die", false);
    const dvec3& side = shape.shape.size;
    if (die && (shape.shape.type != ShapeType::Box || side.x != side.y || side.y != side.z))
        reader.fail("die", "a die is a cube: its shape must be a box of three equal sides");
    reader.finish();
    world.addBody(std::move(body));
    return die;
}

} // namespace pba::scene_detail
