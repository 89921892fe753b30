"""Planning a sweep: probe runs, the dataset layout, and time/disk estimates.

:func:`plan_sweep` counts the runs of a :class:`~bearingsim.sweep_spec.SweepSpec` and estimates
compute time and disk from short timing runs in this process. :func:`probe_run` (a two-sample
run) gives the channels, units and shapes a model produces; :func:`make_layout` turns the probes
of every group of runs into the :class:`~bearingsim.sweep_store.Layout` of the dataset.
"""

from __future__ import annotations

import dataclasses
import math
import os
import time
from dataclasses import asdict, dataclass, field
from typing import Any

import numpy as np
from numpy.typing import NDArray

from ..config import Scenario
from ..errors import BearingsimError, ConfigError, collect_warnings
from ..io.jsonable import to_jsonable
from .spec import SweepSpec
from .store import ChannelLayout, Layout

__all__ = [
    "check_runs",
    "coordinates",
    "extrapolate",
    "first_valid",
    "make_layout",
    "plan_sweep",
    "probe_first",
    "probe_groups",
    "probe_run",
    "start_error",
    "SweepPlan",
    "timing_probe",
    "timing_run",
]


def probe_run(scenario: dict[str, Any], allow_overload: bool = False) -> dict[str, Any]:
    """Two-sample run of ``scenario``: channel names, units and trailing shapes
    (``allow_overload``: the sweep's, :attr:`~bearingsim.sweep.spec.SweepSpec.allow_overload`)."""
    from ..simulation import simulate

    sc = Scenario.from_dict(scenario)
    quiet = {"noise_rms_m_per_s2": 0.0} if hasattr(sc, "noise_rms_m_per_s2") else {}
    with collect_warnings():  # the runs' own warnings: each run records them
        res = simulate(sc.replace(duration_s=2.0 / sc.fs_hz, **quiet),
                       allow_overload=allow_overload)  # fmt: skip
    out = {}
    for name, x in res.channels.items():
        a = np.asarray(x)
        dims = res._dims(name, a)
        out[name] = {
            "units": res.units.get(name, ""),
            "extra_dim": dims[1] if a.ndim == 2 else None,
            "n_extra": int(a.shape[1]) if a.ndim == 2 else 0,
        }
    return out


def probe_first(
    candidates: list[dict[str, Any]], allow_overload: bool = False
) -> dict[str, Any] | str:
    """Probe the first candidate that starts; the first candidate's error text when none does
    (a run that cannot start fails at its check, before any work, so trying every run of a
    group costs little)."""
    err = ""
    for sd in candidates:
        try:
            return probe_run(sd, allow_overload)
        except BearingsimError as exc:
            err = err or " ".join(str(exc).split())
    return err


def check_runs(
    scenarios: list[Scenario], progress: bool = False, allow_overload: bool = False
) -> list[dict[str, Any]]:
    """Every run's own check, before any work: :func:`bearingsim.simulation.validate_scenario`
    with the defaults a sweep runs with (each input against the model — a defect wider than the
    ball, a pit shallower than the contact's approach, a load above twice the static capacity —
    and the run's memory and step estimate). Returns one ``{"run", "error"}`` per run that
    would fail at its start, in run order (``error``: the one-line message the run would
    record). ``progress`` shows a bar on a terminal [-]. Costs ~1 ms a ring run and ~20 ms a
    rotor run (its FE model is built)."""
    from tqdm import tqdm

    bad = []
    with collect_warnings():  # the runs' own warnings: each run records them
        for i, sc in enumerate(
            tqdm(scenarios, desc="checking runs", unit="run", disable=None if progress else True)
        ):
            err = start_error(sc, allow_overload)
            if err is not None:
                bad.append({"run": i, "error": err})
    return bad


def start_error(scenario: Scenario | dict[str, Any], allow_overload: bool = False) -> str | None:
    """The one-line error a run of ``scenario`` would stop at before any work
    (:func:`bearingsim.simulation.validate_scenario` with a sweep's defaults), or None."""
    from ..simulation import as_scenario, validate_scenario

    try:
        validate_scenario(as_scenario(scenario), allow_overload=allow_overload)
    except BearingsimError as exc:
        return sweep_text(" ".join(str(exc).split()))
    return None


def sweep_text(message: str) -> str:
    """A run's error as a sweep says it: the single run's way past an overload
    (``allow_overload=True (--allow-overload)``) is the sweep file's ``[sweep] allow_overload =
    true`` (exploratory testing, twenty-fifth session: a user put it under ``[base]``, an
    unknown key there)."""
    from ..contact.capacity import _OVERLOAD_HINT

    return message.replace(
        _OVERLOAD_HINT, "; [sweep] allow_overload = true in the sweep file runs it anyway"
    )


def rig_warnings(scenarios: list[Scenario], skip: set[int] = frozenset()) -> dict[str, list[int]]:
    """The measurement-chain warnings the runs will give (a bearing of another size than the
    rig's, :func:`bearingsim.rig.bearing_note`; a speed far from the rig's,
    :func:`bearingsim.rig.speed_note`), found without running them: ``"Category: message"``
    -> the runs (not those in ``skip``). Before, ``sweep plan`` printed the timing runs'
    warnings raw and repeated, and said nothing of the other runs' (exploratory testing,
    twenty-fourth session)."""
    from ..catalog import resolve_bearing
    from ..rig import bearing_note, load_rig, speed_note

    out: dict[str, list[int]] = {}
    rigs: dict[tuple[str, bool], Any] = {}
    bearings: dict[tuple, dict] = {}  # a bearing file is read once, not once a run
    for i, sc in enumerate(scenarios):
        name = getattr(sc, "rig", None)
        if i in skip or not name:
            continue
        rotor = hasattr(sc, "de_bearing")
        if (name, rotor) not in rigs:  # the rotor feeds the housing its rig reads
            rigs[name, rotor] = load_rig(name).for_rotor() if rotor else load_rig(name)
        r = rigs[name, rotor]
        if rotor:
            key = (sc.fe_bearing if r.input_channel.endswith("_fe") else sc.de_bearing, None)
        else:
            key = (sc.bearing, sc.bearing_file)
        if key not in bearings:  # as a result's meta["bearing"] holds it
            bearings[key] = dataclasses.asdict(resolve_bearing(*key))
        notes = (("RigBearingWarning", bearing_note(r, bearings[key])),
                 ("RigSpeedWarning", speed_note(r, getattr(sc, "rpm", None))))  # fmt: skip
        for cat, note in notes:
            if note is not None:
                out.setdefault(f"{cat}: {note}", []).append(i)
    return out


# ------------------------------------------------------------------------------ timing
def timing_run(
    scenario: Scenario, max_duration_s: float, allow_overload: bool = False
) -> dict[str, Any] | None:
    """Time ``scenario`` for 2 samples and for ``min(duration_s, max_duration_s)`` (in this
    process): ``fixed_s`` [s] (the two-sample run, the faster of two: the first call of a
    configuration fills caches), ``rate_s_per_s`` (wall time per simulated second beyond it)
    [s/s], ``duration_s`` and ``wall_s`` of the longer run [s], and ``result`` (its
    :class:`~bearingsim.simulate.SimulationResult`); ``None`` when the run raises."""
    from ..simulation import simulate

    d0 = 2.0 / scenario.fs_hz
    d1 = max(min(scenario.duration_s, max_duration_s), 2 * d0)
    t = []
    for d in (d0, d0, d1):
        t0 = time.perf_counter()
        try:
            with collect_warnings():  # the runs' own warnings: rig_warnings lists them
                res = simulate(scenario.replace(duration_s=d), allow_overload=allow_overload)
        except BearingsimError:
            return None
        t.append(time.perf_counter() - t0)
    fixed = min(t[0], t[1])
    rate = max(t[2] - fixed, 0.0) / (d1 - d0)
    return {"duration_s": d1, "wall_s": t[2], "fixed_s": fixed, "rate_s_per_s": rate, "result": res}


def extrapolate(
    scenarios: list[Scenario], fit: dict[str, list[tuple[float, float]]]
) -> NDArray[np.float64]:
    """Per-run compute estimate [s]: fixed part + rate x ``duration_s``, averaged over the
    ``fit`` entries ``(fixed_s, rate_s_per_s)`` of the run's model (of all models when its own
    has none; NaN when there are none)."""
    allfit = [v for vs in fit.values() for v in vs]
    est = np.full(len(scenarios), math.nan)
    for i, sc in enumerate(scenarios):
        f = fit.get(sc.model.value) or allfit
        if f:
            a = float(np.mean([v[0] for v in f]))
            r = float(np.mean([v[1] for v in f]))
            est[i] = a + r * sc.duration_s
    return est


def timing_probe(
    scenario: dict[str, Any], max_duration_s: float, allow_overload: bool = False
) -> tuple[float, float] | None:
    """On a worker: ``(fixed_s, rate_s_per_s)`` of ``scenario`` from :func:`timing_run`, or
    ``None`` when it raises anything (the run itself then records its error in the sweep)."""
    try:  # its warnings are the runs' own: each run records them
        with collect_warnings():
            tr = timing_run(Scenario.from_dict(scenario), max_duration_s, allow_overload)
    except Exception:
        return None
    return None if tr is None else (tr["fixed_s"], tr["rate_s_per_s"])


# ------------------------------------------------------------------------------ layout
def _group_key(sd: dict[str, Any]) -> tuple:
    return (sd["model"], sd.get("per_ball"), sd.get("bearing"), sd.get("bearing_file"))


def first_valid(candidates: list[dict[str, Any]], allow_overload: bool = False) -> int:
    """Position in ``candidates`` (scenario dicts) of the first that passes its check
    (:func:`bearingsim.simulation.validate_scenario`), or -1 when none does."""
    with collect_warnings():
        return next(
            (k for k, sd in enumerate(candidates) if start_error(sd, allow_overload) is None), -1
        )


def probe_groups(
    scenarios: list[Scenario], skip: set[int] | frozenset[int] = frozenset()
) -> dict[tuple, list[int]]:
    """Runs grouped by what decides the channel set (model, per_ball, bearing): every run of a
    group is a candidate for its probe, in run order (:func:`probe_first` stops at the first
    that starts). Runs in ``skip`` (known not to start, :func:`check_runs`) are left out, and
    so is a group with no other run."""
    groups: dict[tuple, list[int]] = {}
    for i, sc in enumerate(scenarios):
        if i not in skip:
            groups.setdefault(_group_key(sc.to_dict()), []).append(i)
    return groups


def make_layout(
    spec: SweepSpec,
    scenarios: list[Scenario],
    probes: dict[tuple, dict[str, Any]],
    n_time: int | None = None,
) -> Layout:
    """Dataset layout from the probe results of the groups that start (see
    :func:`probe_groups`); ``n_time``: the longest run that starts [samples] (default: the
    longest run; one that cannot start stores nothing, so it should not size the time axis)."""
    order: list[str] = []
    info: dict[str, dict[str, Any]] = {}
    for p in probes.values():
        for name, d in p.items():
            if name not in info:
                order.append(name)
                info[name] = dict(d)
            else:
                info[name]["n_extra"] = max(info[name]["n_extra"], d["n_extra"])
    if spec.channels is None:
        names = order
    else:
        names = list(spec.channels)
        for name in names:
            for key, p in probes.items():
                if name not in p:
                    valid = [k for k in order if all(k in q for q in probes.values())]
                    raise ConfigError(
                        f"{spec.origin}: channel {name!r} is not produced by the runs with "
                        f"model = {key[0]!r}, per_ball = {key[1]}; valid: " + ", ".join(valid)
                    )
    chans = tuple(
        ChannelLayout(n, info[n]["units"], info[n]["extra_dim"], info[n]["n_extra"]) for n in names
    )
    lengths = {(sc.fs_hz, sc.n_samples) for sc in scenarios}
    if n_time is None:
        n_time = max(sc.n_samples for sc in scenarios)
    fs = next(iter(lengths))[0] if len(lengths) == 1 else None
    return Layout(len(scenarios), n_time, fs, chans)


def coordinates(spec: SweepSpec, scenarios: list[Scenario]) -> dict[str, list[Any]]:
    dicts = [sc.to_dict() for sc in scenarios]
    return {k: [d[k] for d in dicts] for k in spec.coordinate_keys}


# ------------------------------------------------------------------------------ plan
@dataclass
class SweepPlan:
    """Run count and estimates of a sweep.

    Attributes
    ----------
    n_runs : int
        Number of runs.
    axes : dict
        Number of values per axis.
    channels : list of str
        Stored channels.
    n_samples : tuple of int
        Smallest and largest samples per run (of the runs that start).
    compute_s_per_run : float
        Estimated mean compute time of one run that starts on one worker [s] (one that cannot
        start stops at its check).
    compute_s_total : float
        Estimated compute time of every run on one worker [s].
    workers : int
        Worker count of ``wall_s`` [-].
    wall_s : float
        ``compute_s_total / min(workers, n_runs)`` (ideal scaling), but at least the longest
        run: a run is not split across workers [s].
    bytes_raw, bytes_estimate : int
        Size of the stored arrays uncompressed, and the estimate after compression [byte]
        (the runs that start: one that cannot start stores no signal).
    timing : list of dict
        The timing runs (run, duration [s], wall [s]).
    spec_hash : str
        SHA-256 of the canonical spec.
    invalid_runs : list of dict
        The runs that cannot start (:func:`check_runs`): ``run``, ``values`` (its axis values)
        and ``error`` (the one-line message ``sweep run`` would record for it).
    run_warnings : dict
        The measurement-chain warnings the runs that start will give (:func:`rig_warnings`):
        ``"Category: message"`` -> the runs.
    """

    n_runs: int
    combine: str
    axes: dict[str, int]
    channels: list[str]
    n_samples: tuple[int, int]
    compute_s_per_run: float
    compute_s_total: float
    workers: int
    wall_s: float
    bytes_raw: int
    bytes_estimate: int
    timing: list[dict[str, Any]] = field(default_factory=list)
    spec_hash: str = ""
    invalid_runs: list[dict[str, Any]] = field(default_factory=list)
    run_warnings: dict[str, list[int]] = field(default_factory=dict)

    def as_dict(self) -> dict[str, Any]:
        """Plain dict (JSON)."""
        return to_jsonable(asdict(self))


def plan_sweep(
    spec: SweepSpec,
    *,
    timing_runs: int = 3,
    timing_duration_s: float = 0.1,
    workers: int | None = None,
    seed: int = 0,
    progress: bool = False,
) -> SweepPlan:
    """Count the runs, check each (:func:`check_runs`) and estimate compute time and disk from
    short timing runs (in this process).

    Each timing run is a randomly chosen run (``seed``), at least one per model, simulated
    twice: for 2 samples and for ``min(duration_s, timing_duration_s)``; the per-run cost is
    extrapolated linearly in ``duration_s`` (fixed part + rate per simulated second, per model).
    The disk estimate compresses the timing runs' channels with the dataset's codec.

    Parameters
    ----------
    spec : SweepSpec
        The sweep.
    timing_runs : int
        Number of timing runs (0: count only) [-].
    timing_duration_s : float
        Longest simulated time of a timing run [s].
    workers : int, optional
        Worker count for the wall-time estimate (default: CPU count).
    seed : int
        Choice of the timing runs.
    progress : bool
        A progress bar over the runs' checks on a terminal.

    Raises
    ------
    ConfigError
        When no run can start (the first run's error).
    """
    import numcodecs

    scenarios = spec.scenarios()
    allow = spec.allow_overload
    invalid = check_runs(scenarios, progress, allow)
    bad = {d["run"] for d in invalid}
    if len(bad) == len(scenarios):
        raise ConfigError(f"no run can start; run 0: {invalid[0]['error']}")
    for d in invalid:
        d["values"] = spec.run_values(d["run"])
    groups = probe_groups(scenarios, bad)
    probes = {k: _probe_local(scenarios, idx, allow) for k, idx in groups.items()}
    n = len(scenarios)
    ok = [i for i in range(n) if i not in bad]
    n_ok = len(ok)  # a run that cannot start stores no signal
    layout = make_layout(spec, scenarios, probes, max(scenarios[i].n_samples for i in ok))
    w = workers or os.cpu_count() or 1
    raw_per_run = sum(8 * layout.n_time * max(1, c.n_extra) for c in layout.channels)
    timing: list[dict[str, Any]] = []
    ratio = 1.0
    est = np.full(n, math.nan)
    if timing_runs > 0:
        rng = np.random.default_rng(seed)
        models = sorted({scenarios[i].model.value for i in ok})
        picks = [next(i for i in ok if scenarios[i].model.value == m) for m in models]
        rest = [i for i in rng.permutation(n) if i not in picks and i not in bad]
        picks = sorted(picks + rest[: max(0, timing_runs - len(picks))])
        blosc = numcodecs.Blosc(cname="lz4", clevel=5, shuffle=numcodecs.Blosc.SHUFFLE)
        enc = raw = 0
        fit: dict[str, list[tuple[float, float]]] = {}
        for i in picks:
            sc = scenarios[i]
            tr = timing_run(sc, timing_duration_s, allow)
            if tr is None:
                timing.append({"run": i, "failed": True})
                continue
            res = tr.pop("result")
            fit.setdefault(sc.model.value, []).append((tr["fixed_s"], tr["rate_s_per_s"]))
            timing.append({"run": i, **tr})
            for name in (c.name for c in layout.channels):
                if name in res.channels:
                    x = np.ascontiguousarray(res.channels[name], dtype=np.float64)
                    raw += x.nbytes
                    enc += len(blosc.encode(x))
        ratio = enc / raw if raw else 1.0
        est = extrapolate(scenarios, fit)
        est[sorted(bad)] = 0.0  # a run that cannot start stops at its check
    total = float(np.sum(est))
    # ideal scaling over the workers that get a run, but no less than the longest run (a run
    # runs on one worker); NaN (no estimate) stays NaN
    wall = float(np.maximum(total / min(w, n_ok), np.max(est)))
    ns = [scenarios[i].n_samples for i in ok]
    return SweepPlan(
        n_runs=n,
        combine=spec.combine.value,
        axes={a.name: len(a) for a in spec.axes},
        channels=[c.name for c in layout.channels],
        n_samples=(min(ns), max(ns)),
        compute_s_per_run=total / n_ok,
        compute_s_total=total,
        workers=w,
        wall_s=wall,
        bytes_raw=raw_per_run * n_ok,
        bytes_estimate=int(raw_per_run * n_ok * ratio + 600 * n),
        timing=timing,
        spec_hash=spec.spec_hash,
        invalid_runs=invalid,
        run_warnings=rig_warnings(scenarios, bad),
    )


def _probe_local(scenarios: list[Scenario], idx: list[int], allow: bool) -> dict[str, Any]:
    err: BearingsimError | None = None
    for i in idx:
        try:
            return probe_run(scenarios[i].to_dict(), allow)
        except BearingsimError as exc:
            err = exc
    raise ConfigError(f"run {idx[0]} cannot start: {' '.join(str(err).split())}")
