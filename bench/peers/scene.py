"""The blow-dryer-swarm scene as the peers step it: its numbers, pba's first state, statistics.

Everything is float32, as pba's swarm stores and steps it; each constant is rounded to float32
the way pba rounds it (the scene's doubles converted once, the kernel's derived numbers computed
in float32), so the peers do the same arithmetic as pba's semi-implicit Euler swarm step but for
where a compiler fuses a multiply and an add (pba's AVX-512 clone does; NumPy never does).
"""
import json
import os

import numpy as np

f32 = np.float32
SCENE_FILE = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "scenes", "blow-dryer-swarm.json")
with open(SCENE_FILE) as _f:
    SCENE = json.load(_f)
SWARM = SCENE["swarms"][0]
DRYER = SCENE["forces"][0]
ROOM = SCENE["room"]
# What the peers' step is written for (a change of the scene should fail here, not silently).
assert SCENE["collision_response"] == "reflect" and SWARM["integrator"] == "semi-implicit-euler"
assert DRYER["type"] == "blow-dryer" and DRYER["direction"] == "cone-flow" and DRYER["axis"] == [0, 1, 0]
assert DRYER["nozzle"] == [0, 0, 0] and ROOM["min"][1] == 0 and SCENE["gravity"][0] == SCENE["gravity"][2] == 0
assert DRYER["axial_falloff"] == "linear" and DRYER["radial_falloff"] == "smooth" and "grille_depth" not in DRYER
assert SCENE.get("drag") is None and len(SCENE["forces"]) == 1

DT = f32(SCENE["dt"])
GRAVITY_Y = f32(SCENE["gravity"][1])
E = f32(SWARM["restitution"])
ONE_PLUS_E = f32(1) + E
INV_MASS = f32(1) / f32(SWARM["mass"])
# The dryer's kernel (pba's BlowDryerKernelT<float>, its force scaled by 1 / m once).
H = f32(DRYER["height"])
R0 = f32(DRYER["nozzle_radius"])
INV_H = f32(1) / H
SPREAD = f32(DRYER["top_radius"]) - R0  # R - r0; cone-flow: also the flow's spread
H2 = H * H
SPREAD2 = SPREAD * SPREAD
AXIAL = INV_MASS * f32(DRYER["strength"])  # linear axial falloff: the force on the axis is AXIAL (1 - s)
SHAFT_PUSH = INV_MASS * f32(DRYER["strength"])  # in the hole's shaft: the nozzle's push, along the axis
R0_2 = R0 * R0  # the hole's radius is the nozzle's, squared
# The shaft's wall: a particle at or beyond it is put back just inside (pba's pushIntoShaft).
R_IN = R0 * (f32(1) - f32(16) * np.finfo(np.float32).eps)
# The room (walls with normal +-axis, offsets as float32), and the grille 0.05 m below the hole
# (the scene parser's default grille_depth).
LO = [f32(c) for c in ROOM["min"]]
HI = [f32(c) for c in ROOM["max"]]
GRILLE = f32(float(ROOM["min"][1]) - 0.05)
LANDED_STEPS = 1000  # t = 2 s: where pba bench's landed windows start
RESTED_STEPS = 4000  # t = 8 s: where its rested windows start
PHASE_STEPS = {"flight": 0, "landed": LANDED_STEPS, "rested": RESTED_STEPS}


def mix(z):
    """splitmix64 over uint64 arrays (pba's src/core/swarms/swarm.cpp `mix`); wraps as C++ does."""
    z = z + np.uint64(0x9E3779B97F4A7C15)
    z = (z ^ (z >> np.uint64(30))) * np.uint64(0xBF58476D1CE4E5B9)
    z = (z ^ (z >> np.uint64(27))) * np.uint64(0x94D049BB133111EB)
    return z ^ (z >> np.uint64(31))


def uniform(seed, i, component):
    """pba's `uniform`: a double in [0, 1) from (seed, particle, component)."""
    a = mix(np.array([seed], dtype=np.uint64))
    b = mix(i * np.uint64(8) + np.uint64(component))
    return ((mix(a ^ b) >> np.uint64(11)).astype(np.float64)) * 2.0**-53


def initial_state(n):
    """Six float32 arrays (x, y, z, vx, vy, vz): pba's Swarm(desc) with count n, to the bit."""
    i = np.arange(n, dtype=np.uint64)
    lo, hi = SWARM["region"]["min"], SWARM["region"]["max"]
    seed, jitter = SWARM["seed"], SWARM["velocity_jitter"]
    pos = [(lo[c] + (hi[c] - lo[c]) * uniform(seed, i, c)).astype(np.float32) for c in range(3)]
    vel = [(SWARM["velocity"][c] + jitter * (2.0 * uniform(seed, i, 3 + c) - 1.0)).astype(np.float32) for c in range(3)]
    return pos + vel


def statistics(state, t):
    """pba bench --peer-worker's `stats`: the same figures, computed the same way (in double)."""
    x, y, z = (a.astype(np.float64) for a in state[:3])
    n = max(len(x), 1)
    r = np.sqrt(x * x + z * z)
    height, r0, top = float(DRYER["height"]), float(DRYER["nozzle_radius"]), float(DRYER["top_radius"])
    in_cone = (y >= 0) & (y < height) & (r < r0 + (top - r0) * y / height)
    in_shaft = (y < 0) & (x * x + z * z < r0 * r0)
    bits = sum(int(a.view(np.uint32).sum(dtype=np.uint64)) for a in state) % 2**64
    return {"t": t, "n": len(x), "mean_height": float(y.sum()) / n, "cone_fraction": int(in_cone.sum()) / n,
            "shaft_fraction": int(in_shaft.sum()) / n, "state_bits_sum": bits}
