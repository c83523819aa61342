"""The Numba peer: the same step as numpy_peer.step, one fused pass over the particles on all cores.

`error_model="numpy"`: a float division by zero gives inf or NaN (read by no select) instead of
raising, as in C++ and NumPy; Numba's default checks every division, which also stops the loop
from vectorising.
"""
import numpy as np
from numba import njit, prange

from scene import (AXIAL, DT, GRAVITY_Y, GRILLE, H, H2, HI, INV_H, LO, ONE_PLUS_E, R0, R0_2, R_IN, SHAFT_PUSH,
                   SPREAD, SPREAD2, f32)

ZERO, ONE, TWO, THREE = f32(0), f32(1), f32(2), f32(3)
X_LO, X_HI, Y_HI, Z_LO, Z_HI = LO[0], HI[0], HI[1], LO[2], HI[2]


@njit(parallel=True, fastmath=True, error_model="numpy")
def step(px, py, pz, vx, vy, vz):
    for i in prange(px.size):
        x, y, z, start_y = px[i], py[i], pz[i], py[i]
        # The dryer: cone-flow in its cone, the nozzle's push in the hole's shaft; then the step.
        r2 = x * x + z * z
        r = np.sqrt(r2)
        s = y * INV_H
        q = R0 + SPREAD * s
        inside = (y >= ZERO) & (s < ONE) & (r < q)
        inv_q = ONE / q
        u = ONE - r * inv_q
        scale = ((ONE - s) * AXIAL) * (u * (u * (THREE - TWO * u))) * (q / np.sqrt(H2 * q * q + SPREAD2 * r2))
        scale = scale if inside else ZERO
        radial = (scale * SPREAD) * inv_q if inside else ZERO
        along = SHAFT_PUSH if (y < ZERO) & (r2 < R0_2) else scale * H
        ux, uy, uz = vx[i] + (radial * x) * DT, vy[i] + (GRAVITY_Y + along) * DT, vz[i] + (radial * z) * DT
        x, y, z = x + ux * DT, y + uy * DT, z + uz * DT
        # The floor, its hole (passed over it, or from the shaft) and the shaft's wall.
        rho2 = x * x + z * z
        excused = (rho2 < R0_2) | (start_y < ZERO)
        floor = (y < ZERO) & (rho2 >= R0_2) & (start_y >= ZERO)
        uy = uy - ONE_PLUS_E * uy if floor & (uy < ZERO) else uy
        y = -y if floor else y
        rs = np.sqrt(rho2)
        at_wall = (y < ZERO) & excused & (rs >= R0) & (rs > ZERO)
        ox, oz = x / rs, z / rs
        vr = ux * ox + uz * oz
        bounce = at_wall & (vr > ZERO)
        ux = ux - (ONE_PLUS_E * vr) * ox if bounce else ux
        uz = uz - (ONE_PLUS_E * vr) * oz if bounce else uz
        x = x - (rs - R_IN) * ox if at_wall else x
        z = z - (rs - R_IN) * oz if at_wall else z
        # The ceiling, the four walls and the grille: mirror back, reflect what still moves out.
        d = Y_HI - y
        uy, y = uy - ONE_PLUS_E * uy if (d < ZERO) & (uy > ZERO) else uy, y + TWO * d if d < ZERO else y
        d = x - X_LO
        ux, x = ux - ONE_PLUS_E * ux if (d < ZERO) & (ux < ZERO) else ux, x - TWO * d if d < ZERO else x
        d = X_HI - x
        ux, x = ux - ONE_PLUS_E * ux if (d < ZERO) & (ux > ZERO) else ux, x + TWO * d if d < ZERO else x
        d = z - Z_LO
        uz, z = uz - ONE_PLUS_E * uz if (d < ZERO) & (uz < ZERO) else uz, z - TWO * d if d < ZERO else z
        d = Z_HI - z
        uz, z = uz - ONE_PLUS_E * uz if (d < ZERO) & (uz > ZERO) else uz, z + TWO * d if d < ZERO else z
        d = y - GRILLE
        uy, y = uy - ONE_PLUS_E * uy if (d < ZERO) & (uy < ZERO) else uy, y - TWO * d if d < ZERO else y
        px[i], py[i], pz[i], vx[i], vy[i], vz[i] = x, y, z, ux, uy, uz
