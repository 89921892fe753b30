"""Sweep specification: a base scenario plus axes → the ordered list of runs.

A sweep file is TOML with three tables::

    [sweep]                      # all keys optional
    combine = "cartesian"        # "cartesian" (every combination) | "zip" (axes side by side)
    zip = [["rpm", "fy_n"]]      # groups of axes taken side by side inside a cartesian sweep
    seed = 0                     # seed of the random axes (integer >= 0)
    channels = ["acc_x", "acc_y"]  # channels stored per run, or "all" (IAS default: ["omega"];
                                 # with a rig in [base] or [axes] also "acc_sensor")
    label = "fault"              # scenario key(s) used as the class label (summary, ML loader;
                                 # default: fault, de_fault (rotor), spall_width_m (IAS))
    per_run_seed = false         # true: noise seed of run i = base seed + i
    allow_overload = false       # true: run loads above twice the static capacity C0
                                 # (simulate --allow-overload; a warning above C0 either way)
    base_file = "scenario.toml"  # optional scenario file under [base] (relative to this file)
    name = "..."                 # free text

    [base]                       # a scenario: the keys of :mod:`bearingsim.config`
    model = "dem"
    duration_s = 0.5
    fs_hz = 12000.0

    [axes]                       # each key is a scenario key; its values, one of:
    fault = ["none", "outer", "inner"]                    # a list
    rpm = { values = [1730, 1750, 1772, 1797] }           # the same, as a table
    fy_n = { start = 50.0, stop = 200.0, num = 4 }        # numpy.linspace (stop included)
    seed = { start = 0, stop = 9, step = 1 }              # start + k step <= stop
    defect_width_m = { start = 1e-4, stop = 1e-3, num = 3, scale = "log" }  # numpy.geomspace
    fx_n = { random = "uniform", low = 0.0, high = 20.0, n = 5 }

Random axes (``random`` = ``uniform`` | ``loguniform`` | ``normal`` (``mean``, ``std``) |
``integers`` (``low``, ``high`` inclusive) | ``choice`` (``values``), each with ``n`` draws) are
drawn once, when the spec is read, from ``numpy.random.default_rng(SeedSequence(seed,
spawn_key=(crc32(axis name),)))``, so each axis has its own stream and adding an axis leaves the
others unchanged.

Runs are numbered ``0 .. n_runs - 1`` in :func:`itertools.product` order over the axes as they
appear in ``[axes]`` (first axis slowest; a ``zip`` group sits at the place of its first axis).
Every run's :class:`~bearingsim.config.Scenario` is validated when the spec is read: a bad value
is an error naming the run and its axis values.

:meth:`SweepSpec.canonical` is the resolved content that determines the results (base scenario,
every axis value, combination, stored channels, per-run seeds, the resolved bearings); its
SHA-256 is :attr:`SweepSpec.spec_hash`. Label, name and execution options are not part of it.
"""

from __future__ import annotations

import dataclasses
import enum
import hashlib
import itertools
import json
import math
import zlib
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from ..config import (
    IasScenario,
    RingScenario,
    RotorScenario,
    Scenario,
    family,
    relative_rig_file,
)
from ..errors import ConfigError, check_range, read_toml

__all__ = [
    "Axis",
    "canonical_hash",
    "Combine",
    "expand_axis",
    "MAX_AXIS_VALUES",
    "MAX_RUNS",
    "RANDOM_KINDS",
    "SCENARIO_KEYS",
    "spec_differences",
    "SPEC_FORMAT",
    "SWEEP_KEYS",
    "SweepSpec",
]

#: identifies the canonical spec
SPEC_FORMAT = "bearingsim.SweepSpec/1"
#: guard on the number of runs of one sweep
MAX_RUNS = 10_000_000
#: guard on the number of values of one axis
MAX_AXIS_VALUES = 1_000_000
#: keys of the [sweep] table
SWEEP_KEYS = (
    "combine",
    "zip",
    "seed",
    "channels",
    "label",
    "per_run_seed",
    "allow_overload",
    "base_file",
    "name",
)
#: scenario keys of every family (a sweep's axes are keys of its base's family)
SCENARIO_KEYS = Scenario.keys()
#: the random distributions of an axis and their parameters
RANDOM_KINDS = {
    "uniform": ("low", "high"),
    "loguniform": ("low", "high"),
    "normal": ("mean", "std"),
    "integers": ("low", "high"),
    "choice": ("values",),
}


#: per model family: the default class label and stored channels of a sweep
_FAMILY_DEFAULTS: dict[type[Scenario], tuple[str, tuple[str, ...]]] = {
    RingScenario: ("fault", ("acc_x", "acc_y")),
    RotorScenario: ("de_fault", ("acc_x", "acc_y")),
    IasScenario: ("spall_width_m", ("omega",)),
}


def _one_family(base: Scenario, models: tuple[Any, ...], origin: str) -> None:
    """A sweep runs one model family (one scenario schema, one channel set): refuse a ``model``
    axis that leaves the base's family."""
    fam = type(base)
    for v in models:
        try:
            other = family(v)
        except ConfigError as exc:
            raise ConfigError(f"{origin}: axis {exc}") from None
        if other is not fam:
            raise ConfigError(
                f"{origin}: axis model = {v!r} is a {other.__name__[:-8].lower()} model but the "
                f"base is a {fam.__name__[:-8].lower()} model; valid: "
                + ", ".join(m.value for m in fam.MODELS)
                + " (a sweep runs one model family; sweep the others separately)"
            )


class Combine(enum.Enum):
    """How the axes combine into runs."""

    CARTESIAN = "cartesian"
    ZIP = "zip"


@dataclass(frozen=True)
class Axis:
    """One swept scenario key and its values (plain Python scalars)."""

    name: str
    values: tuple[Any, ...]

    def __len__(self) -> int:
        return len(self.values)


def _plain(v: Any) -> Any:
    """NumPy scalar → Python scalar; other values unchanged."""
    if isinstance(v, np.generic):
        return v.item()
    return v


def _count(origin: str, where: str, value: Any) -> int:
    if isinstance(value, bool) or not isinstance(value, int):
        raise ConfigError(
            f"{origin}: {where} = {value!r} is not an integer; valid range [1, {MAX_AXIS_VALUES}]"
        )
    if not 1 <= value <= MAX_AXIS_VALUES:
        raise ConfigError(
            f"{origin}: {where} = {value} is out of range; valid range [1, {MAX_AXIS_VALUES}]"
        )
    return value


def _num(origin: str, where: str, value: Any, lo: float | None = None, lo_open=False) -> float:
    try:
        return check_range(where, value, lo, lo_open=lo_open)
    except ConfigError as exc:
        raise ConfigError(f"{origin}: {exc}") from None


def _axis_rng(seed: int, name: str) -> np.random.Generator:
    """The random stream of axis ``name``: independent of the other axes."""
    ss = np.random.SeedSequence(seed, spawn_key=(zlib.crc32(name.encode()),))
    return np.random.default_rng(ss)


def expand_axis(name: str, desc: Any, seed: int, origin: str = "<sweep>") -> Axis:
    """Values of one ``[axes]`` entry (list, ``values``, range or random table).

    Parameters
    ----------
    name : str
        Scenario key.
    desc : list or dict
        The TOML value (see the module docstring).
    seed : int
        Seed of the random axes [-].
    origin : str
        File name for the messages.
    """
    where = f"axes.{name}"
    if isinstance(desc, list):
        values = list(desc)
    elif isinstance(desc, dict):
        keys = set(desc)
        if "values" in keys and "random" not in keys:
            if keys != {"values"}:
                raise ConfigError(
                    f"{origin}: {where} has keys {sorted(keys)}; a value list is "
                    "{ values = [...] } alone"
                )
            values = desc["values"]
            if not isinstance(values, list):
                raise ConfigError(f"{origin}: {where}.values = {values!r} is not a list")
            values = list(values)
        elif "random" in keys:
            values = _random_values(name, desc, seed, origin)
        elif {"start", "stop"} <= keys:
            values = _range_values(name, desc, origin)
        else:
            raise ConfigError(
                f"{origin}: {where} = {desc!r} is invalid; valid: a list, {{ values = [...] }}, "
                "{ start, stop, num [, scale] }, { start, stop, step } or { random = KIND, ..., n }"
            )
    else:
        raise ConfigError(
            f"{origin}: {where} = {desc!r} is invalid; valid: a list of values or a range/random "
            "table"
        )
    if not values:
        raise ConfigError(f"{origin}: {where} has no values; valid: at least one value")
    if len(values) > MAX_AXIS_VALUES:
        raise ConfigError(
            f"{origin}: {where} has {len(values)} values; valid range [1, {MAX_AXIS_VALUES}]"
        )
    for v in values:
        if isinstance(v, dict | list):
            raise ConfigError(f"{origin}: {where} value {v!r} is invalid; valid: scalars")
    return Axis(name, tuple(_plain(v) for v in values))


def _range_values(name: str, d: dict[str, Any], origin: str) -> list[Any]:
    where = f"axes.{name}"
    extra = set(d) - {"start", "stop", "num", "step", "scale"}
    if extra:
        raise ConfigError(
            f"{origin}: {where} has unknown key {sorted(extra)[0]!r}; valid keys: start, stop, "
            "num, step, scale"
        )
    start = _num(origin, f"{where}.start", d["start"])
    stop = _num(origin, f"{where}.stop", d["stop"])
    if ("num" in d) == ("step" in d):
        raise ConfigError(f"{origin}: {where} needs exactly one of num or step")
    scale = d.get("scale", "linear")
    if scale not in ("linear", "log"):
        raise ConfigError(f"{origin}: {where}.scale = {scale!r} is invalid; valid: linear, log")
    if "num" in d:
        num = _count(origin, f"{where}.num", d["num"])
        if scale == "log":
            if start <= 0 or stop <= 0:
                raise ConfigError(
                    f"{origin}: {where} = [{start:g}, {stop:g}] with scale = 'log' needs "
                    "start > 0 and stop > 0; valid range (0, inf)"
                )
            return np.geomspace(start, stop, num).tolist()
        return np.linspace(start, stop, num).tolist()
    if scale == "log":
        raise ConfigError(f"{origin}: {where}.scale = 'log' needs num, not step")
    step = _num(origin, f"{where}.step", d["step"], 0.0, lo_open=True)
    if stop < start:
        raise ConfigError(
            f"{origin}: {where}.stop = {stop:g} is below start = {start:g}; valid range "
            f"[{start:g}, inf)"
        )
    n = int(math.floor((stop - start) / step * (1.0 + 1e-12) + 1e-9)) + 1
    _count(origin, f"{where} (number of steps)", n)
    ints = all(isinstance(d[k], int) and not isinstance(d[k], bool) for k in ("start", "step"))
    if ints:
        return [int(d["start"]) + k * int(d["step"]) for k in range(n)]
    return (start + step * np.arange(n)).tolist()


def _random_values(name: str, d: dict[str, Any], seed: int, origin: str) -> list[Any]:
    where = f"axes.{name}"
    kind = d["random"]
    if kind not in RANDOM_KINDS:
        raise ConfigError(
            f"{origin}: {where}.random = {kind!r} is invalid; valid: " + ", ".join(RANDOM_KINDS)
        )
    need = RANDOM_KINDS[kind]
    valid = {"random", "n", *need}
    extra = set(d) - valid
    if extra:
        raise ConfigError(
            f"{origin}: {where} has unknown key {sorted(extra)[0]!r}; valid keys for random = "
            f"{kind!r}: " + ", ".join(sorted(valid))
        )
    for k in ("n", *need):
        if k not in d:
            raise ConfigError(f"{origin}: {where} (random = {kind!r}) needs key {k!r}")
    n = _count(origin, f"{where}.n", d["n"])
    rng = _axis_rng(seed, name)
    if kind == "choice":
        vals = d["values"]
        if not isinstance(vals, list) or not vals:
            raise ConfigError(f"{origin}: {where}.values = {vals!r} must be a non-empty list")
        idx = rng.integers(0, len(vals), size=n)
        return [vals[i] for i in idx]
    if kind == "integers":
        lo, hi = d["low"], d["high"]
        for k, v in (("low", lo), ("high", hi)):
            if isinstance(v, bool) or not isinstance(v, int):
                raise ConfigError(f"{origin}: {where}.{k} = {v!r} is not an integer")
        if hi < lo:
            raise ConfigError(f"{origin}: {where}.high = {hi} is below low = {lo}")
        return [int(v) for v in rng.integers(lo, hi, size=n, endpoint=True)]
    if kind == "normal":
        mean = _num(origin, f"{where}.mean", d["mean"])
        std = _num(origin, f"{where}.std", d["std"], 0.0)
        return rng.normal(mean, std, size=n).tolist()
    lo = _num(origin, f"{where}.low", d["low"])
    hi = _num(origin, f"{where}.high", d["high"])
    if hi < lo:
        raise ConfigError(f"{origin}: {where}.high = {hi:g} is below low = {lo:g}")
    if kind == "uniform":
        return rng.uniform(lo, hi, size=n).tolist()
    if lo <= 0:
        raise ConfigError(
            f"{origin}: {where}.low = {lo:g} is out of range for loguniform; valid range (0, inf)"
        )
    return np.exp(rng.uniform(math.log(lo), math.log(hi), size=n)).tolist()


def _same(v: Any) -> Any:
    """A hashable key under which equal axis values are equal (``12000`` and ``12000.0``)."""
    if isinstance(v, bool) or v is None or isinstance(v, str):
        return (type(v).__name__, v)
    if isinstance(v, int | float):
        return ("num", float(v))
    if isinstance(v, list | tuple):
        return ("seq", tuple(_same(x) for x in v))
    if isinstance(v, dict):
        return ("map", tuple(sorted((k, _same(x)) for k, x in v.items())))
    return ("other", repr(v))


@dataclass(frozen=True)
class SweepSpec:
    """A validated sweep: base scenario, axes and how they combine.

    Attributes
    ----------
    base : dict
        Every scenario key of the base scenario (:meth:`Scenario.to_dict`).
    axes : tuple of Axis
        Swept keys with their values, in file order.
    combine : Combine
        Cartesian product or zip of the axes.
    zip_groups : tuple of tuple of str
        Axes taken side by side inside a cartesian sweep.
    seed : int
        Seed of the random axes [-].
    channels : tuple of str or None
        Stored channels (``None``: all channels the model produces).
    label : tuple of str
        Scenario keys forming the class label.
    per_run_seed : bool
        Noise seed of run ``i`` = base seed + ``i``.
    allow_overload : bool
        Run a radial load above twice the bearing's static capacity C0 (ISO 76) instead of
        failing that run (:func:`bearingsim.simulate`'s ``allow_overload``).
    name : str
        Free text.
    origin : str
        File the spec came from (for messages).
    """

    base: dict[str, Any]
    axes: tuple[Axis, ...] = ()
    combine: Combine = Combine.CARTESIAN
    zip_groups: tuple[tuple[str, ...], ...] = ()
    seed: int = 0
    channels: tuple[str, ...] | None = ("acc_x", "acc_y")
    label: tuple[str, ...] = ("fault",)
    per_run_seed: bool = False
    allow_overload: bool = False
    name: str = ""
    origin: str = "<sweep>"

    def __post_init__(self) -> None:
        o = self.origin
        names = [a.name for a in self.axes]
        keys = family(self.base.get("model", "vsm")).KEYS
        for n in names:
            if n not in keys:
                raise ConfigError(
                    f"{o}: axis {n!r} is not a scenario key; valid: " + ", ".join(keys)
                )
        if len(set(names)) != len(names):
            raise ConfigError(f"{o}: an axis appears twice in {names}")
        for k in self.label:
            if k not in keys:
                raise ConfigError(
                    f"{o}: label key {k!r} is not a scenario key; valid: " + ", ".join(keys)
                )
        if self.per_run_seed and "seed" not in keys:
            raise ConfigError(
                f"{o}: per_run_seed = true but model {self.base.get('model')!r} has no noise "
                "seed; valid: false"
            )
        if self.per_run_seed and "seed" in names:
            raise ConfigError(f"{o}: per_run_seed = true and a 'seed' axis exclude each other")
        lengths = {a.name: len(a) for a in self.axes}
        if self.combine is Combine.ZIP:
            if self.zip_groups:
                raise ConfigError(f"{o}: zip groups apply to combine = 'cartesian' only")
            if len(set(lengths.values())) > 1:
                raise ConfigError(
                    f"{o}: combine = 'zip' needs axes of equal length; got "
                    + ", ".join(f"{k} {v}" for k, v in lengths.items())
                )
        seen: set[str] = set()
        for g in self.zip_groups:
            for k in g:
                if k not in lengths:
                    raise ConfigError(f"{o}: zip group {list(g)} names {k!r}, which is not an axis")
                if k in seen:
                    raise ConfigError(f"{o}: axis {k!r} is in more than one zip group")
                seen.add(k)
            if len({lengths[k] for k in g}) > 1:
                raise ConfigError(
                    f"{o}: zip group {list(g)} has unequal lengths: "
                    + ", ".join(f"{k} {lengths[k]}" for k in g)
                )
        n = self.n_runs
        if n > MAX_RUNS:
            raise ConfigError(
                f"{o}: number of runs = {n} is too large; valid range [1, {MAX_RUNS}]"
            )
        if not self.per_run_seed:  # equal values give equal runs, bit for bit
            for f in self.factors:
                seen_rows: dict[Any, int] = {}
                for i in range(len(f[0])):
                    row = tuple(_same(a.values[i]) for a in f)
                    if row in seen_rows:
                        what = " and ".join(a.name for a in f)
                        vals = ", ".join(repr(a.values[i]) for a in f)
                        raise ConfigError(
                            f"{o}: axis {what} repeats {vals} (values {seen_rows[row]} and {i}); "
                            "valid: distinct values (equal runs are identical, bit for bit, "
                            "and a split would put one on each side: to repeat a condition, "
                            "use a seed axis or sweep.per_run_seed = true)"
                        )
                    seen_rows[row] = i

    # ----------------------------------------------------------------- structure
    @property
    def factors(self) -> list[tuple[Axis, ...]]:
        """The product factors: single axes or zipped groups, in order."""
        if not self.axes:
            return []
        if self.combine is Combine.ZIP:
            return [tuple(self.axes)]
        by_name = {a.name: a for a in self.axes}
        group_of = {k: g for g in self.zip_groups for k in g}
        out, done = [], set()
        for a in self.axes:
            if a.name in done:
                continue
            g = group_of.get(a.name, (a.name,))
            out.append(tuple(by_name[k] for k in g))
            done.update(g)
        return out

    @property
    def shape(self) -> tuple[int, ...]:
        """Number of values of each product factor."""
        return tuple(len(f[0]) for f in self.factors)

    @property
    def n_runs(self) -> int:
        """Number of runs [-]."""
        return math.prod(self.shape) if self.axes else 1

    @property
    def axis_names(self) -> tuple[str, ...]:
        """Swept keys in file order."""
        return tuple(a.name for a in self.axes)

    def run_values(self, i: int) -> dict[str, Any]:
        """Axis values of run ``i`` (plus ``seed`` with ``per_run_seed``)."""
        if not 0 <= i < self.n_runs:
            raise ConfigError(f"run = {i} is out of range; valid range [0, {self.n_runs - 1}]")
        out: dict[str, Any] = {}
        if self.axes:
            idx = np.unravel_index(i, self.shape)
            for f, k in zip(self.factors, idx, strict=True):
                for a in f:
                    out[a.name] = a.values[int(k)]
        if self.per_run_seed:
            out["seed"] = int(self.base["seed"]) + i
        return out

    def iter_values(self):
        """Axis values of every run, in run order (fast path of :meth:`run_values`)."""
        factors = self.factors
        seed0 = int(self.base.get("seed", 0))
        for i, combo in enumerate(itertools.product(*(range(len(f[0])) for f in factors))):
            out = {a.name: a.values[k] for f, k in zip(factors, combo, strict=True) for a in f}
            if self.per_run_seed:
                out["seed"] = seed0 + i
            yield out

    def scenario_dict(self, i: int) -> dict[str, Any]:
        """Every scenario key of run ``i``."""
        return self._merge(self.run_values(i))

    def _merge(self, values: dict[str, Any]) -> dict[str, Any]:
        d = dict(self.base)
        if "bearing_file" in values:
            d["bearing"] = None
        if "bearing" in values:
            d["bearing_file"] = None
        d.update(values)
        return d

    def scenario(self, i: int) -> Scenario:
        """The validated scenario of run ``i``."""
        return self._scenario(i, self.run_values(i))

    def _scenario(self, i: int, values: dict[str, Any]) -> Scenario:
        try:
            return Scenario.from_dict(self._merge(values), origin=f"run {i}")
        except ConfigError as exc:
            desc = ", ".join(f"{k} = {v!r}" for k, v in values.items())
            raise ConfigError(f"{self.origin}: {exc}" + (f" ({desc})" if desc else "")) from None

    def scenarios(self) -> list[Scenario]:
        """Every run's validated scenario, in run order (errors name the run)."""
        return [self._scenario(i, v) for i, v in enumerate(self.iter_values())]

    @property
    def unstored_sensor_note(self) -> str | None:
        """A note where the runs pass through a rig (``rig`` in the base or an axis) but the
        channels named omit ``acc_sensor``, so what the sensor records is not stored
        (exploratory testing, nineteenth session, left for planning; twenty-eighth session:
        ``sweep plan`` and ``sweep run`` said nothing); else None."""
        has_rig = any(a.name == "rig" for a in self.axes) or self.base.get("rig") is not None
        if not has_rig or self.channels is None or "acc_sensor" in self.channels:
            return None
        return (
            f"sweep.channels = {list(self.channels)} omits 'acc_sensor' while the runs pass "
            "through a rig: what the sensor records is not stored (add 'acc_sensor', or leave "
            "channels out for the default, which has it)"
        )

    @property
    def coordinate_keys(self) -> tuple[str, ...]:
        """Keys stored per run as coordinates: the axes, ``seed`` (per-run seeds) and labels."""
        keys = list(self.axis_names)
        if self.per_run_seed:
            keys.append("seed")
        keys += [k for k in self.label if k not in keys]
        return tuple(keys)

    # ----------------------------------------------------------------- identity
    def canonical(self) -> dict[str, Any]:
        """The resolved content that determines the results (JSON-able, deterministic)."""
        from ..catalog import resolve_bearing
        from ..rig import load_rig

        bearings = {}
        names = self.axis_names
        pairs = set()
        if "bearing" in self.base or "bearing_file" in self.base:  # the ring and IAS families
            pairs = {(self.base.get("bearing"), self.base.get("bearing_file"))}
        if "bearing" in names or "bearing_file" in names:
            pairs = {
                (d.get("bearing"), d.get("bearing_file"))
                for d in (self._merge(v) for v in self.iter_values())
            }
        for bid, bfile in sorted(pairs, key=str):
            b = resolve_bearing(bid, bfile)
            bearings[str(bfile) if bfile else str(bid)] = dataclasses.asdict(b)
        # the rigs' content, as the bearings': an edited rig file is a changed spec
        rigs = {self.base.get("rig")}
        if "rig" in names:
            rigs = {self._merge(v).get("rig") for v in self.iter_values()}
        rig_tables = {str(r): load_rig(r).to_dict() for r in sorted(rigs - {None}, key=str)}
        return {
            "format": SPEC_FORMAT,
            "base": self.base,
            "axes": [[a.name, list(a.values)] for a in self.axes],
            "combine": self.combine.value,
            "zip": [list(g) for g in self.zip_groups],
            "channels": None if self.channels is None else list(self.channels),
            "per_run_seed": self.per_run_seed,
            "bearings": bearings,
        } | ({"rigs": rig_tables} if rig_tables else {}) | (
            # only when set: the hash of every sweep without it is that of before
            {"allow_overload": True} if self.allow_overload else {}
        )  # fmt: skip

    @property
    def spec_hash(self) -> str:
        """SHA-256 of :meth:`canonical` (hex)."""
        return canonical_hash(self.canonical())

    # ----------------------------------------------------------------- reading
    @classmethod
    def from_dict(
        cls, data: dict[str, Any], origin: str = "<sweep>", base_dir: str | Path | None = None
    ) -> SweepSpec:
        """Build from the TOML tables ``sweep``, ``base``, ``axes`` (see the module docstring).

        Relative ``base_file`` and ``bearing_file`` paths are taken relative to ``base_dir``.
        """
        if not isinstance(data, dict):
            raise ConfigError(f"{origin}: a sweep spec must be a table")
        unknown = sorted(set(data) - {"sweep", "base", "axes"})
        if unknown:
            raise ConfigError(
                f"{origin}: unknown table {unknown[0]!r}; valid tables: [sweep], [base], [axes]"
            )
        sw = data.get("sweep", {})
        base_t = data.get("base", {})
        axes_t = data.get("axes", {})
        for tname, t in (("sweep", sw), ("base", base_t), ("axes", axes_t)):
            if not isinstance(t, dict):
                raise ConfigError(f"{origin}: [{tname}] must be a table")
        if "base" not in data and "axes" not in data and "base_file" not in sw:
            # nothing says what to run: an empty file would otherwise be one default run
            raise ConfigError(
                f"{origin}: the sweep "
                + (
                    "file is empty"
                    if not data
                    else "has no [base], no sweep.base_file and no [axes]"
                )
                + "; valid: a [base] scenario (or sweep.base_file) and/or [axes]"
            )
        bad = sorted(set(sw) - set(SWEEP_KEYS))
        if bad:
            raise ConfigError(
                f"{origin}: unknown key {bad[0]!r} in [sweep]; valid keys: " + ", ".join(SWEEP_KEYS)
            )
        bdir = Path(base_dir) if base_dir is not None else None

        def rel(p: str) -> str:
            q = Path(p)
            return str(bdir / q) if bdir is not None and not q.is_absolute() else str(q)

        base: dict[str, Any] = {}
        if "base_file" in sw:
            bf = sw["base_file"]
            if not isinstance(bf, str):
                raise ConfigError(f"{origin}: sweep.base_file = {bf!r} is not a path")
            # its unset keys stay unset (the rate too): a rig the sweep sets gives its own
            base = Scenario.from_toml(rel(bf)).to_dict(rate=False)
        base_t = dict(base_t)
        if relative_rig_file(base_t.get("rig")):  # beside the sweep file, as a scenario's
            base_t["rig"] = rel(base_t["rig"])
        if isinstance(base_t.get("bearing_file"), str):
            base_t["bearing_file"] = rel(base_t["bearing_file"])
            base["bearing"] = None
        if "bearing" in base_t:
            base["bearing_file"] = None
        base.update(base_t)
        base_sc = Scenario.from_dict(base, origin=f"{origin} [base]")
        seed = sw.get("seed", 0)
        if isinstance(seed, bool) or not isinstance(seed, int) or seed < 0:
            raise ConfigError(f"{origin}: sweep.seed = {seed!r} is invalid; valid range [0, inf)")
        try:
            combine = Combine(sw.get("combine", "cartesian"))
        except ValueError:
            raise ConfigError(
                f"{origin}: sweep.combine = {sw.get('combine')!r} is invalid; valid: cartesian, zip"
            ) from None
        zips = sw.get("zip", [])
        if not isinstance(zips, list) or not all(
            isinstance(g, list) and g and all(isinstance(k, str) for k in g) for g in zips
        ):
            raise ConfigError(
                f"{origin}: sweep.zip = {zips!r} is invalid; valid: a list of lists of axis names"
            )
        default_label, default_channels = _FAMILY_DEFAULTS[type(base_sc)]
        has_rig = "rig" in axes_t or getattr(base_sc, "rig", None) is not None
        if has_rig:
            default_channels += ("acc_sensor",)  # what the sensor records, beside the model's
        channels = sw.get("channels", list(default_channels))
        if channels == "all":
            chans = None
        elif (
            isinstance(channels, list)
            and channels
            and all(isinstance(c, str) for c in channels)
            and len(set(channels)) == len(channels)
        ):
            chans = tuple(channels)
        else:
            raise ConfigError(
                f'{origin}: sweep.channels = {channels!r} is invalid; valid: "all" or a list of '
                "distinct channel names"
            )
        label = sw.get("label", default_label)
        label = [label] if isinstance(label, str) else label
        if not isinstance(label, list) or not all(isinstance(k, str) for k in label):
            raise ConfigError(
                f"{origin}: sweep.label = {label!r} is invalid; valid: a key or list of keys"
            )
        prs = sw.get("per_run_seed", False)
        if not isinstance(prs, bool):
            raise ConfigError(f"{origin}: sweep.per_run_seed = {prs!r} is invalid; valid: bool")
        allow = sw.get("allow_overload", False)
        if not isinstance(allow, bool):
            raise ConfigError(
                f"{origin}: sweep.allow_overload = {allow!r} is invalid; valid: true or false"
            )
        name = sw.get("name", "")
        axes = []
        keys = type(base_sc).KEYS
        for key, desc in axes_t.items():
            if key not in keys:
                raise ConfigError(
                    f"{origin}: axis {key!r} is not a scenario key; valid: " + ", ".join(keys)
                )
            ax = expand_axis(key, desc, seed, origin)
            if key == "bearing_file":
                ax = Axis(key, tuple(rel(v) if isinstance(v, str) else v for v in ax.values))
            if key == "rig":
                ax = Axis(key, tuple(rel(v) if relative_rig_file(v) else v for v in ax.values))
            if key == "model":
                _one_family(base_sc, ax.values, origin)
            axes.append(ax)
        # with a rig an unset rate stays unset: each run takes its own rig's (and records it
        # among the rig's defaults)
        base = base_sc.to_dict(rate=not has_rig)
        return cls(
            base=base,
            axes=tuple(axes),
            combine=combine,
            zip_groups=tuple(tuple(g) for g in zips),
            seed=seed,
            channels=chans,
            label=tuple(label),
            per_run_seed=prs,
            allow_overload=allow,
            name=str(name),
            origin=origin,
        )

    @classmethod
    def from_toml(cls, path: str | Path) -> SweepSpec:
        """Read a sweep TOML file."""
        p = Path(path)
        return cls.from_dict(read_toml(p, "sweep file"), origin=p.name, base_dir=p.parent)


def canonical_hash(canonical: dict[str, Any]) -> str:
    """SHA-256 (hex) of a canonical spec's JSON with sorted keys."""
    text = json.dumps(canonical, sort_keys=True, separators=(",", ":"), allow_nan=True)
    return hashlib.sha256(text.encode()).hexdigest()


def spec_differences(old: dict[str, Any], new: dict[str, Any]) -> list[str]:
    """Names of the canonical entries that differ (``base.rpm``, ``axes.fy_n``, ``channels``)."""
    out = []
    for key in sorted(set(old) | set(new)):
        a, b = old.get(key), new.get(key)
        if key == "base" and isinstance(a, dict) and isinstance(b, dict):
            out += [f"base.{k}" for k in sorted(set(a) | set(b)) if a.get(k) != b.get(k)]
        elif key == "axes" and isinstance(a, list) and isinstance(b, list):
            da, db = dict((n, v) for n, v in a), dict((n, v) for n, v in b)
            diff = [f"axes.{k}" for k in sorted(set(da) | set(db)) if da.get(k) != db.get(k)]
            if not diff and [n for n, _ in a] != [n for n, _ in b]:
                diff = ["axes (order)"]
            out += diff
        elif a != b:
            out.append(key)
    return out
