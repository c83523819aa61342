#pragma once
// The `ropes` and `cloths` of a scene: each builds its particles and the two-body springs
// between them (docs/scenes.md), and records which particles it made for the renderer.
#include <set>
#include <string>

#include "json_reader.hpp"
#include "pba/fabric.hpp"
#include "pba/world.hpp"

namespace pba::scene_detail {

/// The context a rope or cloth is read in: its particles' names must be new, and their layout
/// is added to `layout`.
struct FabricTarget {
    World& world;
    std::set<std::string>& names;
    FabricLayout& layout;
};

void readRope(const Json& value, const std::string& path, const std::string& file, FabricTarget target);
void readCloth(const Json& value, const std::string& path, const std::string& file, FabricTarget target);

// Shared with the particles' reader (scene_loader.cpp).
Integrator readIntegrator(ObjectReader& reader, const std::string& key, Integrator fallback);
/// Whether a ball of `radius` at x lies inside the ground or room (a point: radius 0).
bool insideSurfaces(const World& world, const dvec3& x, double radius = 0.0);
/// "(x, y, z) lies outside..." for a point, "a ball of radius r at (x, y, z) reaches beyond..." for a ball.
std::string ballOutsideText(const World& world, const dvec3& x, double radius);
/// A particle's (a rope's, a cloth's, a swarm's) "radius" and "friction": not negative, 0 when absent.
struct ContactKeys {
    double radius = 0.0;
    double friction = 0.0;
};
ContactKeys readContactKeys(ObjectReader& reader);
/// "the room spans x -2 to 2, y 0 to 4, z -2 to 2 m" (or the ground's height): the bounds a
/// position outside them is told.
std::string surfacesText(const World& world);
/// "(x, y, z) lies outside the ground or room: " and the bounds.
std::string outsideText(const World& world, const dvec3& x);
std::string readName(ObjectReader& reader, const std::string& key, const std::optional<std::string>& fallback = {});

} // namespace pba::scene_detail
