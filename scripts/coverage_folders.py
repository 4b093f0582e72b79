#!/usr/bin/env python3
"""Line and branch coverage per folder from a gcovr JSON summary (scripts/coverage.sh).

Usage: coverage_folders.py SUMMARY.json [--files N]
Prints the totals of every top folder (core/, capi/, apps/, bindings/) and of its sub-folders, then
the N files with the most uncovered lines (default 15).
"""
import argparse
import collections
import json


def folder_keys(path):
    """'core/src/a.cpp' -> ['core/', 'core/src/']: the folder and its first sub-folder."""
    parts = path.split("/")[:-1]
    return ["/".join(parts[:depth]) + "/" for depth in (1, 2) if len(parts) >= depth]


def percent(covered, total):
    return "%6.1f %%" % (100.0 * covered / total) if total else "     - "


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("summary")
    parser.add_argument("--files", type=int, default=15)
    args = parser.parse_args()
    with open(args.summary) as f:
        files = json.load(f)["files"]

    sums = collections.defaultdict(lambda: [0, 0, 0, 0])
    for entry in files:
        for key in folder_keys(entry["filename"]):
            acc = sums[key]
            acc[0] += entry["line_covered"]
            acc[1] += entry["line_total"]
            acc[2] += entry["branch_covered"]
            acc[3] += entry["branch_total"]

    print("%-28s %15s %8s %17s %8s" % ("folder", "lines", "", "branches", ""))
    for key in sorted(sums):
        lc, lt, bc, bt = sums[key]
        indent = "  " if key.count("/") > 1 else ""
        print("%-28s %7d / %-7d %s %8d / %-7d %s"
              % (indent + key, lc, lt, percent(lc, lt), bc, bt, percent(bc, bt)))

    print("\nmost uncovered lines:")
    worst = sorted(files, key=lambda e: e["line_total"] - e["line_covered"], reverse=True)
    for entry in worst[:args.files]:
        missed = entry["line_total"] - entry["line_covered"]
        if missed:
            print("  %5d  %-50s %s" % (missed, entry["filename"],
                                      percent(entry["line_covered"], entry["line_total"])))


if __name__ == "__main__":
    main()
