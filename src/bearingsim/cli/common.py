"""Shared CLI pieces: the root group (commands loaded on first use), deprecated option
spellings, bearing options, JSON output. The conventions are written down in ``docs/cli.md``.

This module imports nothing heavy (no NumPy, SciPy, Numba, xarray, Dask, Matplotlib): it runs
for every command, ``--help`` and ``--version`` included.
"""

from __future__ import annotations

import contextlib
import functools
import importlib
import json
import math
import os
import sys
import warnings
from collections.abc import Callable, Iterable, Iterator, Mapping
from pathlib import Path
from typing import TYPE_CHECKING, Any

import click

from .._version import __version__
from ..errors import ConfigError, check_range, format_range
from ..materials import POISSON_RANGE, YOUNGS_MODULUS_RANGE

if TYPE_CHECKING:
    from ..geometry import Bearing


class _DeprecatedOption(click.Option):
    """A hidden, deprecated spelling of another option of the same command.

    When given, it prints ``warning: OLD is deprecated; use NEW`` on stderr and hands its
    value to NEW (after ``convert`` when the unit changed), so NEW's type, callback, range
    checks and required flag apply as if NEW had been given.
    """

    def __init__(self, old: str, new: str, convert: Callable[[Any], Any] | None) -> None:
        dest = "deprecated_" + old.lstrip("-").replace("-", "_").lower()
        super().__init__([old, dest], hidden=True, expose_value=False, type=click.UNPROCESSED)
        self.old, self.new, self.convert = old, new, convert


def deprecated(old: str, new: str, convert: Callable[[Any], Any] | None = None) -> Callable:
    """Decorator: keep ``old`` as a hidden alias of option ``new`` for one release.

    Parameters
    ----------
    old : str
        The old spelling, e.g. ``"--torque-nm"``.
    new : str
        An option string of the replacement on the same command, e.g. ``"--torque-n-m"``.
    convert : callable, optional
        Maps the raw value given to ``old`` to a value in ``new``'s unit (e.g. radians to
        degrees); ``None`` when only the name changed.
    """

    def deco(f: Callable) -> Callable:
        params = f.__dict__.setdefault("__click_params__", [])
        params.append(_DeprecatedOption(old, new, convert))
        return f

    return deco


def rad_to_deg(raw: Any) -> Any:
    """Convert one value, or a comma-separated list, from radians to degrees (``convert`` of a
    deprecated ``-rad`` option); what is not a number is passed on for NEW to reject."""

    def one(v: str) -> str:
        try:
            return repr(math.degrees(float(v)))
        except ValueError:
            return v

    if isinstance(raw, str) and "," in raw:
        return ",".join(one(v) for v in raw.split(","))
    return one(raw) if isinstance(raw, str) else raw


class Number(click.ParamType):
    """A numeric option that says its valid range when the text is not a number.

    Click's own ``float``/``int`` types answer ``'abc' is not a valid float``; this type answers
    ``Invalid value for '--fy-n': 'abc' is not a number; valid range (-inf, inf) N``. It only
    parses: the range itself (and finiteness) is checked where the value is used, by the library
    (:func:`bearingsim.errors.check_range`), with the field's name as the library knows it.

    Parameters
    ----------
    lo, hi : float or None
        Bounds of the valid range (``None`` = unbounded).
    lo_open, hi_open : bool
        Whether a bound is excluded.
    unit : str
        Unit of the range, as in the option's help (``"N"``, ``"deg"``).
    integer : bool
        Parse an integer (``int(text)``).
    valid : str, optional
        The valid range as text, when it depends on the bearing or another option
        (``"[-c5, c5] m, c5 the ISO 5753-1 group 5 clearance of the bearing"``).
    """

    def __init__(
        self,
        lo: float | None = None,
        hi: float | None = None,
        *,
        lo_open: bool = False,
        hi_open: bool = False,
        unit: str = "",
        integer: bool = False,
        valid: str | None = None,
    ) -> None:
        self.integer = integer
        self.name = "integer" if integer else "float"
        self.valid = valid or format_range(lo, hi, lo_open=lo_open, hi_open=hi_open, unit=unit)
        # the bounds are enforced here (before, only quoted: a command that did not check an
        # option itself took any value, e.g. rig identify --max-modes 0)
        self._bounds = (
            (lo, hi, lo_open, hi_open, unit) if lo is not None or hi is not None else None
        )

    def convert(self, value: Any, param: click.Parameter | None, ctx: click.Context | None) -> Any:
        if isinstance(value, int | float) and not isinstance(value, bool):
            v = int(value) if self.integer and float(value).is_integer() else value
        else:
            try:
                v = int(value) if self.integer else float(value)
            except (TypeError, ValueError):
                kind = "an integer" if self.integer else "a number"
                self.fail(f"{value!r} is not {kind}; valid range {self.valid}", param, ctx)
        if self._bounds is not None:  # one line naming the option's key (BearingsimError)
            lo, hi, lo_open, hi_open, unit = self._bounds
            # named by its option as a key (--ball-load-n -> ball_load_n), as the commands'
            # own checks name it (the Python name may differ: ball_load)
            longs = [o for o in getattr(param, "opts", ()) if o.startswith("--")]
            name = longs[0][2:].replace("-", "_") if longs else getattr(param, "name", "value")
            check_range(name, v, lo, hi, lo_open=lo_open, hi_open=hi_open, unit=unit)
        return v

    def __repr__(self) -> str:
        return f"Number({self.valid!r})"


#: a diametral clearance option: its range depends on the bearing (ISO 5753-1, group 5, for
#: its bore: :func:`bearingsim.geometry.clearance_range`)
CLEARANCE = Number(valid="[-c5, c5] m, c5 the ISO 5753-1 group 5 clearance of the bearing's bore")


def allow_overload_option(f: Callable) -> Callable:
    """``--allow-overload``: run although the load exceeds twice the static capacity (ISO 76);
    the command receives ``allow_overload``."""
    return click.option(
        "--allow-overload",
        is_flag=True,
        help="Run although the load exceeds 2 x the static capacity C0 (ISO 76); "
        "a warning is printed instead of the error.",
    )(f)


@contextlib.contextmanager
def echo_warnings(seen: set[str] | None = None) -> Iterator[None]:
    """Collect the warnings of a command's work (model warnings such as
    :class:`~bearingsim.contact.capacity.StaticCapacityWarning`) and print each as one line
    ``warning: ...`` on stderr when the work succeeds (a refused or failed run prints only its
    error line). Messages already in ``seen`` (shared between blocks: a check warns again when
    the run repeats it) are not repeated."""
    seen = set() if seen is None else seen
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        yield
    for w in caught:
        msg = " ".join(str(w.message).split())
        if msg not in seen:
            seen.add(msg)
            click.echo(f"warning: {msg}", err=True)


class Command(click.Command):
    """A command whose deprecated option spellings (:func:`deprecated`) warn and work."""

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        super().__init__(*args, **kwargs)
        by_opt = {o: p for p in self.params for o in getattr(p, "opts", ()) + p.secondary_opts}
        self._aliases: list[tuple[_DeprecatedOption, click.Parameter]] = []
        for p in self.params:
            if isinstance(p, _DeprecatedOption):
                target = by_opt.get(p.new)
                if target is None or isinstance(target, _DeprecatedOption):
                    raise TypeError(f"{self.name}: deprecated {p.old} names no option {p.new}")
                self._aliases.append((p, target))

    @property
    def deprecated_spellings(self) -> dict[str, str]:
        """``{old: new}`` for every deprecated option spelling of this command."""
        return {a.old: a.new for a, _ in self._aliases}

    def make_parser(self, ctx: click.Context) -> Any:
        parser = super().make_parser(ctx)
        if not self._aliases:
            return parser
        parse = parser.parse_args

        def parse_args(args: list[str]) -> tuple[dict[str, Any], list[str], list[Any]]:
            opts, largs, order = parse(args=args)
            for alias, target in self._aliases:
                if alias.name not in opts:
                    continue
                raw = opts.pop(alias.name)
                if target.name in opts and not ctx.resilient_parsing:
                    raise click.UsageError(
                        f"give {alias.new}, not both {alias.new} and its old spelling {alias.old}",
                        ctx,
                    )
                if not ctx.resilient_parsing:
                    click.echo(f"warning: {alias.old} is deprecated; use {alias.new}", err=True)
                opts[target.name] = raw if alias.convert is None else alias.convert(raw)
                order = [target if p is alias else p for p in order]
            return opts, largs, order

        parser.parse_args = parse_args
        return parser


class Group(click.Group):
    """A group whose commands are :class:`Command` (sub-groups: this class again)."""

    command_class = Command
    group_class = type


class LazyGroup(Group):
    """The root group: a command's module is imported only when that command runs (or shows
    its help), so ``--help``, ``--version``, ``bearings`` and ``info`` start fast.

    ``lazy`` maps a command name to ``(module, one-line help)``; the module registers the
    command on this group when imported. ``--help`` lists every command from this table without
    importing anything (``tests/test_cli_conventions.py`` checks the table against the modules).
    """

    group_class = Group
    lazy: Mapping[str, tuple[str, str]] = {}

    def list_commands(self, ctx: click.Context) -> list[str]:
        return sorted(set(self.commands) | set(self.lazy))

    def get_command(self, ctx: click.Context, cmd_name: str) -> click.Command | None:
        if cmd_name not in self.commands and cmd_name in self.lazy:
            importlib.import_module(self.lazy[cmd_name][0])
        return self.commands.get(cmd_name)

    def format_commands(self, ctx: click.Context, formatter: click.HelpFormatter) -> None:
        names = self.list_commands(ctx)
        if not names:
            return
        limit = formatter.width - 6 - max(len(n) for n in names)
        rows = []
        for name in names:
            if name in self.lazy:
                # truncated exactly as click shortens a loaded command's help
                text = click.Command(name, help=self.lazy[name][1]).get_short_help_str(limit)
            else:
                cmd = self.commands[name]
                if cmd.hidden:
                    continue
                text = cmd.get_short_help_str(limit)
            rows.append((name, text))
        with formatter.section("Commands"):
            formatter.write_dl(rows)


@click.group(
    cls=LazyGroup,
    context_settings={"help_option_names": ["-h", "--help"], "show_default": True},
)
@click.version_option(__version__, "--version", prog_name="bearingsim")
def cli() -> None:
    """bearingsim: physics-based rolling-bearing analysis (SI units inside).

    Conventions of every command (docs/cli.md): -o/--output names the main output; an option
    with a unit ends in it (--fy-n [N], --torque-n-m [N m], --housing-stiffness-n-per-m [N/m]);
    angles are in degrees; --json prints exactly one JSON object (SI) on stdout; bad input
    prints one line on stderr and exits with code 2.
    """


class DeferredDefaultOption(click.Option):
    """An option whose ``[default: ...]`` text (``show_default``, a callable returning it) is
    computed only when help is shown, so a command module need not import a model to describe
    its defaults (``cls=DeferredDefaultOption``)."""

    def get_help_record(self, ctx: click.Context) -> tuple[str, str] | None:
        if callable(self.show_default):
            self.show_default = self.show_default()
        return super().get_help_record(ctx)


def _shown(v: Any) -> str | bool:
    """A default as ``[default: ...]`` shows it (``False``: nothing shown)."""
    import enum

    if v is None or v is False:
        return False
    if isinstance(v, enum.Enum):
        v = v.value
    return format(v, "g") if isinstance(v, float) else str(v)


def scenario_default(key: str, model: str = "vsm", *, others: bool = True) -> str | bool:
    """What ``[default: ...]`` shows for an option that overrides scenario key ``key``: the
    default of the family of ``model`` that has the key (else of the first family that has it,
    :mod:`bearingsim.config`) when neither the option nor the scenario file sets it (``False``,
    i.e. nothing shown, for a default of ``None`` or ``False``), followed by each other
    family's that differs (``1; ias: 10``: the help showed the ring models' values for
    ``--model ias``, whose run was then ten times longer than the help said); ``others``
    False shows the one family's alone."""
    import dataclasses

    from ..config import IasScenario, RingScenario, RotorScenario, family

    names = {RingScenario: "vsm/dem/tvsm", RotorScenario: "rotor", IasScenario: "ias"}
    fams = [f for f in dict.fromkeys([family(model), *names]) if key in f.KEYS]
    vals = [(f, {g.name: g.default for g in dataclasses.fields(f)}[key]) for f in fams]
    first = vals[0][1]
    if first is True:
        return key.replace("_", "-")
    shown = _shown(first)
    rest = [f"{names[f]}: {_shown(v) or 'none'}" for f, v in vals[1:] if v != first]
    if not rest or not others:
        return shown
    return "; ".join([str(shown) if shown is not False else "none", *rest])


def emit_json(obj: Any) -> None:
    """Print exactly one JSON object on stdout."""
    from ..io.jsonable import to_jsonable

    click.echo(json.dumps(to_jsonable(obj)))


json_option = click.option(
    "--json", "as_json", is_flag=True, help="Print one JSON object (SI) on stdout."
)


def output_option(
    help: str, *, required: bool = False, kind: click.Path | None = None, dest: str = "output"
) -> Callable:
    """``-o/--output``: the main output of a command; a file unless ``kind`` says otherwise.
    The command receives it as ``dest``."""
    kind = click.Path(dir_okay=False) if kind is None else kind
    return click.option("-o", "--output", dest, type=kind, required=required, help=help)


#: the figure formats a ``--plot`` file may name (its suffix chooses the format)
FIGURE_SUFFIXES = (".png", ".pdf", ".svg", ".jpg", ".jpeg")


def check_outputs(*outputs: tuple[str, str | None], directory: bool = False) -> None:
    """Refuse, before any work, an output location that cannot be written: one line naming the
    option, the path and the reason (:func:`bearingsim.io.atomic.check_output`).

    Parameters
    ----------
    *outputs : (option, path) pairs
        Each output option as named in the message (``"-o/--output"``, ``"--plot"``) and its
        value; ``None`` (not given) is skipped.
    directory : bool
        Whether the outputs are directories (``reproduce``, ``sweep run``).
    """
    from ..io.atomic import check_output

    seen: dict[Path, str] = {}
    inputs = _input_files({str(p) for _o, p in outputs if p is not None})
    for option, path in outputs:
        if path is not None:
            check_output(path, option, directory=directory)
            target = Path(path).expanduser().resolve()
            if target in inputs:  # e.g. -o out.nc, a symbolic link to the scenario file
                raise ConfigError(
                    f"{option} = {str(path)!r} is the input {inputs[target]} ({str(target)!r}): "
                    "writing it would replace that file; valid: another path"
                )
            if option.startswith("--plot") and Path(path).suffix.lower() not in FIGURE_SUFFIXES:
                raise ConfigError(
                    f"{option} = {str(path)!r} has no figure suffix; valid: a name ending in "
                    + ", ".join(FIGURE_SUFFIXES)
                )
            key = Path(path).expanduser().resolve()
            if key in seen:  # the second write would replace the first output
                raise ConfigError(
                    f"{option} = {str(path)!r} is also {seen[key]}; valid: a different path for "
                    "each output"
                )
            seen[key] = option


def _input_files(outputs: set[str]) -> dict[Path, str]:
    """The files the running command reads, by resolved path, from its arguments and options
    (click's parameters whose values, or items of them, name existing files; the output
    options' own values left out): an output must not be one of them. Outputs are written
    through symbolic links (:func:`bearingsim.io.atomic.atomic_path`), so an output that
    links to an input would replace it (twenty-first session)."""
    ctx = click.get_current_context(silent=True)
    found: dict[Path, str] = {}
    if ctx is None:
        return found
    shown = {  # the name the user typed: an option's longest flag, an argument's metavar
        p.name: (max(p.opts, key=len) if isinstance(p, click.Option) else p.human_readable_name)
        for p in ctx.command.params
        if p.name
    }
    for name, value in ctx.params.items():
        for v in value if isinstance(value, list | tuple) else (value,):
            if not isinstance(v, str | Path) or str(v) in outputs or not str(v):
                continue
            try:
                p = Path(v).expanduser()
                if p.is_file():
                    found.setdefault(p.resolve(), f"{shown.get(name, name)} = {str(v)!r}")
            except (OSError, ValueError):
                continue
    return found


def available_cores() -> int:
    """Cores this process may run on (its CPU affinity; the machine's count where the platform
    has no affinity)."""
    if hasattr(os, "sched_getaffinity"):
        return max(len(os.sched_getaffinity(0)), 1)
    return os.cpu_count() or 1


def _ignore_sigint() -> None:
    """Worker initializer: Ctrl-C is the parent's to handle (it cancels what is left)."""
    import signal

    signal.signal(signal.SIGINT, signal.SIG_IGN)


def map_in_processes(
    fn: Callable[[Any], Any], items: Iterable[Any], jobs: int, preload: Iterable[str] = ()
) -> Iterator[Any]:
    """``fn(item)`` for each item, yielded in the order of ``items`` as soon as it and those
    before it are done.

    With one job or one item, in this process, one after the other. Otherwise on a pool of
    ``min(jobs, len(items))`` processes (:class:`concurrent.futures.ProcessPoolExecutor`), started
    by ``fork`` on Linux after the modules named in ``preload`` are imported here, so that the
    workers start with them loaded (``spawn`` elsewhere: each worker imports what it needs;
    ``fn`` must then be a module-level function). Ctrl-C cancels the items not started and
    waits for the running ones.

    Parameters
    ----------
    fn : callable
        Picklable function of one item.
    items : iterable
        The items.
    jobs : int
        Largest number of processes [-].
    preload : iterable of str
        Modules to import before the workers are started.
    """
    items = list(items)
    n = min(int(jobs), len(items))
    if n <= 1:
        for it in items:
            yield fn(it)
        return
    import multiprocessing
    from concurrent.futures import ProcessPoolExecutor

    fork = sys.platform.startswith("linux") and "fork" in multiprocessing.get_all_start_methods()
    if fork:
        for name in preload:
            importlib.import_module(name)
    ctx = multiprocessing.get_context("fork" if fork else "spawn")
    pool = ProcessPoolExecutor(max_workers=n, mp_context=ctx, initializer=_ignore_sigint)
    try:
        futures = [pool.submit(fn, it) for it in items]
        for f in futures:
            yield f.result()
    finally:
        pool.shutdown(wait=True, cancel_futures=True)


def bearing_options(required: bool = True) -> Callable:
    """Decorator adding ``BEARING`` (catalogue id), ``--bearing-file``, ``--E-pa``, ``--nu``.

    The wrapped command receives ``bearing: Bearing`` instead of the raw options.
    """

    def deco(f: Callable) -> Callable:
        @click.argument("bearing_id", metavar="BEARING", required=False)
        @click.option(
            "--bearing-file",
            type=click.Path(dir_okay=False),
            default=None,
            help="User bearing TOML file (instead of a catalogue id).",
        )
        @click.option(
            "--E-pa",
            "e_pa",
            type=Number(*YOUNGS_MODULUS_RANGE, unit="Pa"),
            default=None,
            show_default="the bearing's",
            help="Young's modulus [Pa].",
        )
        @click.option(
            "--nu",
            type=Number(*POISSON_RANGE, hi_open=True),
            default=None,
            show_default="the bearing's",
            help="Poisson's ratio [-].",
        )
        @functools.wraps(f)
        def wrapper(
            bearing_id: str | None,
            bearing_file: str | None,
            e_pa: float | None,
            nu: float | None,
            **kw: Any,
        ) -> Any:
            if bearing_id is None and bearing_file is None and not required:
                return f(bearing=None, **kw)
            from ..catalog import resolve_bearing

            b = resolve_bearing(bearing_id, bearing_file, youngs_modulus=e_pa, poisson_ratio=nu)
            return f(bearing=b, **kw)

        return wrapper

    return deco


def bearing_summary(b: Bearing) -> dict[str, Any]:
    """Plain-dict description of a bearing (SI), in the keys of a bearing file: written as TOML
    it reads back as the same bearing (:func:`bearingsim.catalog.bearing_from_dict`)."""
    out = {
        "id": b.id,
        "type": b.kind,
        "n_elements": b.n_elements,
        "element_diameter_m": b.element_diameter,
        "pitch_diameter_m": b.pitch_diameter,
        "contact_angle_rad": b.contact_angle,
        "diametral_clearance_m": b.diametral_clearance,
        "youngs_modulus_pa": b.material.youngs_modulus,
        "poisson_ratio": b.material.poisson_ratio,
        "density_kg_m3": b.material.density,
        "source": b.source,
    }
    if b.kind == "ball":
        out["inner_groove_radius_m"] = b.inner_groove_radius
        out["outer_groove_radius_m"] = b.outer_groove_radius
    else:
        out["roller_length_m"] = b.roller_length
        out["inner_raceway_diameter_m"] = b.inner_raceway_diameter
        out["outer_raceway_diameter_m"] = b.outer_raceway_diameter
    # the envelope, where known: a bearing file written from this dict keeps the checks that
    # depend on it (the clearance range of the bore, the ring wall under a defect)
    for key, v in (("bore_m", b.bore), ("outer_diameter_m", b.outer_diameter),
                   ("width_m", b.width)):  # fmt: skip
        if v is not None:
            out[key] = v
    return out


__all__ = [
    "allow_overload_option",
    "available_cores",
    "CLEARANCE",
    "Command",
    "DeferredDefaultOption",
    "Group",
    "LazyGroup",
    "Number",
    "bearing_options",
    "bearing_summary",
    "check_outputs",
    "cli",
    "deprecated",
    "echo_warnings",
    "emit_json",
    "json_option",
    "map_in_processes",
    "output_option",
    "rad_to_deg",
    "scenario_default",
]


def speed_column_warning(rec: Any, *, in_hz: bool = True, in_rpm: bool = True) -> str | None:
    """The text where ``rec``'s speed column reads like the speed in the other unit, or None:
    ``in_hz``, a column of r/min holding Hz (named ``rpm``, 29.1 for 1746 r/min); ``in_rpm``,
    a column of Hz holding r/min (named ``speed_hz``, 1748). Both read off the record's shaft
    comb (:func:`bearingsim.signal.contact_angle.hz_given_as_rpm`) on one padded spectrum."""
    from ..io.signal import column_median_rpm
    from ..signal.contact_angle import (
        hz_given_as_rpm,
        hz_warning,
        padded_spectrum,
        rpm_column_text,
    )

    n = column_median_rpm(rec)
    if n is None:
        return None
    spec = padded_spectrum(rec.x, rec.fs)
    if in_hz and (c := hz_given_as_rpm(None, rec.fs, n / 60.0, spectrum=spec)) is not None:
        return hz_warning(n, c, column=True)
    if (
        in_rpm
        and (c := hz_given_as_rpm(None, rec.fs, n / 60.0, spectrum=spec, factor=1.0 / 60.0))
        is not None
    ):
        return rpm_column_text(n, c)
    return None
