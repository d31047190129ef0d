#!/usr/bin/env python3
"""Plots iou (and coverage) over time from flowform metrics CSV files.

Usage: python3 docs/plot_iou.py OUT.png NAME=FILE.csv [NAME=FILE.csv ...]
Needs Debian's python3-matplotlib.
"""
import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def main():
    if len(sys.argv) < 3:
        sys.exit(__doc__)
    fig, (a, b) = plt.subplots(1, 2, figsize=(11, 4))
    for arg in sys.argv[2:]:
        name, path = arg.split("=", 1)
        t, iou, cov = [], [], []
        with open(path) as f:
            for row in csv.DictReader(f):
                t.append(float(row["time"]))
                iou.append(float(row["iou"]))
                cov.append(float(row["coverage"]))
        a.plot(t, iou, label=name)
        b.plot(t, cov, label=name)
    a.axhline(0.75, color="grey", lw=0.8, ls="--")
    a.set(xlabel="time (s)", ylabel="iou", ylim=(0, 1), title="iou: target vs fluid voxels")
    b.set(xlabel="time (s)", ylabel="coverage", ylim=(0, 1), title="coverage: mean 1 - s_i")
    a.legend()
    b.legend()
    fig.tight_layout()
    fig.savefig(sys.argv[1], dpi=80)


if __name__ == "__main__":
    main()
