"""The contact angle each CWRU race-fault record's bearing ran at, read from the record itself:
the shaft speed from its shaft harmonics, the fault order from its squared envelope spectrum,
the angle from the order (bearingsim.signal.contact_angle). Prints a Markdown table
(docs/validation.md, "Contact angle of the CWRU bearings").

    python scripts/contact_angles.py [--data ../shared/data/cwru] [--json OUT.json]

Every number is measured from the record; the CWRU bearing table's orders are those of a
contact angle of 0 (the catalogue entries 6205-cwru / 6203-cwru).
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

from bearingsim.catalog import resolve_bearing
from bearingsim.errors import ConfigError
from bearingsim.io.atomic import write_json
from bearingsim.io.cwru import cwru_bearing, cwru_manifest
from bearingsim.signal import load_signal
from bearingsim.signal.contact_angle import estimate_contact_angle
from bearingsim.signal.cwru_benchmark import mounting_of, truth_of

DATA = Path(__file__).resolve().parents[2] / "shared" / "data" / "cwru"


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--data", type=Path, default=DATA)
    ap.add_argument("--json", type=Path, default=None)
    a = ap.parse_args(argv)
    try:
        rows = cwru_manifest(a.data)
    except OSError as e:
        print(f"error: no CWRU manifest in {a.data}: {e}", file=sys.stderr)
        return 2
    out = []
    print(
        "| record | fault | mounting | stored speed [r/min] | measured speed [r/min] (lines) "
        "| line | order (α = 0) | SNR [dB] | contact angle [°] | resolution [°] |"
    )
    print("|---|---|---|---|---|---|---|---|---|---|")
    for name, row in rows.items():
        fam = truth_of(row)
        if fam not in ("outer", "inner"):
            continue
        rec = load_signal(a.data / name, channel=row["end"])
        bearing = resolve_bearing(cwru_bearing(row["end"]))
        try:
            est = estimate_contact_angle(rec.x, rec.fs, bearing, fam, rec.rpm / 60.0)
        except ConfigError as e:
            print(f"| {name} | {fam} | {mounting_of(row)} | {rec.rpm:g} | {e} ||||||")
            continue
        lab = ("BPFO" if fam == "outer" else "BPFI") + (
            "" if est.harmonic == 1 else f" ({est.harmonic}×)"
        )
        print(
            f"| {name} | {fam} | {mounting_of(row)} | {rec.rpm:g} | {60 * est.shaft_hz:.1f} "
            f"({est.shaft_lines}) | {lab} | {est.order:.4f} ({est.order_alpha0:.4f}) | "
            f"{est.snr_db:.1f} | {est.contact_angle_deg:.1f} | {est.resolution_deg:.1f} |"
        )
        out.append(
            {"file": name, "mounting": mounting_of(row), "stored_rpm": rec.rpm, **est.as_dict()}
        )
    if a.json is not None:
        write_json(a.json, out)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
