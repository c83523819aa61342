#pragma once
// The fixed-timestep clock of Glenn Fiedler's "Fix Your Timestep": real frame time
// fills an accumulator and the physics drains it in steps of exactly dt ("Free the
// physics"); what is left, as a fraction of dt, is the alpha with which a renderer
// blends the previous and the current state ("The final touch").
//
// The frame time only decides how many steps run now, never their length: the
// physics depends on dt and the number of steps alone.
#include <cstdint>

namespace pba {

class FixedTimestepClock {
public:
    static constexpr double kDefaultMaxFrameTime = 0.25; ///< s: longer frames are clamped
    static constexpr int kDefaultMaxStepsPerFrame = 500;
    /// A step short of dt by at most this fraction of it is the sum's rounding, and is taken.
    static constexpr double kRoundingTolerance = 1e-9;

    /// Throws std::invalid_argument for a dt, clamp or step cap that is not finite and positive.
    explicit FixedTimestepClock(double dt, double maxFrameTime = kDefaultMaxFrameTime,
                                int maxStepsPerFrame = kDefaultMaxStepsPerFrame);

    /// Feeds one frame's real duration and returns the number of steps of dt to take now.
    /// The frame time is clamped to maxFrameTime (against the spiral of death: a slow frame
    /// would ask for more steps, which make the next frame slower still). Steps beyond the
    /// cap are dropped, whole dt's at a time, so alpha stays in [0, 1).
    /// A frame time that is zero, negative or not finite throws std::invalid_argument and
    /// changes nothing.
    int advance(double frameTime);

    /// Accumulator / dt, in [0, 1): how far the present lies between the last two states.
    double alpha() const { return accumulator() / m_dt; }

    double dt() const { return m_dt; }
    /// Changing dt keeps alpha (the fraction of a step already accumulated).
    void setDt(double dt);
    double maxFrameTime() const { return m_maxFrameTime; }
    void setMaxFrameTime(double seconds);
    int maxStepsPerFrame() const { return m_maxStepsPerFrame; }
    void setMaxStepsPerFrame(int steps);

    double accumulator() const { return m_accumulator + m_compensation; }
    /// Simulated time given up to the clamp and the step cap since the last reset.
    double droppedTime() const { return m_dropped; }
    std::uint64_t totalSteps() const { return m_totalSteps; }
    void reset();

private:
    double m_dt;
    double m_maxFrameTime;
    int m_maxStepsPerFrame;
    /// The accumulator as a compensated (Neumaier) sum, m_accumulator + m_compensation: a
    /// plain sum of frame times loses an ulp a frame, and a long run a whole step.
    void accumulate(double seconds);
    double m_accumulator = 0.0;
    double m_compensation = 0.0;
    double m_dropped = 0.0;
    std::uint64_t m_totalSteps = 0;
};

} // namespace pba
