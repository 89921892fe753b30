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
import csv
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
DATA = ROOT.parent / "shared" / "data" / "cwru"
CUTS = (1, 2, 4)  #: the record whole, in halves, in quarters
#: the sensor a record is read from, by its faulty bearing's end
SENSORS = {"own": {"DE": "DE", "FE": "FE"}, "other": {"DE": "FE", "FE": "DE"},
           "BA": {"DE": "BA", "FE": "BA"}}  # fmt: skip


def main(argv: list[str] | None = None) -> int:
    from bearingsim.catalog import resolve_bearing
    from bearingsim.signal.cwru_benchmark import truth_of
    from bearingsim.signal.diagnosis import load_signal
    from bearingsim.signal.fused import diagnose_fused

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
    with open(a.data / "manifest.csv", newline="") as fh:
        rows = list(csv.DictReader(fh))
    counts = {c: {"right": 0, "wrong": 0, "none/uncertain": 0} for c in a.cuts}
    wrong = []
    skipped = []
    for r in rows:
        bearing = resolve_bearing("6205-cwru" if r["end"] == "DE" else "6203-cwru")
        sensor = SENSORS[a.sensor][r["end"]]
        if f"_{sensor}_time" not in r["channels"]:
            skipped.append(r["file"])
            continue
        rec = load_signal(a.data / r["file"], channel=sensor)
        truth = truth_of(r)
        cells = []
        for cut in a.cuts:
            n = rec.x.size // cut
            part = []
            for k in range(cut):
                d = diagnose_fused(rec.x[k * n : (k + 1) * n], rec.fs, bearing, rec.rpm / 60.0)
                call = d.diagnosis in ("inner", "outer", "ball", "none") and d.confidence >= 0.5
                if d.diagnosis == truth:
                    counts[cut]["right"] += 1
                elif d.diagnosis in ("inner", "outer", "ball") and d.confidence >= 0.5:
                    counts[cut]["wrong"] += 1
                    wrong.append(
                        f"{r['file']} part {k + 1}/{cut}: {d.diagnosis} {d.confidence:.2f}"
                    )
                else:
                    counts[cut]["none/uncertain"] += 1
                part.append(f"{d.diagnosis} {d.confidence:.2f}" if call else d.diagnosis)
            cells.append(", ".join(part))
        print(
            f"| {r['file']} | {truth} | {r['smith_randall_grade'] or '-'} | "
            + " | ".join(cells)
            + " |"
        )
    n = len(rows) - len(skipped)
    print(f"sensor {a.sensor}: {n} records" + (f" ({len(skipped)} without it)" if skipped else ""))
    for cut in a.cuts:
        c = counts[cut]
        print(f"cut into {cut}: {c['right']} right, {c['wrong']} wrong fault types (p >= 0.5), "
              f"{c['none/uncertain']} none/uncertain of {n * cut}")  # fmt: skip
    print("wrong fault types:", *wrong, sep="\n  ")
    return 0


if __name__ == "__main__":
    sys.exit(main())
