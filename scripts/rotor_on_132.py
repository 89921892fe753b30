"""The rotor model beside CWRU record 132 (issue 16: "the rotor model with the CWRU profile meets
the same bounds on record 132") through the shipped cwru-de-12k profile's output-only path, with
the rotor's path gain identified by a chosen method on (a) the profile's own 15 records, 132
among them (in-sample), and (b) the same records but 132 (held out). Prints both rows: RMS,
fault-line (BPFO) ratio, kurtosis, prominence difference and which of issue 16's bounds hold.
Compared with: the measurement (record 132's first 2 s).

    python scripts/rotor_on_132.py [--gain-method power|spectral|whittle] [--duration-s 2]
        [--split profile|size]

``--split size``: instead, the rig of 132's mounting identified without its fault size and
the gain on those records (leave-one-mounting-out, bearingsim.side_by_side.lomo_rig), one row.

``power``: one scale of the output-only path (bearingsim.side_by_side.model_path_scale, the
shipped profile's own ``[[model_gain]]`` when in-sample); ``spectral`` / ``whittle``: every
gain of the path fitted with the rotor's output as the known input
(bearingsim.side_by_side.model_path_fit).
"""

from __future__ import annotations

import argparse
import re
import sys
from pathlib import Path

from bearingsim.rig import load_rig
from bearingsim.side_by_side import (
    lomo_rig,
    model_path_fit,
    model_path_scale,
    side_by_side,
    within_bounds,
)

DATA = Path(__file__).resolve().parents[2] / "shared" / "data" / "cwru"
RECORD = "12k_Drive_End_OR007@6_2_132.mat"


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--gain-method", choices=["power", "spectral", "whittle"], default="spectral")
    ap.add_argument("--duration-s", type=float, default=2.0, help="judged length [s]")
    ap.add_argument("--data", type=Path, default=DATA, help="folder with manifest.csv")
    ap.add_argument("--split", choices=["profile", "size"], default="profile",
                    help="profile: the shipped profile's records, in-sample and held out; size: "
                    "leave-one-mounting-out")  # fmt: skip
    a = ap.parse_args()
    if a.split == "size":
        rig = lomo_rig(a.data, RECORD, model_gain="rotor", gain_method=a.gain_method)
        s = side_by_side(a.data / RECORD, rig, model="rotor", duration_s=a.duration_s)
        _row("the 0.014 in records (leave-one-mounting-out)", rig.model_gain("rotor"), s)
        return 0
    profile = load_rig("cwru-de-12k")
    records = re.findall(r"\.\./shared/data/cwru/(\S+?\.mat)", profile.provenance)
    if RECORD not in records:
        print(f"error: {RECORD} is not among the profile's records", file=sys.stderr)
        return 2
    print(f"cwru-de-12k: {len(records)} records; rotor gain by {a.gain_method}")
    print("| gain identified on | gain | RMS sim / meas [m/s²] | line | "
          "kurtosis sim / meas | prominence sim − meas | bounds met |")  # fmt: skip
    print("|---|---|---|---|---|---|---|")
    for label, use in (
        ("the profile's 15 records, 132 among them (in-sample)", records),
        ("the profile's records but 132 (held out)", [r for r in records if r != RECORD]),
    ):
        paths = [a.data / r for r in use]
        if a.gain_method == "power":
            rig, _ = model_path_scale(profile, paths, model="rotor")
        else:
            rig, _ = model_path_fit(profile, paths, model="rotor", objective=a.gain_method)
        s = side_by_side(a.data / RECORD, rig, model="rotor", duration_s=a.duration_s)
        _row(label, rig.model_gain("rotor"), s)
    return 0


def _row(label: str, gain, s: dict) -> None:
    """One Markdown row: the gain and 132's numbers against issue 16's bounds."""
    m, q, r = s["measured"], s["simulated"], s["ratio"]
    ok = within_bounds(r)
    print(
        f"| {label} | {gain.describe()} | {q['rms']:.3g} / {m['rms']:.3g} | {r['line']:.3g}× | "
        f"{q['kurtosis']:.2g} / {m['kurtosis']:.2g} | {r['prominence_db']:+.1f} dB | "
        f"{sum(ok.values())} of 4 ({', '.join(k for k, v in ok.items() if v) or 'none'}) |"
    )


if __name__ == "__main__":
    sys.exit(main())
