#include "picture_options.hpp"

#include <charconv>
#include <cmath>
#include <vector>

#include <fmt/format.h>

#include "command.hpp"

namespace pba::app {

namespace {

std::vector<std::string> split(const std::string& text, char separator)
{
    std::vector<std::string> parts(1);
    for (const char c : text) {
        if (c == separator)
            parts.emplace_back();
        else
            parts.back() += c;
    }
    return parts;
}

std::optional<render::NamedView> viewNamed(const std::string& name)
{
    if (name == "front")
        return render::NamedView::Front;
    if (name == "side")
        return render::NamedView::Side;
    if (name == "top")
        return render::NamedView::Top;
    if (name == "corner")
        return render::NamedView::Corner;
    return std::nullopt;
}

/// A whole field as a finite number, or nothing.
std::optional<double> finiteNumber(const std::string& field)
{
    double value = 0.0;
    const char* end = field.data() + field.size();
    const auto [ptr, error] = std::from_chars(field.data(), end, value);
    if (field.empty() || error != std::errc() || ptr != end || !std::isfinite(value))
        return std::nullopt;
    return value;
}

} // namespace

CameraChoice parseCamera(const std::string& text)
{
    CameraChoice choice;
    if ((choice.view = viewNamed(text)))
        return choice;
    const std::vector<std::string> fields = split(text, ',');
    const std::string expected = fmt::format("expected a view ({}) or X,Y,Z,TX,TY,TZ (the camera's position and the "
                                             "point it looks at, six numbers in metres)", kCameraViews);
    if (fields.size() != 6)
        throw UsageError(fmt::format("--camera: {}, got '{}'", expected, text));
    double v[6];
    for (int k = 0; k < 6; ++k) {
        const auto number = finiteNumber(fields[k]);
        if (!number)
            throw UsageError(fmt::format("--camera: '{}' (number {} of 6) is not a finite number; {}", fields[k], k + 1,
                                         expected));
        v[k] = *number;
    }
    choice.position = glm::vec3(float(v[0]), float(v[1]), float(v[2]));
    choice.target = glm::vec3(float(v[3]), float(v[4]), float(v[5]));
    // Compared as the camera keeps it, in single precision: 0.1 m apart is 0.1f, not below it.
    const double apart = std::hypot(v[0] - v[3], v[1] - v[4], v[2] - v[5]);
    const float kept = float(apart);
    if (!(kept >= render::OrbitCamera::kMinDistance && kept <= render::OrbitCamera::kMaxDistance))
        throw UsageError(fmt::format("--camera: the position and the target must be {:g} to {:g} m apart, got {:.6g} m",
                                     render::OrbitCamera::kMinDistance, render::OrbitCamera::kMaxDistance, apart));
    const float pitch = render::OrbitCamera::pitchOf(choice.position, choice.target);
    if (std::abs(pitch) > render::OrbitCamera::kMaxPitch)
        throw UsageError(fmt::format("--camera: the position is straight {} the target ({:.1f} degrees from level, at "
                                     "most {:.1f}); move it sideways, or use --camera top",
                                     pitch > 0 ? "above" : "below", std::abs(pitch) * 57.29578f,
                                     render::OrbitCamera::kMaxPitch * 57.29578f));
    return choice;
}

static_assert(float(SceneCamera::kMinDistance) == render::OrbitCamera::kMinDistance &&
              float(SceneCamera::kMaxDistance) == render::OrbitCamera::kMaxDistance &&
              float(SceneCamera::kMaxPitch) == render::OrbitCamera::kMaxPitch,
              "a scene's camera takes what --camera takes");

render::OrbitCamera cameraFor(const std::optional<CameraChoice>& choice, const World& world,
                              const std::optional<SceneCamera>& sceneCamera)
{
    const render::OrbitCamera framing = render::frameWorld(world);
    if (choice && choice->view)
        return render::namedView(*choice->view, framing);
    if (!choice && !sceneCamera)
        return framing;
    const glm::vec3 position = choice ? choice->position : glm::vec3(sceneCamera->position);
    const glm::vec3 target = choice ? choice->target : glm::vec3(sceneCamera->target);
    render::OrbitCamera camera = render::OrbitCamera::lookingFrom(position, target);
    camera.fovY = framing.fovY;
    return camera;
}

bool framingCamera(const std::optional<CameraChoice>& choice, const std::optional<SceneCamera>& sceneCamera)
{
    return choice ? choice->view.has_value() : !sceneCamera;
}

void applyShow(const std::string& list, render::ViewSettings& settings)
{
    for (const std::string& name : split(list, ',')) {
        if (name == "contacts")
            settings.contacts = true;
        else if (name == "joints")
            settings.joints = true;
        else if (name == "axes")
            settings.axes = true;
        else if (name.empty())
            throw UsageError(fmt::format("--show: an empty name in '{}' (expected a comma-separated list of {})", list,
                                         kShowNames));
        else
            throw UsageError(fmt::format("--show: unknown mark '{}' (expected a comma-separated list of {})", name,
                                         kShowNames));
    }
}

void addPictureFlags(CLI::App& command, std::optional<std::string>& camera, std::optional<std::string>& show)
{
    command.add_option("--camera", camera,
                       fmt::format("Where the camera stands: a view of the room ({}), or X,Y,Z,TX,TY,TZ, its "
                                   "position and the point it looks at, in metres (default: the scene's own "
                                   "camera, if it gives one, else the whole room from above a corner)",
                                   kCameraViews))
        ->type_name("VIEW|X,Y,Z,TX,TY,TZ");
    command.add_option("--show", show,
                       fmt::format("Marks drawn over the scene, comma-separated: contacts (each contact point and "
                                   "its normal, longer the harder it pushes, of rigid bodies and balls; not a "
                                   "swarm's grains'), joints (each joint's point on each "
                                   "body, a hinge's axis), axes (each rigid body's axes, omega and L arrows); "
                                   "any of {}", kShowNames))
        ->type_name("LIST");
}

} // namespace pba::app
