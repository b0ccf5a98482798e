#!/usr/bin/env python3
"""Plots of docs/benchmarks from the CSVs `buoyancy bench` writes.
Usage: bench_plots.py DIR   -> DIR/pareto_volume.png, DIR/pareto_cob.png (flat water), DIR/pareto_waves.png (the wave
rows), DIR/fig9_sphere_volume.png, DIR/scaling.png
A configuration's error is its worst error over the poses, its time the mean."""
import csv, math, os, sys
from collections import OrderedDict

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt

COLOURS = {"default": "black", "texel-centre": "tab:red", "exact-coverage": "tab:blue", "exact-mesh": "tab:green",
           "probes": "tab:purple", "downward-faces": "tab:orange", "sub-texel": "tab:cyan", "lod": "tab:brown",
           "tangent-plane": "tab:olive", "fitted-plane": "tab:pink"}
FLOOR = 1e-10  # exact methods sit at rounding level (1e-12 %): drawn at this floor


def read(path):
    with open(path) as f:
        return list(csv.DictReader(f))


def configs(rows):
    """Flat-water configurations (rows without a `water` column are flat: files written before it existed)."""
    out = OrderedDict()
    for r in rows:
        if r.get("water", "flat") != "flat":
            continue
        k = (r["shape"], r["method"], int(r["texture"]), r["variant"])
        c = out.setdefault(k, {"vol": 0.0, "cob": 0.0, "ns": [], "tri": int(r["triangles"])})
        c["vol"] = max(c["vol"], float(r["volume_error_pct"]))
        c["cob"] = max(c["cob"], float(r["cob_error_pct"]))
        c["ns"].append(float(r["ns_per_body_substep"]))
    for c in out.values():
        c["ns"] = sum(c["ns"]) / len(c["ns"])
    return out


def pareto(d, key, title, fname):
    cf = configs(read(os.path.join(d, "speed_vs_error.csv")))
    shapes = list(OrderedDict.fromkeys(k[0] for k in cf))
    if not shapes: return  # no flat rows (e.g. --parts waves)
    cols = min(4, len(shapes)); rows = math.ceil(len(shapes) / cols)
    fig, axes = plt.subplots(rows, cols, figsize=(4.2 * cols, 3.6 * rows), squeeze=False)
    for ax, s in zip(axes.flat, shapes):
        for method in COLOURS:
            pts = [(c["ns"], max(c[key], FLOOR), k) for k, c in cf.items() if k[0] == s and k[1] == method]
            if not pts: continue
            pts.sort()
            if method in ("texel-centre", "exact-coverage", "sub-texel"):
                ax.plot([p[0] for p in pts], [p[1] for p in pts], "-o", color=COLOURS[method], ms=4, label=method)
                for x, y, k in pts: ax.annotate(str(k[2]), (x, y), fontsize=6, xytext=(2, 2), textcoords="offset points")
            else:
                mk = "*" if method == "default" else ("s" if method == "exact-mesh" else "^")
                ax.scatter([p[0] for p in pts], [p[1] for p in pts], marker=mk, s=90 if method == "default" else 30,
                           color=COLOURS[method], label=method, zorder=3)
        tri = next(c["tri"] for k, c in cf.items() if k[0] == s)
        ax.set_xscale("log"); ax.set_yscale("log")
        ax.set_title(f"{s} ({tri} triangles)", fontsize=9)
        ax.set_xlabel("ns per body-substep (drag on, 1 thread)", fontsize=8)
        ax.set_ylabel(title, fontsize=8)
        ax.tick_params(labelsize=7)
        ax.grid(True, which="major", alpha=0.3)
    for ax in list(axes.flat)[len(shapes):]: ax.axis("off")
    axes.flat[0].legend(fontsize=6, loc="lower left")
    fig.suptitle(f"{title} against time (exact methods drawn at {FLOOR:g} %); labels: texture N", fontsize=10)
    fig.tight_layout()
    fig.savefig(os.path.join(d, fname), dpi=110)
    plt.close(fig)


def pareto_waves(d):
    """The wave rows: worst volume error against the mean time of the hydrostatics alone, one panel per shape and sea."""
    rows = [r for r in read(os.path.join(d, "speed_vs_error.csv")) if r.get("water", "flat") != "flat"]
    if not rows: return
    cf = OrderedDict()
    for r in rows:
        k = (r["shape"], r["water"], r["method"], r["variant"])
        c = cf.setdefault(k, {"vol": 0.0, "ns": []})
        c["vol"] = max(c["vol"], float(r["volume_error_pct"]))
        if r["ns_hydrostatics"]: c["ns"].append(float(r["ns_hydrostatics"]))
    groups = list(OrderedDict.fromkeys((k[0], k[1]) for k in cf))
    cols = min(3, len(groups)); nrows = math.ceil(len(groups) / cols)
    fig, axes = plt.subplots(nrows, cols, figsize=(4.2 * cols, 3.6 * nrows), squeeze=False)
    for ax, (shape, water) in zip(axes.flat, groups):
        for k, c in cf.items():
            if (k[0], k[1]) != (shape, water) or not c["ns"]: continue
            method = k[2]
            mk = "*" if method == "default" else ("s" if method == "exact-mesh" else "^")
            ax.scatter([sum(c["ns"]) / len(c["ns"])], [max(c["vol"], FLOOR)], marker=mk,
                       s=90 if method == "default" else 30, color=COLOURS.get(method, "grey"),
                       label=method + (" " + k[3] if k[3] and method == "probes" else ""), zorder=3)
        ax.set_xscale("log"); ax.set_yscale("log")
        ax.set_title(f"{shape} in {water}", fontsize=9)
        ax.set_xlabel("ns per hydrostatics (drag off, 1 thread)", fontsize=8)
        ax.set_ylabel("worst volume error, % of V", fontsize=8)
        ax.tick_params(labelsize=7)
        ax.grid(True, which="major", alpha=0.3)
    for ax in list(axes.flat)[len(groups):]: ax.axis("off")
    axes.flat[0].legend(fontsize=6, loc="lower left")
    fig.suptitle("Waves: worst volume error against time (reference: tests/oracles/WaveOracle)", fontsize=10)
    fig.tight_layout()
    fig.savefig(os.path.join(d, "pareto_waves.png"), dpi=110)
    plt.close(fig)


def fig9(d):
    p = os.path.join(d, "fig9_sphere_volume.csv")
    if not os.path.exists(p): return
    rows = read(p)
    series = OrderedDict()
    for r in rows:
        series.setdefault((r["method"], int(r["texture"])), []).append(
            (float(r["depth"]), float(r["volume"]), float(r["analytic_volume"]), float(r["error_pct"])))
    fig, (a, b) = plt.subplots(1, 2, figsize=(12, 4.5))
    first = next(iter(series.values()))
    a.plot([x[0] for x in first], [x[2] for x in first], "k-", lw=2.5, label="analytic π d²(3R−d)/3")
    styles = {"texel-centre": "-", "exact-coverage": "--", "exact-mesh": ":", "downward-faces": "-"}
    cmap = plt.get_cmap("viridis")
    texs = sorted({k[1] for k in series if k[1] > 0})
    for (m, n), pts in series.items():
        colour = COLOURS.get(m) if n == 0 else cmap(texs.index(n) / max(1, len(texs) - 1))
        lab = m + (f" {n}²" if n else "")
        a.plot([x[0] for x in pts], [x[1] for x in pts], styles[m], color=colour, lw=1, label=lab)
        b.plot([x[0] for x in pts], [x[3] for x in pts], styles[m], color=colour, lw=1, label=lab)
    a.set_xlabel("depth of the lowest point d, m"); a.set_ylabel("submerged volume, m³")
    a.set_title("Sphere R = 0.5: submerged volume against depth (paper Fig. 9)")
    b.set_xlabel("depth d, m"); b.set_ylabel("(V − analytic) / V_sphere, %")
    b.set_yscale("symlog", linthresh=1e-3); b.set_title("error against the analytic sphere")
    b.legend(fontsize=6, ncol=2); a.legend(fontsize=6, ncol=2)
    for ax in (a, b): ax.grid(True, alpha=0.3)
    fig.tight_layout(); fig.savefig(os.path.join(d, "fig9_sphere_volume.png"), dpi=110); plt.close(fig)


def scaling(d):
    p = os.path.join(d, "scaling.csv")
    if not os.path.exists(p): return
    rows = read(p)
    fig, ax = plt.subplots(figsize=(6.5, 4.5))
    # one line per (variant, driver, threads): driver `world` = the public API, `bench` = the benchmark's own driver
    variants = sorted({(r.get("variant", ""), r.get("driver", "bench")) for r in rows})
    for v, drv in variants:
        sel = [r for r in rows if r.get("variant", "") == v and r.get("driver", "bench") == drv]
        for t in sorted({int(r["threads"]) for r in sel}):
            rs = sorted((r for r in sel if int(r["threads"]) == t), key=lambda r: int(r["bodies"]))
            x = [int(r["bodies"]) for r in rs]
            tag = (f", {v}" if v else "") + (f", {drv} driver" if drv != "world" else "")
            ax.plot(x, [float(r["ns_per_body_substep_total"]) / 1e3 for r in rs], "-o", label=f"total, {t} thread(s){tag}")
            ax.plot(x, [float(r["ns_per_body_substep_buoyancy"]) / 1e3 for r in rs], "--x", label=f"buoyancy, {t} thread(s){tag}")
    budget = 1e6 / 240 / 1000  # µs of wall time per body-substep for 1,000 bodies in real time at 240 Hz
    ax.axhline(budget, color="grey", lw=0.8)
    ax.text(1, budget * 1.15, "real time, 1,000 bodies at 240 Hz", fontsize=7, color="grey")
    ax.set_xscale("log"); ax.set_yscale("log")
    ax.set_xlabel("bodies"); ax.set_ylabel("µs per body-substep (wall)")
    m = rows[0]
    ax.set_title(f"{m['model']} ({m['triangles']} triangles, {m['method']}) in 4 Gerstner waves, 240 Hz", fontsize=9)
    ax.grid(True, which="both", alpha=0.3); ax.legend(fontsize=7)
    fig.tight_layout(); fig.savefig(os.path.join(d, "scaling.png"), dpi=110); plt.close(fig)


if __name__ == "__main__":
    if len(sys.argv) != 2: print(__doc__); sys.exit(2)
    d = sys.argv[1]
    if os.path.exists(os.path.join(d, "speed_vs_error.csv")):
        pareto(d, "vol", "worst submerged-volume error, % of V", "pareto_volume.png")
        pareto(d, "cob", "worst centre-of-buoyancy error, % of diagonal", "pareto_cob.png")
        pareto_waves(d)
    fig9(d)
    scaling(d)
    print("plots written to", d)
