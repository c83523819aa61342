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
    /// baumgarte of the overlap a sweep, on the poses alone.
    int positionIterations = 8;
    double linearSlop = 0.0005;
    double baumgarte = 0.8;
    /// Contacts are kept while the shapes are this much (m) further apart than their motion in
    /// the step could close, so a resting contact keeps its points, and its impulses, from step to step.
    double contactMargin = 0.005;
    /// Whether still islands sleep: a body slower than sleepSpeed (m/s; its centre, or its furthest
    /// point turning) for timeToSleep seconds, with all of its island, sleeps until touched.
    bool sleeping = true;
    double sleepSpeed = 0.03;
    double timeToSleep = 0.5;
};

} // namespace pba
