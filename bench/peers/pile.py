#!/usr/bin/python3
"""pba's pile of dice against Bullet's, the same throw side by side, and a check of both piles.

    bench/peers/pile.py [--n 1000 10000] [--span 4] [--iterations 10] [--pba build/pba]
                        [--bullet build/bench/peers/bullet_pile]
    bench/peers/pile.py --validate-only --n 100 --steps 40     (the ctest: seconds)
    bench/peers/pile.py --self-test                            (the check's geometry on known boxes)

The workload is manyDice's throw: n 10 cm dice (600 kg/m^3, friction 0.5, restitution 0.4) from
cells of a lattice over the dice scene's 4 m room, each with its own orientation, velocity and
spin, falling under gravity at dt 0.005, dice against dice and against the room. pba steps it in
`pba bench --pile-worker` (all cores), Bullet in bullet_pile (bench/peers/bullet_pile.cpp:
btDiscreteDynamicsWorld, its default sequential-impulse solver with --iterations iterations (pba's
solver the same fixed count),
sleeping on with Bullet's default thresholds; single precision; one thread, as Debian's
libbullet is built). Bullet builds its pile from the state pba saves at the start and from the
numbers pba's ready line gives (dt, gravity, room, a die's size, mass, inertia, friction and
restitution); both report a checksum of that start state, which must agree.

For each n: windows of half a second of simulated time (--window-steps, 100 steps), taken in
turn, pba then Bullet, each stepping on from where its last window ended, over --span seconds
from the throw. Each engine's rate is steps per second in its slowest window (the half second a
real-time program must keep up with) and in its median window; the ratio is pba's over
Bullet's. Then both final states are checked by pile_check.py, independently of either engine:
every die at rest (speed below --rest-speed and spin below --rest-spin), no pair of dice
interpenetrating deeper than --deep (5 mm) and no die that deep through a wall.

--validate-only (the ctest): the start checksums; one step of each, after which every die that
could not have touched anything in that step (its bounding sphere, moved by the step, clear of
the walls and of every other die's by 2 cm) must be where the other engine has it (position
1e-5 m, velocity 1e-4 m/s, quaternion 1e-4, angular velocity 1e-4 rad/s: float rounding and the
two engines' orientation updates, pba's normalised q + dt/2 w q against Bullet's exponential
map, differ by less; a swapped quaternion order or a body-frame spin would not); then the rest of
--steps in one window each and the final states, which must be complete and finite (the check's
figures are printed, not required: the dice are still in the air).

Exit status: 0 when everything checked passed, 1 when a check failed (the figures are printed
all the same), 2 for bad arguments, 77 (ctest's skip) without NumPy or the Bullet peer.
"""
import argparse
import json
import math
import os
import shutil
import statistics
import sys
import tempfile

sys.dont_write_bytecode = True  # no __pycache__ in the source tree
HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.normpath(os.path.join(HERE, "..", ".."))
SKIP = 77  # ctest's SKIP_RETURN_CODE

try:
    import numpy as np
except ImportError:
    # Debian's python3-numpy is for Debian's Python; another python3 first on PATH does not see it.
    if os.path.realpath(sys.executable) != os.path.realpath("/usr/bin/python3") and os.path.exists("/usr/bin/python3"):
        os.execv("/usr/bin/python3", ["/usr/bin/python3", *sys.argv])
    print("pile.py: SKIP: needs NumPy (Debian: apt-get install python3-numpy)", file=sys.stderr)
    sys.exit(SKIP)

import pile_check  # noqa: E402 (after the check above: it imports NumPy)
from line_worker import Worker  # noqa: E402

# The targets, each engine's slowest half second after the throw (pba on all cores).
TARGETS = {1000: (200.0, 5.0), 10000: (0.0, 10.0)}  # n: (pba's steps/s, times Bullet's)


def log(message):
    print(message, file=sys.stderr, flush=True)


def file_bits(path):
    """pba's pileStateBits of a state file: its 13 numbers a die, as float32 bits, summed mod 2^64."""
    s = pile_check.State.read(path)
    a = np.concatenate([s.x, s.q_raw, s.v, s.w], axis=1).astype(np.float32)
    return int(a.view(np.uint32).astype(np.uint64).sum(dtype=np.uint64))


def start_workers(args, n, tmp):
    """pba's worker, its start state saved, and Bullet's built from it. Returns (pba, bullet, start, ok)."""
    pba = Worker("pba", [args.pba, "bench", "--pile-worker", "--dice", str(n), "--iterations", str(args.iterations)],
                 "pile.py", HERE)
    r = pba.ready
    start = os.path.join(tmp, f"start-{n}.csv")
    pba.ask(f"save {start}")
    die = r["die"]
    numbers = lambda v: ",".join(repr(float(c)) for c in v)
    command = [args.bullet, "--state", start, "--dt", repr(r["dt"]), "--gravity", numbers(r["gravity"]),
               "--room", numbers(r["room"]["min"] + r["room"]["max"]), "--size", numbers(die["size"]),
               "--mass", repr(die["mass"]), "--inertia", numbers(die["inertia"]),
               "--friction", repr(die["friction"]), "--restitution", repr(die["restitution"]),
               "--iterations", str(args.iterations)]
    bullet = Worker("bullet", command, "pile.py", HERE)
    sums = {"pba": r["start_bits_sum"], "its file": file_bits(start), "bullet": bullet.ready["start_bits_sum"]}
    ok = len(set(sums.values())) == 1 and bullet.ready["n"] == n == r["n"]
    log(f"n = {n}: start state {'the same' if ok else 'DIFFERS'} in pba, its file and Bullet ({sums}); "
        f"pba on {r['threads']} threads, Bullet on {bullet.ready['threads']}")
    return pba, bullet, start, ok


def free_dice(state, dt, g, lo, hi, half, margin=0.02):
    """Dice that cannot touch anything in one step: bounding spheres, moved by the step, clear by `margin`."""
    radius = float(np.linalg.norm(half))
    moved = np.linalg.norm(state.v, axis=1) * dt + 0.5 * np.linalg.norm(g) * dt * dt
    clear = np.minimum((state.x - lo).min(axis=1), (hi - state.x).min(axis=1)) > radius + moved + margin
    pairs = pile_check.pairs_within(state.x, 2 * radius + 2 * moved.max() + margin)
    i, j = pairs[:, 0], pairs[:, 1]
    close = np.linalg.norm(state.x[i] - state.x[j], axis=1) <= 2 * radius + moved[i] + moved[j] + margin
    clear[i[close]] = False
    clear[j[close]] = False
    return clear


def compare_first_step(a, b, free):
    """The largest differences of the free dice's states after one step, and whether each is within tolerance."""
    q = np.minimum(np.linalg.norm(a.q - b.q, axis=1), np.linalg.norm(a.q + b.q, axis=1))
    worst = {"position (m)": np.linalg.norm(a.x - b.x, axis=1), "velocity (m/s)": np.linalg.norm(a.v - b.v, axis=1),
             "quaternion": q, "angular velocity (rad/s)": np.linalg.norm(a.w - b.w, axis=1)}
    tolerance = {"position (m)": 1e-5, "velocity (m/s)": 1e-4, "quaternion": 1e-4, "angular velocity (rad/s)": 1e-4}
    return {k: (float(v[free].max()), float(v[free].max()) <= tolerance[k]) for k, v in worst.items()}


def read_final(path, names):
    """A final state: complete (the start's dice in order) and finite, or a ValueError."""
    s = pile_check.State.read(path)
    if s.names != names:
        raise ValueError(f"{path}: the dice are not the start's, in its order")
    return s


def validate(args, n, pba, bullet, start, tmp):
    """--validate-only's checks after the start checksum. Returns (ok, final states)."""
    r = pba.ready
    lo, hi = np.array(r["room"]["min"]), np.array(r["room"]["max"])
    half = 0.5 * np.array(r["die"]["size"])
    first = pile_check.State.read(start)
    free = free_dice(first, r["dt"], np.array(r["gravity"]), lo, hi, half)
    states = {}
    for w in (pba, bullet):
        w.ask("window 1")
        states[w.name] = pile_check.State.read(w.ask(f"save {os.path.join(tmp, f'{w.name}-step1-{n}.csv')}")["saved"])
    ok = bool(free.sum() >= min(10, n))
    log(f"n = {n}: after one step, {int(free.sum())} dice that touched nothing compared "
        f"({'enough' if ok else 'too few to compare'}):")
    for name, (worst, good) in compare_first_step(states["pba"], states["bullet"], free).items():
        log(f"  largest {name} difference {worst:.2e}: {'within' if good else 'NOT within'} tolerance")
        ok = ok and good
    windows = {}
    if args.steps > 1:
        for w in (pba, bullet):
            windows[w.name] = w.ask(f"window {args.steps - 1}")
            log(f"  {w.name}: window of {args.steps - 1} steps to t = {windows[w.name]['t']:.3g} s, "
                f"{windows[w.name]['steps_per_s']:.4g} steps/s")
    return ok, windows


def time_windows(args, n, pba, bullet, dt):
    """Windows of --window-steps in turn, pba then Bullet, over --span. Returns {name: [(t0, steps/s, asleep)]}."""
    total = round(args.span / dt)
    rates = {"pba": [], "bullet": []}
    done = 0
    while done < total:
        steps = min(args.window_steps, total - done)
        line = []
        for w in (pba, bullet):
            answer = w.ask(f"window {steps}")
            rates[w.name].append((done * dt, answer["steps_per_s"], answer.get("sleeping")))
            line.append(f"{w.name} {answer['steps_per_s']:.4g}")
        log(f"  n = {n}, t = {done * dt:.2f}-{(done + steps) * dt:.2f} s: " + ", ".join(line) + " steps/s")
        done += steps
    return rates


def final_states(n, pba, bullet, start, tmp):
    names = pile_check.State.read(start).names
    return {w.name: read_final(w.ask(f"save {os.path.join(tmp, f'{w.name}-final-{n}.csv')}")["saved"], names)
            for w in (pba, bullet)}


def print_rates(n, rates, threads, args, dt):
    print(f"\nn = {n}: windows of {args.window_steps} steps ({args.window_steps * dt:g} s), pba then Bullet in turn, "
          f"from the throw to t = {args.span:g} s; Bullet {args.iterations} solver iterations")
    print("| from t (s) | pba steps/s | Bullet steps/s | Bullet dice asleep |")
    print("|---:|---:|---:|---:|")
    for (t, p, _), (_, b, asleep) in zip(rates["pba"], rates["bullet"]):
        print(f"| {t:.2f} | {p:.4g} | {b:.4g} | {asleep} |")
    print("\n| engine | threads | slowest half second (steps/s) | from t (s) | median (steps/s) |")
    print("|---|---:|---:|---:|---:|")
    for name in ("pba", "bullet"):
        t, slowest, _ = min(rates[name], key=lambda r: r[1])
        median = statistics.median(r[1] for r in rates[name])
        print(f"| {name} | {threads[name]} | {slowest:.4g} | {t:.2f} | {median:.4g} |")
    slowest = {name: min(r[1] for r in rates[name]) for name in rates}
    median = {name: statistics.median(r[1] for r in rates[name]) for name in rates}
    ratio = slowest["pba"] / slowest["bullet"]
    print(f"pba / Bullet: {ratio:.3g} in the slowest half second, {median['pba'] / median['bullet']:.3g} in the median")
    if n in TARGETS:
        steps, times = TARGETS[n]
        wanted = ([f"pba at least {steps:g} steps/s ({slowest['pba']:.4g})"] if steps else []) + \
                 [f"at least {times:g} times Bullet's ({ratio:.3g})"]
        met = slowest["pba"] >= steps and ratio >= times
        print(f"target (slowest half second): {' and '.join(wanted)}: {'met' if met else 'not met'}")


def print_checks(n, checks, args, t):
    print(f"\nCheck of the final states at t = {t:g} s (pile_check.py, independent of both engines): at rest = speed "
          f"below {args.rest_speed:g} m/s and spin below {args.rest_spin:g} rad/s; deep = more than "
          f"{args.deep * 1000:g} mm (separating-axis depth of two boxes, or a corner through a wall)")
    print("| n | engine | dice not at rest | fastest (m/s) | fastest spin (rad/s) | pairs interpenetrating | "
          "deep | deepest (mm) | dice deep through a wall | deepest through a wall (mm) | passes |")
    print("|---:|---|---:|---:|---:|---:|---:|---:|---:|---:|---|")
    for name, c in checks.items():
        print(f"| {n} | {name} | {c['moving']} | {c['fastest']:.3g} | {c['fastest_spin']:.3g} | "
              f"{c['overlapping_pairs']} | {c['deep_pairs']} | {c['deepest'] * 1000:.3g} | {c['through_walls']} | "
              f"{c['deepest_wall'] * 1000:.3g} | {'yes' if c['passes'] else 'NO'} |")


def run(args, n, tmp, failed):
    """One n: returns whether every check passed, and adds to `failed` the piles whose final check did not."""
    pba, bullet, start, ok = start_workers(args, n, tmp)
    r = pba.ready
    dt = r["dt"]
    threads = {"pba": r["threads"], "bullet": bullet.ready["threads"]}
    if args.validate_only:
        good, windows = validate(args, n, pba, bullet, start, tmp)
        ok = ok and good
        t = args.steps * dt
    else:
        rates = time_windows(args, n, pba, bullet, dt)
        t = round(args.span / dt) * dt
    finals = final_states(n, pba, bullet, start, tmp)
    for w in (pba, bullet):
        w.close()
    half = 0.5 * np.array(r["die"]["size"])
    lo, hi = np.array(r["room"]["min"]), np.array(r["room"]["max"])
    checks = {name: pile_check.check(s, half, lo, hi, args.rest_speed, args.rest_spin, args.deep)
              for name, s in finals.items()}
    if not args.validate_only:
        print_rates(n, rates, threads, args, dt)
        ok = ok and all(c["passes"] for c in checks.values())
        failed += [f"{'Bullet' if name == 'bullet' else name}'s {n} dice" for name, c in checks.items()
                   if not c["passes"]]
    print_checks(n, checks, args, t)
    return ok


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--n", type=int, nargs="+", default=[1000, 10000], help="dice counts (default 1000 10000)")
    parser.add_argument("--span", type=float, default=4.0, help="simulated seconds from the throw (default 4)")
    parser.add_argument("--window-steps", type=int, default=100, help="steps a window (default 100: 0.5 s)")
    parser.add_argument("--iterations", type=int, default=10,
                        help="velocity iterations of both solvers, a fixed count each step (default 10, Bullet's)")
    parser.add_argument("--rest-speed", type=float, default=0.05, help="at rest below this speed, m/s (0.05)")
    parser.add_argument("--rest-spin", type=float, default=0.5, help="at rest below this spin, rad/s (0.5)")
    parser.add_argument("--deep", type=float, default=0.005, help="a deep overlap, m (0.005)")
    parser.add_argument("--validate-only", action="store_true", help="the start and the first steps only (the ctest)")
    parser.add_argument("--self-test", action="store_true", help="only pile_check.py's geometry on known boxes")
    parser.add_argument("--steps", type=int, default=40, help="with --validate-only: steps in all (default 40)")
    parser.add_argument("--keep", metavar="DIR", help="also keep the start and final states' CSVs in DIR")
    parser.add_argument("--pba", default=os.path.join(ROOT, "build", "pba"), help="the pba binary (build/pba)")
    parser.add_argument("--bullet", default=os.path.join(ROOT, "build", "bench", "peers", "bullet_pile"),
                        help="the Bullet peer (build/bench/peers/bullet_pile)")
    args = parser.parse_args()
    if args.self_test:
        failures = pile_check.self_test()
        for failure in failures:
            print(f"pile.py: FAILED: pile_check: {failure}", file=sys.stderr)
        print("pile.py: pile_check self-test " + ("failed" if failures else "passed"))
        return 1 if failures else 0
    if any(n < 1 for n in args.n) or args.span <= 0 or args.window_steps < 1 or args.steps < 1 \
            or not 1 <= args.iterations <= 1000:
        parser.error("--n, --window-steps, --steps and --iterations (up to 1000) must be positive, --span too")
    if not args.bullet or not os.access(args.bullet, os.X_OK):
        print(f"pile.py: SKIP: no Bullet peer at '{args.bullet}' (built where Debian's libbullet-dev is installed: "
              "scripts/install-deps.sh)", file=sys.stderr)
        return SKIP
    args.pba, args.bullet = os.path.abspath(args.pba), os.path.abspath(args.bullet)
    with tempfile.TemporaryDirectory(prefix="pba-pile-") as tmp:
        failed = []
        ok = all([run(args, n, tmp, failed) for n in args.n])
        if args.keep:
            os.makedirs(args.keep, exist_ok=True)
            for name in sorted(os.listdir(tmp)):
                shutil.copy(os.path.join(tmp, name), args.keep)
            print(f"pile.py: the states are in {args.keep}")
    if not ok:
        which = f": the final state of {', '.join(failed)}" if failed else ""
        print(f"pile.py: FAILED: a check did not pass{which} (see above)", file=sys.stderr)
        return 1
    print("pile.py: every check passed")
    return 0


if __name__ == "__main__":
    sys.exit(main())
