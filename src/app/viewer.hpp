#pragma once
// The interactive viewer: a window, the fixed-timestep clock fed by real frame time, the
// scene drawn at the interpolated state beside a docked Dear ImGui control panel.
#include <optional>
#include <string>

#include "viewer_state.hpp"

namespace pba::app {

/// Draws the control panel, docked at the right of the window; may load another scene into
/// `state`. Returns the width it covers (0 when folded), which the scene is drawn beside.
float drawPanel(ViewerState& state);

struct ViewerRun {
    std::optional<int> frames;       ///< close after this many frames of real time
    std::optional<double> time;      ///< capture: synthetic frames to exactly this simulated time
    std::optional<std::string> screenshot; ///< with `time`: save the frame at it here, then close
    std::optional<double> pauseAt;   ///< pause when the simulated time reaches it
    bool lanes = false;
    ClockKind clock = ClockKind::Fixed; ///< `--clock`
    bool noInterpolation = false;       ///< `--no-interpolation`
    std::optional<CameraChoice> camera; ///< `--camera`
    std::optional<std::string> show;    ///< `--show`, already checked
};

/// Frames per second of the capture's synthetic frames (as `pba render`'s default): trails
/// and plots sample the run as a render at that rate does.
inline constexpr int kCaptureFps = 60;

/// Runs the window until it is closed or the run's options end it. Returns an exit code.
int runViewer(Scene scene, const ViewerRun& run);

} // namespace pba::app
