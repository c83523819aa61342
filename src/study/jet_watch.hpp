#pragma once
// What bodies and swarms do in a blow dryer's jet over a run: how much of the time each body
// spends in the cone, when the jet first holds it, how high it hovers, and how long it ever
// lies in the hole under the floor. `pba sim` prints these; the tests hold the built-in scenes'
// descriptions to them.
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "pba/blow_dryer.hpp"
#include "pba/detail/blow_dryer_kernel.hpp"
#include "pba/world.hpp"

namespace pba::study {

/// A stay in the cone this long counts as a catch: a ball thrown across the cone, or bounced
/// through it, leaves it well within this time.
inline constexpr double kCatchStay = 2.0;

struct BodyInJet {
    std::string name;
    double mass = 0.0;
    bool liftable = false;       ///< the dryer's strength exceeds m g: it can lift the body
    double timeInCone = 0.0;     ///< s
    double longestStay = 0.0;    ///< the longest time in the cone without leaving it, s
    std::optional<double> caughtAt; ///< start of the first stay of kCatchStay or more, s
    double meanHeightInCone = 0.0;  ///< m, over the steps spent in the cone (NaN if none)
    double meanOffAxisInCone = 0.0; ///< its distance from the axis, m, likewise: the Bernoulli pull's work
    double longestInShaft = 0.0;    ///< the longest time under the floor's hole without leaving it, s
};

class ShaftLister; // jet_watch.cpp

class JetWatch {
public:
    /// Watches the world's first blow dryer; inactive (nothing recorded) without one.
    explicit JetWatch(const World& world);
    JetWatch(JetWatch&&) noexcept;
    JetWatch& operator=(JetWatch&&) noexcept;
    ~JetWatch();

    /// While it lives, the swarms' particles under the hole are listed as the world's step
    /// finishes with each range of them, still in the core's caches, instead of in a pass of
    /// record's own over every height: the same figures (`pba sim fountain-1m` 0.96 times as
    /// long as with the watch's own pass). It must go before the watch and the world do.
    class Attachment {
    public:
        Attachment(Attachment&& other) noexcept : m_world(std::exchange(other.m_world, nullptr)) {}
        Attachment& operator=(Attachment&&) = delete;
        ~Attachment();

    private:
        friend class JetWatch;
        explicit Attachment(World* world) : m_world(world) {}
        World* m_world;
    };
    [[nodiscard]] Attachment attach(World& world);
    /// Steps whose lists were made inside the step (while attached), for the tests.
    std::uint64_t stepsListedInStep() const { return m_listedInStep; }
    bool active() const { return m_field.has_value(); }
    const BlowDryerField& field() const { return *m_field; }

    /// Call after every step.
    void record(const World& world);
    /// The figures so far, one per body (fixed bodies included, for indexing by body).
    std::vector<BodyInJet> bodies() const;
    /// The fraction of the watched time body i spent in the cone.
    double fractionInCone(std::size_t i) const;
    double watchedTime() const { return m_watched; }
    /// Particles of each swarm under the floor's hole now.
    std::vector<std::size_t> swarmsInShaft(const World& world) const;

    /// How many particles of a swarm are in the cone is counted every kSwarmSample seconds of
    /// simulated time; whether each is under the hole, every step (see countStepsInShaft).
    static constexpr double kSwarmSample = 0.1;
    struct SwarmInJet {
        std::size_t peakInCone = 0;   ///< the most particles in the cone at one count
        double peakAt = 0.0;          ///< when, s
        double longestInShaft = 0.0;  ///< the longest any particle stayed under the hole, s
    };
    const std::vector<SwarmInJet>& swarms() const { return m_swarms; }

    /// A particle under the hole, and how many steps in a row it has been there.
    struct ShaftStay {
        std::size_t index;
        std::uint32_t steps;
    };

private:
    void lookAtSwarms(const World& world);
    void countStepsInShaft(const World& world);
    void noteLongest(const World& world, std::size_t s);

    struct Track {
        BodyInJet figures;
        double stay = 0.0, stayStart = 0.0, shaftStay = 0.0, heightTime = 0.0, offAxisTime = 0.0;
    };
    std::optional<BlowDryerField> m_field;
    std::vector<Track> m_tracks;
    std::vector<SwarmInJet> m_swarms;
    std::vector<std::vector<ShaftStay>> m_inShaft; ///< per swarm: its particles under the hole, by index
    std::vector<std::vector<ShaftStay>> m_segmentLists; ///< its segments' lists, made on all cores
    std::vector<std::unique_ptr<ShaftLister>> m_listers; ///< per swarm, once attached: its lists by range
    std::vector<ShaftStay> m_listed;                     ///< a lister's list, swapped in
    std::uint64_t m_listedInStep = 0;
    std::vector<std::uint32_t> m_longestSteps;     ///< per swarm: the most steps in a row
    double m_nextLook = 0.0;
    double m_watched = 0.0;
};

} // namespace pba::study
