#!/usr/bin/python3
"""pba's swarm step against a NumPy and a Numba peer doing the same work, side by side.

    bench/peers/run.py [--n 1e6 1e7] [--windows 5] [--pba build/pba]
    bench/peers/run.py --validate-only --n 1e4 --validation-steps 300   (the ctest: seconds)

The workload is blow-dryer-swarm with n particles: gravity, the cone-flow blow dryer (and its push
in the hole's shaft), the room's six walls with `reflect`, the hole in the floor with its shaft and
grille, restitution 0.6, dt 0.002, semi-implicit Euler in float32, all cores. pba is timed through
`pba bench --peer-worker`, the peers (numpy_peer.py, numba_peer.py) through worker.py: each runs
in its own process and takes one window when asked, so the windows are interleaved round by round
(pba, Numba, NumPy, in turn) and a slow spell of the machine slows all alike.

For each n:
 1. Validation: every implementation starts from pba's first state (the peers generate it with
    pba's splitmix64, checked to the bit by a checksum of the state), steps 1000 steps (t = 2 s)
    and reports the mean height and the fractions of the particles in the dryer's cone and in its
    shaft, which must match pba's within --tolerance (absolute). NumPy is validated up to
    --numpy-validate-max particles (1000 NumPy steps of 1e7 particles take about 20 minutes).
 2. In flight: windows from t = 0, each `steps` steps (the same for pba and Numba; NumPy takes
    fewer, shorter windows: its step costs the same in any state, every particle taking every
    select, so a shorter window from the same start measures the same rate).
 3. Landed: windows from t = 2 s: pba from its own state there, each peer from the state it
    reached in step 1 (NumPy above --numpy-validate-max from the Numba peer's).
 4. Rested: windows from t = 8 s (nearly all the rain on the floor): pba from its own state there,
    each peer from the Numba peer's, stepped on from its state at t = 2 s; the Numba peer's
    statistics at t = 8 s are validated against pba's there as in step 1.
Rates are particle-steps per second, best and median window; last, pba over Numba round by round
(the median of the rounds' ratios). Numba's compilation is done before any window.
"""
import argparse
import os
import statistics
import sys
import tempfile

sys.dont_write_bytecode = True  # no __pycache__ in the source tree (the workers: PYTHONDONTWRITEBYTECODE)
os.environ["PYTHONDONTWRITEBYTECODE"] = "1"
HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.normpath(os.path.join(HERE, "..", ".."))
SKIP = 77  # ctest's SKIP_RETURN_CODE

try:
    import numba  # noqa: F401
    import numpy  # noqa: F401
except ImportError:
    # Debian's python3-numba is for Debian's Python; another python3 (pyenv, a venv) first on PATH
    # does not see it.
    if os.path.realpath(sys.executable) != os.path.realpath("/usr/bin/python3") and os.path.exists("/usr/bin/python3"):
        os.execv("/usr/bin/python3", ["/usr/bin/python3", *sys.argv])
    print("run.py: SKIP: needs NumPy and Numba (Debian: apt-get install python3-numba)", file=sys.stderr)
    sys.exit(SKIP)

import scene  # noqa: E402 (after the check above: it imports NumPy)
from line_worker import Worker  # noqa: E402


def pba_worker(args, n, phase):
    return Worker("pba", [args.pba, "bench", "--peer-worker", "--sizes", str(n), "--phase", phase], "run.py", HERE)


def peer_worker(impl, n, phase, state=None):
    command = [sys.executable, os.path.join(HERE, "worker.py"), "--impl", impl, "--n", str(n), "--phase", phase]
    return Worker(impl, command + (["--state", state] if state else []), "run.py", HERE)


def log(message):
    print(message, file=sys.stderr, flush=True)


def differences(s, reference):
    """The statistics' differences from the reference's: mean height, cone and shaft fractions."""
    return tuple(s[k] - reference[k] for k in ("mean_height", "cone_fraction", "shaft_fraction"))


def validate(args, n, workers, tmp):
    """Step 1: the same first state, then stats after the validation steps. Returns (rows, ok, saved)."""
    first = {w.name: w.ask("stats") for w in workers}
    bits = {name: s["state_bits_sum"] for name, s in first.items()}
    ok = len(set(bits.values())) == 1
    log(f"n = {n:g}: first state {'the same to the bit' if ok else 'DIFFERS'} in every implementation ({bits})")
    rows, saved = [], {}
    reference = None
    for w in workers:
        if w.name == "numpy" and n > args.numpy_validate_max:
            continue
        log(f"n = {n:g}: {w.name} steps {args.validation_steps} steps for the validation")
        ran = w.ask(f"window {args.validation_steps}")
        s = w.ask("stats")
        if w.name != "pba":
            saved[w.name] = os.path.join(tmp, f"{w.name}-{n}.npy")
            w.ask(f"save {saved[w.name]}")
        reference = reference or s
        dh, dc, ds = differences(s, reference)
        good = max(abs(dh), abs(dc), abs(ds)) <= args.tolerance
        ok = ok and good
        same = s["state_bits_sum"] == reference["state_bits_sum"]
        rows.append((n, w.name, s, dh, dc, ds, good, same))
    return rows, ok, saved


def rested_state(n, numba, tmp):
    """The Numba peer's state at t = 8 s, stepped on from its landed start (t = 2 s). Returns its file."""
    more = scene.RESTED_STEPS - scene.LANDED_STEPS
    log(f"n = {n:g}: numba steps {more} steps more, to t = 8 s")
    numba.ask(f"window {more}")
    path = os.path.join(tmp, f"numba-rested-{n}.npy")
    numba.ask(f"save {path}")
    return path


def validate_rested(args, n, pba, numba):
    """Step 4's check: the Numba peer's statistics at t = 8 s against pba's. Returns (rows, ok).

    Not to 2e-6 as at t = 2 s: 3000 steps more of bounces amplify the rounding differences until
    the two swarms are two samples of the same physics (at 1e5: mean heights 1.62 and 1.57 mm,
    nine particles more in the cone). So the fractions must agree within four standard errors of
    a fraction of n, sqrt(p (1 - p) / n), and the mean heights within 1 mm (a peer without the
    floor's bounce, or without the jet, which holds 0.4% of the rain a metre or more up, is off by
    more)."""
    reference, s = pba.ask("stats"), numba.ask("stats")
    rows, ok = [], True
    for name, stats in (("pba", reference), ("numba", s)):
        dh, dc, ds = differences(stats, reference)
        error = lambda p: 4.0 * (max(p * (1.0 - p), 1.0 / n) / n) ** 0.5
        good = (abs(dh) <= 1e-3 and abs(dc) <= error(reference["cone_fraction"]) and
                abs(ds) <= error(reference["shaft_fraction"]))
        ok = ok and good
        rows.append((n, name, stats, dh, dc, ds, good, stats["state_bits_sum"] == reference["state_bits_sum"]))
    return rows, ok


def time_windows(args, n, workers, steps, rates):
    """Rounds of one window per implementation, in turn (the order rotates each round)."""
    for r in range(args.windows):
        turn = workers[r % len(workers):] + workers[:r % len(workers)]
        taken = {}
        for w in turn:
            if w.name == "numpy" and r >= args.numpy_windows:
                continue
            taken[w.name] = w.ask(f"window {steps[w.name]}")["particle_steps_per_s"]
            rates.setdefault(w.name, []).append(taken[w.name])
        log(f"  round {r + 1}: " + ", ".join(f"{name} {rate:.3g}" for name, rate in taken.items()))


def steps_for(args, n):
    auto = max(1, min(1000, round(4e8 / n)))
    return {"pba": args.steps or auto, "numba": args.steps or auto,
            "numpy": args.numpy_steps or max(1, min(1000, round(2e7 / n)))}


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--n", type=float, nargs="+", default=[1e6, 1e7], help="particle counts (default 1e6 1e7)")
    parser.add_argument("--windows", type=int, default=5, help="windows per implementation and phase (default 5)")
    parser.add_argument("--numpy-windows", type=int, default=3, help="NumPy's windows (default 3)")
    parser.add_argument("--steps", type=int, default=0, help="steps per window of pba and Numba (default 4e8 / n)")
    parser.add_argument("--numpy-steps", type=int, default=0, help="steps per NumPy window (default 2e7 / n)")
    parser.add_argument("--validation-steps", type=int, default=1000, help="steps before the validation (default 1000)")
    parser.add_argument("--tolerance", type=float, default=2e-6,
                        help="largest difference from pba's mean height (m) and cone and shaft fractions (2e-6)")
    parser.add_argument("--numpy-validate-max", type=float, default=1e6, help="validate NumPy up to this n (1e6)")
    parser.add_argument("--validate-only", action="store_true", help="step 1 only (the ctest)")
    parser.add_argument("--pba", default=os.path.join(ROOT, "build", "pba"), help="the pba binary (build/pba)")
    args = parser.parse_args()
    args.pba = os.path.abspath(args.pba)
    if not args.validate_only and args.validation_steps != 1000:
        parser.error("the landed windows start at t = 2 s: --validation-steps 1000 (or --validate-only)")
    sizes = [int(n) for n in args.n]
    names = ["pba", "numba", "numpy"]
    validation, results, all_ok = [], {}, True
    with tempfile.TemporaryDirectory(prefix="pba-peers-") as tmp:
        for n in sizes:
            steps = steps_for(args, n)
            workers = [pba_worker(args, n, "flight"), peer_worker("numba", n, "flight"), peer_worker("numpy", n, "flight")]
            rows, ok, saved = validate(args, n, workers, tmp)
            validation += rows
            all_ok = all_ok and ok
            if not args.validate_only:
                log(f"n = {n:g}, in flight: {args.windows} rounds of windows of {steps} steps")
                time_windows(args, n, workers, steps, results.setdefault((n, "flight"), {}))
            for w in workers:
                w.close()
            if args.validate_only:
                continue
            workers = [pba_worker(args, n, "landed"), peer_worker("numba", n, "landed", saved["numba"]),
                       peer_worker("numpy", n, "landed", saved.get("numpy", saved["numba"]))]
            log(f"n = {n:g}, landed (from t = 2 s): {args.windows} rounds")
            time_windows(args, n, workers, steps, results.setdefault((n, "landed"), {}))
            rested = rested_state(n, workers[1], tmp)
            for w in workers:
                w.close()
            workers = [pba_worker(args, n, "rested"), peer_worker("numba", n, "rested", rested),
                       peer_worker("numpy", n, "rested", rested)]
            rows, ok = validate_rested(args, n, workers[0], workers[1])
            validation += rows
            all_ok = all_ok and ok
            log(f"n = {n:g}, rested (from t = 8 s): {args.windows} rounds")
            time_windows(args, n, workers, steps, results.setdefault((n, "rested"), {}))
            for w in workers:
                w.close()
    print("Validation: {} steps from pba's first state, within {:g}; at t = 8 s for the rested windows, within 1 mm "
          "and four standard errors (differences from pba's own)".format(args.validation_steps, args.tolerance))
    print("| n | t (s) | implementation | mean height (m) | difference | cone fraction | difference | shaft fraction | "
          "within | state to the bit |")
    print("|---:|---:|---|---:|---:|---:|---:|---:|---|---|")
    for n, name, s, dh, dc, ds, good, same in validation:
        print(f"| {n:.0e} | {s['t']:g} | {name} | {s['mean_height']:.9f} | {dh:+.2e} | {s['cone_fraction']:.7f} | "
              f"{dc:+.1e} | {s['shaft_fraction']:.7f} | {'yes' if good else 'NO'} | {'yes' if same else 'no'} |")
    if results:
        print("\nParticle-steps per second, best window (median), and the best's ratio to pba's:")
        print("| n | implementation | in flight (from t = 0) | landed (from t = 2 s) | rested (from t = 8 s) | "
              "steps a window |")
        print("|---:|---|---:|---:|---:|---:|")
        for n in sizes:
            steps = steps_for(args, n)
            for name in names:
                cells = []
                for phase in ("flight", "landed", "rested"):
                    rates = results[(n, phase)].get(name, [])
                    pba = max(results[(n, phase)]["pba"])
                    ratio = "" if name == "pba" else f", {max(rates) / pba:.2f}x"
                    cells.append(f"{max(rates):.3g} ({statistics.median(rates):.3g}{ratio})" if rates else "")
                windows = args.numpy_windows if name == "numpy" else args.windows
                print(f"| {n:.0e} | {name} | {' | '.join(cells)} | {min(windows, args.windows)} x {steps[name]} |")
        print("\npba over Numba round by round: the median of each round's ratio of pba's window to Numba's, "
              "taken one after the other, which a change of the machine's speed between rounds does not move "
              "(docs/performance.md, 'Memory bandwidth'):")
        for n in sizes:
            cells = []
            for phase in ("flight", "landed", "rested"):
                ratios = [p / q for p, q in zip(results[(n, phase)]["pba"], results[(n, phase)]["numba"])]
                cells.append(f"{phase} {statistics.median(ratios):.2f}x ({min(ratios):.2f}-{max(ratios):.2f})")
            print(f"  n = {n:.0e}: " + ", ".join(cells))
    if not all_ok:
        print("run.py: FAILED: a peer does not match pba's statistics or first state", file=sys.stderr)
        return 1
    print("run.py: every implementation validated")
    return 0


if __name__ == "__main__":
    sys.exit(main())
