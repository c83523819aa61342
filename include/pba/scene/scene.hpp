#pragma once
// Scenes: JSON files (documented in docs/scenes.md) that build a World. This library
// sits on top of the core; the core itself knows no file format.
#include <filesystem>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "pba/fabric.hpp"
#include "pba/world.hpp"

namespace pba {

/// Where a picture of the scene looks from unless told otherwise (the scene's `camera`): a
/// position and the point it looks at, kMinDistance to kMaxDistance apart, and not straight
/// above or below it (at most kMaxPitch from level), as `--camera X,Y,Z,TX,TY,TZ` takes them.
struct SceneCamera {
    dvec3 position{0.0};
    dvec3 target{0.0};
    static constexpr double kMinDistance = 0.1;
    static constexpr double kMaxDistance = 1000.0;
    static constexpr double kMaxPitch = 1.5; ///< rad
};

/// A scene as loaded: the world at t = 0 plus how long and with which dt to run it.
struct Scene {
    std::string name;
    std::string summary;     ///< one line for lists (`pba scenes`, --help)
    std::string description;
    double dt = 0.01;        ///< s
    double duration = 10.0;  ///< s
    World world;
    FabricLayout fabric;     ///< which of the world's particles form its ropes and cloths
    std::optional<SceneCamera> camera;
    std::vector<std::size_t> dice; ///< the bodies drawn as dice (`"die": true`), ascending
    std::string source;      ///< file path, or "builtin:NAME"
};

/// Bad input: names the file, the field (as a JSON path such as particles[1].mass) and the reason.
/// what() is the one-line message "FILE: FIELD: REASON".
class SceneError : public std::runtime_error {
public:
    SceneError(std::string file, std::string field, std::string reason);
    const std::string& file() const { return m_file; }
    const std::string& field() const { return m_field; }
    const std::string& reason() const { return m_reason; }

private:
    std::string m_file;
    std::string m_field;
    std::string m_reason;
};

/// Parses scene JSON text; `source` names it in errors.
Scene parseScene(std::string_view json, const std::string& source);
/// Reads and parses a scene file.
Scene loadSceneFile(const std::filesystem::path& path);
/// A built-in scene name ("integrators") or a path to a JSON file.
Scene loadScene(std::string_view nameOrPath);

/// The built-in cloth-in-the-dryer with a sheet of `side` x `side` particles instead of 10 x 10,
/// the same weight in all: its springs' stiffness and damping and the dryer's strength scale
/// with each particle's mass, so every particle's accelerations and the step's stability
/// (omega dt) are the built-in's. The workload of `pba bench`'s cloth row (128 x 128: 16,384
/// particles, 97,026 springs) and of the tests that step it on any number of threads.
Scene resizedClothInTheDryer(int side);

/// The built-in dice scene's room, gravity and dice (restitution, friction) with `count` 10 cm
/// dice instead of its own and without its tray, each thrown from its own place in the room with its own velocity, spin
/// and orientation (numbers that depend on the die's index alone): the places are cells of a
/// lattice over the whole room, each die jittered within its cell, so no two dice overlap at the
/// start. The workload of `pba bench`'s pile rows and bench/peers/pile.py (1,000 and 10,000 dice)
/// and of the tests that step it on any number of threads. std::invalid_argument for no dice or
/// for more than the room's cells (10,648).
Scene manyDice(std::size_t count);

/// The built-in scenes, shipped as files in scenes/ and compiled into the library.
std::vector<std::string> builtinSceneNames();
/// The JSON text of a built-in scene, or an empty view if there is none of that name.
std::string_view builtinSceneText(std::string_view name);
/// The one-line summary of a built-in scene (its "summary"), read without building its world
/// (a swarm's arrays are not allocated to list it); empty if there is no such scene.
std::string builtinSceneSummary(std::string_view name);

} // namespace pba
