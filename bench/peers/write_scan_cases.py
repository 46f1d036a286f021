#!/usr/bin/env python3
"""Writes the generated cases of bench/scan_cases.py (the kinds of data users bring) as .rows
files, for run_peers.py --scan-dir.

  write_scan_cases.py DIR [--seed 7] [--only NAME,...]

The same generators and seed as bench/scan_cases.py (default 7, the seed of every number quoted
in docs/). Generated files are not committed: this writes them again in a second.
"""
import argparse
import os
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
import scan_cases  # noqa: E402  (bench/scan_cases.py)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("dir")
    ap.add_argument("--seed", type=int, default=7)
    ap.add_argument("--only", default="", help="comma-separated case names (default: all)")
    a = ap.parse_args()
    os.makedirs(a.dir, exist_ok=True)
    names = a.only.split(",") if a.only else list(scan_cases.CASES)
    for name in names:
        make, _ = scan_cases.CASES[name]
        rows = make(np.random.default_rng(a.seed))
        path = os.path.join(a.dir, name + ".rows")
        scan_cases.write_rows(path + ".tmp", rows)
        os.replace(path + ".tmp", path)
        print(f"{path}: {sum(len(r) for r in rows)} points in {len(rows)} rows")


if __name__ == "__main__":
    main()
