"""The NumPy peer: pba's semi-implicit Euler step of blow-dryer-swarm as whole-array operations.

The same arithmetic as numba_peer.step, particle for particle: the dryer's force (cone-flow in
its cone, the nozzle's push in the hole's shaft), the step, then the reflect rule's pass over
the room's six walls and the grille, the floor's hole and its shaft wall as selects.
"""
import numpy as np

from scene import (AXIAL, DT, E, GRAVITY_Y, GRILLE, H, H2, HI, INV_H, LO, ONE_PLUS_E, R0, R0_2, R_IN,
                   SHAFT_PUSH, SPREAD, SPREAD2, f32)


def step(s):
    """One step of dt for the six float32 arrays s = [x, y, z, vx, vy, vz], in place."""
    x, y, z, vx, vy, vz = s
    start_y = y.copy()
    with np.errstate(divide="ignore", invalid="ignore"):
        # The dryer's acceleration (outside the cone q may be <= 0: only the selects read it).
        r2 = x * x + z * z
        r = np.sqrt(r2)
        h = y * INV_H
        q = R0 + SPREAD * h
        in_shaft = (y < 0) & (r2 < R0_2)
        inside = (y >= 0) & (h < 1) & (r < q)
        inv_q = f32(1) / q
        u = f32(1) - r * inv_q
        magnitude = ((f32(1) - h) * AXIAL) * (u * (u * (f32(3) - f32(2) * u)))
        scale = np.where(inside, magnitude * (q / np.sqrt(H2 * q * q + SPREAD2 * r2)), f32(0))
        radial = np.where(inside, (scale * SPREAD) * inv_q, f32(0))
        along = np.where(in_shaft, SHAFT_PUSH, scale * H)
    # Semi-implicit Euler.
    vx += (radial * x) * DT
    vy += (GRAVITY_Y + along) * DT
    vz += (radial * z) * DT
    x += vx * DT
    y += vy * DT
    z += vz * DT
    # The floor (y = 0), with the hole: over the hole, or already in the shaft, a particle passes.
    rho2 = x * x + z * z
    excused = (rho2 < R0_2) | (start_y < 0)
    below = y < 0
    bounce = below & ~excused & (vy < 0)
    y[...] = np.where(below & ~excused, -y, y)
    vy -= np.where(bounce, ONE_PLUS_E * vy, f32(0))
    # The shaft's wall: a particle in the shaft at or beyond it is put just inside, and its
    # outward radial velocity reflected.
    rs = np.sqrt(rho2)
    at_wall = below & excused & ~(rs < R0) & (rs > 0)
    with np.errstate(divide="ignore", invalid="ignore"):
        ox, oz = x / rs, z / rs  # read only at the wall
    vr = vx * ox + vz * oz
    back = -(rs - R_IN)
    wall_bounce = at_wall & (vr > 0)
    x[...] = np.where(at_wall, x + back * ox, x)
    z[...] = np.where(at_wall, z + back * oz, z)
    vx[...] = np.where(wall_bounce, vx - (ONE_PLUS_E * vr) * ox, vx)
    vz[...] = np.where(wall_bounce, vz - (ONE_PLUS_E * vr) * oz, vz)
    # The ceiling, the four walls and the grille: mirror back whatever crossed, reflect its
    # velocity if it still moves outward.
    for c, w, low, high in ((y, vy, None, HI[1]), (x, vx, LO[0], HI[0]), (z, vz, LO[2], HI[2]), (y, vy, GRILLE, None)):
        if low is not None:
            d = c - low
            c[...] = np.where(d < 0, c - f32(2) * d, c)
            w -= np.where((d < 0) & (w < 0), ONE_PLUS_E * w, f32(0))
        if high is not None:
            d = high - c
            c[...] = np.where(d < 0, c + f32(2) * d, c)
            w -= np.where((d < 0) & (w > 0), ONE_PLUS_E * w, f32(0))
