#!/usr/bin/env python3
"""Plots iou, filled and stray over time from flowform metrics CSV files
(docs/METRICS.md).

Usage: python3 docs/plot_iou.py OUT.png NAME=FILE.csv [NAME=FILE.csv ...] [--title TEXT]
A file without the filled and stray columns (written before 2026-11-29)
plots its iou and coverage instead. Needs Debian's python3-matplotlib.
"""
import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def main():
    args = sys.argv[1:]
    title = None
    if "--title" in args:
        k = args.index("--title")
        if k + 1 >= len(args):
            sys.exit(__doc__)
        title = args[k + 1]
        args = args[:k] + args[k + 2:]
    if len(args) < 2:
        sys.exit(__doc__)
    fig, axes = plt.subplots(1, 3, figsize=(15, 4))
    for arg in args[1:]:
        name, path = arg.split("=", 1)
        with open(path) as f:
            rows = list(csv.DictReader(f))
        t = [float(r["time"]) for r in rows]
        cols = ("iou", "filled", "stray") if rows and "stray" in rows[0] else ("iou", "coverage", None)
        for ax, col in zip(axes, cols):
            if col:
                ax.plot(t, [float(r[col]) for r in rows], label=name)
    axes[0].axhline(0.75, color="grey", lw=0.8, ls="--")
    axes[0].set(xlabel="time (s)", ylabel="iou", ylim=(0, 1), title="iou: target vs fluid voxels")
    axes[1].set(xlabel="time (s)", ylabel="filled", ylim=(0, 1), title="filled: share of the target's voxels")
    axes[2].axhline(0.05, color="grey", lw=0.8, ls="--")
    axes[2].set(xlabel="time (s)", ylabel="stray", title="stray: share of the controlled fluid out of reach")
    axes[2].set_ylim(bottom=0)
    for ax in axes:
        ax.legend()
    if title:
        fig.suptitle(title)
    fig.tight_layout()
    fig.savefig(args[0], dpi=80)


if __name__ == "__main__":
    main()
