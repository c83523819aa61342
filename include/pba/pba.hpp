#pragma once
// Everything of the physics core in one include.
#include "pba/blow_dryer.hpp"
#include "pba/body.hpp"
#include "pba/clock.hpp"
#include "pba/collision.hpp"
#include "pba/force.hpp"
#include "pba/forces.hpp"
#include "pba/integrator.hpp"
#include "pba/mesh.hpp"
#include "pba/particle.hpp"
#include "pba/state.hpp"
#include "pba/world.hpp"
