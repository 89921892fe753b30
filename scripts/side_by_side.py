"""Simulated beside measured: every fault record (outer race, inner race, ball) of
../shared/data/cwru, its condition simulated and passed through a rig identified WITHOUT that
record's fault size (leave-one-mounting-out: Smith & Randall 2015 found the mounting, not the
fault size, dominates these records). Prints a Markdown table and the share of records
within issue 16's bounds.

    python scripts/side_by_side.py [--model vsm|dem|tvsm|rotor] [--duration-s 2]
        [--slip-percent 1.5] [--pocket-jitter-percent 0]
        [--defect-profile geometric] [--contact-roughness-m 1e-7] [--model-gain]
        [--gain-method power|spectral|whittle] [--direct-gain G] [--split size|load]
        [--json OUT.json]

The rig for a record is identified (bearingsim.rig_identify) from the records of the same
end and sample rate with another fault size; a mounting with no other size in the folder (the
fan end: 0.014 in only) gets no rig and is listed as such. Ball records are simulated with the
models' ball defect (fault line 2×BSF). ``--model rotor`` simulates the bearing-rotor-housing
model of the CWRU motor with the fault in the record's bearing.
"""

from __future__ import annotations

import argparse
import sys
from dataclasses import replace
from pathlib import Path

from bearingsim.errors import ConfigError
from bearingsim.io.atomic import write_json
from bearingsim.io.cwru import cwru_manifest
from bearingsim.side_by_side import (
    BOUNDS,
    CONTACT_ROUGHNESS_M,
    DEFECT_PROFILE,
    SLIP_PERCENT,
    lomo_rig,
    rig_other_loads,
    side_by_side,
    within_bounds,
)

DATA = Path(__file__).resolve().parents[2] / "shared" / "data" / "cwru"


def _check_inputs(a, realism: dict) -> dict:
    """The manifest rows of ``--data``, after checking the options a run would otherwise
    refuse record by record (duration, realism keys against the model) and ``--json``'s
    location (it was written after every simulation, and a bad one ended in a traceback)."""
    from bearingsim.cli.common import check_outputs
    from bearingsim.config import Scenario

    check_outputs(("--json", None if a.json is None else str(a.json)))
    keys = {"duration_s": a.duration_s, **realism}
    Scenario.from_dict({"model": a.model, **keys}, origin="options")
    if not a.data.is_dir():
        raise ConfigError(f"--data = {str(a.data)!r} is not a folder; valid: the CWRU data folder")
    try:
        return cwru_manifest(a.data)
    except OSError as exc:
        raise ConfigError(f"--data = {str(a.data)!r}: {exc.strerror or exc}") from None


def main() -> int:
    ap = argparse.ArgumentParser(
        description=" ".join(__doc__.split("\n\n")[0].split())  # the first paragraph
    )
    ap.add_argument("--model", default="vsm", choices=["vsm", "dem", "tvsm", "rotor"])
    ap.add_argument("--duration-s", type=float, default=2.0)
    ap.add_argument("--slip-percent", type=float, default=SLIP_PERCENT, help="random slip [%%]")
    ap.add_argument(
        "--pocket-jitter-percent",
        type=float,
        default=0.0,
        help="balls wandering in their pockets: pass intervals jittered, the phase locked [%%]",
    )
    ap.add_argument(
        "--defect-profile", default=DEFECT_PROFILE, choices=["geometric", "rectangular", "pit"]
    )
    ap.add_argument(
        "--contact-roughness-m",
        type=float,
        default=CONTACT_ROUGHNESS_M,
        help="composite RMS roughness of the contacts [m] (0: Hertz's smooth onset)",
    )
    ap.add_argument(
        "--direct-gain",
        type=float,
        default=None,
        help="replace the identified rig's direct gain (1: output-only identification; 0: the "
        "sensor sees the identified modes only); --model-gain then scales it with the modes",
    )
    ap.add_argument(
        "--band",
        choices=["own", "measured"],
        default="own",
        help="where each signal's envelope (fault line, prominence) is taken: own: each "
        "signal's own fast-kurtogram band; measured: both in the measured record's",
    )
    ap.add_argument(
        "--axial-load-n",
        type=float,
        default=None,
        help="an axial load on every simulated bearing [N] (DEM and TVSM; the CWRU rig's is not "
        "published: 20 N gives the 9.3 deg contact angle the 0.007 in drive-end records show)",
    )
    ap.add_argument("--data", type=Path, default=DATA)
    ap.add_argument("--json", type=Path, default=None, help="also write the rows as JSON")
    ap.add_argument(
        "--model-gain",
        action="store_true",
        help="scale each rig's path so that the model carries the identification records' "
        "power above the rig's background (bearingsim.side_by_side.model_path_scale)",
    )
    ap.add_argument(
        "--gain-method",
        choices=["power", "spectral", "whittle"],
        default="power",
        help="with --model-gain: power: one scale of the output-only path "
        "(model_path_scale); spectral: the direct gain and every mode's gain fitted to the "
        "identification records' spectra with the model's output as the known input (the "
        "shape in dB, the level by the power balance); whittle: the same by Whittle's "
        "likelihood (bearingsim.side_by_side.model_path_fit)",
    )
    ap.add_argument(
        "--split",
        choices=["size", "load"],
        default="size",
        help="size: the rig identified on the records with another fault size (leave-one-"
        "mounting-out, issue 16's split); load: on the same mounting's records at the other "
        "loads (leave-one-load-out)",
    )
    a = ap.parse_args()
    if a.gain_method != "power" and not a.model_gain:
        ap.error("--gain-method needs --model-gain")
    if a.gain_method != "power" and a.direct_gain is not None:
        ap.error(
            "--direct-gain replaces the output-only path's direct gain; a fitted path has its own"
        )
    realism = {
        "slip_percent": a.slip_percent,
        "pocket_jitter_percent": a.pocket_jitter_percent,
        "defect_profile": a.defect_profile,
        "contact_roughness_m": a.contact_roughness_m,
    }
    if a.axial_load_n is not None:
        realism["axial_load_n"] = a.axial_load_n
    try:  # every input before any simulation: one line, exit 2 (not an error in every row)
        rows = _check_inputs(a, realism)
    except ConfigError as exc:
        print(f"error: {' '.join(str(exc).split())}", file=sys.stderr)
        return 2
    faults = {f: r for f, r in rows.items() if r["fault_diameter_in"]}
    rigs: dict[object, object] = {}  # by mounting set (size split) or by record (load split)
    make_rig = lomo_rig if a.split == "size" else rig_other_loads
    missing = "no other fault size" if a.split == "size" else "no other load"
    out = []
    for name, r in sorted(faults.items(), key=lambda kv: (kv[1]["end"], kv[1]["fs_hz"], kv[0])):
        key = (r["end"], r["fs_hz"], r["fault_diameter_in"]) if a.split == "size" else name
        fault = r["fault"].split()[0]
        base = {
            "record": name,
            "fault": fault,
            "size_in": float(r["fault_diameter_in"]),
            "end": r["end"],
            "fs_hz": float(r["fs_hz"]),
            "grade": r.get("smith_randall_grade", ""),
        }
        if key not in rigs:
            try:
                rigs[key] = make_rig(
                    a.data,
                    name,
                    model_gain=a.model if a.model_gain else None,
                    realism=realism,
                    gain_method=a.gain_method,
                )
            except ConfigError as exc:  # e.g. no power above the background to scale to
                rigs[key] = exc
        rig = rigs[key]
        if isinstance(rig, ConfigError):
            out.append(base | {"status": f"error: {rig}"})
            continue
        if rig is not None and a.direct_gain is not None:
            rig = replace(
                rig,
                gain=a.direct_gain,
                gain_provenance=f"{rig.gain_provenance}; set to {a.direct_gain:g} (--direct-gain)",
            )
        if rig is None:
            out.append(base | {"status": f"no rig: {missing} of this mounting here"})
            continue
        try:
            s = side_by_side(
                a.data / name,
                rig,
                model=a.model,
                duration_s=a.duration_s,
                realism=realism,
                band=a.band,
            )
        except ConfigError as exc:
            out.append(base | {"status": f"error: {exc}"})
            continue
        ok = within_bounds(s["ratio"])
        out.append(
            base
            | s
            | {
                "within": ok,
                "status": "pass" if all(ok.values()) else "fail",
                "rig_modes_hz": [round(m.frequency_hz) for m in rig.modes],
            }
        )
    print(
        "| record | fault | in | end | kHz | grade | RMS meas / sim [m/s²] | line sim/meas "
        "| kurtosis meas / sim | prominence meas / sim [dB] | band meas / sim [kHz] | "
        "within bounds (RMS, line, kurt, prom) |"
    )
    print("|---|---|---|---|---|---|---|---|---|---|---|---|")
    for o in out:
        head = (
            f"| {o['record']} | {o['fault']} | {o['size_in']:.3f} | {o['end']} | "
            f"{o['fs_hz'] / 1000:g} | {o['grade'] or '–'} |"
        )
        if "measured" not in o:
            print(head + f" {o['status']} |||||| ")
            continue
        m, s, q, w = o["measured"], o["simulated"], o["ratio"], o["within"]
        flags = ", ".join(
            "yes" if w[k] else "no" for k in ("rms", "line", "kurtosis", "prominence_db")
        )
        print(
            head + f" {m['rms']:.3g} / {s['rms']:.3g} | {q['line']:.3g}× | "
            f"{m['kurtosis']:.3g} / {s['kurtosis']:.3g} | {m['prominence_db']:.1f} / "
            f"{s['prominence_db']:.1f} | {m['band_lo_hz'] / 1e3:.2f}–{m['band_hi_hz'] / 1e3:.2f} / "
            f"{s['band_lo_hz'] / 1e3:.2f}–{s['band_hi_hz'] / 1e3:.2f} | {flags} |"
        )
    judged = [o for o in out if "within" in o]
    diag = [o for o in judged if str(o["grade"]).startswith("Y")]
    for label, group in (("simulated records", judged), ("graded diagnosable (Y1/Y2)", diag)):
        n = sum(all(o["within"].values()) for o in group)
        print(f"\n{label}: {n} of {len(group)} within all four bounds {BOUNDS}")
        for k in ("rms", "line", "kurtosis", "prominence_db"):
            print(f"  {k}: {sum(o['within'][k] for o in group)} of {len(group)}")
    if a.json:
        write_json(a.json, out)
    return 0


if __name__ == "__main__":
    sys.exit(main())
