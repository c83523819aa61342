"""A pile's final state checked independently of the engine that made it (bench/peers/pile.py).

    pile.py --self-test     (a ctest: the geometry on boxes whose answers are known)

A state is the CSV both pile workers write: name,x,y,z,qw,qx,qy,qz,vx,vy,vz,wx,wy,wz per die (SI
units, the orientation body to world, the angular velocity in the world frame). The check:
  - at rest: every die's speed and spin below the thresholds given;
  - overlaps: how deep each pair of dice interpenetrates, by the separating-axis test of two
    oriented boxes (the 15 axes: each box's 3 face normals and the 9 cross products of their
    edges; the depth is the smallest overlap of the two boxes' projections over the axes, 0 when
    some axis separates them), the candidate pairs found with a uniform grid of cells one box
    diagonal wide (two boxes farther apart than that cannot touch);
  - the room: how far each die's deepest corner is through a wall.
"""
import csv
import sys

import numpy as np

COLUMNS = ["name", "x", "y", "z", "qw", "qx", "qy", "qz", "vx", "vy", "vz", "wx", "wy", "wz"]


class State:
    """A pile's state: names, positions (n, 3), unit quaternions w, x, y, z (n, 4), v, w (n, 3)."""

    def __init__(self, names, x, q, v, w):
        self.names, self.x, self.v, self.w = names, x, v, w
        self.q_raw = q  # as written, for a checksum of the file
        self.q = q / np.linalg.norm(q, axis=1, keepdims=True)

    @classmethod
    def read(cls, path):
        with open(path, newline="") as f:
            rows = list(csv.reader(f))
        if not rows or rows[0] != COLUMNS:
            raise ValueError(f"{path}: line 1: the header must be {','.join(COLUMNS)}")
        names = [r[0] for r in rows[1:]]
        for k, r in enumerate(rows[1:]):
            if len(r) != len(COLUMNS):
                raise ValueError(f"{path}: line {k + 2}: {len(COLUMNS)} fields, got {len(r)}")
        a = np.array([[float(c) for c in r[1:]] for r in rows[1:]], dtype=np.float64).reshape(-1, 13)
        if not np.all(np.isfinite(a)):
            raise ValueError(f"{path}: a number is not finite")
        return cls(names, a[:, 0:3], a[:, 3:7], a[:, 7:10], a[:, 10:13])

    def rotations(self):
        """Rotation matrices (n, 3, 3): column k is the box's axis k in the world."""
        w, x, y, z = self.q.T
        return np.stack([
            np.stack([1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)], axis=-1),
            np.stack([2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)], axis=-1),
            np.stack([2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)], axis=-1),
        ], axis=1)


def pairs_within(x, reach):
    """Index pairs (i < j) whose centres are closer than `reach`, found with a grid of cells `reach` wide."""
    n = len(x)
    if n < 2:
        return np.zeros((0, 2), dtype=np.int64)
    cell = np.floor((x - x.min(axis=0)) / reach).astype(np.int64)
    span = cell.max(axis=0) + 3  # room for the neighbours' offsets
    key = ((cell[:, 0] + 1) * span[1] + cell[:, 1] + 1) * span[2] + cell[:, 2] + 1
    order = np.argsort(key, kind="stable")
    sorted_keys = key[order]
    found = []
    # Half of the 27 neighbouring cells (and the cell itself), so each pair of cells is met once.
    offsets = [(a, b, c) for a in (-1, 0, 1) for b in (-1, 0, 1) for c in (-1, 0, 1) if (a, b, c) > (0, 0, 0)]
    for a, b, c in [(0, 0, 0)] + offsets:
        target = key + (a * span[1] + b) * span[2] + c
        first = np.searchsorted(sorted_keys, target, side="left")
        last = np.searchsorted(sorted_keys, target, side="right")
        counts = last - first
        i = np.repeat(np.arange(n), counts)
        within = np.arange(counts.sum()) - np.repeat(np.cumsum(counts) - counts, counts)
        j = order[np.repeat(first, counts) + within]
        keep = i < j if (a, b, c) == (0, 0, 0) else np.ones(len(i), dtype=bool)
        found.append(np.stack([np.minimum(i, j), np.maximum(i, j)], axis=1)[keep])
    pairs = np.concatenate(found)
    d = x[pairs[:, 1]] - x[pairs[:, 0]]
    return pairs[np.einsum("pc,pc->p", d, d) < reach * reach]


def box_depths(xa, ra, xb, rb, half):
    """Interpenetration depth of box pairs (separating-axis test): centres (m, 3), rotations
    (m, 3, 3), the boxes' half extents (3,). 0 where an axis separates the two."""
    axes_a, axes_b = np.swapaxes(ra, 1, 2), np.swapaxes(rb, 1, 2)  # (m, 3 axes, 3)
    cross = np.cross(axes_a[:, :, None, :], axes_b[:, None, :, :]).reshape(-1, 9, 3)
    axes = np.concatenate([axes_a, axes_b, cross], axis=1)  # (m, 15, 3)
    length = np.linalg.norm(axes, axis=2)
    parallel = length < 1e-6  # edges of the two boxes nearly parallel: a face axis covers them
    axes = axes / np.where(parallel, 1.0, length)[:, :, None]
    reach_a = np.abs(np.einsum("mnc,mkc->mnk", axes, axes_a)) @ half
    reach_b = np.abs(np.einsum("mnc,mkc->mnk", axes, axes_b)) @ half
    apart = np.abs(np.einsum("mnc,mc->mn", axes, xb - xa))
    overlap = np.where(parallel, np.inf, reach_a + reach_b - apart)
    return np.maximum(overlap.min(axis=1), 0.0)


def pair_depths(state, half, chunk=100000):
    """Every pair of dice that interpenetrates: (pairs (p, 2), depths (p,))."""
    pairs = pairs_within(state.x, 2.0 * float(np.linalg.norm(half)))
    rot = state.rotations()
    depths = np.zeros(len(pairs))
    for s in range(0, len(pairs), chunk):
        i, j = pairs[s:s + chunk, 0], pairs[s:s + chunk, 1]
        depths[s:s + chunk] = box_depths(state.x[i], rot[i], state.x[j], rot[j], half)
    return pairs[depths > 0], depths[depths > 0]


def wall_depths(state, half, lo, hi):
    """How far each die's deepest corner is through the room's walls (0 inside)."""
    reach = np.abs(state.rotations()) @ half  # (n, 3): the box's half width along each world axis
    through = np.maximum(lo - (state.x - reach), (state.x + reach) - hi)
    return np.maximum(through.max(axis=1), 0.0)


def check(state, half, lo, hi, rest_speed, rest_spin, deep):
    """The pile check's figures for one state (a dict)."""
    speed, spin = np.linalg.norm(state.v, axis=1), np.linalg.norm(state.w, axis=1)
    moving = (speed >= rest_speed) | (spin >= rest_spin)
    pairs, depths = pair_depths(state, half)
    walls = wall_depths(state, half, lo, hi)
    result = {
        "n": len(state.x), "moving": int(moving.sum()), "fastest": float(speed.max()), "fastest_spin": float(spin.max()),
        "overlapping_pairs": len(pairs), "deep_pairs": int((depths > deep).sum()),
        "deepest": float(depths.max()) if len(depths) else 0.0,
        "through_walls": int((walls > deep).sum()), "deepest_wall": float(walls.max()),
    }
    result["passes"] = result["moving"] == 0 and result["deep_pairs"] == 0 and result["through_walls"] == 0
    return result


def turned(axis, angle):
    """A unit quaternion w, x, y, z: `angle` about `axis`."""
    axis = np.asarray(axis, dtype=float) / np.linalg.norm(axis)
    return np.concatenate([[np.cos(angle / 2)], np.sin(angle / 2) * axis])


def self_test():
    """The geometry on boxes whose answers are known; returns the failures' descriptions."""
    half = np.array([0.05, 0.05, 0.05])
    still = np.zeros((1, 3))
    one = lambda x, q: State(["a"], np.array([x], float), np.array([q], float), still, still)
    two = lambda xa, qa, xb, qb: State(["a", "b"], np.array([xa, xb], float), np.array([qa, qb], float),
                                       np.zeros((2, 3)), np.zeros((2, 3)))
    ident = [1, 0, 0, 0]
    diagonal = 0.1 * np.sqrt(3) / 2
    q45 = turned([0, 0, 1], np.pi / 4)
    corner_up = turned(np.cross([1, 1, 1], [0, 0, 1]), np.arccos(1 / np.sqrt(3)))  # the (1, 1, 1) corner on +z
    cases = [
        # Face to face, 1 cm deep along x.
        ("aligned, 1 cm deep", two([0, 0, 0], ident, [0.09, 0.001, -0.002], ident), 0.01),
        ("aligned, 1 mm apart", two([0, 0, 0], ident, [0.101, 0, 0], ident), 0.0),
        # b turned 45 degrees about z: its edge reaches 0.05 sqrt 2 along x, so 5 mm into a's face.
        ("an edge 5 mm into a face", two([0, 0, 0], ident, [0.05 + 0.05 * np.sqrt(2) - 0.005, 0, 0], q45), 0.005),
        # Both turned 45 degrees about z, side by side along the diagonal direction: face to face.
        ("turned alike, 2 mm deep", two([0, 0, 0], q45, [0.098 / np.sqrt(2), 0.098 / np.sqrt(2), 0], q45), 0.002),
        # Edge against edge, crossed: a turned 45 about z, b about x, stacked along y. Their faces'
        # projections overlap 0.05 sqrt 2 deep, but the crossed edges (x cross z = y) are 0.1 sqrt 2
        # apart less the gap: 3 mm apart.
        ("crossed edges, 3 mm apart", two([0, 0, 0], q45, [0, 0.1 * np.sqrt(2) + 0.003, 0],
                                          turned([1, 0, 0], np.pi / 4)), 0.0),
        ("crossed edges, 3 mm deep", two([0, 0, 0], q45, [0, 0.1 * np.sqrt(2) - 0.003, 0],
                                         turned([1, 0, 0], np.pi / 4)), 0.003),
        # A corner pointing along +z into a's top face, 4 mm deep.
        ("a corner 4 mm into a face", two([0, 0, 0], ident, [0.002, -0.001, 0.05 + diagonal - 0.004],
                                          [-c for c in corner_up]), 0.004),
    ]
    failures = []
    for name, state, expected in cases:
        _, depths = pair_depths(state, half)
        got = float(depths.max()) if len(depths) else 0.0
        if abs(got - expected) > 1e-9:
            failures.append(f"{name}: depth {got:.6g} m, expected {expected:.6g}")
    # The corner case's orientation really puts a corner on top (else its expected depth is wrong).
    if abs(wall_depths(one([0, 0, 0], corner_up), half, -np.ones(3), np.array([1, 1, diagonal - 0.001]))[0] - 0.001) > 1e-12:
        failures.append("a corner through the ceiling: not 1 mm")
    if wall_depths(one([0, 0.0501, 0], ident), half, np.array([-2, 0, -2]), np.array([2, 4, 2]))[0] != 0.0:
        failures.append("a die resting 0.1 mm above the floor is not inside")
    # The grid finds exactly the pairs closer than its reach, across cells, against a direct search.
    rng = np.random.default_rng(1)
    x = rng.uniform(-1, 1, size=(400, 3))
    found = {tuple(p) for p in pairs_within(x, 0.2)}
    d = np.linalg.norm(x[:, None] - x[None], axis=2)
    direct = {(i, j) for i in range(len(x)) for j in range(i + 1, len(x)) if d[i, j] < 0.2}
    if found != direct:
        failures.append(f"the grid found {len(found)} pairs, a direct search {len(direct)}")
    # The rest thresholds: strictly below.
    s = State(["a", "b"], np.array([[0, 0.05, 0], [1, 0.05, 0]]), np.array([ident, ident], float),
              np.array([[0.049, 0, 0], [0, 0, 0]]), np.array([[0, 0, 0], [0, 0.5, 0]]))
    result = check(s, half, np.array([-2, 0, -2]), np.array([2, 4, 2]), 0.05, 0.5, 0.005)
    if result["moving"] != 1 or result["passes"]:
        failures.append(f"rest: {result['moving']} moving, expected 1 (the spin at the threshold)")
    return failures
