#pragma once
// What `pba render` and `pba view` take about the picture itself: where the camera stands
// (`--camera`: a named view, or a position and a target) and which marks are drawn (`--show`:
// contacts, joints, axes). Parsed before any work, each bad value one line naming the flag.
#include <optional>
#include <string>

#include <CLI/CLI.hpp>
#include <glm/glm.hpp>

#include "pba/scene/scene.hpp"
#include "pba/world.hpp"
#include "render/camera.hpp"
#include "render/world_view.hpp"

namespace pba::app {

/// A --camera value: a named view, or a position and a target (world coordinates, metres).
struct CameraChoice {
    std::optional<render::NamedView> view;
    glm::vec3 position{0.0f};
    glm::vec3 target{0.0f};
};

/// "front", "side", "top", "corner", or "X,Y,Z,TX,TY,TZ". Throws UsageError naming --camera:
/// not six finite numbers, the two points less than 0.1 m or more than 1000 m apart, or the
/// position straight above or below the target (where no view is upright).
CameraChoice parseCamera(const std::string& text);

/// The camera a choice gives for this scene: a named view keeps the framing camera's target
/// and distance; without a choice, the scene's own camera, or else the framing camera.
render::OrbitCamera cameraFor(const std::optional<CameraChoice>& choice, const World& world,
                              const std::optional<SceneCamera>& sceneCamera);
/// Whether that camera is a framing one, which may move to keep the room out of the legend's
/// corner (a camera placed by hand, on the command line or in the scene, stays put).
bool framingCamera(const std::optional<CameraChoice>& choice, const std::optional<SceneCamera>& sceneCamera);

/// "contacts,joints,axes" (any of them, in any order): turns those marks on. Throws UsageError
/// naming --show for an empty list or an unknown name.
void applyShow(const std::string& list, render::ViewSettings& settings);

/// Adds --camera and --show to a command that draws.
void addPictureFlags(CLI::App& command, std::optional<std::string>& camera, std::optional<std::string>& show);

/// The names --show takes, for its help and its errors.
inline constexpr const char* kShowNames = "contacts, joints, axes";
inline constexpr const char* kCameraViews = "front, side, top, corner";

} // namespace pba::app
