"""``bearingsim rig``: measurement chains (issue 16): identify one from measured records, show
one."""

from __future__ import annotations

import shlex
import sys
import tomllib
from dataclasses import replace
from pathlib import Path
from typing import TYPE_CHECKING

import click

from ..errors import ConfigError
from .common import Number, check_outputs, cli, emit_json, json_option, output_option

if TYPE_CHECKING:
    from ..rig import RigBearing


@cli.group("rig")
def rig_group() -> None:
    """Measurement chains (rigs): identify one from measured records, show one."""


@rig_group.command("identify")
@click.argument("records", nargs=-1, required=True, metavar="RECORD...")
@click.option("--name", required=True, help="Name of the rig (written into the file).")
@click.option("--description", default="", help="What the rig is (sensor, machine).")
@click.option(
    "--channel",
    default=None,
    show_default="auto for .mat: FE when every name says Fan_End, else DE",
    help="DE|FE|BA (CWRU .mat), sensor|x|y (result; a result with a rig: sensor), or a CSV "
    "column; the same for every record.",
)
@click.option(
    "--rpm",
    type=Number(0.0, lo_open=True, unit="r/min"),
    default=None,
    show_default="from each file",
    help="Shaft speed [r/min] of every record (for the shaft-order tones and the rig's "
    "rpm_range; one speed gives no speed law). Refused against a record's own speed column.",
)
@click.option(
    "--fs-hz",
    "fs_hz",
    type=Number(0.0, lo_open=True, unit="Hz"),
    default=None,
    show_default="from each file; CWRU: 12k/48k in the name",
    help="Sample rate of every record [Hz] (needed for a CSV file without a time column).",
)
@click.option(
    "--max-modes",
    type=Number(1, integer=True),
    default=3,
    show_default=True,
    help="Largest number of modes.",
)
@click.option(
    "--model-gain",
    "model_gains",
    multiple=True,
    # bearingsim.rig.GAIN_MODELS, written out: the CLI starts without importing NumPy
    type=click.Choice(("vsm", "dem", "tvsm", "rotor")),
    help="Also identify this model's path gain (repeatable): the records' conditions are "
    "simulated with it (1 s each, with the realism a rig brings) and the path scaled so "
    "that it carries the fault records' power above the background (healthy records are "
    "skipped). The records must be CWRU records listed in a manifest.csv beside them.",
)
@click.option(
    "--gain-method",
    type=click.Choice(("power", "spectral")),
    default="power",
    show_default=True,
    help="How --model-gain is identified: power, one scale of the output-only path (the fault "
    "records' power above the background); spectral, every gain of the path (direct and each "
    "mode's) fitted to the records' spectra with the model's output as the known input, the "
    "level by the same power balance (written as path_gain and mode_gains).",
)
@click.option(
    "--defect-profile",
    type=click.Choice(("geometric", "rectangular", "pit")),
    default=None,
    show_default="geometric, the realism a rig brings",
    help="Drop profile the records' faults are simulated with for --model-gain (a model gain "
    "matches that profile's level; it is written into the rig, and a run with another "
    "profile through it is warned).",
)
@click.option(
    "--conditions",
    default=None,
    type=click.Path(dir_okay=False),
    help="CSV of the records' conditions for --model-gain on a user's own records (columns "
    "file, fault, bearing (a catalogue id or a bearing TOML beside the CSV), defect_width_m; "
    "optional defect_depth_m, rpm); without it the records must be CWRU records listed in a "
    "manifest.csv.",
)
@click.option(
    "--plot",
    default=None,
    type=click.Path(dir_okay=False),
    help="PNG: measured vs identified spectra and the impulsive spectrum.",
)
@output_option("Rig TOML file to write.", required=True)
@json_option
def identify_cmd(
    records: tuple[str, ...],
    name: str,
    description: str,
    channel: str | None,
    rpm: float | None,
    fs_hz: float | None,
    max_modes: int,
    model_gains: tuple[str, ...],
    gain_method: str,
    conditions: str | None,
    defect_profile: str | None,
    plot: str | None,
    output: str,
    as_json: bool,
) -> None:
    """Identify a rig from measured records of one machine and channel (output-only: modes
    from the impulsive spectrum and the ringing decay, background, shaft-order tones; with
    --model-gain, a model-based path gain per model). Records at speeds spanning 1.5x or more
    (three or more with a known speed) also give the background's growth with speed."""
    check_outputs(("-o/--output", output), ("--plot", plot))
    if Path(output).suffix.lower() != ".toml":  # `--rig FILE` reads it as a rig file by name
        raise ConfigError(
            f"-o/--output = {output!r} names no TOML file; valid: a name ending in .toml (a rig "
            "file, read back by --rig FILE and rig show)"
        )
    inputs = {Path(p).expanduser().resolve(): p for p in records}
    for option, path in (("-o/--output", output), ("--plot", plot)):
        if path is not None and Path(path).expanduser().resolve() in inputs:
            raise ConfigError(
                f"{option} = {path!r} is the record {inputs[Path(path).expanduser().resolve()]!r}"
                "; valid: an output apart from the records (writing it would replace one)"
            )
    from ..io.atomic import atomic_open
    from ..io.signal import read_signal
    from ..rig import Rig
    from ..rig_identify import identify_rig, rig_to_toml
    from ..signal.diagnosis import check_samples

    if not name.strip():
        raise ConfigError(f"name = {name!r} is empty; valid: a name for the rig (--name)")
    if not name.isprintable() and not any(0xD800 <= ord(c) <= 0xDFFF for c in name):
        raise ConfigError(
            f"name = {name!r} holds a control character; valid: printable text (--name)"
        )
    for field, text in (("name", name), ("description", description)):
        try:  # bytes that are not UTF-8 reach Python as surrogates, which no file can hold
            text.encode("utf-8")
        except UnicodeEncodeError:
            shown = text.encode("utf-8", "surrogateescape").decode("utf-8", "backslashreplace")
            raise ConfigError(
                f"{field} = {shown!r} is not UTF-8 text; valid: text in the terminal's UTF-8 "
                f"(--{field})"
            ) from None
    seen: dict[Path, str] = {}
    for p in records:  # one record given twice would count twice in every median
        key = Path(p).resolve()
        if key in seen:
            raise ConfigError(
                f"records: {p!r} is the same file as {seen[key]!r}; valid: each record once"
            )
        seen[key] = p
    ch = _channel(records, channel)
    recs = [check_samples(read_signal(p, channel=ch, rpm=rpm, fs_hz=fs_hz)) for p in records]
    if rpm is not None:  # a speed column: --rpm would override it unseen (analyze's rule)
        from ..signal.diagnosis import rpm_over_column

        valid = "the records' speed (or no --rpm, to take each file's)"
        recs = [rpm_over_column(r, rpm, valid=valid) for r in recs]
    speed_warnings: list[str] = []  # printed after the rig is written
    _column_hz_warnings(recs, speed_warnings)
    _check_steady_columns(recs)
    if rpm is not None:  # the shaft-order tones are placed at this speed: the record may refute it
        from ..io.signal import RPM_OPTION_REL
        from ..signal.contact_angle import check_speed_given, hz_hint, hz_warning

        for r in recs:
            # a CWRU file's X###RPM, or a speed column its shaft lines refute, which --rpm
            # overrides (rpm_over_column)
            stated = r.info.get("rpm_file")
            c, in_hz = check_speed_given(
                r.x, r.fs, rpm / 60.0, stated_hz=None if stated is None else stated / 60.0
            )
            if c is not None:
                off = 100.0 * (rpm / (60.0 * c.shaft_hz) - 1.0)  # as the override's warning
                raise ConfigError(
                    f"rpm = {rpm:.6g} r/min: the shaft harmonics of {Path(r.source).name!r} put "
                    f"its speed at {60.0 * c.shaft_hz:.6g} r/min (the speed given is {off:+.2f} % "
                    f"off it{hz_hint(rpm, 60.0 * c.shaft_hz)}); valid: the records' speed (or no "
                    "--rpm, to take each file's)"
                )
            if stated is not None and abs(rpm / stated - 1.0) > RPM_OPTION_REL:
                # its shaft lines neither confirm nor refute the file: said, not refused
                # (exploratory testing, twenty-sixth session: 107 at 2000 r/min passed unsaid)
                what = (
                    "steady speed column its shaft harmonics refute"
                    if r.info.get("speed_column_refuted")
                    else "its file states"
                )
                speed_warnings.append(
                    f"warning: {Path(r.source).name}: rpm = {rpm:.6g} r/min overrides the "
                    f"{stated:.6g} r/min {what} ({100.0 * (rpm / stated - 1.0):+.2f} %"
                    f"{hz_hint(rpm, stated)}); the rig's shaft-order tones and rpm_range take the "
                    "speed given"
                )
            if r.speed_hz is None and in_hz is not None:
                speed_warnings.append(f"warning: {Path(r.source).name}: {hz_warning(rpm, in_hz)}")
    faulty: list[Path] = []
    user: list[tuple[object, dict]] = []  # (record, condition) with --conditions
    if conditions is not None and not model_gains:
        raise ConfigError("--conditions is only read with --model-gain; give both or neither")
    if defect_profile is not None and not model_gains:
        raise ConfigError(
            f"--defect-profile {defect_profile} is only read with --model-gain; give both or "
            "neither"
        )
    if gain_method != "power" and not model_gains:
        raise ConfigError(
            f"--gain-method {gain_method} is only read with --model-gain; give both or neither"
        )
    if conditions is not None:
        realism = {"defect_profile": defect_profile} if defect_profile else {}
        user = _user_conditions(conditions, records, recs, model_gains, realism, speed_warnings)
        named = {  # a bearing file the CSV names is an input too
            Path(c["bearing_file"]).resolve(): c["bearing_file"]
            for _r, c in user
            if "bearing_file" in c
        }
        for option, path in (("-o/--output", output), ("--plot", plot)):
            if path is not None and Path(path).expanduser().resolve() in named:
                raise ConfigError(
                    f"{option} = {path!r} is the bearing file "
                    f"{named[Path(path).expanduser().resolve()]!r} that --conditions names: "
                    "writing it would replace that file; valid: another path"
                )
    elif model_gains:  # before any work: is every record's condition known?
        from ..side_by_side import FAULT_FAMILIES, cwru_row

        for p in records:
            row = cwru_row(p)
            if row is None:
                raise ConfigError(
                    f"--model-gain: record {Path(p).name!r} is not in "
                    f"{Path(p).parent / 'manifest.csv'}; valid: CWRU records listed there, or "
                    "--conditions FILE.csv giving each of your own records' fault, bearing, "
                    "defect size and speed (the simulation needs them)"
                )
            if row["fault"].split()[0] in FAULT_FAMILIES:
                faulty.append(Path(p))
        if not faulty:
            raise ConfigError(
                "--model-gain: no record has a bearing fault; valid: at least one outer-race, "
                "inner-race or ball fault record (a model gain is matched to a fault's power; "
                "healthy records are skipped)"
            )
    # printed after the rig is written: a run that ends in an error prints the error alone
    # (after --conditions, whose rows give a speed to records without one)
    unknown = [Path(r.source).name for r in recs if r.rpm is None and r.speed_hz is None]
    how = "model_path_scale" if gain_method == "power" else "model_path_fit"
    # the exact command, as typed (run from the folder it names its files relative to)
    command = "bearingsim rig identify " + " ".join(shlex.quote(a) for a in sys.argv[3:])
    ir = identify_rig(
        recs,
        name=name,
        description=description,
        provenance=f"identified by `{command}` (bearingsim.rig_identify, output-only"
        + (f"; the [[model_gain]] entries model-based: bearingsim.side_by_side.{how})"
           if model_gains else ")"),  # fmt: skip
        max_modes=int(max_modes),
        # a CWRU sensor's end: the rotor model reads that end's housing through the rig
        end=ch.upper() if ch and ch.upper() in ("DE", "FE")
        and all(Path(p).suffix.lower() == ".mat" for p in records) else None,
    )  # fmt: skip
    rig = ir.rig
    # the bearing the records were taken on, where known: a CWRU end's, or the one catalogue
    # bearing of every --conditions row (a run of another size through the rig is warned)
    if user:  # the rows say which bearing, also for CWRU-format records of another machine
        rig = replace(rig, bearing=_conditions_bearing(c for _r, c in user))
    elif rig.end is not None:
        from ..io.cwru import cwru_bearing

        rig = replace(rig, bearing=cwru_bearing(rig.end))
    no_bearing = None  # said after the rig is written: why it names no bearing
    if user and rig.bearing is None:
        named = sorted({c.get("bearing") or Path(c["bearing_file"]).name for _r, c in user})
        no_bearing = (
            f"note: the rig names no bearing (the conditions give {', '.join(named)}, of "
            "different sizes, and a rig records one): a run with a bearing of another size "
            "through it is not warned"
        )
    if model_gains:
        from .. import side_by_side as sbs

        bar = sys.stderr.isatty()
        spectral = gain_method == "spectral"
        kw: dict = {"objective": "spectral"} if spectral else {}
        if defect_profile is not None:
            kw["realism"] = {"defect_profile": defect_profile}
        for m in dict.fromkeys(model_gains):
            if user:
                f = sbs.model_path_fit_conditions if spectral else sbs.model_path_scale_conditions
                rig, _ = f(rig, [r for r, _ in user], [c for _, c in user], model=m,
                           progress=bar, **kw)  # fmt: skip
            else:
                f = sbs.model_path_fit if spectral else sbs.model_path_scale
                rig, _ = f(rig, faulty, model=m, progress=bar, **kw)
    text = rig_to_toml(rig)
    Rig.from_dict(tomllib.loads(text), source="identified rig")  # round-trip check
    with atomic_open(output, "w", field="-o/--output", encoding="utf-8") as fh:
        fh.write(text)
    if plot:
        from ..report.figures import save_figure

        save_figure(ir.plot(rig), plot)
    if unknown:
        click.echo(
            f"warning: no shaft speed for {', '.join(unknown)} (no --rpm, no rpm in the file"
            + (" or in its --conditions row" if conditions else "")
            + "): "
            "the rig got no shaft-order tones from them",
            err=True,
        )
    if no_bearing:
        click.echo(no_bearing, err=True)
    for w in speed_warnings:
        click.echo(w, err=True)
    out = {
        "output": str(output),
        "name": name,
        "records": [str(r.source) for r in recs],
        "modes": [
            {"frequency_hz": m.frequency_hz, "damping_ratio": m.damping_ratio, "gain": m.gain}
            for m in ir.rig.modes
        ],
        "tones": [
            {"order": t.order, "amplitude_m_per_s2": t.amplitude_m_per_s2} for t in ir.rig.tones
        ],
        "model_gains": {g.model: g.scale for g in rig.model_gains},
        "model_paths": {
            g.model: {"path_gain": g.path_gain, "mode_gains": list(g.mode_gains or ())}
            for g in rig.model_gains
            if g.scale is None
        },
        "background_rms_m_per_s2": rig.background.rms() if rig.background else 0.0,
        "background_speed_exponent": rig.background.speed_exponent if rig.background else None,
        "background_rpm_ref": rig.background.rpm_ref if rig.background else None,
        "background_speed_exponent_stderr": ir.speed_law.stderr if ir.speed_law else None,
        "background_speed_law": ir.speed_law.note if ir.speed_law else None,
    }
    if as_json:
        emit_json(out)
        return
    modes = ", ".join(
        f"{m.frequency_hz:.0f} Hz (zeta {m.damping_ratio:.3f}, gain {m.gain:.2f})"
        for m in ir.rig.modes
    )
    gains = "".join(f"; {g.model}: {g.describe()}" for g in rig.model_gains)
    click.echo(
        f"wrote {output}: rig {name} from {len(recs)} records; modes {modes}; background "
        f"{out['background_rms_m_per_s2']:.3g} m/s^2 RMS{gains}"
    )
    click.echo(f"  background speed law: {out['background_speed_law']}")


@rig_group.command("show")
@click.argument("rig_name", metavar="NAME|FILE")
@json_option
def show_cmd(rig_name: str, as_json: bool) -> None:
    """Print a rig (a shipped profile or a file) after validating it."""
    from ..rig import coverage_rate_hz, load_rig

    r = load_rig(rig_name)
    if as_json:
        emit_json(r.to_dict())
        return
    click.echo(f"rig {r.name}" + (f": {r.description}" if r.description else ""))
    click.echo(f"  provenance: {r.provenance}")
    end = f"; sensor at the {r.end} end" if r.end else ""
    click.echo(f"  direct gain {r.gain:g}; input channel {r.input_channel}{end}")
    if r.bearing is not None:
        what = r.bearing if isinstance(r.bearing, str) else r.bearing.describe()
        click.echo(
            f"  identified on records of the {what} (a run's bearing of another size is warned)"
        )
    if r.fs_hz is not None:
        click.echo(
            f"  identified from records at {r.fs_hz:g} Hz: a scenario with this rig and no "
            "fs_hz of its own is sampled at it"
        )
    if r.rpm_range is not None:
        lo, hi = r.rpm_range
        click.echo(
            f"  identified at {lo:g}-{hi:g} r/min: a run more than 10 % outside gets a "
            "RigSpeedWarning"
        )
    for m in r.modes:
        click.echo(f"  mode {m.frequency_hz:.1f} Hz, zeta {m.damping_ratio:.4f}, gain {m.gain:.3g}")
    for t in r.tones:
        where = f"order {t.order:g}" if t.order is not None else f"{t.frequency_hz:g} Hz"
        click.echo(f"  tone {where}: {t.amplitude_m_per_s2:.4g} m/s^2")
    if r.background is not None:
        fb = r.background.frequency_hz
        click.echo(
            f"  background: {len(r.background.psd)} PSD points, {min(fb):g}-{max(fb):g} Hz "
            f"(an output rate above {coverage_rate_hz(r):g} Hz gets a RigRateWarning)"
        )
        b = r.background
        if b.speed_exponent is not None:
            click.echo(
                f"  background amplitude x (speed / {b.rpm_ref:.5g} r/min)^{b.speed_exponent:.3g}"
            )
        else:
            click.echo("  background the same at every shaft speed (no speed law)")
    click.echo(f"  sensor noise {r.noise_rms_m_per_s2:g} m/s^2")
    for g in r.model_gains:
        click.echo(f"  {g.describe()} for the {g.model} model's output (model-based)")


#: columns of a --conditions file: required, then optional
_COND_REQUIRED = ("file", "fault", "bearing", "defect_width_m")
_COND_OPTIONAL = ("defect_depth_m", "rpm")


def _user_conditions(
    path: str,
    records: tuple[str, ...],
    recs: list,
    models: tuple[str, ...],
    realism: dict,
    warnings_out: list[str],
):
    """The (record, condition) pairs of the fault records for a model gain on a user's own
    records, read from the --conditions CSV and checked before any work (one-line errors):
    every record listed once by file name, a known fault and bearing, positive sizes. A row's
    speed becomes its record's where the record has none (``recs`` is updated in place: the
    rig's tones and ``rpm_range`` take it); warnings are appended to ``warnings_out``."""
    import csv

    from ..io.signal import RPM_OPTION_REL, column_speed_refutes, speed_span_text
    from ..rig_identify import _record_rpm
    from ..side_by_side import FAULT_FAMILIES
    from ..signal.contact_angle import check_speed_given, hz_warning

    if "rotor" in models:
        raise ConfigError(
            "--model-gain rotor with --conditions: the rotor model is the CWRU motor; its gain "
            "is identified from CWRU records (without --conditions); valid models here: vsm, "
            "dem, tvsm"
        )
    try:  # utf-8-sig: a spreadsheet's "CSV UTF-8" starts with a byte-order mark
        with open(path, encoding="utf-8-sig", newline="") as fh:
            reader = csv.DictReader(fh)
            rows = list(reader)
            header = [h.strip() for h in (reader.fieldnames or [])]
    except OSError as exc:
        raise ConfigError(f"--conditions {path}: cannot be read ({exc.strerror})") from None
    except UnicodeDecodeError as exc:
        raise ConfigError(
            f"--conditions {path}: byte {exc.start} is not UTF-8; valid: a UTF-8 text file"
        ) from None
    except csv.Error as exc:
        raise ConfigError(f"--conditions {path}: not a CSV file ({exc})") from None
    for i, row in enumerate(rows, start=2):
        if None in row:
            raise ConfigError(
                f"--conditions {path}, line {i}: more fields than the header's {len(header)}"
            )
    rows = [{k.strip(): v for k, v in row.items()} for row in rows]
    missing = [c for c in _COND_REQUIRED if c not in header]
    if missing:
        raise ConfigError(
            f"--conditions {path}: column {missing[0]!r} is missing; valid columns: "
            + ", ".join(_COND_REQUIRED + _COND_OPTIONAL)
        )
    unknown = [c for c in header if c not in _COND_REQUIRED + _COND_OPTIONAL]
    if unknown:
        raise ConfigError(
            f"--conditions {path}: unknown column {unknown[0]!r}; valid columns: "
            + ", ".join(_COND_REQUIRED + _COND_OPTIONAL)
        )
    by_name: dict[str, dict] = {}
    lines: dict[str, int] = {}
    for i, row in enumerate(rows, start=2):  # line numbers of the file (header = 1)
        name = (row["file"] or "").strip()
        lines[name] = i
        if name in by_name:
            raise ConfigError(f"--conditions {path}, line {i}: file {name!r} is listed twice")
        fault = (row["fault"] or "").strip().lower()
        if fault not in ("none", *FAULT_FAMILIES):
            raise ConfigError(
                f"--conditions {path}, line {i}: fault = {row['fault']!r} is invalid; valid: "
                "none, outer, inner, ball"
            )
        cond: dict = {"fault": fault}
        try:
            # a healthy row's speed is read too: the rig's tones and rpm_range take it
            cond.update(_condition_values(row, path) if fault != "none"
                        else _row_numbers(row, ("rpm",)))  # fmt: skip
        except ConfigError as exc:
            raise ConfigError(f"--conditions {path}, line {i}: {exc}") from None
        by_name[name] = cond
    pairs = []
    for i, (p, rec) in enumerate(zip(records, recs, strict=True)):
        cond = by_name.get(Path(p).name)
        if cond is None:
            listed = ", ".join(repr(n) for n in list(by_name)[:5]) + (
                ", ..." if len(by_name) > 5 else "")  # fmt: skip
            raise ConfigError(
                f"--conditions {path}: record {Path(p).name!r} is not listed (rows name "
                f"{listed or 'nothing'}); valid: one row per record (column file: its file "
                "name, without a folder)"
            )
        own = _record_rpm(rec)  # its rpm, or its speed column's median
        where = f"--conditions {path}, line {lines[Path(p).name]}"
        # the model gain simulates the row's speed: one the record refutes fits the gain to
        # another condition (exploratory testing, twenty-fourth session: accepted, and the
        # gain moved 0.0130 -> 0.0091). A speed column: the rule --rpm has (a run-up takes a
        # speed it passed through; twenty-fifth session)
        if "rpm" in cond and rec.speed_hz is not None:
            if (span := column_speed_refutes(rec, cond["rpm"])) is not None:
                raise ConfigError(
                    f"{where}: rpm = {cond['rpm']:.6g} r/min for {Path(p).name!r}, whose speed "
                    f"column holds {speed_span_text(span, cond['rpm'])}; valid: a speed it "
                    "holds (or an empty rpm, to take its median)"
                )
        elif "rpm" in cond and own and abs(cond["rpm"] / own - 1.0) > RPM_OPTION_REL:
            raise ConfigError(
                f"{where}: rpm = {cond['rpm']:.6g} r/min for {Path(p).name!r}, whose own speed "
                f"is {own:.6g} r/min; valid: the record's speed (or an empty rpm, to take it)"
            )
        elif "rpm" in cond and own is None:
            # a record without a speed of its own: its shaft lines, as they refute --rpm
            # (exploratory testing, twenty-fifth session: a row in Hz, 29.1 for 1746 r/min,
            # was accepted and moved the gain 250-fold; the Hz case is warned)
            c, in_hz = check_speed_given(rec.x, rec.fs, cond["rpm"] / 60.0)
            if c is not None:
                raise ConfigError(
                    f"{where}: rpm = {cond['rpm']:.6g} r/min for {Path(p).name!r}, whose shaft "
                    f"harmonics put its speed at {60.0 * c.shaft_hz:.6g} r/min; valid: the "
                    "record's speed (or an empty rpm, where it has none of its own)"
                )
            if in_hz is not None:
                warnings_out.append(
                    f"warning: {where}: {Path(p).name}: {hz_warning(cond['rpm'], in_hz)}"
                )
        if own is None and "rpm" in cond:  # the row's speed is the record's (tones, rpm_range)
            rec = recs[i] = replace(rec, rpm=cond["rpm"], info={**rec.info, "rpm_source": where})
        if cond["fault"] != "none":
            _check_condition(cond, own, rec, models, realism, where)
            pairs.append((rec, cond))
    if not pairs:
        raise ConfigError(
            f"--conditions {path}: no record has a bearing fault; valid: at least one outer, "
            "inner or ball row (a model gain is matched to a fault's power)"
        )
    return pairs


def _conditions_bearing(conds) -> str | RigBearing | None:
    """The bearing a rig identified from ``--conditions`` rows was taken on: the rows' one
    catalogue id, or the size (:class:`~bearingsim.rig.RigBearing`) of the one size that
    their bearing files (and ids) give; None where the rows give bearings of different sizes."""
    import dataclasses

    from ..catalog import resolve_bearing
    from ..rig import RigBearing, _check_not_a_catalogue_twin

    conds = [c for c in conds if "bearing" in c or "bearing_file" in c]
    ids = {c.get("bearing") for c in conds}
    if not conds or (len(ids) == 1 and None not in ids):
        return ids.pop() if conds else None
    sizes = {}
    for c in conds:
        b = resolve_bearing(c.get("bearing"), c.get("bearing_file"))
        try:  # the rig's own check, before any work (an id the rig refuses failed at the end)
            sizes[b.id] = RigBearing.from_dict(dataclasses.asdict(RigBearing.of(b)))
            if "bearing_file" in c:  # a file's id that names a catalogue bearing of another size
                _check_not_a_catalogue_twin(sizes[b.id])
        except ConfigError as exc:
            raise ConfigError(
                f"--conditions: the bearing of {c.get('bearing_file') or c['bearing']!r} cannot "
                f"name a rig's bearing: {exc}"
            ) from None
    # one size under several names (a file and its catalogue twin, the 6205 and the CWRU's
    # 6205 0.1 % apart) is one size, as RigBearingWarning judges sizes
    ref = min(sizes.values(), key=lambda s: s.id)
    if not all(ref.same_size(s) for s in sizes.values()):
        return None
    cat = sorted(i for i in ids if i is not None)  # a catalogue id, where the rows give one
    return cat[0] if cat else ref


def _check_condition(cond: dict, own: float | None, rec, models, realism: dict, where: str) -> None:
    """Each model's own check of the scenario that will simulate a --conditions row (a defect
    wider than the ball, a pit shallower than the contact's approach, ...) with the gain fit's
    ``realism`` keys (``--defect-profile``), before any work, its error prefixed with the row
    (exploratory testing, twenty-fourth session: a width wider than the ball was refused
    naming neither the file nor the line; twenty-fifth: a pit's depth was checked as a slot's)."""
    import warnings

    from ..config import REALISM
    from ..errors import BearingsimError
    from ..side_by_side import condition_scenario
    from ..simulation import as_scenario, validate_scenario

    rpm = cond.get("rpm") or own
    if rpm is None:  # the gain's own error names the record without a speed
        return
    for m in dict.fromkeys(models):
        sc = condition_scenario(m, cond, rpm, 2.0 / float(rec.fs), float(rec.fs), 0,
                                REALISM | realism)  # fmt: skip
        try:
            with warnings.catch_warnings():  # the runs give their own warnings
                warnings.simplefilter("ignore")
                validate_scenario(as_scenario(sc))
        except BearingsimError as exc:
            raise ConfigError(f"{where}: {' '.join(str(exc).split())}") from None


def _column_hz_warnings(recs: list, out: list[str]) -> None:
    """A warning in ``out`` for each record whose speed column reads like the speed in the
    other unit (:func:`.common.speed_column_warning`: a column named ``rpm`` holding Hz, or
    ``speed_hz`` holding r/min; the rig's tones and ``rpm_range`` took 29 or 104880 r/min
    silently; exploratory testing, twenty-sixth session)."""
    from .common import speed_column_warning

    for r in recs:
        if (text := speed_column_warning(r)) is not None:
            out.append(f"warning: {Path(r.source).name}: {text}")


def _check_steady_columns(recs: list) -> None:
    """Refuse a record whose speed column is steady (within 1 %, 1st-99th percentile) at a
    speed its shaft harmonics refute, as ``--rpm`` is refused (exploratory testing,
    twenty-seventh session: record 172, 1728 r/min, with a column of 1800 r/min wrote
    ``rpm_range = [1800, 1800]`` and tones at 1800 r/min)."""
    from ..signal.diagnosis import refuted_column

    for r in recs:
        if r.rpm is not None:
            continue
        if (refuted := refuted_column(r)) is not None:
            med, c = refuted
            off = 100.0 * (med / c.shaft_hz - 1.0)
            raise ConfigError(
                f"the speed column of {Path(r.source).name!r} (median {60.0 * med:.6g} r/min) "
                f"is refuted by its shaft harmonics, which put its speed at "
                f"{60.0 * c.shaft_hz:.6g} r/min (the column is {off:+.2f} % off it); valid: a "
                "column with the record's speed (or --rpm R)"
            )


def _row_numbers(row: dict, keys: tuple[str, ...], required: str | None = None) -> dict:
    """The positive numbers of a --conditions row's columns ``keys`` that it gives (``required``
    also when empty, as an error), one-line errors."""
    from ..errors import check_range

    out: dict = {}
    for key in keys:
        text = (row.get(key) or "").strip()
        if key != required and not text:
            continue
        try:
            value = float(text)
        except ValueError:
            raise ConfigError(f"{key} = {text!r} is not a number") from None
        out[key] = check_range(key, value, 0.0, lo_open=True)
    return out


def _condition_values(row: dict, path: str) -> dict:
    """The bearing and sizes of one fault row of a --conditions CSV (one-line errors)."""
    from ..catalog import get_bearing, load_bearing_file

    cond: dict = {}
    b = (row["bearing"] or "").strip()
    if b.lower().endswith(".toml"):  # a user's bearing file, beside the CSV
        f = Path(b) if Path(b).is_absolute() else Path(path).parent / b
        load_bearing_file(f)  # checked now, read again by the scenario
        cond["bearing_file"] = str(f)
    else:
        cond["bearing"] = get_bearing(b).id
    return cond | _row_numbers(row, ("defect_width_m",) + _COND_OPTIONAL, "defect_width_m")


def _channel(records: tuple[str, ...], channel: str | None) -> str | None:
    """The channel every record is read on: the option, else for CWRU ``.mat`` files the
    fan-end sensor when every name says ``Fan_End`` (their faults, and the chain identified from
    them, are the fan end's; as ``analyze``), the drive end's when none does; names of both
    ends are a one-line error (one rig is one sensor's chain)."""
    from ..io.cwru import cwru_end

    if channel is not None and channel.strip().lower() != "auto":
        return channel
    mats = [p for p in records if Path(p).suffix.lower() == ".mat"]
    if len(mats) < len(records):  # other files too: each file type's own default, as before
        return None
    fan = sum(cwru_end(p) == "FE" for p in mats)
    if fan and fan < len(mats):
        raise ConfigError(
            f"channel: {fan} of the {len(mats)} CWRU records are fan-end records (Fan_End in the "
            "name) and the others not; one rig is one sensor's chain: give --channel DE or FE"
        )
    return "FE" if fan else "DE"
