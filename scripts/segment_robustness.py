"""The fused diagnosis on parts of each CWRU record and through other sensors (issue 17,
robustness): every record of ``../shared/data/cwru`` cut into halves and quarters, each part
diagnosed on its own as if it were a shorter recording of the same mounting; optionally read
from another accelerometer than the faulty bearing's own (``--sensor other``: the other end's;
``--sensor BA``: the base's, where the record has one). Prints one line per record (the
verdicts of the whole record, its halves and its quarters) and the counts of right answers,
wrong fault types at confidence >= 0.5 and none/uncertain per cut. Compared with: the CWRU
labels (measured). Nothing is fitted here; the rule and its calibration are the shipped ones.

    python scripts/segment_robustness.py [--data ../shared/data/cwru] [--sensor own|other|BA]
        [--cuts 1 2 4]
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
DATA = ROOT.parent / "shared" / "data" / "cwru"
CUTS = (1, 2, 4)  #: the record whole, in halves, in quarters


def main(argv: list[str] | None = None) -> int:
    from bearingsim.signal.cwru_benchmark import SENSORS, parts_check

    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--data", type=Path, default=DATA, help="folder with manifest.csv")
    ap.add_argument("--sensor", choices=list(SENSORS), default="own", help="accelerometer read")
    ap.add_argument("--cuts", type=int, nargs="+", default=list(CUTS), help="parts per record")
    a = ap.parse_args(argv)
    if any(c < 1 for c in a.cuts):
        print(f"error: --cuts = {a.cuts}; valid: integers >= 1", file=sys.stderr)
        return 2
    if not (a.data / "manifest.csv").is_file():
        print(f"error: data = {str(a.data)!r} has no manifest.csv", file=sys.stderr)
        return 2
    parts = {c: parts_check(a.data, c, a.sensor) for c in a.cuts}
    files = list(dict.fromkeys(p["file"] for p in parts[a.cuts[0]]))
    for f in files:
        cells = []
        for c in a.cuts:
            ps = [p for p in parts[c] if p["file"] == f]
            cells.append(", ".join(_cell(p) for p in ps))
        truth = next(p["truth"] for p in parts[a.cuts[0]] if p["file"] == f)
        print(f"| {f} | {truth} | " + " | ".join(cells) + " |")
    print(f"sensor {a.sensor}: {len(files)} records with it")
    wrong = []
    for c in a.cuts:
        n = {
            k: sum(p["outcome"] == k for p in parts[c])
            for k in ("right", "wrong", "none/uncertain")
        }
        print(f"cut into {c}: {n['right']} right, {n['wrong']} wrong fault types (p >= 0.5), "
              f"{n['none/uncertain']} none/uncertain of {len(parts[c])}")  # fmt: skip
        wrong += [f"{p['file']} part {p['part']}/{c}: {_cell(p)}" for p in parts[c]
                  if p["outcome"] == "wrong"]  # fmt: skip
    print("wrong fault types:", *wrong, sep="\n  ")
    return 0


def _cell(p: dict) -> str:
    """A part's verdict, with its confidence when it is a call (>= 0.5)."""
    call = p["verdict"] in ("inner", "outer", "ball", "none") and p["confidence"] >= 0.5
    return f"{p['verdict']} {p['confidence']:.2f}" if call else p["verdict"]


if __name__ == "__main__":
    sys.exit(main())
