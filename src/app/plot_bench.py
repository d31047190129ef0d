#!/usr/bin/env python3
"""Plots the CSV of `flowform bench` (embedded in the flowform binary).

usage: plot_bench.py BENCH.csv STEM
Writes STEM_table1.png (stacked ms per phase, per scene and backend),
STEM_fluid.png (total ms per step against fluid count) and STEM_control.png
(total ms per step against control count), each only when the CSV has rows
for it, and prints "wrote FILE" for each. Exit 3: matplotlib is missing.
"""
import csv
import sys
import textwrap
from collections import OrderedDict

try:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
except ImportError:
    sys.exit(3)

PHASES = ["grid", "density", "forces", "control_scale", "control_forces", "pressure", "integrate",
          "shape_matching", "metrics"]


def read(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def label(row):
    return row["backend"] + " (" + row["device"] + ")"


def table1(rows, stem):
    scenes = [s for s in ["bunny", "teapot", "runner", "dragon"] if any(r["scene"] == s for r in rows)]
    if not scenes:
        return
    backends = list(OrderedDict.fromkeys(label(r) for r in rows if r["scene"] in scenes))
    fig, ax = plt.subplots(figsize=(9, 4.5))
    width = 0.8 / len(backends)
    colors = plt.get_cmap("tab10")
    for bi, b in enumerate(backends):
        bottom = [0.0] * len(scenes)
        for pi, phase in enumerate(PHASES):
            vals = []
            for s in scenes:
                v = [float(r["ms_median"]) for r in rows
                     if r["scene"] == s and label(r) == b and r["phase"] == phase]
                vals.append(v[0] if v else 0.0)
            xs = [i + (bi - (len(backends) - 1) / 2) * width for i in range(len(scenes))]
            ax.bar(xs, vals, width * 0.95, bottom=bottom, color=colors(pi),
                   label=phase if bi == 0 else None, edgecolor="black" if bi else "none", linewidth=0.3)
            bottom = [a + v for a, v in zip(bottom, vals)]
        for i, t in enumerate(bottom):
            ax.text(i + (bi - (len(backends) - 1) / 2) * width, t, "%.1f" % t, ha="center", va="bottom",
                    fontsize=7)
    ax.set_xticks(range(len(scenes)))
    ax.set_xticklabels(["%s\n%s control" % (s, next(r["control"] for r in rows if r["scene"] == s))
                        for s in scenes])
    ax.set_ylabel("ms per step (median)")
    title = "Table 1 scenes, 12k fluid particles (sums of phase medians); bars left to right: " + "; ".join(
        backends)
    ax.set_title(textwrap.fill(title, 120), fontsize=8)
    ax.legend(fontsize=7, ncol=2)
    fig.tight_layout()
    out = stem + "_table1.png"
    fig.savefig(out, dpi=110)
    print("wrote " + out)


def sweep(rows, stem, scene, xkey, xlabel, suffix):
    sel = [r for r in rows if r["scene"] == scene and r["phase"] == "total"]
    if not sel:
        return
    fig, ax = plt.subplots(figsize=(6.5, 4.2))
    for b in OrderedDict.fromkeys(label(r) for r in sel):
        pts = sorted((int(r[xkey]), float(r["ms_median"])) for r in sel if label(r) == b)
        ax.plot([p[0] for p in pts], [p[1] for p in pts], "o-", label=b)
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel(xlabel)
    ax.set_ylabel("ms per step (median)")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=7)
    fig.tight_layout()
    out = stem + suffix
    fig.savefig(out, dpi=110)
    print("wrote " + out)


def main():
    if len(sys.argv) != 3:
        sys.stderr.write(__doc__)
        sys.exit(2)
    rows = read(sys.argv[1])
    stem = sys.argv[2]
    table1(rows, stem)
    sweep(rows, stem, "fluid-sweep", "fluid", "fluid particles (control = 0.266 x fluid)", "_fluid.png")
    sweep(rows, stem, "control-sweep", "control", "control particles (12k fluid)", "_control.png")


if __name__ == "__main__":
    main()
