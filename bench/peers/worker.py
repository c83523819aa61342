"""One peer's windows, taken on request: the Python side of pba bench --peer-worker's protocol.

    worker.py --impl numba|numpy --n N --phase flight|landed|rested [--state FILE.npy]

Sets up the peer's start state (pba's first state, generated here; landed and rested: the state
at t = 2 s or 8 s in FILE.npy, or the first state stepped here to that time), prints
{"ready": ...}, then answers each line of standard input with one JSON line:
    window STEPS   restart from the start state, time STEPS steps
    stats          the current state's statistics (scene.statistics)
    save PATH      write the current state to PATH (.npy, six rows of n float32)
The Numba peer is compiled, and its threads started, on a small copy before "ready": no window
includes the compilation.
"""
import argparse
import json
import sys
import time

import numpy as np

import scene


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--impl", choices=["numba", "numpy"], required=True)
    parser.add_argument("--n", type=float, required=True)
    parser.add_argument("--phase", choices=list(scene.PHASE_STEPS), default="flight")
    parser.add_argument("--state", help="a .npy state at the phase's start to start from")
    args = parser.parse_args()
    n = int(args.n)
    began = time.perf_counter()
    if args.impl == "numba":
        import numba_peer
        sample = [a[:64].copy() for a in scene.initial_state(64)]
        numba_peer.step(*sample)  # compile, start the thread pool
        step = lambda s: numba_peer.step(*s)
    else:
        import numpy_peer
        step = numpy_peer.step
    compiled = time.perf_counter() - began
    t0 = 0.002 * scene.PHASE_STEPS[args.phase]
    if args.state:
        start = list(np.load(args.state))
        assert len(start) == 6 and len(start[0]) == n and start[0].dtype == np.float32
    else:
        start = scene.initial_state(n)
        for _ in range(scene.PHASE_STEPS[args.phase]):
            step(start)
    state = [a.copy() for a in start]
    t = t0
    print(json.dumps({"ready": True, "impl": args.impl, "n": n, "phase": args.phase, "t": t,
                      "setup_seconds": time.perf_counter() - began, "compile_seconds": compiled}), flush=True)
    for line in sys.stdin:
        words = line.split()
        if not words:
            continue
        if words[0] == "window":
            steps = int(words[1])
            for a, b in zip(state, start):
                np.copyto(a, b)
            began = time.perf_counter()
            for _ in range(steps):
                step(state)
            seconds = time.perf_counter() - began
            t = t0 + 0.002 * steps
            answer = {"seconds": seconds, "steps": steps, "t": t, "particle_steps_per_s": n * steps / seconds}
        elif words[0] == "stats":
            answer = scene.statistics(state, t)
        elif words[0] == "save":
            np.save(words[1], np.stack(state))
            answer = {"saved": words[1]}
        else:
            raise SystemExit(f"worker: unknown command {line.strip()!r} (window STEPS, stats, save PATH)")
        print(json.dumps(answer), flush=True)


if __name__ == "__main__":
    main()
