#!/usr/bin/python3
"""Force-indentation of the sphere pressed on the block under displacement control, against Hertz
(docs/scenes.md): runs input/pressed.opts (quasi-static, the sphere's top cap moved down in 8 steps)
on the meshes of scripts/hertz.py's levels, and for every step measures

- the peak of the contact_pressure field at the last step against Hertz's p0 = 3 F / (2 pi a^2);
- F: the cap's reaction (/bodies/ball/reactions/<cap>, the force the cap's support takes) and the sum
  of the normal contact forces of the step, which equilibrium makes equal;
- d: the approach, as scripts/hertz.py measures it, but at depth 0.2 R below the contact point
  rather than at the centre: the drop of that point (P1 interpolation of the displacement) plus the
  half-space's displacement there under the Hertz pressure of F. Loaded through its top cap, the
  whole force crosses the sphere's equator, whose compression is no part of Hertz's approach: the
  centre's drop would hold it, a point near the contact much less (under gravity, scripts/hertz.py,
  the load is spread over the volume);
- Hertz's force for that d, F_H = 4/3 E* sqrt(R) d^(3/2), and F / F_H - 1.

Usage: /usr/bin/python3 scripts/pressed.py [--levels 1,2,3] [--np N] [--no-plot]
Prints the Markdown table of docs/scenes.md and writes docs/pressed.png."""
import argparse
import os
import sys

import h5py
import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import hertz  # noqa: E402

ROOT = hertz.ROOT
OPTS = os.path.join(ROOT, "input", "pressed.opts")
DEPTH = 0.2  # where the approach is taken, in units of R below the contact point (see the docstring)


def steps(h5path, P):
    rows = []
    with h5py.File(h5path, "r") as H:
        off = H["contacts/offset"][:]
        cells = H["bodies/ball/mesh/cells"][:]
        X = H["bodies/ball/mesh/reference"][:]
        cap = [k for k in H["bodies/ball/reactions"] if k.startswith("box:")][0]
        R = H["bodies/ball/reactions/" + cap][:]
        for s in range(len(off) - 1):
            Fc = H["contacts/force"][off[s]:off[s + 1], 0].sum()
            fr = list(H["frames/step"][:]).index(s + 1)
            U = H["bodies/ball/positions"][fr] - X
            z = DEPTH * P["R"]  # below the contact point
            drop = -hertz.p1_displacement(cells, X, U, P["centre"] + np.array([0, 0, z - P["R"]]))[2]
            d = drop + hertz.w_axis(P, Fc, z)
            a_h = (3 * Fc * P["R"] / (4 * P["Estar"]))**(1.0 / 3.0)
            rows.append(dict(step=s + 1, F=-R[s, 2], Fc=Fc, d=d, FH=hertz.hertz_force(P, d), contacts=int(off[s + 1] - off[s]),
                             pmax=H["bodies/ball/contact_pressure"][fr].max(), p0=3 * Fc / (2 * np.pi * a_h**2)))
    return rows


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--levels", default="1,2,3")
    ap.add_argument("--np", type=int, default=1)
    ap.add_argument("--no-plot", action="store_true")
    a = ap.parse_args()
    P = hertz.params(os.path.join(ROOT, "input", "hertz.opts"))
    P["centre"] = np.array([0.0, 0.0, 0.5])
    out = {}
    print("| level | step | d (mm) | d/R (%) | F cap (N) | F contacts (N) | F Hertz (N) | F / F_H - 1 | contacts |")
    print("|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
    for level in [int(x) for x in a.levels.split(",")]:
        f = os.path.join("/tmp", "pressed_%d.h5" % level)
        hertz.run(hertz.mesh_args(level) + ["-output_file", f, "-output_fields", "contact_pressure"], a.np, OPTS)
        out[level] = steps(f, P)
        for r in out[level]:
            print("| %d | %d | %.3f | %.2f | %.1f | %.1f | %.1f | %+.2f %% | %d |" % (
                level, r["step"], 1e3 * r["d"], 100 * r["d"] / P["R"], r["F"], r["Fc"], r["FH"],
                100 * (r["F"] / r["FH"] - 1), r["contacts"]))
        r = out[level][-1]
        print("| | level %d, last step: peak contact_pressure %.0f Pa against Hertz's p0 = 3 F / (2 pi a^2) = %.0f Pa | | | | | | | |"
              % (level, r["pmax"], r["p0"]))
    if not a.no_plot:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        fig, ax = plt.subplots(figsize=(6, 4))
        dd = np.linspace(0, max(r["d"] for v in out.values() for r in v) * 1.05, 100)
        ax.plot(1e3 * dd, hertz.hertz_force(P, dd), "k-", label="Hertz $4/3\\,E^*\\sqrt{R}\\,d^{3/2}$")
        for level, v in out.items():
            ax.plot([1e3 * r["d"] for r in v], [r["F"] for r in v], "o", label="mesh level %d (cap reaction)" % level)
        ax.set_xlabel("approach d (mm)")
        ax.set_ylabel("force (N)")
        ax.set_title("FE sphere pressed on FE block, displacement control, static")
        ax.legend()
        fig.tight_layout()
        fig.savefig(os.path.join(ROOT, "docs", "pressed.png"), dpi=100)


if __name__ == "__main__":
    main()
