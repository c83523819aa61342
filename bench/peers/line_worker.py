"""A benchmark's process spoken to a line at a time: `pba bench --peer-worker` and worker.py.

Each answer is one JSON line; the first, read when the process starts, is its ready line.
Shared by run.py (pba and the peers) and bench/alternate.py (builds of pba).
"""
import json
import subprocess
import sys


class Worker:
    """One implementation's process; `who` names the script in its one-line errors."""

    def __init__(self, name, command, who, cwd=None):
        self.name = name
        self.who = who
        try:
            self.proc = subprocess.Popen(command, stdin=subprocess.PIPE, stdout=subprocess.PIPE, text=True, cwd=cwd)
        except OSError as error:
            sys.exit(f"{who}: {command[0]}: {error.strerror}")
        self.ready = self.read()

    def read(self):
        line = self.proc.stdout.readline()
        if not line:
            raise SystemExit(f"{self.who}: {self.name} stopped (exit {self.proc.wait()})")
        return json.loads(line)

    def ask(self, command):
        self.proc.stdin.write(command + "\n")
        self.proc.stdin.flush()
        return self.read()

    def close(self):
        self.proc.stdin.close()
        if self.proc.wait() != 0:
            raise SystemExit(f"{self.who}: {self.name} exited with {self.proc.returncode}")
