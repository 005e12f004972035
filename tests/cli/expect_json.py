#!/usr/bin/env python3
"""Runs a command with --json and checks the convention (README "Command line"): the exit status,
and that stdout is exactly one JSON object holding the given keys; on a usage error (status 2)
stdout is empty.

Usage: expect_json.py STATUS KEYS COMMAND [ARG...]
  KEYS: comma-separated key paths, nested keys joined by dots (e.g. "outcome,outputs.run_png").
"""
import json
import subprocess
import sys


def fail(message, proc):
    sys.stderr.write("expect_json: %s: %s\n" % (message, " ".join(sys.argv[3:])))
    sys.stderr.write("--- stdout\n%s\n--- stderr\n%s\n" % (proc.stdout, proc.stderr))
    sys.exit(1)


def main():
    expected = int(sys.argv[1])
    keys = [k for k in sys.argv[2].split(",") if k]
    proc = subprocess.run(sys.argv[3:], capture_output=True, text=True)
    if proc.returncode != expected:
        fail("exit status %d, expected %d" % (proc.returncode, expected), proc)
    if expected == 2:
        if proc.stdout.strip():
            fail("a usage error printed on stdout", proc)
        return
    try:
        figures = json.loads(proc.stdout)  # raises on anything before or after the one value
    except json.JSONDecodeError as e:
        fail("stdout is not one JSON value (%s)" % e, proc)
    if not isinstance(figures, dict):
        fail("stdout is JSON but not an object", proc)
    for path in keys:
        node = figures
        for part in path.split("."):
            if not isinstance(node, dict) or part not in node:
                fail("no key '%s'" % path, proc)
            node = node[part]
    print(json.dumps(figures, indent=2)[:4000])


if __name__ == "__main__":
    main()
