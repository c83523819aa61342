#!/usr/bin/python3
"""Time two or more builds of pba on the same swarm step, window by window in turn.

    bench/alternate.py build/pba /tmp/pba-before [--n 1e6] [--phase rested] [--integrator rk4]

Each build runs `pba bench --peer-worker` in its own process (blow-dryer-swarm on all cores, from
the phase's start state); the rounds take one window of each, in turn, reversing the order every
round, so a machine's drifting speed slows them alike. It prints each build's median and best
window and the median of its per-round ratio to the first build's: the figure to weigh a change by
(docs/performance.md, "The machine, and how to compare two builds"). Compare builds of one tree,
on an idle machine.
"""
import argparse
import os
import statistics
import sys

sys.dont_write_bytecode = True  # no __pycache__ in the source tree
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "peers"))
from line_worker import Worker  # noqa: E402


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("builds", nargs="+", help="pba programs; the first is the reference")
    parser.add_argument("--n", default="1e6", help="particles (default 1e6)")
    parser.add_argument("--phase", default="rested", choices=["flight", "landed", "rested"])
    parser.add_argument("--integrator", default="semi-implicit-euler", help="any name pba sim's --integrator takes")
    parser.add_argument("--rounds", type=int, default=8, help="windows per build (default 8)")
    parser.add_argument("--steps", type=int, default=0, help="steps a window (default 4e8 / n)")
    args = parser.parse_args()
    steps = args.steps or max(1, int(4e8 / float(args.n)))
    workers = [Worker(build, [build, "bench", "--peer-worker", "--sizes", args.n, "--phase", args.phase,
                              "--integrator", args.integrator], "alternate.py") for build in args.builds]
    rates = [[] for _ in workers]
    for r in range(args.rounds):
        order = range(len(workers)) if r % 2 == 0 else reversed(range(len(workers)))
        for i in order:
            rates[i].append(workers[i].ask(f"window {steps}")["particle_steps_per_s"])
        print(f"round {r + 1}/{args.rounds}", file=sys.stderr)
    print(f"{args.integrator}, n = {args.n}, {args.phase}, {args.rounds} rounds of {steps} steps; "
          "particle-steps/s")
    for i, build in enumerate(args.builds):
        ratio = statistics.median(rates[i][r] / rates[0][r] for r in range(args.rounds))
        print(f"  {build}: median {statistics.median(rates[i]):.3e}, best {max(rates[i]):.3e}, "
              f"ratio to the first {ratio:.3f}")
    for worker in workers:
        worker.close()


if __name__ == "__main__":
    main()
