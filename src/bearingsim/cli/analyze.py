"""Diagnosis of signal files: ``analyze FILE...`` (issue 17; docs/cli.md, "Diagnosis of signal
files")."""

from __future__ import annotations

import csv
import functools
import io
import math
import re
import sys
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import click

from ..errors import ConfigError, check_range
from .common import (
    Number,
    available_cores,
    check_outputs,
    cli,
    deprecated,
    emit_json,
    map_in_processes,
    speed_column_warning,
)

__all__ = ["analyze_cmd"]

#: modules an analysis imports; loaded before the worker processes are forked
_ANALYZE_MODULES = (
    *("numpy", "scipy.constants", "scipy.fft", "scipy.io"),
    *("bearingsim.catalog", "bearingsim.io", "bearingsim.signal"),
)
#: note on a simulation result sampled without an anti-aliasing filter (``antialiased``
#: false: the ring models' default, the seeds' boxcar sampling, docs/models.md "Sampling"):
#: the impacts' content above fs/2 folds into the band, e.g. a line at a third of BPFO in the
#: README's outer-race simulation at 48 kHz, which its ball family read
ALIASING_NOTE = (
    "the result was simulated without an anti-aliasing filter: content above fs/2 aliases "
    "into its spectrum and may add lines (e.g. at fractions of the fault frequency); "
    "simulate with --antialias"
)
NOISE_FREE_NOTE = (
    "a noise-free model channel (no rig, no noise): the ball passes of even a healthy bearing "
    "(its varying compliance) stand far above a floor no measurement has, and read as an "
    "outer-race series; simulate through a rig (--rig) or with sensor noise to compare with "
    "a measured record"
)
#: how far a --rpm may lie from a simulation result's own speed before a note says so: the
#: fault-line search's tolerance (1 %, :class:`bearingsim.signal.diagnosis.DiagnosisRule`)
SPEED_NOTE_REL = 0.01


#: fewest cage revolutions a record holds for its "none" or "uncertain" to rule out a ball
#: fault [-]: VSM ball faults (6205, through cwru-de-12k, seeds 0 and 1) read "ball" from 6
#: cage revolutions (900 r/min 1 s, 600 r/min 2 s, 300 r/min 4 s) and "none" or "uncertain"
#: at 4 or fewer (300 r/min 1-2 s, 600 r/min 1 s): a ball fault's lines are told by their
#: cage-rate sidebands (twenty-sixth session; docs/validation.md "Simulations through the
#: rig, diagnosed")
MIN_CAGE_REVOLUTIONS = 6.0


def cage_note(revolutions: float) -> str:
    """The note of a "none" or "uncertain" on a record of ``revolutions`` [-] cage turns."""
    return (
        f"the record holds {revolutions:.3g} cage revolutions, fewer than the "
        f"{MIN_CAGE_REVOLUTIONS:g} from which simulated ball faults read 'ball': a ball fault "
        "is not ruled out (a longer record can tell)"
    )


def speed_note(rpm: float, own: float, simulated: bool = True) -> str:
    """The note of a --rpm [r/min] that overrides a result simulated at ``own`` [r/min] (or,
    ``simulated`` False, the speed a measured record's file states)."""
    what = "the result was simulated at" if simulated else "the record's file states"
    return (
        f"rpm = {rpm:g} r/min overrides the {own:g} r/min {what} "
        f"({100.0 * (rpm / own - 1.0):+.2f} %, more than the 1 % the line search allows for a "
        "speed error): the fault lines were searched at the speed given, in windows that also "
        "reach the orders of contact angles up to 20 deg, so a line may still be found off its "
        "target"
    )


def bearing_note(given: str, own: str) -> str:
    """The note of a --bearing that overrides the bearing a simulated result states."""
    return (
        f"bearing = {given} overrides the {own} the result was simulated with: the fault lines "
        f"were searched at {given}'s frequencies"
    )


def signal_unit(rec) -> str | None:
    """The unit of a record's samples: m/s^2 for a CWRU ``.mat`` channel and a simulation
    result's (``sensor``, ``x``, ``y``, ``x_fe``, ``y_fe``: accelerations; the plot said "signal
    unit" for them); a text column's when its name gives an acceleration unit (``de_g`` is read
    in m/s^2, ``io.signal``), None for another text column (its unit is not known)."""
    from ..io.signal import RESULT_SUFFIXES

    if rec.columns:
        return rec.info.get("signal_unit")
    suffix = Path(rec.source).suffix.lower()
    if suffix in RESULT_SUFFIXES or (
        suffix == ".mat" and rec.channel.upper() in ("DE", "FE", "BA")
    ):
        return "m/s^2"
    return None


#: columns of ``analyze --csv``
_CSV_COLUMNS = (
    *("file", "channel", "fs_hz", "rpm", "rpm_source", "bearing", "diagnosis", "confidence"),
    *("leading", "probability", "band_lo_hz", "band_hi_hz", "error"),
    *("channel_source", "contact_angle_deg", "why", "rpm_unchecked"),
)


@dataclass(frozen=True)
class _Request:
    """What ``analyze`` does with each file (the options, checked)."""

    channel: str | None
    fs_hz: float | None
    rpm: float | None
    band: tuple[float, float] | str
    bearing: Any  # Bearing or None (the file's, else the CWRU bearing of the channel)
    plot: str | None = None


@cli.command("analyze", context_settings={"ignore_unknown_options": False})
@click.argument("inputs", nargs=-1, required=True, metavar="FILE...")
@click.option(
    "--bearing",
    "bearing_id",
    default=None,
    show_default="6205-cwru for .mat, 6203-cwru for its channel FE; the result's for .nc",
    help="Catalogue bearing id.",
)
@click.option(
    "--bearing-file", default=None, type=click.Path(dir_okay=False), help="User bearing TOML file."
)
@click.option(
    "--rpm",
    type=Number(0.0, lo_open=True, unit="r/min"),
    default=None,
    show_default="from the file, else the CWRU nominal speed of the load in the file name",
    help="Shaft speed [r/min].",
)
@click.option(
    "--fs-hz",
    "fs_hz",
    type=Number(0.0, lo_open=True, unit="Hz"),
    default=None,
    show_default="from the file; CWRU .mat: 12k/48k in the name, else read off the shaft lines",
    help="Sample rate of the signal [Hz].",
)
@deprecated("--fs", "--fs-hz")
@click.option(
    "--channel",
    default=None,
    show_default="auto for .mat; for results sensor if simulated through a rig, else y",
    help="DE|FE|BA (CWRU .mat; auto: FE when the file name contains Fan_End, else DE), "
    "x|y (result; rotor results also x_fe|y_fe; sensor: the rig's output), or a CSV column.",
)
@click.option(
    "--band-hz",
    "band",
    default="auto",
    help="Envelope band: 'auto' (fast kurtogram), LO,HI or LO HI [Hz] (in orders for a record "
    "order tracked from its speed column).",
)
@deprecated("--band", "--band-hz")
@click.option(
    "--plot",
    default=None,
    type=click.Path(dir_okay=False),
    help="PNG with the envelope spectrum and the matched lines (one FILE only).",
)
@click.option(
    "--jobs",
    type=Number(1, integer=True),
    default=None,
    show_default="the available cores",
    help="Files analysed at once, one process each; 1: one after the other in this process [-].",
)
@click.option("--csv", "as_csv", is_flag=True, help="Print a CSV table, one row per FILE.")
@click.option(
    "--json",
    "as_json",
    is_flag=True,
    help="Print one JSON object (SI) per FILE, one per line (JSON Lines), on stdout.",
)
def analyze_cmd(
    inputs: tuple[str, ...],
    bearing_id: str | None,
    bearing_file: str | None,
    rpm: float | None,
    fs_hz: float | None,
    channel: str | None,
    band: str,
    plot: str | None,
    jobs: int | None,
    as_csv: bool,
    as_json: bool,
) -> None:
    """Envelope analysis and diagnosis of a measured (CWRU .mat), simulated (.nc) or CSV signal.

    Prints {"diagnosis": outer|inner|ball|none|uncertain, "confidence", "band_hz", "shaft_hz"
    (shaft frequency), "fs_hz" (sample rate), "rpm", "rpm_source", "channel", "channel_source",
    "bearing", "peaks": [...]}; a CWRU file whose name says Fan_End is read on its FE channel
    with the fan-end bearing unless --channel says otherwise; "uncertain" when the evidence is
    weak or ambiguous. Several FILEs are analysed in parallel (--jobs) and reported in their
    order, one line (--json: one object, --csv: one row) each; a FILE that cannot be analysed
    gets its own error line (--json: {"file", "error"}) and the others go on; the exit code is
    then 2.
    """
    check_outputs(("--plot", plot))
    if as_json and as_csv:
        raise ConfigError("--json and --csv given together; give one")
    files, band_v = _parse_band(inputs, band)
    if plot is not None and len(files) > 1:
        raise ConfigError(
            f"--plot writes the figure of one FILE; {len(files)} FILEs given: give one FILE"
        )
    if rpm is not None:
        check_range("rpm", rpm, 0.0, lo_open=True, unit="r/min")
    if fs_hz is not None:
        check_range("fs_hz", fs_hz, 0.0, lo_open=True, unit="Hz")
    if jobs is not None:
        check_range("jobs", jobs, 1.0)
    if channel is not None and channel.strip().lower() == "auto":
        channel = "auto"
    bearing = None
    if bearing_id is not None or bearing_file is not None:  # an empty id is an error too
        from ..catalog import resolve_bearing

        bearing = resolve_bearing(bearing_id, bearing_file)
    req = _Request(channel, fs_hz, rpm, band_v, bearing, plot)
    if len(files) == 1 and not (as_json or as_csv):  # today's output; an error is the one line
        _echo_text(_analyze_file(files[0], req), detail=True)
        return
    if as_csv:
        click.echo(_csv_line(_CSV_COLUMNS))
    failed = 0
    work = functools.partial(_analyze_or_error, req=req)
    n_jobs = available_cores() if jobs is None else jobs
    for out in map_in_processes(work, files, n_jobs, preload=_ANALYZE_MODULES):
        if "error" in out:
            failed += 1
            where = "" if len(files) == 1 else f"{out['file']}: "
            click.echo(f"{where}error: {out['error']}", err=True)
        if as_json:
            emit_json(out)
        elif as_csv:
            click.echo(_csv_line(_csv_row(out)))
        elif "error" not in out:
            _echo_text(out, detail=False)
    if failed:
        sys.exit(2)


def _analyze_or_error(path: str, req: _Request) -> dict[str, Any]:
    """:func:`_analyze_file`, or ``{"file", "error"}`` (the one-line message) when the file
    cannot be analysed."""
    from ..errors import BearingsimError

    try:
        return _analyze_file(path, req)
    except BearingsimError as exc:
        return {"file": path, "error": " ".join(str(exc).split())}


def _analyze_file(path: str, req: _Request) -> dict[str, Any]:
    """Load, check and diagnose one file: the JSON object of ``analyze --json``."""
    from ..catalog import resolve_bearing
    from ..io.cwru import cwru_bearing, cwru_end
    from ..io.jsonable import to_jsonable
    from ..signal import analyze_record
    from ..signal.diagnosis import check_resolvable, check_samples

    rec, rpm_source, channel_source = _load_record(path, req)
    check_samples(rec)
    try:
        check_resolvable(rec)
    except ConfigError as exc:  # a speed column in r/min named speed_hz, said so
        raise ConfigError(f"{exc}{_column_in_rpm_hint(rec)}") from None
    mat = Path(rec.source).suffix.lower() == ".mat"
    # a text file named like a CWRU fan-end record gets the fan end's bearing, as a .mat does
    end = rec.channel if mat else cwru_end(path)
    bearing = req.bearing or rec.bearing or resolve_bearing(cwru_bearing(end))
    overridden = (  # a --bearing that is not the one a simulated result states
        rec.bearing.id
        if req.bearing is not None and rec.bearing is not None and req.bearing != rec.bearing
        else None
    )
    if not mat and end == "FE" and bearing.id == cwru_bearing("FE"):
        channel_source = f"{channel_source}; bearing from the file name (Fan_End)"
    # an order-tracked record's angle grid is checked against the memory budget (a speed
    # column in the wrong unit would ask for an unbounded grid)
    from ..dynamics.budget import Budget

    limit = Budget().memory_limit()[0]
    try:
        d = analyze_record(
            rec, bearing, band=req.band, max_memory=limit if math.isfinite(limit) else None
        )
    except ConfigError as exc:
        raise ConfigError(f"{exc}{_column_in_rpm_hint(rec)}") from None
    if req.plot:
        from ..report.figures import save_figure

        save_figure(
            d.plot(
                title=f"{Path(path).name} [{rec.channel}]: {d.diagnosis} ({d.confidence:.2f})",
                unit=signal_unit(rec),
            ),
            req.plot,
        )
    out = {
        "file": str(path),
        **d.as_dict(),
        "contact_angle": _contact_angle(rec, bearing, d.diagnosis),
        "channel": rec.channel,
        "channel_source": channel_source,
        "fs_hz": rec.fs,
        "bearing": bearing.id,
        "rpm": rec.rpm,
        **rec.info,
        "rpm_source": rpm_source,
    }
    if overridden is not None:
        out["bearing_file"] = overridden  # the result's own, which --bearing overrode
    in_hz = None  # a speed in Hz typed for --rpm, or a column of Hz named rpm
    from ..signal.fused import SPEED_REFUTED, refuted_rpm

    own_rpm = refuted_rpm(d.why)  # the record's own speed, where it refutes the one used
    refuted = SPEED_REFUTED in (d.why or "")  # also an order-tracked column's (no r/min named)
    given = rpm_source == "option" and rec.rpm is not None and rec.speed_hz is None
    spec = None  # the record's padded spectrum: one for the Hz check and the unchecked note
    if given:
        from ..signal.contact_angle import hz_given_as_rpm, hz_warning, padded_spectrum

        spec = padded_spectrum(rec.x, rec.fs)
        c = hz_given_as_rpm(None, rec.fs, rec.rpm / 60.0, spectrum=spec)
        # read as Hz only where that agrees with the record's own speed, if named (a helper,
        # twenty-seventh session: 311 at --rpm 1600 was refuted naming 1751 r/min and noted
        # "reads like the speed in Hz ... (96569 r/min)" beside it)
        if c is not None and (own_rpm is None or abs(c.shaft_hz / (own_rpm / 60.0) - 1) < 0.02):
            in_hz = hz_warning(rec.rpm, c)
    elif rec.speed_hz is not None and rec.rpm is None:
        in_hz = speed_column_warning(rec, in_rpm=False)
    # too short to rule a ball fault out? Not said where the speed itself is refuted or reads
    # like Hz: its revolutions are the wrong speed's (a helper: "2 cage revolutions" beside
    # "reads like the speed in Hz" on a 10 s record of 118)
    wrong_speed = in_hz is not None or refuted
    if d.diagnosis in ("none", "uncertain") and not wrong_speed:
        import numpy as np

        from ..geometry import characteristic_frequencies

        shaft_revs = (  # the shaft turns the record spans
            rec.rpm / 60.0 * rec.x.size / rec.fs
            if rec.rpm is not None
            else float(np.sum(rec.speed_hz)) / rec.fs
        )
        revs = shaft_revs * characteristic_frequencies(bearing, 1.0).ftf_hz
        if revs < MIN_CAGE_REVOLUTIONS:
            out["cage_revolutions"] = revs
    if in_hz is not None:
        out["rpm_warning"] = in_hz
    elif given and rec.info.get("rpm_file") is None and not wrong_speed:
        # a measured record's only speed is the one given: could its shaft lines judge it?
        from ..io.signal import RESULT_SUFFIXES
        from ..signal.contact_angle import unchecked_speed_note

        if Path(rec.source).suffix.lower() not in RESULT_SUFFIXES and (
            text := unchecked_speed_note(None, rec.fs, rec.rpm / 60.0, spectrum=spec)
        ):
            out["rpm_unchecked"] = text
    elif getattr(d, "speed_unchecked", "") and not wrong_speed:
        # an order-tracked speed column its shaft comb cannot judge (a helper, twenty-eighth
        # session: 132 with a column 5 % off and 1 % noise read "inner" 0.66 without a word)
        out["rpm_unchecked"] = d.speed_unchecked
    extra = _result_notes(out)
    if extra:
        out["notes"] = [*out.get("notes", []), *extra]
    return to_jsonable(out)


def _column_in_rpm_hint(rec: Any) -> str:
    """``"; the speed column ... reads like r/min"`` where ``rec``'s speed column holds r/min
    under a name read as Hz (``speed_hz`` holding 1748: the order tracking at 104880 r/min
    failed naming fs_hz; exploratory testing, twenty-sixth session), else ``""``."""
    text = speed_column_warning(rec, in_hz=False)
    return "" if text is None else f"; {text}"


def _result_notes(out: dict[str, Any]) -> list[str]:
    """The notes about a simulated result, from what its reader recorded (``antialiased``,
    ``noise_free``, ``rpm_file``, ``bearing_file``: keys of the file's output), a --rpm that
    reads like a speed in Hz (``rpm_warning``) and a "none" or "uncertain" on too few cage
    revolutions (``cage_revolutions``): added to ``notes`` and printed by the text output."""
    notes = [out["rpm_warning"]] if out.get("rpm_warning") else []
    if out.get("rpm_unchecked"):
        notes.append(out["rpm_unchecked"])
    if out.get("cage_revolutions") is not None:
        notes.append(cage_note(out["cage_revolutions"]))
    if out.get("antialiased") is False:
        notes.append(ALIASING_NOTE)
    if out.get("noise_free"):
        notes.append(NOISE_FREE_NOTE)
    own = out.get("rpm_file")  # a result's own speed, when --rpm overrode it
    if own is not None and out.get("speed_column_refuted"):
        # a steady speed column its shaft lines refute, which --rpm overrode (rpm_over_column)
        notes.append(
            f"rpm = {out['rpm']:g} r/min overrides the record's steady speed column (median "
            f"{own:.6g} r/min, {100.0 * (out['rpm'] / own - 1.0):+.2f} %), which its shaft "
            "harmonics refute"
        )
    elif own is not None and abs(out["rpm"] / own - 1.0) > SPEED_NOTE_REL:
        from ..io.signal import RESULT_SUFFIXES

        simulated = Path(out["file"]).suffix.lower() in RESULT_SUFFIXES
        notes.append(speed_note(out["rpm"], own, simulated))
    if out.get("bearing_file"):  # a result's own bearing, when --bearing overrode it
        notes.append(bearing_note(out["bearing"], out["bearing_file"]))
    return notes


def _contact_angle(rec: Any, bearing: Any, verdict: str) -> dict[str, Any] | None:
    """The contact angle a ball bearing with a race fault runs at, read from the record's own
    fault line and shaft lines (:func:`bearingsim.signal.contact_angle.estimate_contact_angle`;
    docs/validation.md, "Contact angle of the CWRU bearings"): a few degrees mean an axial
    load. None for another verdict, a roller bearing or an order-tracked record;
    ``{"error": ...}`` when the record's lines do not give it."""
    from ..errors import ConfigError
    from ..geometry import BallBearing
    from ..io.signal import RESULT_SUFFIXES
    from ..signal.contact_angle import estimate_contact_angle

    if verdict not in ("inner", "outer") or not isinstance(bearing, BallBearing):
        return None
    if rec.rpm is None:  # order tracked: no shaft lines at a fixed frequency
        return None
    # a simulation's speed is exact (and a model without unbalance has no shaft line to read);
    # a measured record's stored speed is rounded: measured from its own shaft harmonics
    simulated = Path(rec.source).suffix.lower() in RESULT_SUFFIXES
    try:
        est = estimate_contact_angle(
            rec.x, rec.fs, bearing, verdict, rec.rpm / 60.0, measure_shaft=not simulated
        )
    except ConfigError as exc:
        return {"error": " ".join(str(exc).split())}
    return est.as_dict()


def _load_record(path: str, req: _Request) -> tuple[Any, str, str]:
    """The record (``load_signal``), where its speed came from (the option, the file, or the
    CWRU nominal speed of the load in the file name when the file gives none) and where its
    channel came from: ``"option"``, ``"file name (Fan_End)"`` — a CWRU fan-end record's fault
    is in the fan-end bearing, which its FE accelerometer faces — or ``"default"``."""
    from ..io.cwru import cwru_end
    from ..signal.diagnosis import load_signal_and_speed

    ch, source = req.channel, "option"
    if ch is None or ch == "auto":
        ch, source = None, "default"
        if Path(path).suffix.lower() == ".mat":  # CWRU: DE unless the name says fan end
            ch = cwru_end(path)
            if ch == "FE":
                source = "file name (Fan_End)"
    rec, rpm_source = load_signal_and_speed(path, channel=ch, fs_hz=req.fs_hz, rpm=req.rpm)
    return rec, rpm_source, source


def _echo_text(out: dict[str, Any], detail: bool) -> None:
    """The human line of one analysed file (``detail``: the file's name and its detected
    lines, as for a single FILE; else the path as given)."""
    name = Path(out["file"]).name if detail else out["file"]
    lo, hi = out["band_hz"]
    speed = ""
    if out["rpm_source"].startswith("name"):  # say when the speed is not the record's
        speed = f", rpm {out['rpm']:g} from the file {out['rpm_source']}"
    if str(out.get("fs_source", "")).startswith("inferred"):  # nor the sample rate
        speed += f", fs {out['fs_hz'] / 1000:g} kHz {out['fs_source']}"
    if str(out.get("channel_source", "")).startswith("file name"):  # nor a fan-end default
        speed += f", channel {out['channel']} and {out['bearing']} from the file name"
    elif "bearing from the file name" in str(out.get("channel_source", "")):
        speed += f", {out['bearing']} from the file name"
    from ..signal.fused import SPEED_REFUTED

    lead = ""
    refuted = SPEED_REFUTED in str(out.get("why") or "")  # a family led at the wrong speed
    if (
        out["diagnosis"] == "uncertain"
        and out.get("leading")
        and out.get("probability")
        and not refuted
    ):
        # an "uncertain" with a leading family: say which family led, at what probability
        lead = f", leading family {out['leading']} at p {out['probability']:.2f}"
    orders = out.get("domain") == "order"  # an order-tracked record: band and lines in orders
    band = f"band {lo:g}-{hi:g} orders" if orders else f"band {lo:.0f}-{hi:.0f}"
    click.echo(
        f"{name} [{out['channel']}]: {out['diagnosis']} (confidence "
        f"{out['confidence']:.2f}), {band}"
        + (f" ({out['method']})" if "method" in out else "")
        + lead
        + speed
    )
    if out.get("why"):  # what made the verdict "uncertain"
        click.echo(f"  why: {out['why']}")
    for note in _result_notes(out):
        click.echo(f"  note: {note}")
    if not detail:
        return
    ca = out.get("contact_angle")
    if ca and "error" not in ca:
        line = "BPFO" if ca["family"] == "outer" else "BPFI"
        click.echo(
            f"  contact angle {ca['contact_angle_deg']:.1f} deg: {line} at order "
            f"{ca['order']:.4f} (alpha = 0: {ca['order_alpha0']:.4f}) of the "
            + (
                "measured shaft speed"
                if ca["shaft_lines"]
                else ("speed given" if out["rpm_source"] == "option" else "file's speed")
            )
            + f" {ca['shaft_hz'] * 60:.1f} r/min ({ca['harmonic']}x line, SNR "
            f"{ca['snr_db']:.0f} dB); below {ca['resolution_deg']:.1f} deg not told from 0 "
            "(1.5 % random slip over this record)"
        )
        if ca["contact_angle_deg"] == 0.0 and ca["order"] != ca["order_alpha0"]:
            # BPFO's order rises with the angle, BPFI's falls: a line on the other side of
            # its alpha = 0 order (within the search's padding) is read as alpha = 0
            click.echo(
                f"  note: the line lies {100 * abs(ca['order'] / ca['order_alpha0'] - 1):.2f} % "
                "on the far side of its alpha = 0 order (speed or line precision): read as 0 deg"
            )
    shown = [p for p in out["peaks"] if p["detected"]]
    for p in shown:
        at = "" if orders else f"{p['freq_hz']:9.2f} Hz  "  # freq_hz is an order there
        click.echo(f"  {p['label']:<12} {at}order {p['order']:7.3f}  SNR {p['snr_db']:5.1f} dB")
    # the labels' grammar where a higher sideband stands beside a harmonic's first one
    # (BPFI-2xfr beside 2xBPFI-fr read alike; twenty-fifth session's note)
    higher = [m for p in shown if (m := re.fullmatch(r"(.+?)([+-])(\d+)x(\w+)", p["label"]))]
    if higher:  # explained with a label of this record's (109 lists 2xBSF-2xFTF only)
        carrier, sign, m, mod = higher[0].groups()
        click.echo(
            f"  (labels: {higher[0].group(0)} = {carrier.replace('x', ' x ')} {sign} {m} {mod},"
            f" a higher sideband; a prefix hx is a harmonic, {carrier}{sign}{mod} its first "
            'sideband; docs/cli.md, "Line labels")'
        )


def _csv_row(out: dict[str, Any]) -> list[Any]:
    """The ``--csv`` row of one file; the band is empty for an order-tracked record (its band
    is in orders: ``--json``)."""
    row = {k: out.get(k) for k in _CSV_COLUMNS}
    if "error" not in out and out.get("domain") != "order":
        row["band_lo_hz"], row["band_hi_hz"] = out["band_hz"]
    ca = out.get("contact_angle") or {}
    row["contact_angle_deg"] = ca.get("contact_angle_deg")
    return [row[k] for k in _CSV_COLUMNS]


def _csv_line(values: Any) -> str:
    """One CSV line (RFC 4180 quoting; None as an empty field)."""
    buf = io.StringIO()
    csv.writer(buf, lineterminator="").writerow(["" if v is None else v for v in values])
    return buf.getvalue()


def _parse_band(inputs: tuple[str, ...], band: str) -> tuple[list[str], tuple[float, float] | str]:
    """The FILEs and the band of ``--band-hz auto``, ``--band-hz LO,HI`` or ``--band-hz LO HI``.

    In the last form click hands HI over as a positional argument beside the FILEs: HI is then
    the one positional argument that is a number and not an existing path; with ``auto`` or two
    values every positional argument is a FILE."""
    items = list(inputs)
    b = band.strip().lower()
    if b == "auto":
        return items, "auto"
    parts = [v for v in b.replace(",", " ").split() if v]
    if len(parts) == 1 and _is_float(parts[0]):
        nums = [v for v in items if _is_float(v) and not Path(v).exists()]
        if len(nums) != 1:
            found = f"{len(nums)} numbers among the FILEs" if nums else "no HI"
            raise ConfigError(
                f"band = {band!r} is invalid ({found}); valid: --band-hz auto or --band-hz LO,HI "
                "(two numbers in Hz)"
            )
        parts.append(nums[0])
        items.remove(nums[0])
    if len(parts) != 2 or not all(_is_float(v) for v in parts):
        raise ConfigError(
            f"band = {band!r} is invalid; valid: --band-hz auto or --band-hz LO,HI [Hz]"
        )
    if not items:
        raise ConfigError("analyze: no FILE given")
    return items, (float(parts[0]), float(parts[1]))


def _is_float(v: str) -> bool:
    try:
        float(v)
        return True
    except ValueError:
        return False
