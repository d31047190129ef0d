#!/usr/bin/env python3
"""target_changes.py - how cleanly each target change settles, from the metrics
CSV of `flowform run --metrics` (docs/METRICS.md): per change, the time to
iou >= 0.8, the number of overshoots (falls of the iou by more than DROP
from a peak, after it first reached 0.8, each counted once until it rises
by more than DROP again: a shape that rings counts each swing), the iou 2 s after the change, the climb (base_height at the end of the
change's segment less its lowest value after the shape first reached 0.8)
and the largest and the last tilt.

Usage: python3 bench/target_changes.py METRICS.csv T1 [T2 ...]
  T1, T2, ...: the times of the changes (0 for the first target).
"""
import csv
import sys

DROP = 0.02


def main():
    if len(sys.argv) < 3:
        sys.exit("usage: python3 bench/target_changes.py METRICS.csv T1 [T2 ...]")
    rows = list(csv.DictReader(open(sys.argv[1])))
    for key in ("time", "iou", "tilt", "base_height"):
        if rows and key not in rows[0]:
            sys.exit("%s: no column '%s' (a metrics CSV of flowform run --metrics)" % (sys.argv[1], key))
    t = [float(r["time"]) for r in rows]
    iou = [float(r["iou"]) for r in rows]
    tilt = [float(r["tilt"]) for r in rows]
    base = [float(r["base_height"]) for r in rows]
    changes = [float(a) for a in sys.argv[2:]]
    ends = changes[1:] + [t[-1] + 1e-9]
    print("change (s) | first iou >= 0.8 | overshoots | iou +2 s | climb (cm) | tilt max / end (deg)")
    for c, e in zip(changes, ends):
        idx = [i for i in range(len(t)) if c < t[i] <= e]
        if c > 0:
            idx = idx[1:]  # the step that changes the target reports the old one
        if not idx:
            continue
        first = next((i for i in idx if iou[i] >= 0.8), None)
        # Overshoots, with hysteresis DROP both ways: from each peak a fall of
        # more than DROP counts one, and the next peak starts at a rise of more
        # than DROP from the valley after it.
        shoots, ext, falling = 0, None, False
        for i in [i for i in idx if first is not None and i >= first]:
            if ext is None:
                ext = iou[i]
            elif not falling:
                if iou[i] > ext:
                    ext = iou[i]
                elif ext - iou[i] > DROP:
                    shoots, ext, falling = shoots + 1, iou[i], True
            else:
                if iou[i] < ext:
                    ext = iou[i]
                elif iou[i] - ext > DROP:
                    ext, falling = iou[i], False
        at2 = min(idx, key=lambda i: abs(t[i] - (c + 2.0)))
        after = [i for i in idx if first is not None and i >= first]
        climb = (base[idx[-1]] - min(base[i] for i in after)) * 100 if after else float("nan")
        print("%g | %s | %d | %.3f | %.1f | %.1f / %.1f" % (
            c, "+%.2f s" % (t[first] - c) if first is not None else "never", shoots, iou[at2], climb,
            max(tilt[i] for i in idx), tilt[idx[-1]]))


if __name__ == "__main__":
    main()
