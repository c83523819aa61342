#include "rigid_body_reader.hpp"

#include <cmath>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include <fmt/format.h>

#include "fabric_readers.hpp"

namespace pba::scene_detail {

ObjMesh readObj(const std::filesystem::path& path)
{
    std::ifstream in(path);
    if (!in)
        throw std::runtime_error("cannot be opened for reading");
    ObjMesh mesh;
    std::string line;
    for (int number = 1; std::getline(in, line); ++number) {
        std::istringstream words(line);
        std::string kind;
        words >> kind;
        if (kind == "v") {
            dvec3 v;
            if (!(words >> v.x >> v.y >> v.z) || !std::isfinite(v.x) || !std::isfinite(v.y) || !std::isfinite(v.z))
                throw std::runtime_error(fmt::format("line {}: a vertex needs three finite numbers", number));
            mesh.vertices.push_back(v);
        } else if (kind == "f") {
            std::vector<std::uint32_t> polygon;
            for (std::string corner; words >> corner;) {
                long index = 0;
                try {
                    index = std::stol(corner.substr(0, corner.find('/')));
                } catch (const std::exception&) {
                    throw std::runtime_error(fmt::format("line {}: '{}' is not a vertex index", number, corner));
                }
                const long count = static_cast<long>(mesh.vertices.size());
                const long resolved = index < 0 ? count + index : index - 1;
                if (index == 0 || resolved < 0 || resolved >= count)
                    throw std::runtime_error(
                        fmt::format("line {}: vertex {} does not exist (there are {} so far)", number, index, count));
                polygon.push_back(static_cast<std::uint32_t>(resolved));
            }
            if (polygon.size() < 3)
                throw std::runtime_error(fmt::format("line {}: a face needs at least three vertices", number));
            for (std::size_t k = 1; k + 1 < polygon.size(); ++k)
                mesh.triangles.insert(mesh.triangles.end(), {polygon[0], polygon[k], polygon[k + 1]});
        }
    }
    if (mesh.triangles.empty())
        throw std::runtime_error("has no faces");
    return mesh;
}

namespace {

Shape readShape(ObjectReader& body, const std::filesystem::path& directory)
{
    ObjectReader shape = body.object("shape");
    if (!shape.has("type")) // a mistyped "type" is named as one, not as a missing type
        shape.expectKeys({"type", "size", "radius", "height", "path"});
    const std::string type = shape.string("type");
    Shape result;
    if (type == "box") {
        shape.expectKeys({"type", "size"});
        const dvec3 size = shape.vec3("size");
        if (!(size.x > 0.0 && size.y > 0.0 && size.z > 0.0))
            shape.fail("size", fmt::format("every side must be positive, got [{}, {}, {}]", size.x, size.y, size.z));
        result = Shape::box(size);
    } else if (type == "sphere") {
        shape.expectKeys({"type", "radius"});
        result = Shape::sphere(shape.positive("radius"));
    } else if (type == "cylinder") {
        shape.expectKeys({"type", "radius", "height"});
        result = Shape::cylinder(shape.positive("radius"), shape.positive("height"));
    } else if (type == "mesh") {
        shape.expectKeys({"type", "path"});
        const std::string relative = shape.string("path");
        if (directory.empty())
            shape.fail("path", "a scene read from text (a built-in scene) cannot name a mesh file: its path would have no folder to start from");
        const std::filesystem::path file = directory / relative;
        try {
            ObjMesh obj = readObj(file);
            result = Shape::mesh(std::move(obj.vertices), std::move(obj.triangles));
        } catch (const std::exception& error) {
            shape.fail("path", fmt::format("{}: {}", file.string(), error.what()));
        }
    } else {
        shape.fail("type", fmt::format("unknown shape '{}' (expected box, sphere, cylinder or mesh)", type));
    }
    shape.finish();
    return result;
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
    const dquat q(value[0].get<double>(), value[1].get<double>(), value[2].get<double>(), value[3].get<double>());
    if (!(glm::length(q) > 0.0) || !std::isfinite(glm::length(q)))
        reader.fail("orientation", "must not be zero (it is normalised, and a zero quaternion has no direction)");
    return glm::normalize(q);
}

} // namespace

void readRigidBody(const Json& value, const std::string& path, const std::string& file,
                   const std::filesystem::path& directory, World& world, std::set<std::string>& names)
{
    ObjectReader reader(value, path, file);
    reader.expectKeys({"name", "shape", "density", "mass", "position", "orientation", "velocity", "angular_velocity",
                       "restitution", "friction", "integrator", "fixed"});
    auto body = std::make_unique<RigidBody>();
    const std::string name = readName(reader, "name");
    if (name.empty())
        reader.fail("name", "must not be empty");
    if (!names.insert(name).second)
        reader.fail("name", fmt::format("another body is already named '{}'", name));
    body->setName(name);
    const Shape shape = readShape(reader, directory);
    if (reader.has("density") && reader.has("mass"))
        reader.fail("mass", "give a density or a mass, not both");
    try {
        if (reader.has("mass"))
            body->setShapeWithMass(shape, reader.positive("mass"));
        else
            body->setShape(shape, reader.positive("density", 1000.0));
    } catch (const std::invalid_argument& error) { // sizes whose mass or inertia overflow, or underflow to zero
        reader.fail(reader.has("mass") ? "mass" : "density", fmt::format("gives no usable mass properties: {}", error.what()));
    }
    body->setPos(reader.vec3("position"));
    body->setOrientation(readOrientation(reader));
    body->setVel(reader.vec3("velocity", dvec3(0.0)));
    body->setAngularVelocity(reader.vec3("angular_velocity", dvec3(0.0)));
    const double restitution = reader.number("restitution", 0.5);
    if (!(restitution >= 0.0 && restitution <= 1.0))
        reader.fail("restitution", fmt::format("must be in [0, 1], got {}", restitution));
    body->setCor(restitution);
    body->setFriction(reader.nonNegative("friction", 0.5));
    body->setIntegrator(readIntegrator(reader, "integrator", Integrator::SemiImplicitEuler));
    body->setFixed(reader.boolean("fixed", false));
    if (!insideSurfaces(world, body->getPos()))
        reader.fail("position", "lies outside the ground or room");
    // A moving body whose centre of mass lies on a surface is half inside it, which its first
    // step reports as a blow-up (World::step): it is bad input, refused here.
    for (const Plane& plane : world.planes())
        if (!body->isFixed() && plane.distance(body->getPos()) == 0.0)
            reader.fail("position", "lies on the ground or a wall of the room: a rigid body's centre must be inside it");
    if (!std::isfinite(body->getRotationalKineticEnergy()))
        reader.fail("angular_velocity", "too large: the rotational kinetic energy is not finite");
    reader.finish();
    world.addBody(std::move(body));
}

} // namespace pba::scene_detail
