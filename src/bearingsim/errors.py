"""Project exceptions.

Every error raised on bad input is a :class:`BearingsimError` whose message is one line naming
the offending field, its value and the valid range, so the CLI can print it unchanged.
"""

from __future__ import annotations

import contextlib
import math
import numbers
import threading
import tomllib
import warnings
from collections.abc import Iterator
from pathlib import Path
from typing import Any

__all__ = [
    "BearingsimError",
    "check_int",
    "check_positive",
    "check_range",
    "collect_warnings",
    "ConfigError",
    "format_range",
    "DeprecatedKeyWarning",
    "exception_text",
    "MAX_TOML_BYTES",
    "read_toml",
    "SolverError",
]


class BearingsimError(ValueError):
    """Base class of every error bearingsim raises on bad input or an impossible request."""


class ConfigError(BearingsimError):
    """A configuration, catalogue or input file is malformed or has invalid values."""


class SolverError(BearingsimError):
    """A solver found no solution (no equilibrium, divergence, ...)."""


class DeprecatedKeyWarning(FutureWarning):
    """A renamed scenario key or CLI option was used; it works for one more release."""


#: this thread's list of collected warnings (``collect_warnings``), or no attribute
_SINK = threading.local()
#: the ``warnings.showwarning`` that ours replaced (called for threads that collect nothing)
_shown_by: list[Any] = [None]
#: a warning raised in bearingsim's code is collected every time, not once per code location:
#: a sweep records each run's warnings with that run (the default action would show only the
#: first); appended, so the filters set before it (``ignore``, ``error``) come first
_ALWAYS_MODULE = r"bearingsim(\.|$)"


def _show(message: Any, category: type, filename: str, lineno: int, file=None, line=None) -> None:
    caught = getattr(_SINK, "caught", None)
    if caught is None:
        _shown_by[0](message, category, filename, lineno, file, line)
    else:
        caught.append(f"{category.__name__}: {' '.join(str(message).split())}")


@contextlib.contextmanager
def collect_warnings() -> Iterator[list[str]]:
    """Collect the warnings this thread raises inside the block, each as one line
    ``"Category: message"``, in a list (the block's value), instead of printing them.

    Other threads are not affected (unlike :class:`warnings.catch_warnings`, which swaps
    process-wide state): a sweep worker with several threads records each run's warnings with
    that run. Warnings raised in bearingsim's modules are collected every time they occur, not
    once per code location (the filter ``always`` for ``bearingsim.*``, appended once per
    process: filters set before it, such as ``ignore`` or ``error`` for a category, still
    apply)."""
    if warnings.showwarning is not _show:  # (re)install: catch_warnings blocks restore theirs
        _shown_by[0] = warnings.showwarning
        warnings.showwarning = _show
    if not any(
        f[0] == "always" and f[3] is not None and f[3].pattern == _ALWAYS_MODULE
        for f in warnings.filters
    ):
        warnings.filterwarnings("always", module=_ALWAYS_MODULE, append=True)
    outer = getattr(_SINK, "caught", None)
    caught: list[str] = []
    _SINK.caught = caught
    try:
        yield caught
    finally:
        _SINK.caught = outer


def _fmt(value: Any) -> str:
    if isinstance(value, float):
        return f"{value:.6g}"
    return repr(value)


def exception_text(exc: BaseException, limit: int = 120) -> str:
    """``Type: message`` of an exception on one line, the message cut to ``limit`` characters:
    how a one-line error quotes what a third-party reader raised on a damaged file."""
    msg = " ".join(str(exc).split())
    if len(msg) > limit:
        msg = msg[: limit - 3] + "..."
    return f"{type(exc).__name__}: {msg}" if msg else type(exc).__name__


def check_positive(name: str, value: Any, unit: str = "") -> float:
    """Return ``float(value)`` if finite and > 0, else raise a one-line :class:`ConfigError`."""
    return check_range(name, value, lo=0.0, lo_open=True, unit=unit)


def format_range(
    lo: float | None = None,
    hi: float | None = None,
    *,
    lo_open: bool = False,
    hi_open: bool = False,
    unit: str = "",
    digits: int = 6,
) -> str:
    """The interval as the messages write it: ``(0, inf) N``, ``[-90, 90] deg``, ``[1, 10000]``
    (``None`` = unbounded, always open), its bounds with ``digits`` significant digits."""
    lb = "(" if (lo_open or lo is None) else "["
    rb = ")" if (hi_open or hi is None) else "]"
    lo_s = "-inf" if lo is None else f"{float(lo):.{digits}g}"
    hi_s = "inf" if hi is None else f"{float(hi):.{digits}g}"
    return f"{lb}{lo_s}, {hi_s}{rb}" + (f" {unit}" if unit else "")


#: largest acceleration an input may ask for [m/s^2]: beyond any accelerometer (shock
#: accelerometers reach ~1e5 g = 1e6 m/s^2); keeps noise, tones and backgrounds finite (a
#: noise of 1e308 m/s^2 wrote infinite samples)
MAX_ACCELERATION = 1e6


def _is_bool(value: Any) -> bool:
    """True for ``bool`` and NumPy booleans (without importing NumPy)."""
    return isinstance(value, bool) or getattr(getattr(value, "dtype", None), "kind", "") == "b"


def check_int(name: str, value: Any, lo: int = 0) -> int:
    """``value`` as an ``int`` >= ``lo`` (a NumPy integer too; not a bool, not a float), else a
    one-line :class:`ConfigError` ``NAME = VALUE is invalid; valid range [LO, inf) integer``."""
    if isinstance(value, bool) or not isinstance(value, numbers.Integral) or value < lo:
        raise ConfigError(f"{name} = {value!r} is invalid; valid range [{lo}, inf) integer")
    return int(value)


def check_range(
    name: str,
    value: Any,
    lo: float | None = None,
    hi: float | None = None,
    *,
    lo_open: bool = False,
    hi_open: bool = False,
    unit: str = "",
) -> float:
    """Validate a finite real number against an interval and return it as ``float``.

    A boolean is not a number: ``rpm = true`` in a TOML file is refused, not read as 1 r/min.
    Nor is text: ``fs_hz = "12000"`` is refused, as rig and bearing files refuse it, not read.

    Parameters
    ----------
    name : str
        Field name shown in the message.
    value : Any
        Value to check.
    lo, hi : float or None
        Interval bounds (``None`` = unbounded).
    lo_open, hi_open : bool
        Whether the bound itself is excluded.
    unit : str
        Unit appended to the range in the message.
    """
    u = f" {unit}" if unit else ""
    rng = format_range(lo, hi, lo_open=lo_open, hi_open=hi_open, unit=unit)
    if _is_bool(value):
        raise ConfigError(f"{name} = {_fmt(value)} is not a number; valid range {rng}")
    if isinstance(value, str):  # a number written as text ("12000" in a TOML file)
        raise ConfigError(f"{name} = {value!r} is text; valid: a number without quotes, {rng}")
    try:
        x = float(value)
    except OverflowError:  # an integer beyond the float range: out of any range
        raise ConfigError(f"{name} = {value} is out of range; valid range {rng}") from None
    except (TypeError, ValueError):
        raise ConfigError(f"{name} = {_fmt(value)} is not a number; valid range {rng}") from None
    if not math.isfinite(x):
        raise ConfigError(f"{name} = {_fmt(value)} is not finite; valid range {rng}")
    bad = (lo is not None and (x < lo or (lo_open and x == lo))) or (
        hi is not None and (x > hi or (hi_open and x == hi))
    )
    if bad:
        xs, rng = _fmt_apart(x, lo, hi, lo_open=lo_open, hi_open=hi_open, unit=unit)
        raise ConfigError(f"{name} = {xs}{u} is out of range; valid range {rng}")
    return x


def _fmt_apart(x: float, lo: float | None, hi: float | None, **kw: Any) -> tuple[str, str]:
    """``x`` and the interval printed with as many significant digits (6, 10, then 17) as it
    takes for ``x`` to read unlike the bounds: ``0.2000001`` against a bound of ``0.2`` must not
    print as ``0.2 is out of range; valid range (0.2, ...``."""
    bounds = [float(b) for b in (lo, hi) if b is not None and float(b) != x]
    for digits in (6, 10, 17):
        xs = f"{x:.{digits}g}"
        if all(xs != f"{b:.{digits}g}" for b in bounds):
            break
    return xs, format_range(lo, hi, digits=digits, **kw)


#: largest TOML file read [bytes]: bearing, scenario and sweep files are a few kB; a larger file
#: is not one of them (and ``/dev/zero`` given as a file must not fill the memory)
MAX_TOML_BYTES = 16 * 2**20


def read_toml(path: str | Path, what: str) -> dict[str, Any]:
    """The parsed TOML file ``path``; a file that cannot be read or parsed raises a one-line
    :class:`ConfigError` that names it as ``what`` (e.g. ``"sweep file"``, ``"scenario ="``).

    Refused in one line: a file that cannot be opened, one larger than :data:`MAX_TOML_BYTES`,
    one that is not UTF-8 text (a binary file), invalid TOML, and arrays or tables nested too
    deeply for the parser. A leading UTF-8 byte-order mark (some Windows editors write one) is
    skipped.
    """
    p = Path(path)
    name = f"{what} {str(p)!r}"
    try:
        with open(p, "rb") as fh:
            raw = fh.read(MAX_TOML_BYTES + 1)
    except OSError as exc:
        raise ConfigError(f"{name} cannot be read ({exc.strerror})") from None
    if len(raw) > MAX_TOML_BYTES:
        raise ConfigError(
            f"{name} is larger than {MAX_TOML_BYTES // 2**20} MiB; valid: a TOML text file"
        )
    try:
        text = raw.decode("utf-8-sig")
    except UnicodeDecodeError as exc:
        raise ConfigError(
            f"{name} is not a UTF-8 text file (byte 0x{raw[exc.start]:02x} at offset "
            f"{exc.start}); valid: a TOML text file"
        ) from None
    try:
        return tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise ConfigError(f"{name} is not valid TOML ({exc})") from None
    except RecursionError:
        raise ConfigError(
            f"{name} nests arrays or tables too deeply; valid: a TOML file of bearingsim keys"
        ) from None
