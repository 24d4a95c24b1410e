#!/usr/bin/python3
"""Summary plot of a fecontact run (HDF5 output, schema in docs/output.md).

    scripts/plot_run.py out.h5 [-o out.png]

Writes one PNG (default: beside the .h5, with the suffix .png) with four panels:
  (a) centroid height z against time, every body;
  (b) centroid path in the x-y plane, every body (o: start, x: end);
  (c) energy (kinetic + elastic + gravity) per body and the scene total against time;
  (d) wall time per phase per step (/steps/timing/*, max over ranks), stacked.
Prints the path of the PNG. Works for any number of bodies, bodies without /rotation, runs
with zero steps, and files of runs that stopped early (or are still running).
Needs h5py, numpy and matplotlib (the system python, /usr/bin/python3).
"""
import argparse
import os
import sys

import numpy as np

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

import h5py  # noqa: E402

PHASES = ["assembly", "factorization", "free_motion", "integration", "output"]


def text(v):
    """An HDF5 string attribute as str (h5py returns fixed-length strings as bytes)."""
    if isinstance(v, bytes):
        return v.decode("utf-8", "replace")
    if isinstance(v, np.ndarray) and v.shape == ():
        return text(v[()])
    return str(v)


def scalar(v):
    """A numeric attribute as a Python number (time_step is stored as a 1-element array)."""
    a = np.asarray(v)
    return a.reshape(-1)[0].item() if a.size else None


def body_order(f):
    """Bodies in scene order (from -scene_bodies in the 'options' attribute); HDF5 itself lists
    the groups alphabetically. Falls back to that order when the option cannot be parsed."""
    names = list(f["bodies"].keys()) if "bodies" in f else []
    opts = text(f.attrs.get("options", "")).split()
    order = []
    for i, tok in enumerate(opts):
        if tok == "-scene_bodies" and i + 1 < len(opts):
            order = [n for n in opts[i + 1].split(",") if n]
    if sorted(order) == sorted(names):
        return order
    return sorted(names)


def open_h5(path):
    try:  # no file lock: the file may still be open for writing by a running simulation
        return h5py.File(path, "r", locking=False)
    except TypeError:  # h5py < 3.5
        return h5py.File(path, "r")


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


def plot(path, png):
    f = open_h5(path)
    names = body_order(f)
    cols = colours(len(names))

    steps = f["steps/step"][:] if "steps/step" in f else np.zeros(0, dtype=np.int64)
    t = f["steps/time"][:] if "steps/time" in f else np.zeros(0)
    nrows = len(t)

    ranks = scalar(f.attrs.get("mpi_ranks", np.nan))
    h = scalar(f.attrs.get("time_step", np.nan))
    nreq = scalar(f.attrs.get("time_steps", np.nan))
    every = scalar(f.attrs.get("output_every", np.nan))
    version = text(f.attrs.get("fecontact_version", "?"))
    created = text(f.attrs.get("created", "?"))
    nframes = len(f["frames/step"]) if "frames/step" in f else 0

    many = len(names) > MANY
    ncol = 1 + (len(names) - 1) // 40 if many else 0
    fig, axes = plt.subplots(2, 2, figsize=(14 + 1.6 * ncol, 9.5))
    (az, axy), (ae, at) = axes
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
        g = f["bodies"][name]
        kind = text(g.attrs.get("type", "?"))
        c0 = np.asarray(g.attrs.get("initial_centroid", [np.nan] * 3), dtype=float).reshape(1, 3)
        cen = g["centroid"][:] if "centroid" in g else np.zeros((0, 3))
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
            g = f["bodies"][name]
            if "energy" not in g:
                continue
            e = g["energy"][:nrows]
            ae.plot(t[: len(e)], e.sum(axis=1), color=c, label=f"{name}")
        if "steps/energy" in f:
            tot = ae.plot(t, f["steps/energy"][:nrows], color="k", lw=2.2, ls="--", label="total")
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
    phases = [p for p in PHASES if f"steps/timing/{p}" in f]
    phases += sorted(p for p in (f["steps/timing"].keys() if "steps/timing" in f else []) if p not in phases)
    if nrows and phases:
        ms = np.array([f[f"steps/timing/{p}"][:nrows] * 1e3 for p in phases])
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

    right = 1.0
    if many:  # one legend for all panels: the colours are the same in each
        right = 1.0 - 1.5 * ncol / (14 + 1.6 * ncol)
        handles, labels = az.get_legend_handles_labels()
        fig.legend(handles, labels, loc="center right", fontsize="x-small", ncol=ncol, title="body (type)",
                   title_fontsize="small", frameon=False)
    fig.tight_layout(rect=(0, 0, right, 0.95))
    fig.savefig(png, dpi=110)
    plt.close(fig)
    f.close()


def main(argv=None):
    ap = argparse.ArgumentParser(description="Plot centroids, energies and phase timings of a fecontact HDF5 run.")
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
