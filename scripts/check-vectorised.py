#!/usr/bin/env python3
"""Fails when a hot loop of the swarm step stops vectorising.

The loops are marked in the sources by a comment line `// vectorised: checked` right above the
`for` (in src/core/swarms/swarm.cpp and the private headers it includes). This compiles src/core/swarms/swarm.cpp exactly as the build does (its command from
compile_commands.json) with GCC's vectorisation report (-fopt-info-vec-optimized-missed), and requires
every marked loop to be reported "vectorized using 64 byte vectors" (the AVX-512 copy that
target_clones makes) and "using 32 byte vectors" (the AVX2 copy), and no copy of it to be
reported "couldn't vectorize loop". A loop is compiled once for each instantiation (integrator,
acceleration, response) and instruction set, and one instantiation can stop vectorising while
the others still do: an acceleration closure holding a Vec3 by value left RK4's and velocity
Verlet's copies of the away loop scalar (4 times slower) while the report still had every width
for it. A marker may allow a number of scalar copies, with the reason:
`// vectorised: checked, but 24 scalar copies (...)`; more than that fails too. A change that
turns a select into a branch, or adds an alias the compiler cannot rule out, fails here with the
loop's place and GCC's reason.

Usage: check-vectorised.py BUILD_DIR SOURCE_DIR. Exits 77 (skipped) where the check does not
apply: not GCC, not x86-64, or a build whose command lacks -O2/-O3 (the sanitizer build).
"""
import json
import os
import platform
import re
import shlex
import subprocess
import sys
import tempfile

MARKER = "// vectorised: checked"


def marked_loops(paths):
    loops = []
    for path in paths:
        with open(path) as f:
            lines = f.read().splitlines()
        for i, line in enumerate(lines):
            text = line.strip()
            if text.startswith(MARKER):
                allowed = re.match(re.escape(MARKER) + r", but (\d+) scalar copies", text)
                loops.append((path, i + 2, int(allowed.group(1)) if allowed else 0))  # the next line, 1-based
    return loops


def main():
    build, source = sys.argv[1], sys.argv[2]
    if platform.machine() not in ("x86_64", "AMD64"):
        print("check-vectorised: not x86-64, skipped")
        return 77
    with open(os.path.join(build, "compile_commands.json")) as f:
        commands = json.load(f)
    swarm = os.path.realpath(os.path.join(source, "src/core/swarms/swarm.cpp"))
    entry = next((c for c in commands if os.path.realpath(c["file"]) == swarm), None)
    if entry is None:
        print("check-vectorised: swarm.cpp is not in compile_commands.json")
        return 1
    argv = shlex.split(entry["command"]) if "command" in entry else entry["arguments"]
    version = subprocess.run([argv[0], "--version"], capture_output=True, text=True).stdout
    if "Free Software Foundation" not in version or not ({"-O2", "-O3"} & set(argv)):
        print("check-vectorised: not an optimised GCC build, skipped")
        return 77
    core = os.path.join(source, "src/core")
    sources = [swarm] + [os.path.join(core, name) for name in
                         ("surfaces/surface_tests.hpp", "swarms/swarm_block.hpp", "swarms/swarm_integrate.hpp",
                          "swarms/swarm_collide.hpp")]
    loops = marked_loops(sources)
    if not loops:
        print("check-vectorised: no marked loops found")
        return 1
    with tempfile.TemporaryDirectory() as tmp:
        report = os.path.join(tmp, "vec.txt")
        out = argv.index("-o")
        argv = argv[:out] + ["-o", os.path.join(tmp, "swarm.o")] + argv[out + 2:]
        argv.append("-fopt-info-vec-optimized-missed=" + report)
        subprocess.run(argv, check=True, cwd=entry["directory"])
        with open(report) as f:
            text = f.read()
    failures = []
    for path, line, allowed in loops:
        place = r"%s:%d:\d+: " % (re.escape(os.path.basename(path)), line)
        widths = set(re.findall(place + r"optimized: loop vectorized using (\d+) byte vectors", text))
        missing = {"64", "32"} - widths
        if missing:
            failures.append("%s:%d: not vectorised with %s byte vectors (report: %s)" % (
                path, line, " and ".join(sorted(missing, reverse=True)), ", ".join(sorted(widths)) or "none"))
        # Each scalar copy, with GCC's reason when the report gives one within the next two lines.
        scalar = re.findall(place + r"missed: couldn't vectorize loop\n(?:(?:.*\n)??.*?not vectorized: ([^\n]*))?", text)
        copies = len(scalar)
        if copies > allowed:
            reasons = sorted({re.sub(r"\bD\.\d+", "D", r) for r in scalar if r})[:3] or ["none given"]  # GCC's temporaries
            failures.append("%s:%d: %d copies not vectorised (%d allowed); GCC: %s" % (
                path, line, copies, allowed, "; ".join(reasons)))
    for f in failures:
        print("check-vectorised: " + f)
    failed = {f.split(": ")[0] for f in failures}
    print("check-vectorised: %d marked loops, %d vectorised for AVX-512 and AVX2 in every copy" % (
        len(loops), len(loops) - len(failed)))
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
