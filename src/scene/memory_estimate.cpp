#include "memory_estimate.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <fstream>
#include <functional>
#include <numbers>
#include <optional>
#include <sstream>
#include <vector>

#include <fmt/format.h>
#include <sys/resource.h>
#include <unistd.h>

namespace pba::scene_detail {

namespace {

// What one thing costs while the scene is built and stepped, from the peak resident memory of
// `pba sim` over scenes of a few hundred to a million of them (rounded up):
/// A particle (of `particles`, a rope or a cloth): the Particle with its name, the names' set
/// node, its entries in the world's per-body arrays and in its coupled group's.
constexpr double kParticleBytes = 850;
/// A spring of a rope or cloth: its link (two indices and three numbers) and the coupled
/// group's per-step data for it.
constexpr double kSpringBytes = 140;
/// A rigid body of a primitive shape: its surface samples and its draw mesh (a sphere's smooth
/// mesh is the largest, a box's eight corners the smallest).
constexpr double kBoxBytes = 10e3;
constexpr double kCylinderBytes = 30e3;
constexpr double kSphereBytes = 45e3;
/// A mesh keeps about 240 bytes a triangle (its indices, a surface sample, three corners of its
/// flat-shaded draw mesh) against the 8 bytes of the shortest face line, "f 1 2 3".
constexpr double kMeshBytesPerFileByte = 30;
/// A swarm's arrays: six floats a particle, and a byte of "clear of every surface" with exact.
constexpr double kSwarmBytesPerParticle = 6 * sizeof(float) + 1;
/// A colliding swarm's grain besides: its copies in cell order, its sort's keys and cells, about
/// three pairs a grain in a heap and their memory for the next step (impulses and slip), the
/// vectors grown (a layer of 10^6 grains settling took 308 MB more than the same layer not
/// colliding did).
constexpr double kGrainContactBytes = 400;

struct Estimate {
    std::string key;  ///< the field the refusal names
    std::string what; ///< "a 1000 x 1000 cloth with 5988004 springs"
    double bytes = 0.0;
};

/// The value at `key` if it is a whole number in [lo, hi] (else its reader refuses it).
std::optional<double> wholeNumber(const Json& object, const std::string& key, double lo, double hi)
{
    if (!object.contains(key) || !object[key].is_number())
        return std::nullopt;
    const double x = object[key].get<double>();
    if (!(x >= lo && x <= hi && std::floor(x) == x))
        return std::nullopt;
    return x;
}

/// Whether `key` holds a positive number: springs of that kind are made.
bool positiveAt(const Json& object, const std::string& key)
{
    return object.contains(key) && object[key].is_number() && object[key].get<double>() > 0.0;
}

/// The vector at `key` if it is three numbers (else its reader refuses it), or zero.
std::array<double, 3> vectorAt(const Json& object, const std::string& key)
{
    std::array<double, 3> v{0.0, 0.0, 0.0};
    if (!object.contains(key) || !object[key].is_array() || object[key].size() != 3)
        return v;
    for (std::size_t k = 0; k < 3; ++k)
        if (object[key][k].is_number())
            v[k] = object[key][k].get<double>();
    return v;
}

double lengthOf(const std::array<double, 3>& v) { return std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]); }

/// A rope's or cloth's neighbour lists, when its particles have a radius (spring_neighbours.hpp):
/// each particle lists those within twice the sum of radii along the springs, about 8 r / s of
/// them along a rope of spacing s and pi (4 r / s)^2 across a cloth, about 8 bytes each while
/// they are made. Nothing for points, or where the spacing is not known.
double neighbourBytes(const Json& fabric, double count, double spacing, bool sheet)
{
    if (!fabric.contains("radius") || !fabric["radius"].is_number() || !(spacing > 0.0))
        return 0.0;
    const double reach = 4.0 * fabric["radius"].get<double>() / spacing;
    if (!(reach > 0.0))
        return 0.0;
    return count * (sheet ? std::numbers::pi * reach * reach : 2.0 * reach) * 8.0;
}

std::optional<Estimate> particleEstimate(const Json&, const std::string& path, const std::filesystem::path&)
{
    return Estimate{path, "a particle", kParticleBytes};
}

std::optional<Estimate> ropeEstimate(const Json& rope, const std::string& path, const std::filesystem::path&)
{
    const auto count = wholeNumber(rope, "count", 2, 100000);
    if (!count)
        return std::nullopt;
    const double springs = *count - 1 + (positiveAt(rope, "bending_stiffness") ? *count - 2 : 0);
    const std::array<double, 3> from = vectorAt(rope, "from"), to = vectorAt(rope, "to");
    const double spacing = lengthOf({to[0] - from[0], to[1] - from[1], to[2] - from[2]}) / (*count - 1);
    return Estimate{path + ".count", fmt::format("a rope of {:.0f} particles and {:.0f} springs", *count, springs),
                    *count * kParticleBytes + springs * kSpringBytes + neighbourBytes(rope, *count, spacing, false)};
}

std::optional<Estimate> clothEstimate(const Json& cloth, const std::string& path, const std::filesystem::path&)
{
    const auto w = wholeNumber(cloth, "columns", 2, 1000), h = wholeNumber(cloth, "rows", 2, 1000);
    if (!w || !h)
        return std::nullopt;
    const Json none = Json::object();
    const Json& k = cloth.contains("stiffness") && cloth["stiffness"].is_object() ? cloth["stiffness"] : none;
    // Structural along rows and columns, two shear springs a cell, bending skipping one particle.
    double springs = (*w - 1) * *h + *w * (*h - 1);
    if (positiveAt(k, "shear"))
        springs += 2 * (*w - 1) * (*h - 1);
    if (positiveAt(k, "bending"))
        springs += (*w - 2) * *h + *w * (*h - 2);
    const double spacing =
        std::min(lengthOf(vectorAt(cloth, "across")) / (*w - 1), lengthOf(vectorAt(cloth, "down")) / (*h - 1));
    return Estimate{path, fmt::format("a {:.0f} x {:.0f} cloth with {:.0f} springs", *w, *h, springs),
                    *w * *h * kParticleBytes + springs * kSpringBytes + neighbourBytes(cloth, *w * *h, spacing, true)};
}

std::optional<Estimate> rigidBodyEstimate(const Json& body, const std::string& path,
                                          const std::filesystem::path& directory)
{
    if (!body.contains("shape") || !body["shape"].is_object() || !body["shape"].contains("type") ||
        !body["shape"]["type"].is_string())
        return std::nullopt;
    const Json& shape = body["shape"];
    const std::string type = shape["type"].get<std::string>();
    if (type == "box")
        return Estimate{path + ".shape", "a box", kBoxBytes};
    if (type == "cylinder")
        return Estimate{path + ".shape", "a cylinder", kCylinderBytes};
    if (type == "sphere")
        return Estimate{path + ".shape", "a sphere", kSphereBytes};
    if (type != "mesh" || !shape.contains("path") || !shape["path"].is_string() || directory.empty())
        return std::nullopt;
    std::error_code error;
    const auto size = std::filesystem::file_size(directory / shape["path"].get<std::string>(), error);
    if (error)
        return std::nullopt;
    return Estimate{path + ".shape.path", fmt::format("a mesh from a file of {:.3g} MB", double(size) / 1e6),
                    double(size) * kMeshBytesPerFileByte + kBoxBytes};
}

std::optional<Estimate> swarmEstimate(const Json& swarm, const std::string& path, const std::filesystem::path&)
{
    const auto count = wholeNumber(swarm, "count", 0, 1e8);
    if (!count)
        return std::nullopt;
    if (swarm.contains("collide") && swarm["collide"] == true)
        return Estimate{path + ".count", fmt::format("{:.0f} colliding swarm grains", *count),
                        *count * (kSwarmBytesPerParticle + kGrainContactBytes)};
    return Estimate{path + ".count", fmt::format("{:.0f} swarm particles", *count), *count * kSwarmBytesPerParticle};
}

/// "1.56 GB", "850 KB".
std::string bytesText(double bytes)
{
    if (bytes >= 1e9)
        return fmt::format("{:.3g} GB", bytes / 1e9);
    if (bytes >= 1e6)
        return fmt::format("{:.3g} MB", bytes / 1e6);
    return fmt::format("{:.3g} KB", bytes / 1e3);
}

/// A number from a line "Key: value kB" of a /proc file, in bytes.
std::optional<double> procKilobytes(const char* file, const std::string& wanted)
{
    std::ifstream in(file);
    for (std::string line; std::getline(in, line);) {
        std::istringstream words(line);
        std::string key;
        double kilobytes = 0.0;
        if (words >> key >> kilobytes && key == wanted)
            return kilobytes * 1024.0;
    }
    return std::nullopt;
}

/// What a limit on this process leaves: the limit less the use /proc/self/status gives under
/// `usedKey`; nothing when unlimited.
std::optional<double> headroom(int resource, const std::string& usedKey)
{
    rlimit limit{};
    if (::getrlimit(resource, &limit) != 0 || limit.rlim_cur == RLIM_INFINITY)
        return std::nullopt;
    return double(limit.rlim_cur) - procKilobytes("/proc/self/status", usedKey).value_or(0.0);
}

/// The bytes this process may still take: the kernel's MemAvailable (the physical memory where
/// that cannot be read), or less where a limit on the process's address space or data leaves
/// less. Nothing where none of them can be read.
std::optional<double> availableMemory()
{
    std::optional<double> available = procKilobytes("/proc/meminfo", "MemAvailable:");
    if (!available) {
        const long pages = ::sysconf(_SC_PHYS_PAGES), size = ::sysconf(_SC_PAGE_SIZE);
        if (pages > 0 && size > 0)
            available = double(pages) * double(size);
    }
    for (const auto& limit : {headroom(RLIMIT_AS, "VmSize:"), headroom(RLIMIT_DATA, "VmData:")})
        if (limit && (!available || *limit < *available))
            available = std::max(0.0, *limit);
    return available;
}

} // namespace

void requireMemoryForBodies(const Json& document, const std::string& file, const std::filesystem::path& directory)
{
    using Estimator = std::function<std::optional<Estimate>(const Json&, const std::string&,
                                                            const std::filesystem::path&)>;
    const std::vector<std::pair<std::string, Estimator>> kinds{{"particles", &particleEstimate},
                                                               {"ropes", &ropeEstimate},
                                                               {"cloths", &clothEstimate},
                                                               {"rigid_bodies", &rigidBodyEstimate},
                                                               {"swarms", &swarmEstimate}};
    if (!document.is_object())
        return;
    const auto available = availableMemory();
    if (!available)
        return;
    double total = 0.0;
    for (const auto& [kind, estimate] : kinds) {
        if (!document.contains(kind) || !document[kind].is_array())
            continue;
        for (std::size_t i = 0; i < document[kind].size(); ++i) {
            const Json& entry = document[kind][i];
            const auto e = entry.is_object() ? estimate(entry, fmt::format("{}[{}]", kind, i), directory) : std::nullopt;
            if (!e)
                continue;
            total += e->bytes;
            if (total > *available)
                throw SceneError(file, e->key,
                                 fmt::format("{} needs about {}, and the scene's bodies up to it {}: more than the {} "
                                             "of memory available", e->what, bytesText(e->bytes), bytesText(total),
                                             bytesText(*available)));
        }
    }
}

} // namespace pba::scene_detail
