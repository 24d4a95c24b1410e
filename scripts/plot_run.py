#!/usr/bin/python3
"""Summary plot of a fecontact run (HDF5 output, schema in docs/output.md).

    scripts/plot_run.py out.h5 [-o out.png]

Writes one PNG (default: beside the .h5, with the suffix .png) with five panels:
  (a) centroid height z against time, every body;
  (b) centroid path in the x-y plane, every body (o: start, x: end);
  (c) energy (kinetic + elastic + gravity) per body and the scene total against time;
  (d) wall time per phase per step (/steps/timing/*, max over ranks), stacked;
  (e) contact force per pair of bodies against time: the norm of the pair's total force (the sum
      of /contacts/force_world, on the pair's first body) and the sum of its normal forces.
Prints the path of the PNG. Works for any number of bodies, bodies without /rotation, runs
with zero steps, scenes without contact pairs, and files of runs that stopped early (or are
still running: only the steps and frames of /complete are read).
Reads the file with fecontact.Output (python/fecontact/output.py, docs/python_output.md).
Needs h5py, numpy and matplotlib (the system python, /usr/bin/python3).
"""
import argparse
import importlib.util
import os
import sys

import numpy as np

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402



def load_reader():
    """fecontact.Output from python/fecontact/output.py, loaded by its path: the reader needs only
    h5py and NumPy, whereas importing the package fecontact loads the C library (petsc4py, MPI)."""
    path = os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "python", "fecontact", "output.py")
    spec = importlib.util.spec_from_file_location("fecontact_output", path)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module.Output


Output = load_reader()

PHASES = ["assembly", "factorization", "free_motion", "integration", "output"]


def colours(n):
    cmap = plt.get_cmap("tab10" if n <= 10 else "tab20")
    m = 10 if n <= 10 else 20
    return [cmap(i % m) for i in range(n)]


MANY = 8  # more bodies than this: one legend for the whole figure, at its right


def legend(ax, n, **kw):
    """A legend per panel for a few bodies (none when the figure has a shared one)."""
    if 0 < n <= MANY:
        ax.legend(fontsize="small", **kw)


def no_data(ax, msg):
    ax.text(0.5, 0.5, msg, ha="center", va="center", transform=ax.transAxes, color="0.4")


def plot_pairs(ap, o, t):
    """(e): per contact pair and step, |sum of force_world| (solid) and the sum of the normal forces
    (dashed), one colour per pair."""
    nrows = len(t)
    forces, normals = o.pair_forces(), o.pair_normal_forces()
    if not forces:
        no_data(ap, "no contact pairs")
    elif not nrows:
        no_data(ap, "no completed steps")
    else:
        pcols = colours(len(forces))
        for (pair, fw), c in zip(forces.items(), pcols):
            label = f"{pair[0]}:{pair[1]}"
            mark = "." if nrows <= 2 else None
            ap.plot(t, np.linalg.norm(fw, axis=1), color=c, marker=mark, label=f"{label} |total force|")
            ap.plot(t, normals[pair], color=c, ls="--", marker=mark, label=f"{label} sum of normal forces")
        ap.legend(fontsize="small", loc="best", ncol=1 + len(forces) // 6)
        ap.text(0.01, 0.98, f"{int(o.steps.contacts.max()) if 'contacts' in o.steps else 0} contacts at most in a step",
                transform=ap.transAxes, va="top", fontsize="small")
    ap.set_xlabel("time t (s)")
    ap.set_ylabel("contact force (N)")
    ap.set_title("(e) contact force per pair: norm of the total force on the first body (solid), "
                 "sum of the normal forces (dashed)")
    ap.grid(True, alpha=0.3)


def plot(path, png):
    with Output(path) as o:
        plot_output(o, path, png)


def plot_output(o, path, png):
    names = o.bodies
    cols = colours(len(names))

    steps = o.steps.step if "step" in o.steps else np.zeros(0, dtype=np.int64)
    t = o.time
    nrows = len(t)

    ranks, h, nreq, every = o.mpi_ranks, o.time_step, o.time_steps, o.output_every
    version, created = o.version or "?", o.created or "?"
    nframes = o.nframes

    many = len(names) > MANY
    ncol = 1 + (len(names) - 1) // 40 if many else 0
    fig = plt.figure(figsize=(14 + 1.6 * ncol, 14))
    grid = fig.add_gridspec(3, 2, height_ratios=(1, 1, 0.9))
    az, axy = fig.add_subplot(grid[0, 0]), fig.add_subplot(grid[0, 1])
    ae, at = fig.add_subplot(grid[1, 0]), fig.add_subplot(grid[1, 1])
    ap = fig.add_subplot(grid[2, :])
    done = f"{nrows}/{nreq}" if nrows != nreq else f"{nrows}"
    fig.suptitle(
        f"{os.path.basename(path)}  ({len(names)} bod{'y' if len(names) == 1 else 'ies'}, "
        f"{ranks} MPI rank{'s' if ranks != 1 else ''}, h = {h:g} s, {done} steps, "
        f"t_end = {t[-1] if nrows else 0.0:g} s, {nframes} frame{'s' if nframes != 1 else ''} every {every})\n"
        f"fecontact {version}, created {created}",
        fontsize=11,
    )

    # (a), (b): centroid trajectories; the initial point t = 0 comes from the attribute
    for i, (name, c) in enumerate(zip(names, cols)):
        b = o.body(name)
        kind = b.type or "?"
        try:
            c0 = b.initial_centroid.reshape(1, 3)
        except KeyError:
            c0 = np.full((1, 3), np.nan)
        try:
            cen = b.centroid
        except KeyError:
            cen = np.zeros((0, 3))
        n = min(len(cen), nrows)
        x = np.vstack([c0, cen[:n]])
        tt = np.concatenate([[0.0], t[:n]])
        label = f"{name} ({kind})"
        az.plot(tt, x[:, 2], color=c, label=label, marker="." if len(tt) <= 2 else None)
        axy.plot(x[:, 0], x[:, 1], color=c, label=label)
        # hollow markers, larger for earlier bodies, so that bodies at the same point stay visible
        ms = 5 + 7 * (len(names) - 1 - i) / max(len(names) - 1, 1)
        axy.plot(x[0, 0], x[0, 1], "o", color=c, ms=ms, mfc="none")
        axy.plot(x[-1, 0], x[-1, 1], "x", color=c, ms=ms)
    az.set_xlabel("time t (s)")
    az.set_ylabel("centroid z (m)")
    az.set_title("(a) centroid height")
    az.grid(True, alpha=0.3)
    legend(az, len(names), loc="best")
    axy.set_xlabel("centroid x (m)")
    axy.set_ylabel("centroid y (m)")
    axy.set_title("(b) centroid path in the x-y plane (o start, x end)")
    axy.set_aspect("equal", adjustable="datalim")
    axy.margins(0.1)
    axy.grid(True, alpha=0.3)
    legend(axy, len(names), loc="best")

    # (c): energy per body (kinetic + elastic + gravity) and the scene total
    if nrows:
        for name, c in zip(names, cols):
            try:
                e = o.body(name).energy_total
            except KeyError:
                continue
            ae.plot(t[: len(e)], e, color=c, label=f"{name}")
        if "energy" in o.steps:
            tot = ae.plot(t, o.steps.energy, color="k", lw=2.2, ls="--", label="total")
            if many:
                ae.legend(handles=tot, fontsize="small", loc="best")
        legend(ae, len(names) + 1, loc="best")
    else:
        no_data(ae, "no completed steps")
    ae.set_xlabel("time t (s)")
    ae.set_ylabel("energy (J)")
    ae.set_title("(c) energy: kinetic + elastic + gravity (potential zero at z = 0)")
    ae.grid(True, alpha=0.3)

    # (d): wall time per phase per step, stacked (max over ranks, per phase)
    timing = o.steps.timing
    phases = [p for p in PHASES if p in timing]
    phases += sorted(p for p in timing if p not in phases)
    if nrows and phases:
        ms = np.array([timing[p] * 1e3 for p in phases])
        labels = [f"{p} ({ms[i].sum() / 1e3:.3g} s)" for i, p in enumerate(phases)]
        pc = plt.get_cmap("Set2")
        pcols = [pc(i % 8) for i in range(len(phases))]
        if nrows <= 200:
            bottom = np.zeros(nrows)
            for i in range(len(phases)):
                at.bar(steps, ms[i], bottom=bottom, width=1.0, color=pcols[i], label=labels[i], align="center")
                bottom += ms[i]
        else:
            at.stackplot(steps, ms, colors=pcols, labels=labels)
        at.set_xlim(steps[0] - 0.5, steps[-1] + 0.5)
        at.set_ylim(0, 1.45 * max(ms.sum(axis=0).max(), 1e-9))  # room for the legend
        at.legend(fontsize="small", loc="upper right", title="phase (sum)", title_fontsize="small")
        tot = ms.sum()
        at.text(0.01, 0.98, f"sum over steps: {tot / 1e3:.3g} s ({tot / nrows:.3g} ms/step)",
                transform=at.transAxes, va="top", fontsize="small")
    else:
        no_data(at, "no completed steps")
    at.set_xlabel("step")
    at.set_ylabel("wall time per step (ms, max over ranks)")
    at.set_title("(d) time per phase per step (output: previous step's frame)")
    at.grid(True, axis="y", alpha=0.3)

    # (e): contact forces per pair
    plot_pairs(ap, o, t)

    right = 1.0
    if many:  # one legend for all panels: the colours are the same in each
        right = 1.0 - 1.5 * ncol / (14 + 1.6 * ncol)
        handles, labels = az.get_legend_handles_labels()
        fig.legend(handles, labels, loc="center right", fontsize="x-small", ncol=ncol, title="body (type)",
                   title_fontsize="small", frameon=False)
    fig.tight_layout(rect=(0, 0, right, 0.96))
    fig.savefig(png, dpi=110)
    plt.close(fig)


def main(argv=None):
    ap = argparse.ArgumentParser(
        description="Plot centroids, energies, phase timings and contact forces per pair of a fecontact HDF5 run.")
    ap.add_argument("h5", help="HDF5 output of fecontact (-output_file)")
    ap.add_argument("-o", "--output", help="PNG to write (default: the .h5 path with the suffix .png)")
    args = ap.parse_args(argv)
    if not os.path.isfile(args.h5):
        sys.exit(f"plot_run.py: no such file: {args.h5}")
    png = args.output or os.path.splitext(args.h5)[0] + ".png"
    try:
        plot(args.h5, png)
    except (OSError, KeyError) as e:
        sys.exit(f"plot_run.py: cannot read {args.h5} as a fecontact output file: {e}")
    print(png)


if __name__ == "__main__":
    main()
