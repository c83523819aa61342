#pragma once
// The clocks study (`pba compare --clocks`): Task 2's lesson, a robust approach to timing,
// measured. One scene is run with each clock (frame_clock.hpp) at 30, 60 and 144 frames a second,
// steady and with one frame that takes kHitchSeconds (a simulated stall: a disk, a page fault, a
// window dragged), and the runs at 30 and 144 Hz are compared with the one at 60 Hz at the frames
// all three share (every 1/6 s). With the fixed clock the physics depends on dt and the step
// count alone, so the runs agree to the bit; with the variable clock every frame rate is a
// different dt, and the hitch is one step of a quarter of a second.
#include <array>
#include <limits>
#include <string>
#include <vector>

#include "pba/frame_clock.hpp"
#include "pba/scene/scene.hpp"

namespace pba::study {

inline constexpr std::array<int, 3> kClockRates{30, 60, 144};
inline constexpr int kClockReferenceRate = 60;
/// The frames all three rates share: 1/6 s apart (5, 10 and 24 frames).
inline constexpr double kClockSampleSeconds = 1.0 / 6.0;
/// The hitch: at kHitchAt s, one frame of kHitchSeconds (the fixed clock's clamp, so it keeps all of it).
inline constexpr double kHitchAt = 1.0;
inline constexpr double kHitchSeconds = 0.25;
/// The shortest run the study takes: the hitch, and a second after it.
inline constexpr double kClockMinDuration = kHitchAt + kHitchSeconds + 1.0;

struct ClockConfig {
    Scene scene;
    double dt = 0.01; ///< the fixed clock's dt, and the semi-fixed clock's longest step
    double duration = 10.0;
};

/// One run: a clock at a frame rate, steady or with the hitch, sampled at the shared frames.
struct ClockRun {
    ClockKind clock{};
    int rate = 60;
    bool hitch = false;
    std::uint64_t steps = 0;
    double shortestStep = 0.0, longestStep = 0.0;
    std::vector<double> t;                    ///< the shared frames' (wall-clock) times, s
    std::vector<std::vector<dvec3>> position; ///< each moving body's position at each of them
    double blewUpAt = std::numeric_limits<double>::quiet_NaN(); ///< wall-clock time of a blow-up
    std::string blowUp;                                         ///< its message
};

/// The distance of a run at 30 or 144 Hz from the run at 60 Hz of its clock and hitch.
struct ClockDrift {
    ClockKind clock{};
    int rate = 30;
    bool hitch = false;
    std::vector<double> t, distance; ///< the largest distance of a moving body, m, at each shared frame
    double maxDistance = 0.0;         ///< NaN if either run blew up
    bool identical = false;           ///< every sample equal to the bit
};

struct ClockResult {
    std::vector<ClockRun> runs;     ///< clock by clock, steady then hitch, rate by rate
    std::vector<ClockDrift> drifts; ///< clock by clock, steady then hitch, 30 then 144 Hz
};

/// Runs every clock, rate and hitch. Throws std::invalid_argument for a duration below
/// kClockMinDuration or a dt that is not positive.
ClockResult runClockStudy(const ClockConfig& config);

/// The frame times of a run: 1/rate apart, with the hitch if asked, up to `duration`; the
/// frame times are differences of k / rate, so the shared frames fall on the same times.
std::vector<double> frameTimes(int rate, bool hitch, double duration);

} // namespace pba::study
