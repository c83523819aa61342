#pragma once
// How the rigid bodies' contacts and joints are solved, and when a body sleeps: the knobs a
// program (or a scene, or `pba bench`) may turn. The defaults suit the built-in scenes.
namespace pba {

struct ContactSettings {
    /// Sweeps of the velocity pass (sequential impulses, warm-started) every step...
    int velocityIterations = 10;
    /// ...and past that while the contacts' impulses still change, at most this many in all: a
    /// warm-started pile needs the first few, a tower's new contacts dozens. Set it to
    /// velocityIterations for a fixed count (as an engine compared sweep for sweep).
    int maxVelocityIterations = 64;
    /// Sweeps of the position pass, which pushes apart what overlaps beyond linearSlop (m) by
    /// baumgarte of the overlap a sweep, on the poses alone. Over throws of 700 to 1,300 dice the
    /// landing's deepest overlap, looked at every step, was 4.8-8.3 mm with 8 sweeps and 1.8-4.1
    /// mm with 16; since the pass looks again where it moved a body beyond its contacts' reach
    /// and holds what the room pushed out, 1.2-1.8 mm in ten throws of 600 to 2,000 dice.
    int positionIterations = 16;
    double linearSlop = 0.0005;
    double baumgarte = 0.8;
    /// Contacts are kept while the shapes are this much (m) further apart than their free motion
    /// in the step could close, so a resting contact keeps its points, and its impulses, from step
    /// to step. It is also the warning a body has of being struck within the step into another
    /// (a die on the heap knocked down by one landing on it); a body that a partner comes towards
    /// faster than this a step reaches as far as it may be pushed. Over throws of 600 to 2,000
    /// dice, looked at every step, the landing's deepest overlap was 1.5 to 16.6 mm (over 5 mm in
    /// 10 throws of 13) before that reach, 1.4 to 6.2 mm (1 of 13) with it.
    double contactMargin = 0.01;
    /// Whether still islands sleep: a body slower than sleepSpeed (m/s; its centre, or its furthest
    /// point turning) for timeToSleep seconds, with all of its island, sleeps until touched.
    bool sleeping = true;
    double sleepSpeed = 0.03;
    double timeToSleep = 0.5;
};

} // namespace pba
