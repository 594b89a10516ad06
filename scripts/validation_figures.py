#!/usr/bin/python3
"""Draws the figures of docs/validation.md from fresh runs of build/sablier.

    bash scripts/setup.sh       # builds, and installs Debian's python3-matplotlib
    /usr/bin/python3 scripts/validation_figures.py [--only NAME ...] [--reuse]

Each figure runs the shipped scenes with the overrides of the matching test
(tests/test_engine_physics.cpp, tests/test_mui_layer.cpp,
tests/validation_physics.cpp), reads the
runs' stats.csv and last particle frame, and writes a PNG into
docs/images/validation/. The runs stay in --work (default
/tmp/sablier_validation); --reuse skips the runs that finished there. All
figures take about 10 minutes on 2 cores; each prints what it measured.
"""
import argparse
import csv
import glob
import json
import math
import os
import shutil
import subprocess
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from mui_layer import G, PHI_MAX, RHO, infinite_layer  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def finished(out):
    """Whether WORK/NAME holds a run that ended (run.json says so)."""
    try:
        with open(os.path.join(out, "run.json")) as f:
            return json.load(f).get("status") == "finished"
    except (OSError, ValueError):
        return False


def run(args, name, scene, sets):
    """Runs scenes/SCENE.toml (or SCENE itself, a path ending in .toml) with --set
    overrides into WORK/NAME (CSV frames too)."""
    out = os.path.join(args.work, name)
    if args.reuse and finished(out):
        return out
    shutil.rmtree(out, ignore_errors=True)
    path = scene if scene.endswith(".toml") else os.path.join(ROOT, "scenes", scene + ".toml")
    cmd = [args.sablier, "run", path, "--out", out,
           "--threads", str(args.threads), "--format", "vtp,csv"]
    for s in sets:
        cmd += ["--set", s]
    print("  run", name, flush=True)
    done = subprocess.run(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    if done.returncode != 0:
        sys.exit(f"error: {' '.join(cmd)} failed:\n{done.stderr[-2000:]}")
    return out


def columns(path):
    """A CSV file as a dict of float arrays, by header name."""
    with open(path) as f:
        rows = list(csv.reader(f))
    data = np.array([[float(v) if v not in ("", "nan") else np.nan for v in r] for r in rows[1:]])
    return {k: data[:, i] for i, k in enumerate(rows[0])}


def stats(out):
    return columns(os.path.join(out, "stats.csv"))


def frame(out, index=None):
    files = sorted(glob.glob(os.path.join(out, "frames", "particles_*.csv")))
    return columns(files[-1] if index is None else files[index])


def save(args, fig, name):
    path = os.path.join(args.images, name + ".png")
    fig.savefig(path + ".tmp.png", dpi=100, bbox_inches="tight")
    os.replace(path + ".tmp.png", path)
    plt.close(fig)
    if os.path.getsize(path) < 1000:
        sys.exit(f"error: {path}: empty picture")
    print("  wrote", os.path.relpath(path, ROOT))


def percentile_front(x):
    return np.sort(x)[int(0.99 * (len(x) - 1))]


def bed(args):
    """Vertical stress against depth in the beds at rest (BedAtRest2D/3D)."""
    fig, axes = plt.subplots(1, 2, figsize=(10, 4.5))
    for ax, (scene, depth, dim) in zip(axes, [("bed2d", 0.3, 2), ("bed3d", 0.25, 3)]):
        out = run(args, scene, scene, [])
        p, s = frame(out), stats(out)
        up = "y" if dim == 2 else "z"
        sv = p["syy" if dim == 2 else "szz"]
        d = depth - p[up]
        ax.plot(sv, d, ".", ms=1, color="0.7", label="grains")
        layer = 0.025
        edges = np.arange(0, depth + layer, layer)
        mids, means = [], []
        for a, b in zip(edges[:-1], edges[1:]):
            sel = (d >= a) & (d < b)
            if sel.any():
                mids.append(d[sel].mean()), means.append(sv[sel].mean())
        ax.plot(means, mids, "o", color="C0", label="mean per layer")
        z = np.linspace(0, depth, 10)
        ax.plot(RHO * PHI_MAX * G * z, z, "k-", label=r"weight above, $\rho\,\phi_{max}\,g\,$depth")
        ax.invert_yaxis()
        ax.set_xlabel("bulk vertical stress (Pa, compression positive)")
        ax.set_ylabel("depth (m)")
        ax.set_title(f"{scene}: 1 s at rest, fastest grain {s['max_speed'][-1]:.1e} m/s")
        ax.legend(loc="upper right", fontsize=8)
        deep = d > depth - 0.05
        print(f"  {scene}: mean stress of the deepest 5 cm {sv[deep].mean():.1f} Pa at mean depth "
              f"{d[deep].mean():.4f} m, weight {RHO * PHI_MAX * G * d[deep].mean():.1f} Pa")
    fig.tight_layout()
    save(args, fig, "bed_stress")


def energy(args):
    """Total energy in a closed box (EnergyNeverGrowsInAClosedBox, and WithPushedGrains)."""
    closed = ["boundary.ymax=\"slip\"", "solver.tolerance=1e-6", "solver.max_iterations=20000",
              "time.cfl=0.5", "time.frames=30"]
    fig, axes = plt.subplots(1, 2, figsize=(10, 4))
    for rule, label in [("project", "the projection (the default)"), ("move", "the moves"),
                        ("push", "decompaction = \"push\"")]:
        out = run(args, f"energy_{rule}", "collapse2d", closed + [f"solver.decompaction=\"{rule}\""])
        s, p0 = stats(out), frame(out, 0)
        # stats.csv has a row per step, after the step; E(0) is frame 0's: the
        # column at rest, its potential energy relative to y = 0.
        e0 = np.sum(RHO * p0["volume"] * G * p0["y"])
        t = np.concatenate([[0.0], s["time"]])
        e = np.concatenate([[e0], s["kinetic_energy"] + s["potential_energy"]])
        axes[0].plot(t, e / e0, label=label)
        axes[1].plot(t, np.concatenate([[0.0], np.cumsum(s["decompaction_work"])]) / e0, label=label)
        print(f"  {label}: E(1 s)/E(0) = {e[-1] / e0:.3f}, largest step-to-step change "
              f"{np.diff(e).max() / e0:+.2e} E(0), decompaction work "
              f"{np.sum(s['decompaction_work']) / e0:.3f} E(0)")
    axes[0].set_xlabel("time (s)"), axes[0].set_ylabel("(kinetic + potential) / E(0)")
    axes[0].set_title("2D collapse in a box closed on every side")
    axes[1].set_xlabel("time (s)"), axes[1].set_ylabel("cumulative decompaction work / E(0)")
    axes[1].set_title("energy the decompaction may add (in the bound)")
    for ax in axes:
        ax.legend(fontsize=8)
    fig.tight_layout()
    save(args, fig, "energy_closed_box")


def runout_panel(ax, ra, rr, size, front, measure, title, fits):
    """Run-out against aspect ratio: the measured points and experimental fits
    (a_lo, a_hi, function, line style, label)."""
    for lo, hi, f, style, label in fits:
        a = np.linspace(lo, hi, 20)
        ax.plot(a, f(a), style, label=label)
    ax.plot(ra, rr, "o", color="C3", label=f"Sablier ({measure})")
    ax.set_xlabel(f"aspect ratio a = H0 / {size}"), ax.set_ylabel(f"({front} - {size}) / {size}")
    ax.set_title(title, fontsize=10)
    ax.legend(fontsize=8)


def save_runout(args, fig, axes, name):
    """Deposit profiles (left) and run-out (right): the shared finish."""
    axes[0].set_ylabel("thickness / H0")
    axes[0].legend(fontsize=8)
    fig.tight_layout()
    save(args, fig, name)


def collapse(args):
    """Run-out against aspect ratio (CollapseRunOutGrowsWithAspectRatio) and two taller columns."""
    cases = [(0.5, 0.1), (1.0, 0.1), (2.0, 0.1), (3.0, 0.2), (4.0, 0.2)]
    fig, axes = plt.subplots(1, 2, figsize=(11, 4.2), gridspec_kw={"width_ratios": [1.6, 1]})
    ra, rr = [], []
    for k, (a, h0) in enumerate(cases):
        l0 = h0 / a
        out = run(args, f"collapse_a{a:g}_h{h0:g}", "collapse2d",
                  ["grid.resolution=[100,25]", f"sand.0.max=[{l0},{h0}]"])
        p = frame(out)
        runout = (percentile_front(p["x"]) - l0) / l0
        ra.append(a), rr.append(runout)
        # Deposit thickness: grain volume per 1 cm column over phi_max, scaled by H0.
        bins = np.arange(0, 1.0 + 1e-9, 0.01)
        vol, _ = np.histogram(p["x"], bins=bins, weights=p["volume"])
        axes[0].plot(bins[:-1] / l0, vol / 0.01 / PHI_MAX / h0, color=f"C{k}",
                     label=f"a = {a:g} (H0 = {h0:g} m)")
        print(f"  a = {a:g}, H0 = {h0:g} m: run-out (L - L0)/L0 = {runout:.2f}")
    axes[0].set_xlim(0, 8), axes[0].set_xlabel("x / L0")
    axes[0].set_title("2D collapse (1 cm cells, mu = 0.5): deposits at 1.5 s")
    runout_panel(axes[1], ra, rr, "L0", "L", "99th percentile of x",
                 "run-out; lines: Lube et al. 2005, 2D experiments",
                 [(0.3, 1.8, lambda a: 1.2 * a, "k-", "1.2 a (a < 1.8)"),
                  (2.8, 4.5, lambda a: 1.9 * a ** (2 / 3), "k--", "1.9 a^(2/3) (a > 2.8)")])
    save_runout(args, fig, axes, "collapse_runout")


def frictionless(args):
    """A frictionless column spreads to a flat layer (FrictionlessColumnBecomesAFlatLayer)."""
    out = run(args, "frictionless", "collapse2d",
              ["material.mu=0", "material.viscosity=2", "grid.resolution=[80,20]",
               "sand.0.max=[0.2,0.2]", "boundary.xmax=\"slip\"", "time.frames=120"])
    fig, ax = plt.subplots(figsize=(9, 3))
    h = 1.0 / 80
    for index, style, label in [(0, "--", "t = 0"), (15, "-", "t = 0.5 s"), (None, "-", "t = 4 s")]:
        p = frame(out, index)
        cols = np.floor(p["x"] / h).astype(int)
        xs = np.arange(80)
        top = np.array([p["y"][cols == c].max() if np.any(cols == c) else 0.0 for c in xs])
        ax.step((xs + 0.5) * h, top, where="mid", linestyle=style, label=label)
    expected = 0.2 * 0.2 / 1.0 - 0.25 * h
    ax.axhline(expected, color="k", lw=0.8, label="area / width, less a quarter cell")
    print(f"  frictionless: top grains at 4 s between {top.min():.4f} and {top.max():.4f} m "
          f"(mean {top.mean():.4f}), expected {expected:.4f} m")
    ax.set_xlabel("x (m)"), ax.set_ylabel("highest grain (m)")
    ax.set_title("mu = 0, viscosity 2 Pa s: a 0.2 m column in a 1 m box spreads flat", fontsize=10)
    ax.legend(fontsize=8, loc="upper right")
    fig.tight_layout()
    save(args, fig, "frictionless")


def incline(args):
    """Fastest grain on a tilted rough floor (TiltedLayerStopsBelowFrictionAngle, ...Flows...)."""
    fig, ax = plt.subplots(figsize=(6.5, 4))
    for theta, mu, end, label in [(20, 0.5, "slip", "20 deg, mu = 0.5, walled: tan < mu"),
                                  (35, 0.4, "free", "35 deg, mu = 0.4, free end: > asin(mu)")]:
        th = math.radians(theta)
        s = stats(run(args, f"incline_{theta}", "collapse2d",
                      ["grid.resolution=[80,20]", "sand.0.max=[1.0,0.1]",
                       f"gravity=[{G * math.sin(th)},{-G * math.cos(th)}]", f"material.mu={mu}",
                       f"boundary.xmax=\"{end}\"", "time.frames=45"]))
        ax.semilogy(s["time"], s["max_speed"], label=label)
        print(f"  {label}: fastest grain {s['max_speed'][-1]:.2e} m/s at {s['time'][-1]:.2f} s")
    ax.set_xlabel("time (s)"), ax.set_ylabel("fastest grain (m/s)")
    ax.set_title("0.1 m layer on a rough floor, tilted gravity")
    ax.legend(fontsize=8)
    fig.tight_layout()
    save(args, fig, "incline")


def mui(args):
    """A mu(I) layer on a slope keeps accelerating, as the infinite layer of the same
    rheology does (tests/test_mui_layer.cpp)."""
    th, mu_s = math.radians(25), 0.38
    bound = G * (math.sin(th) - mu_s * math.cos(th))
    fig, (ax, ax2) = plt.subplots(1, 2, figsize=(11, 4.2))
    ref_t = np.arange(1, 37) / 30.0
    ref = infinite_layer(ref_t)
    ax.plot(np.concatenate([[0], ref_t]), [0] + [u.mean() for u in ref], "k:",
            label="infinite layer, same rheology (1D)")
    z = (np.arange(200) + 0.5) * 0.02 / 200
    for i, (rule, label) in enumerate([("move", "moves"), ("project", "projection (the default)")]):
        out = run(args, f"mui_{rule}", "incline_mui2d",
                  [f"solver.decompaction=\"{rule}\"", "time.frames=36"])
        t, u = [], []
        for k in range(len(glob.glob(os.path.join(out, "frames", "particles_*.csv")))):
            f = frame(out, k)
            near = np.abs(f["x"] - 0.5) < 0.025
            t.append(k / 30.0), u.append(np.mean(np.hypot(f["vx"][near], f["vy"][near])))
            if rule == "project" and k in (10, 20):
                bands = np.clip((f["y"][near] / 0.0025).astype(int), 0, 7)
                speed = np.hypot(f["vx"][near], f["vy"][near])
                prof = [speed[bands == b].mean() for b in range(8)]
                ax2.plot(prof, (np.arange(8) + 0.5) * 2.5, "o", color=f"C{k // 10}",
                         label=f"grains, {k / 30:.2f} s (mean per 2.5 mm cell)")
                ax2.plot(ref[k - 1], z * 1000, "-", color=f"C{k // 10}", lw=1,
                         label=f"infinite layer, {k / 30:.2f} s")
        ax.plot(t, u, label=label, color=f"C{i}")
        print(f"  {label}: mean speed in the middle " +
              ", ".join(f"{u[k]:.3f} m/s at {t[k]:.2f} s (layer {ref[k - 1].mean():.3f})"
                        for k in (9, 18, 24, 30, 36)))
    tt = np.linspace(0, 1.2, 50)
    ax.plot(tt, bound * tt, "k--", label="bound g (sin 25 - mu_s cos 25) t")
    ax.set_ylim(0, 0.6)
    ax.set_xlabel("time (s)"), ax.set_ylabel("mean speed, |x - 0.5| < 2.5 cm (m/s)")
    ax.set_title("incline_mui2d: mu(I) glass beads, 2 cm on a 25 degree slope", fontsize=10)
    ax.legend(fontsize=8)
    ax2.set_xlabel("speed (m/s)"), ax2.set_ylabel("height above the bed (mm)")
    ax2.set_title("profile in the middle, projection", fontsize=10)
    ax2.legend(fontsize=8)
    fig.tight_layout()
    save(args, fig, "incline_mui")


def fit_power(D, Q, e):
    """Q = K (D - D0)^e by a line through Q^(1/e); returns K, D0."""
    a, b = np.polyfit(D, Q ** (1 / e), 1)
    return a ** e, -b / a


def silo(args):
    """Discharge against fill height and orifice width (the Validation.Silo* tests)."""
    fig, axes = plt.subplots(1, 3, figsize=(14, 4.2))
    s = stats(run(args, "silo2d_fill", "silo2d", ["time.frames=45"]))
    vp = (0.01 / 4) ** 2 * PHI_MAX  # 4 grains per cell and axis
    mass = s["particles"] * vp * RHO
    axes[0].plot(s["time"], mass, color="C0")
    for t0, t1 in [(0.3, 0.9), (0.9, 1.5)]:
        sel = (s["time"] >= t0) & (s["time"] <= t1)
        q, c = np.polyfit(s["time"][sel], mass[sel], 1)
        axes[0].plot([t0, t1], [q * t0 + c, q * t1 + c], "k--")
        axes[0].text(t1, q * t1 + c, f" {-q:.0f} kg/s/m", fontsize=8, va="bottom")
        print(f"  silo2d discharge {t0}-{t1} s: {-q:.1f} kg/s per metre")
    axes[0].set_xlabel("time (s)"), axes[0].set_ylabel("grains in the bin (kg per m of depth)")
    axes[0].set_title("silo2d: the rate does not depend on the fill")
    for ax, dim, ns in [(axes[1], 2, [4, 6, 10, 16]), (axes[2], 3, [3, 5, 7, 9])]:
        D, Q = [], []
        h = 0.01 if dim == 2 else 0.0075  # the tests' cells
        for n in ns:
            lo = lambda c, sign: c + sign * (0.5 * (n - 1) + 0.3) * h  # noqa: E731
            if dim == 2:
                sets = ["grid.size=[0.81,0.61]", "grid.resolution=[81,61]", "sand.0.max=[0.81,0.45]",
                        f"boundary.opening.0.min=[{lo(0.405, -1)},0.0]",
                        f"boundary.opening.0.max=[{lo(0.405, 1)},0.0]", "time.frames=18"]
                vp, t0, t1 = (0.01 / 4) ** 2 * PHI_MAX, 0.2, 0.6
            else:
                sets = ["grid.size=[0.3,0.3,0.2025]", "grid.resolution=[40,40,27]",
                        "sand.0.max=[0.3,0.3,0.15]", "sand.0.particles_per_cell=2",
                        "solver.tolerance=1e-4", "solver.max_iterations=500",
                        f"boundary.opening.0.min=[{lo(0.15, -1)},{lo(0.15, -1)},0.0]",
                        f"boundary.opening.0.max=[{lo(0.15, 1)},{lo(0.15, 1)},0.0]", "time.frames=12"]
                vp, t0, t1 = (h / 2) ** 3 * PHI_MAX, 0.1, 0.4  # 2 grains per cell and axis, as the tests
            st = stats(run(args, f"beverloo{dim}d_{n}", f"silo{dim}d", sets))
            sel = (st["time"] >= t0 - 1e-9) & (st["time"] <= t1 + 1e-9)
            q = -np.polyfit(st["time"][sel], st["particles"][sel] * vp * RHO, 1)[0]
            D.append(n * h), Q.append(q)
        D, Q = np.array(D), np.array(Q)
        e = 1.5 if dim == 2 else 2.5
        K, D0 = fit_power(D, Q, e)
        C = K / (RHO * PHI_MAX * math.sqrt(G))
        x = np.linspace(0.8 * D.min(), 1.2 * D.max(), 50)
        ax.loglog(D, Q, "o", color="C3", label=f"Sablier ({1000 * h:g} mm cells)")
        ax.loglog(x, K * (x - D0) ** e, "k-", label=f"C rho_b sqrt(g) (D - D0)^{e:g}: C = {C:.2f}, D0 = {D0 / h:.2f} h")
        Kl, D0l = fit_power(D, Q, e - 0.5)
        xl = x[x > D0l]
        ax.loglog(xl, Kl * (xl - D0l) ** (e - 0.5), "k:",
                  label=f"best fit with a liquid's exponent {e - 0.5:g} (D0 = {D0l / h:.1f} h)")
        ax.set_xlabel("orifice width D (m)" + (", square side" if dim == 3 else ""))
        ax.set_ylabel("discharge (kg/s" + (" per m)" if dim == 2 else ")"))
        ax.set_title(f"Beverloo's law in {dim}D (silo{dim}d, widened bin)")
        ax.legend(fontsize=7)
        print(f"  {dim}D: D = {D}, Q = {np.round(Q, 3)}, C = {C:.2f}, D0 = {D0 / h:.2f} h")
    fig.tight_layout()
    save(args, fig, "silo")


def refinement(args):
    """Deposit profiles of the 2D collapse on four grids, pushed and under the default
    (CollapseConvergesUnderGridRefinement)."""
    fig, axes = plt.subplots(1, 2, figsize=(12, 4), sharey=True)
    grids = [(40, 10), (80, 20), (160, 40), (320, 80)]
    for ax, (rule, ppc, title) in zip(axes, [("push", 3, "decompaction = \"push\", 3 grains per cell"),
                                            ("project", 4, "the default (projection), 4 grains per cell")]):
        previous = None
        for k, (nx, ny) in enumerate(grids):
            out = run(args, f"refine_{rule}_{nx}", "collapse2d",
                      [f"grid.resolution=[{nx},{ny}]", "sand.0.jitter=0.5", "seed=1",
                       f"sand.0.particles_per_cell={ppc}", f"solver.decompaction=\"{rule}\"",
                       "time.frames=27"])
            p = frame(out)
            bins = np.arange(0, 0.8 + 1e-9, 0.02)
            vol, _ = np.histogram(p["x"], bins=bins, weights=p["volume"])
            th = vol / 0.02 / PHI_MAX
            gap = "" if previous is None else f", gap {1e3 * np.mean(np.abs(th - previous)):.1f} mm"
            runout = (percentile_front(p["x"]) - 0.25) / 0.25
            ax.step(bins[:-1], 1e3 * th, where="post", color=f"C{k}",
                    label=f"h = {1000 / nx:g} mm: run-out {runout:.2f}{gap}")
            print(f"  {rule}, h = {1000 / nx:g} mm: run-out {runout:.2f}{gap}, median phi "
                  f"{np.median(p['phi']):.3f}")
            previous = th
        ax.set_title(title, fontsize=10), ax.set_xlabel("x (m)")
        ax.legend(fontsize=8)
    axes[0].set_ylabel("deposit thickness at 0.9 s (mm)")
    fig.suptitle("2D collapse under grid refinement (collapse2d, jitter 0.5, seed 1)", fontsize=11)
    fig.tight_layout()
    save(args, fig, "grid_refinement")


def pile(args):
    """The poured pile's free surface (pile2d) against atan(mu) and asin(mu)."""
    out = run(args, "pile2d", "pile2d", [])
    p = frame(out)
    fig, ax = plt.subplots(figsize=(10, 3.2))
    ax.plot(p["x"], p["y"], ".", ms=0.5, color="0.6")
    w = 0.005
    cols = np.floor(p["x"] / w).astype(int)
    top = {c: p["y"][cols == c].max() for c in np.unique(cols)}
    xs = np.array([(c + 0.5) * w for c in top]), np.array(list(top.values()))
    height = xs[1].max()
    peak = xs[0][np.argmax(xs[1])]
    angles = []
    refs = [(math.atan(0.5), "k--", "atan(mu) = 26.6 deg"), (math.asin(0.5), "k:", "asin(mu) = 30 deg")]
    for side in (-1, 1):
        sel = (np.sign(xs[0] - peak) == side) & (xs[1] > 0.2 * height) & (xs[1] < 0.8 * height)
        slope, c = np.polyfit(xs[0][sel], xs[1][sel], 1)
        angles.append(math.degrees(math.atan(abs(slope))))
        xx = np.array([xs[0][sel].min(), xs[0][sel].max()])
        ax.plot(xx, slope * xx + c, "r-", lw=2, label="fitted flank" if side < 0 else None)
        # Reference slopes through the fitted segment's middle.
        xm = xx.mean()
        for ang, style, label in refs:
            t = -side * math.tan(ang)
            ax.plot(xx, slope * xm + c + t * (xx - xm), style, label=label if side < 0 else None)
    ax.set_aspect("equal"), ax.set_xlabel("x (m)"), ax.set_ylabel("y (m)")
    ax.set_title(f"pile2d at 2 s: flanks at {angles[0]:.1f} and {angles[1]:.1f} deg (red fits)")
    ax.legend(fontsize=8, loc="upper right")
    print(f"  pile2d: height {height:.4f} m, flanks {angles[0]:.1f} and {angles[1]:.1f} deg")
    fig.tight_layout()
    save(args, fig, "pile")


def heap(args):
    """A slumped heap's flank against the cell, 3, 4 and 5 grains per cell and axis
    (tests/heap_fixture.hpp, validation_heap.cpp)."""
    h0, theta = 0.12, 28.0
    l0 = h0 / math.tan(math.radians(theta))
    scene = os.path.join(args.work, "heap28.toml")
    with open(scene, "w") as f:
        f.write('dimension = 2\ngravity = [0.0, -9.81]\n[grid]\nsize = [0.6, 0.15]\n'
                'resolution = [120, 30]\n[time]\nfps = 30\nframes = 45\n[material]\n'
                'density = 2500\nmu = 0.5\nphi_max = 0.6\n[boundary]\ndefault = "slip"\n'
                'ymin = "stick"\nymax = "free"\n[[sand]]\nshape = "polygon"\n'
                f"vertices = [[0.0, 0.0], [{l0:.6f}, 0.0], [0.0, {h0}]]\n")
    fig, ax = plt.subplots(figsize=(6.5, 4))
    rows = [15, 30, 60]  # 10, 5 and 2.5 mm cells
    for k, grains in enumerate((3, 4, 5)):
        angles = []
        for n in rows:
            out = run(args, f"heap_g{grains}_r{n}", scene,
                      [f"grid.resolution=[{4 * n},{n}]", f"sand.0.particles_per_cell={grains}"])
            p, h = frame(out), 0.15 / n
            cols = np.floor(p["x"] / h).astype(int)
            top = np.array([p["y"][cols == c].max() for c in np.unique(cols)])
            xs = (np.unique(cols) + 0.5) * h
            sel = (top >= 0.2 * top.max()) & (top <= 0.8 * top.max())
            angles.append(math.degrees(math.atan(-np.polyfit(xs[sel], top[sel], 1)[0])))
        print(f"  {grains} grains per axis: flank " +
              ", ".join(f"{a:.1f}" for a in angles) + " deg at 10, 5 and 2.5 mm")
        ax.plot([1000 * 0.15 / n for n in rows], angles, "o-", color=f"C{k}",
                label=f"{grains} grains per cell and axis")
    ax.axhline(math.degrees(math.atan(0.5)), color="k", ls="--", label="atan(mu) = 26.6 deg")
    ax.axhline(theta, color="k", ls=":", label="the flank at the start, 28 deg")
    ax.invert_xaxis()
    ax.set_xlabel("cell (mm)"), ax.set_ylabel("flank after 1.5 s (deg)")
    ax.set_title("a 12 cm heap slumping from 28 deg (mu = 0.5)", fontsize=10)
    ax.legend(fontsize=8)
    fig.tight_layout()
    save(args, fig, "heap")


def tolerance(args):
    """Run-out against the solver tolerance, five seedings (CollapseConvergesWithSolverTolerance)."""
    fig, ax = plt.subplots(figsize=(6.5, 4))
    tols = ["1e-4", "1e-5", "1e-6"]
    means = []
    for k, tol in enumerate(tols):
        r = []
        for seed in range(1, 6):
            out = run(args, f"tolerance_{tol}_{seed}", "collapse2d",
                      [f"solver.tolerance={tol}", "solver.max_iterations=20000", f"seed={seed}",
                       "sand.0.jitter=0.5", "time.frames=36"])
            r.append((percentile_front(frame(out)["x"]) - 0.25) / 0.25)
        ax.plot([k] * len(r), r, "o", color="0.6", label="one seeding" if k == 0 else None)
        means.append(np.mean(r))
        print(f"  tolerance {tol}: run-outs {np.round(r, 3)}, mean {means[-1]:.3f}, "
              f"standard deviation {np.std(r, ddof=1):.3f}")
    ax.plot(range(len(tols)), means, "s-", color="C3", label="mean of the five")
    ax.set_xticks(range(len(tols)), tols)
    ax.set_xlabel("solver tolerance"), ax.set_ylabel("(L - L0) / L0 at 1.2 s")
    ax.set_title("collapse2d, jitter 0.5, seeds 1-5: run-out against tolerance", fontsize=10)
    ax.legend(fontsize=8)
    fig.tight_layout()
    save(args, fig, "tolerance")


def axisym(args):
    """Axisymmetric collapses in 3D (collapse_axisym3d) against Lube et al. 2004."""
    cases = [(0.5, 0.08), (1.0, 0.06), (2.0, 0.045), (3.0, 0.04)]  # (a, R0)
    fig, axes = plt.subplots(1, 2, figsize=(11, 4.2), gridspec_kw={"width_ratios": [1.6, 1]})
    ra, rr = [], []
    for k, (a, r0) in enumerate(cases):
        h0 = a * r0
        nz = int(math.ceil((h0 + 0.03) / 0.006))
        out = run(args, f"axisym_a{a:g}", "collapse_axisym3d",
                  [f"grid.size=[0.36,0.36,{nz * 0.006:.3f}]", f"grid.resolution=[60,60,{nz}]",
                   f"sand.0.radius={r0}", f"sand.0.height={h0}", "time.frames=18"])
        p = frame(out)
        r = np.hypot(p["x"] - 0.18, p["y"] - 0.18)
        front = np.sort(r)[int(0.995 * (len(r) - 1))]
        runout = (front - r0) / r0
        ra.append(a), rr.append(runout)
        # Deposit thickness against radius: grain volume per ring over phi_max.
        bins = np.arange(0, 0.18 + 1e-9, 0.006)
        vol, _ = np.histogram(r, bins=bins, weights=p["volume"])
        area = math.pi * (bins[1:] ** 2 - bins[:-1] ** 2)
        axes[0].plot(0.5 * (bins[1:] + bins[:-1]) / r0, vol / area / PHI_MAX / h0, color=f"C{k}",
                     label=f"a = {a:g} (R0 = {100 * r0:g} cm)")
        print(f"  a = {a:g}, R0 = {r0} m: run-out (R - R0)/R0 = {runout:.2f} (99.5th percentile of r)")
    axes[0].set_xlim(0, 5), axes[0].set_xlabel("r / R0")
    axes[0].set_title("3D axisymmetric collapse (6 mm cells, mu = 0.5): deposits at 0.6 s")
    runout_panel(axes[1], ra, rr, "R0", "R", "99.5th percentile of r",
                 "run-out; lines: Lube et al. 2004, experiments",
                 [(0.3, 1.7, lambda a: 1.24 * a, "k-", "1.24 a (a < 1.7)"),
                  (1.7, 3.3, lambda a: 1.6 * np.sqrt(a), "k--", "1.6 a^(1/2) (a > 1.7)")])
    save_runout(args, fig, axes, "axisym_runout")


def plough(args):
    """The plough's thrust against the grains per cell and the step (docs/method.md)."""
    rankine = 3.0 * RHO * PHI_MAX * G * 0.1 ** 2 / 2  # K_p = 3 for sin(phi) = mu = 0.5

    def thrust(out, t0=0.05, t1=0.3):
        """The blade's mean force over (t0, t1], each step weighted by its length."""
        o = columns(os.path.join(out, "obstacles.csv"))
        t = o["time"]
        dt = np.diff(np.concatenate([[0.0], t]))
        w = (t > t0 + 1e-12) & (t <= t1 + 1e-12)
        return float(np.sum(-o["fx"][w] * dt[w]) / np.sum(dt[w]))

    fig, axes = plt.subplots(1, 2, figsize=(11, 4.2))
    for k, n in enumerate([3, 5, 8]):
        out = run(args, f"plough_1cm_n{n}_long", "plough2d",
                  [f"sand.0.particles_per_cell={n}", "time.frames=15"])
        o = columns(os.path.join(out, "obstacles.csv"))
        axes[0].plot(o["time"], -o["fx"], color=f"C{k}", lw=1, label=f"{n} grains per cell and axis")
    axes[0].axhline(rankine, color="k", ls="--", lw=1, label="Rankine, level 10 cm bed")
    axes[0].set_xlabel("t (s)"), axes[0].set_ylabel("force on the blade (N/m)")
    axes[0].set_title("plough2d at 1 cm cells, default step: force per step", fontsize=10)
    axes[0].legend(fontsize=8)
    # (cells in cm, resolution, cfl, grains per cell and axis, seeds, marker, colour)
    cases = [(1.0, "[100,30]", 1.0, (3, 4, 5, 6, 8), (1, 2, 3), "o", "C0"),
             (1.0, "[100,30]", 0.5, (3, 5), (1,), "o", "C0"),
             (0.5, "[200,60]", 1.0, (3, 4, 5), (1,), "s", "C3"),
             (0.5, "[200,60]", 0.5, (3, 5), (1,), "s", "C3")]
    for cells, res, cfl, counts, seeds, marker, colour in cases:
        xs, ys = [], []
        for n in counts:
            for seed in seeds:
                out = run(args, f"plough_{cells:g}cm_n{n}_cfl{cfl:g}_s{seed}", "plough2d",
                          [f"grid.resolution={res}", f"sand.0.particles_per_cell={n}",
                           f"time.cfl={cfl}", f"seed={seed}", "time.frames=9"])
                f = thrust(out)
                xs.append(n), ys.append(f)
                print(f"  {cells:g} cm, cfl {cfl:g}, {n} per axis, seed {seed}: {f:.1f} N/m")
        axes[1].plot(xs, ys, marker, color=colour, mfc=colour if cfl == 1.0 else "none",
                     label=f"{cells:g} cm cells, cfl {cfl:g}")
    axes[1].axhline(rankine, color="k", ls="--", lw=1, label=f"Rankine {rankine:.0f} N/m")
    axes[1].set_xlabel("grains per cell and axis"), axes[1].set_ylabel("mean force, 0.05-0.3 s (N/m)")
    axes[1].set_title("mean thrust against the particle quadrature and the step", fontsize=10)
    axes[1].legend(fontsize=8)
    fig.tight_layout()
    save(args, fig, "plough")


FIGURES = {"bed": bed, "energy": energy, "collapse": collapse, "incline": incline, "mui": mui,
           "silo": silo, "refinement": refinement, "pile": pile,
           "tolerance": tolerance, "axisym": axisym, "frictionless": frictionless,
           "plough": plough, "heap": heap}


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawTextHelpFormatter)
    ap.add_argument("--sablier", default=os.path.join(ROOT, "build", "sablier"))
    ap.add_argument("--work", default="/tmp/sablier_validation")
    ap.add_argument("--images", default=os.path.join(ROOT, "docs", "images", "validation"))
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--only", nargs="*", choices=sorted(FIGURES), default=sorted(FIGURES))
    ap.add_argument("--reuse", action="store_true", help="keep runs already finished in --work")
    args = ap.parse_args()
    if not os.access(args.sablier, os.X_OK):
        sys.exit(f"error: {args.sablier} not found: build first (scripts/setup.sh)")
    os.makedirs(args.work, exist_ok=True), os.makedirs(args.images, exist_ok=True)
    for name in args.only:
        print(name, flush=True)
        FIGURES[name](args)


if __name__ == "__main__":
    main()
