#!/usr/bin/python3
"""kill -9 at random moments, many times: after each kill the output file must open, and every
step and frame up to /complete must read (the per-step rows, the frames, the contacts), as
docs/output.md promises. tests/test_interrupt.py kills at three moments; this runs as many kills
as asked, which is what found a flush cut short leaving an unreadable file (1 in 25-30 kills).

Usage: scripts/kill_stress.py [--kills N] [--np P] [--seed S] [--max-delay SECONDS]
Prints one line per failed kill and a summary: kills, failures, complete steps (min/median/max)."""
import argparse
import os
import random
import signal
import sys
import tempfile

import h5py
import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(ROOT, "tests"))
os.chdir(ROOT)
from fctest import complete_prefix, start, wait_for_frames  # noqa: E402

ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
ap.add_argument("--kills", type=int, default=30)
ap.add_argument("--np", type=int, default=1)
ap.add_argument("--seed", type=int, default=1)
ap.add_argument("--max-delay", type=float, default=3.0)
a = ap.parse_args()
SCENE = ["-options_file", "input/grasp_rotate.opts", "-time_steps", "1000000", "-output_every", "1", "-quiet"]


def check(f):
    """The complete steps S of a killed run's file; raises where something up to /complete does not
    read (fctest.complete_prefix)"""
    with h5py.File(f, "r") as h:
        return complete_prefix(h)[0]


random.seed(a.seed)
bad, done = 0, []
with tempfile.TemporaryDirectory() as d:
    for i in range(a.kills):
        f = os.path.join(d, "kill%d.h5" % i)
        p = start(SCENE + ["-output_file", f], a.np)
        wait_for_frames(f, random.uniform(0.2, a.max_delay))
        os.killpg(p.pid, signal.SIGKILL)
        p.communicate(timeout=60)
        try:
            done.append(check(f))
        except Exception as e:  # an unreadable file or step is what this looks for
            bad += 1
            print("kill %d: FAILED: %s" % (i, e), flush=True)
        os.remove(f)
print("kill_stress: %d ranks, %d kills, %d failed; complete steps min %s median %s max %s" % (
    a.np, a.kills, bad, min(done) if done else "-", int(np.median(done)) if done else "-", max(done) if done else "-"))
sys.exit(1 if bad else 0)
