"""Report section for issue 16, item 5: simulated signals beside the measured CWRU records.

Each fault record of ``../shared/data/cwru`` whose mounting has records of another fault size
is simulated (VSM, the record's bearing, speed and sample rate, the CWRU fault diameter as the
defect width, EDM depth 0.011 in, the ball resting on the slot's nearer edge
(:data:`bearingsim.side_by_side.DEFECT_PROFILE`), the random slip of real bearings
(:data:`bearingsim.side_by_side.SLIP_PERCENT`), anti-aliased sampling; ball records with the ball
defect) and passed through a rig
identified **without** the record's fault size (leave-one-mounting-out:
:func:`bearingsim.side_by_side.lomo_rig`). The same code computes RMS, fault-line amplitude,
kurtosis and line prominence on both signals (:func:`bearingsim.side_by_side.signal_metrics`);
each is a row against the measurement, judged by issue 16's bounds (RMS and line within ×2,
kurtosis within ×1.5, prominence within 6 dB). The fan end's records, whose mounting has one
fault size here, are judged through a rig of their own mounting's other loads instead
(leave-one-load-out, :func:`bearingsim.side_by_side.rig_other_loads`), counted apart. Record
132 is also set beside the rotor model (the bearing–rotor–housing model of the CWRU motor)
through the same rig, as issue 16 asks.
A figure sets the waveform, the spectrum and the squared envelope spectrum of three records
(outer, inner, ball) side by side, and of the record whose simulated level misses most (the
largest RMS ratio either way), so that the misses the table judges are drawn too.
"""

from __future__ import annotations

import numpy as np

from ...io.cwru import cwru_data_dir, cwru_manifest, cwru_record_number
from ...signal import amplitude_spectrum
from ...signal.benchmark import squared_envelope_spectrum
from ...signal.diagnosis import FAMILY_LINE
from .. import Context, Section, info, judge
from ..figures import FULL_WIDTH, new_figure, save_figure

__all__ = ["TITLE", "run"]

TITLE = (
    "Signals as a sensor records them: VSM + rig beside the measured CWRU records "
    "(issue 16, item 5)"
)

#: the records drawn in the figure: an outer, an inner and a ball fault of the drive end
FIGURE_RECORDS = (
    "12k_Drive_End_OR007@6_2_132.mat",
    "12k_Drive_End_IR007_2_107.mat",
    "12k_Drive_End_B014_2_187.mat",
)
#: (metric key, label, unit) of the rows
METRICS = (
    ("rms", "RMS", "m/s²"),
    ("line", "fault-line amplitude (envelope)", "m/s²"),
    ("kurtosis", "kurtosis", "-"),
    ("prominence_db", "fault-line prominence", "dB"),
)
NOTE = "see docs/validation.md, 'Simulated beside measured through a rig'"
#: the record the rotor model is set beside (issue 16 names it)
ROTOR_RECORD = "12k_Drive_End_OR007@6_2_132.mat"
ROTOR_NOTE = "see docs/validation.md, 'The rotor model beside the records'"


def _figure(ctx: Context, sec: Section, cases: list[dict]) -> None:
    fig, axs = new_figure(
        len(cases), 3, width=FULL_WIDTH, row_height=2.2, squeeze=False, sharex="col"
    )
    for i, c in enumerate(cases):
        fs = c["fs_hz"]
        for lab, x, col in (("measured", c["measured"], "k"), ("VSM + rig", c["simulated"], "C3")):
            a = x - x.mean()
            rms = float(np.sqrt(np.mean(a * a)))
            n = int(0.1 * fs)
            axs[i, 0].plot(np.arange(n) / fs * 1e3, a[:n] / rms, color=col, lw=0.6, label=lab)
            sp = amplitude_spectrum(a, fs)
            axs[i, 1].semilogy(sp.freq / 1e3, np.maximum(sp.amplitude, 1e-9), color=col, lw=0.5)
            es = squared_envelope_spectrum(a, fs, (0.0, 0.5 * fs))
            sel = es.freq <= 600.0
            amp = es.amplitude[sel] / np.median(es.amplitude[sel])
            axs[i, 2].semilogy(es.freq[sel], amp, color=col, lw=0.6)
        name = c["record"].replace(".mat", "")
        # the panels are normalised (shapes side by side): the level misses the table judges
        # are said in the title, so the figure does not read as agreement (a helper's review)
        r = c["ratios"]  # the rows' (_judge_rows)
        axs[i, 0].set_title(
            ("largest miss: " if c.get("largest_miss") else "")
            + f"{name} ({c['fault']}): simulated RMS {r['rms']:.3g}×, fault line "
            f"{r['line']:.3g}× the record's",
            fontsize=9,
            loc="left",
        )
        axs[i, 0].set_ylabel("acceleration / RMS [-]")
        axs[i, 1].set_ylabel("amplitude [m/s²]")
        axs[i, 2].set_ylabel("SES / its median [-]")
        line = FAMILY_LINE.get(c["fault"], "fault line").replace("2x", "2×")
        axs[i, 2].axvline(c["fault_hz"], color="C0", lw=0.8, ls="--", label=line)
        axs[i, 2].legend(fontsize=7, loc="upper right")
    for ax in axs[:-1].ravel():
        ax.tick_params(labelbottom=False)
    axs[-1, 0].set_xlabel("time [ms]")
    axs[-1, 1].set_xlabel("frequency [kHz]")
    axs[-1, 2].set_xlabel("cyclic frequency [Hz]")
    axs[0, 0].legend(fontsize=8, loc="upper right")
    fname = "signals_side_by_side.png"
    save_figure(fig, ctx.out_dir / fname)
    worst = [c for c in cases if c.get("largest_miss")]
    last = (
        f" (here CWRU {cwru_record_number(worst[0]['record'])}, simulated RMS "
        f"{worst[0]['ratios']['rms']:.3g}× the record's)"
        if worst
        else " (none here: a drawn record misses most)"
    )
    sec.figures.append(
        (
            fname,
            "Measured (black) and simulated through the leave-one-mounting-out rig (red), one "
            "drive-end record of each fault type (every record is judged in the table above), "
            "and last the record whose simulated RMS misses the measured one most, where that "
            f"is another record{last}: "
            "the first 0.1 s normalised by the RMS, the amplitude spectrum, and the whole-band "
            "squared envelope spectrum over its median below 600 Hz (dashed: the record's fault "
            "line, BPFO, BPFI or 2×BSF, as its legend says). The normalised panels show shapes, "
            "not levels: each title gives the simulated RMS and fault-line amplitude over the "
            "record's (the line in each signal's own kurtogram band, as the table's rows).",
        )
    )


#: the note of the fan end's rows (leave-one-load-out)
LOLO_NOTE = "see docs/validation.md, 'Leave-one-load-out: a rig of the record's own mounting'"


def _other_loads(sec: Section, data, names: list[str], duration: float) -> None:
    """Judge the records ``names``, whose mounting has no other fault size here (the fan
    end's), through a rig of their own mounting's records at the other loads
    (:func:`bearingsim.side_by_side.rig_other_loads`), with a count of their own: the fan end
    was not judged at all before (a helper's review, twenty-fifth session)."""
    from ...side_by_side import rig_other_loads, simulate_record  # as run(): at run time

    n_within = n_judged = 0
    for name in names:
        rig = rig_other_loads(data, name)
        if rig is None:  # one record of its mounting (313): nothing to identify a rig on
            sec.rows.append(
                info(
                    f"CWRU {cwru_record_number(name)}: VSM + rig (leave-one-load-out)",
                    "scripts/side_by_side.py --split load",
                    "not judged",
                    "no other load of this mounting here",
                )
            )
            continue
        c = simulate_record(data / name, rig, duration_s=duration)
        ok = _judge_rows(sec, c, "VSM + rig (leave-one-load-out)", LOLO_NOTE)
        n_judged += 1
        n_within += all(ok.values())
    if n_judged:
        sec.rows.append(
            info(
                "records without another fault size (the fan end) within all four bounds, "
                "leave-one-load-out (the rig from the same mounting's other loads)",
                "scripts/side_by_side.py --split load; docs/validation.md",
                f"{n_within} of {n_judged}",
            )
        )


def _miss(c: dict) -> float:
    """How far a judged record's simulated RMS lies from the measured one, either way [-]
    (``|log ratio|``; :func:`_judge_rows` keeps the ratios)."""
    return abs(float(np.log(c["ratios"]["rms"])))


def _size_text(key: str, value: float, bound: float, ok: bool) -> str:
    """A ratio (``×``) or a difference in dB (prominence) as the row prints it, with as many
    digits as it takes to read on its side of the bound: a kurtosis ratio of 1.502 printed
    "1.5×; bound ×1.5" beside "mismatch" (twentieth session)."""
    for d in (1, 2, 3, 4, 6) if key == "prominence_db" else (3, 4, 6, 10):
        text = f"{value:+.{d}f}" if key == "prominence_db" else f"{value:.{d}g}"
        v = float(text)
        inside = abs(v) <= bound if key == "prominence_db" else 1.0 / bound <= v <= bound
        if inside == ok:
            break
    return f"{text} dB" if key == "prominence_db" else f"{text}×"


def _judge_rows(sec: Section, c: dict, what: str, note: str) -> dict[str, bool]:
    """Append the four rows of one simulated record ``c`` (:func:`simulate_record`) against its
    measurement, the simulation named ``what``; returns which bounds it meets, and keeps the
    ratios in ``c["ratios"]`` (the figure's titles)."""
    from ...side_by_side import BOUNDS, ratios, signal_metrics, within_bounds

    m = signal_metrics(c["measured"], c["fs_hz"], c["fault_hz"])
    s = signal_metrics(c["simulated"], c["fs_hz"], c["fault_hz"])
    ratio = ratios(m, s)
    c["ratios"] = ratio  # the figure's titles give them (_figure)
    ok = within_bounds(ratio)
    num = cwru_record_number(c["record"])
    for k, label, unit in METRICS:
        size = _size_text(k, ratio[k], BOUNDS[k], ok[k])
        bound = f"±{BOUNDS[k]:g} dB" if k == "prominence_db" else f"×{BOUNDS[k]:g}"
        sec.rows.append(
            judge(
                f"CWRU {num} ({c['fault']} {c['size_in']:.3f} in, {c['end']}, "
                f"{c['fs_hz'] / 1e3:g} kHz): {label} [{unit}], {what} ({size}; bound "
                f"{bound})",
                f"CWRU {num} {c['end']} (measured)",
                getattr(m, k),
                getattr(s, k),
                ok[k],
                "" if ok[k] else note,
                kind="measured",
                db_level=k == "prominence_db",  # its size is the difference in dB
            )
        )

    # issue 16, item 5 also lists the crest factor and the ringing band, without a bound. The
    # crest factor is shown; the ringing band is judged by whether the simulated band overlaps
    # the record's (the rig exists to put the ringing where the records ring: issue 16's "why",
    # the rotor's housing rang at 1 kHz where the records ring at 3.35 kHz). Both were "info",
    # which hid band misses against measurements (a helper's review, twenty-fifth session)
    def band(x) -> str:
        return f"{x.band_lo_hz / 1e3:.2f}–{x.band_hi_hz / 1e3:.2f} kHz"

    head = f"CWRU {num} ({c['fault']} {c['size_in']:.3f} in, {c['end']}, {c['fs_hz'] / 1e3:g} kHz)"
    sec.rows.append(
        info(
            f"{head}: crest factor [-], {what}, beside the measured {m.crest:.3g} (no bound in "
            "issue 16)",
            f"CWRU {num} {c['end']} (measured)",
            f"{s.crest:.3g}",
        )
    )
    overlap = min(m.band_hi_hz, s.band_hi_hz) - max(m.band_lo_hz, s.band_lo_hz)
    sec.rows.append(
        judge(
            f"{head}: ringing band (fast kurtogram) [kHz], {what} (bound: it overlaps the "
            "record's)",
            f"CWRU {num} {c['end']} (measured)",
            band(m),
            band(s),
            overlap > 0.0,
            "" if overlap > 0.0 else note,
            kind="measured",
        )
    )
    return ok


def run(ctx: Context) -> Section:
    # side_by_side sits above the report layer (it runs the rig and the simulations): loaded
    # here, when the section runs, not at import time (tests/test_layers.py)
    from ...side_by_side import DEFECT_PROFILE, SLIP_PERCENT, lomo_rig, simulate_record

    sec = Section("signals", TITLE)
    data = cwru_data_dir()
    if not (data / "manifest.csv").is_file():
        sec.rows.append(info("side by side", "CWRU records", "missing", f"no {data}"))
        return sec
    rows = cwru_manifest(data)
    duration = 1.0 if ctx.quick else 2.0
    rigs: dict[tuple, object] = {}
    cases = []
    worst: dict | None = None  # the record whose simulated RMS misses most (the figure's last)
    n_within = n_judged = 0
    no_lomo = []  # records whose mounting has no other fault size here (the fan end's)
    for name in sorted(rows, key=lambda f: (rows[f]["end"], rows[f]["fs_hz"], f)):
        r = rows[name]
        if not r["fault_diameter_in"]:
            continue
        key = (r["end"], r["fs_hz"], r["fault_diameter_in"])
        if key not in rigs:
            rigs[key] = lomo_rig(data, name)
        if rigs[key] is None:
            no_lomo.append(name)
            continue
        c = simulate_record(data / name, rigs[key], duration_s=duration)
        ok = _judge_rows(sec, c, "VSM + rig", NOTE)
        n_judged += 1
        n_within += all(ok.values())
        if name in FIGURE_RECORDS:
            cases.append(c)
        elif worst is None or _miss(c) > _miss(worst):
            worst = c
    sec.rows.append(
        info(
            "records within all four bounds (issue 16: RMS, line ×2, kurtosis ×1.5, "
            "prominence 6 dB)",
            "scripts/side_by_side.py; docs/validation.md",
            f"{n_within} of {n_judged}",
        )
    )
    # issue 16: "the rotor model with the CWRU profile meets the same bounds on record 132"
    rec = ROTOR_RECORD
    r = rows.get(rec)
    key = (r["end"], r["fs_hz"], r["fault_diameter_in"]) if r else None
    if key in rigs and rigs[key] is not None:
        c = simulate_record(data / rec, rigs[key], model="rotor", duration_s=duration)
        ok = _judge_rows(sec, c, "rotor + rig", ROTOR_NOTE)
        sec.rows.append(
            info(
                "record 132 with the rotor model and the rig within all four bounds (issue 16)",
                "scripts/side_by_side.py --model rotor; docs/validation.md",
                "yes" if all(ok.values()) else "no",
            )
        )
    _other_loads(sec, data, no_lomo, duration)
    if cases:
        cases.sort(key=lambda c: FIGURE_RECORDS.index(c["record"]))
        if worst is not None and _miss(worst) > max(_miss(c) for c in cases):
            cases.append(worst | {"largest_miss": True})
        _figure(ctx, sec, cases)
    sec.text = (
        f"Simulated time {duration:g} s per record (the record's first {duration:g} s "
        f"measured), {SLIP_PERCENT:g} % random slip, {DEFECT_PROFILE} drop profile, "
        "anti-aliased. Rigs identified "
        "leave-one-mounting-out; the fan end has one fault size here, so its records are "
        "judged with a rig of their own mounting's other loads instead (leave-one-load-out: a "
        "weaker split than the issue's, counted apart). This section alone: "
        f"`bearingsim reproduce --section signals{' --quick' if ctx.quick else ''} -o OUT`; "
        "the 2 s tables of docs/validation.md: `python scripts/side_by_side.py`. Each "
        "signal's envelope is taken in its own fast-kurtogram band, which for a measured "
        "record can move with the length read (docs/validation.md, 'Counts')."
    )
    return sec
