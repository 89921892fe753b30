"""Property-based tests (Hypothesis) over the input schemas and the main CLI commands (issue 14,
item 6): any generated input either runs to a finite result or is refused with one line — no
traceback, no hang, no NaN written.

Profiles: ``ci`` (the default run: a bounded number of examples per test, seeded, so the suite
keeps its time budget) and ``long`` (``HYPOTHESIS_PROFILE=long python -m pytest
tests/test_properties.py -m ''`` — ≥ 10,000 examples over the file; docs/validation.md,
"Reliability", reports its figures).

Values are drawn to hit the edges: zero, negative, tiny, huge, non-finite, booleans and strings
where numbers belong, valid values near the catalogue's. An input that is refused must name a
field; an input that runs must give finite numbers. Every example runs under an alarm: a command
that does not answer within ``HANG_S`` seconds is a hang.
"""

from __future__ import annotations

import contextlib
import json
import math
import os
import signal
import warnings

import numpy as np
import pytest
from hypothesis import HealthCheck, event, example, given, settings
from hypothesis import strategies as st

from bearingsim.contact.capacity import StaticCapacityWarning
from bearingsim.dynamics.checks import SpeedWarning
from bearingsim.errors import BearingsimError, DeprecatedKeyWarning

settings.register_profile(
    "ci",
    max_examples=40,
    deadline=None,
    derandomize=True,
    suppress_health_check=[HealthCheck.too_slow, HealthCheck.function_scoped_fixture],
)
settings.register_profile(
    "long",
    max_examples=1500,
    deadline=None,
    suppress_health_check=[HealthCheck.too_slow, HealthCheck.function_scoped_fixture],
)
settings.load_profile(os.environ.get("HYPOTHESIS_PROFILE", "ci"))

#: seconds an example may take before it counts as a hang
HANG_S = 60

pytestmark = pytest.mark.properties


class Hang(Exception):
    """Raised by the alarm: the example did not finish in time."""


#: the project's own warnings (a load above C0, a fast bearing, an old key): one line each and
#: allowed; every other warning (NumPy overflow, ...) stays an error as in the rest of the suite
MODEL_WARNINGS = (StaticCapacityWarning, SpeedWarning, DeprecatedKeyWarning)


@contextlib.contextmanager
def no_hang(seconds: int = HANG_S):
    """Run the block under an alarm (a hang fails) with the model warnings recorded and checked
    to be one line each."""

    def on_alarm(signum, frame):
        raise Hang(f"no answer within {seconds} s")

    old = signal.signal(signal.SIGALRM, on_alarm)
    signal.alarm(seconds)
    try:
        with warnings.catch_warnings(record=True) as seen:
            warnings.simplefilter("error")
            for cat in MODEL_WARNINGS:
                warnings.simplefilter("always", cat)
            yield
        for w in seen:
            msg = str(w.message).strip()
            assert msg and "\n" not in msg, f"warning not one line: {msg!r}"
    finally:
        signal.alarm(0)
        signal.signal(signal.SIGALRM, old)


# ------------------------------------------------------------------ value strategies
EDGE_FLOATS = [0.0, -0.0, -1.0, 1e-300, -1e-300, 1e30, -1e30, math.inf, -math.inf, math.nan]


def numbers(lo: float, hi: float) -> st.SearchStrategy:
    """Plausible values in [lo, hi] (about half the draws, so that runs are exercised too), the
    edges, and the wrong types."""
    plausible = st.floats(lo, hi, allow_nan=False)
    return st.one_of(
        plausible,
        plausible,
        plausible,
        plausible,
        plausible,
        st.sampled_from(EDGE_FLOATS),
        st.integers(-(10**12), 10**12),
        st.booleans(),
        st.text(max_size=4),
        st.none(),
    )


def _finite(obj) -> bool:
    """Every number in ``obj`` (nested dicts/lists, NumPy arrays) is finite (None = not given)."""
    if isinstance(obj, dict):
        return all(_finite(v) for v in obj.values())
    if isinstance(obj, list | tuple):
        return all(_finite(v) for v in obj)
    if isinstance(obj, np.ndarray):
        return obj.dtype.kind not in "fc" or bool(np.all(np.isfinite(obj)))
    if isinstance(obj, float):
        return math.isfinite(obj)
    return True


def _one_line(exc: BaseException) -> None:
    """A refusal: a project error whose message is one non-empty line (counted as an outcome in
    ``--hypothesis-show-statistics``)."""
    event("refused")
    msg = str(exc)
    assert isinstance(exc, BearingsimError), f"{type(exc).__name__}: {msg}"
    assert msg.strip() and "\n" not in msg.strip(), f"not one line: {msg!r}"


# ------------------------------------------------------------------ bearing schema
BALL = {
    "id": "gen",
    "type": "ball",
    "n_elements": 9,
    "element_diameter_m": 7.94e-3,
    "pitch_diameter_m": 39.0e-3,
    "inner_groove_radius_m": 4.089e-3,
    "outer_groove_radius_m": 4.169e-3,
    "diametral_clearance_m": 6e-6,
}
BALL_RANGES = {
    "n_elements": numbers(0, 40),
    "element_diameter_m": numbers(1e-4, 0.1),
    "pitch_diameter_m": numbers(1e-3, 0.5),
    "inner_groove_radius_m": numbers(1e-4, 0.1),
    "outer_groove_radius_m": numbers(1e-4, 0.1),
    "diametral_clearance_m": numbers(-1e-3, 1e-3),
    "contact_angle_rad": numbers(-1.0, 2.0),
    "youngs_modulus_pa": numbers(1e9, 1e12),
    "poisson_ratio": numbers(-1.0, 1.0),
    "density_kg_m3": numbers(100.0, 2e4),
}


@st.composite
def ball_bearing_dicts(draw):
    d = dict(BALL)
    for k in draw(st.sets(st.sampled_from(sorted(BALL_RANGES)), max_size=4)):
        d[k] = draw(BALL_RANGES[k])
    return d


@given(data=ball_bearing_dicts(), load=numbers(0.0, 2e5))
@example(data=dict(BALL), load=9362.0)  # long run: just above C0, the warning was an error
def test_bearing_schema_and_contact(data, load):
    """A generated bearing is built or refused in one line; a built one gives finite contact and
    load-distribution results for a generated radial load, or a one-line refusal."""
    from bearingsim.catalog import bearing_from_dict
    from bearingsim.contact import ball_contact
    from bearingsim.load_distribution import radial_load_distribution, stribeck_qmax

    with no_hang():
        try:
            b = bearing_from_dict(data)
        except BearingsimError as exc:
            _one_line(exc)
            return
        try:
            q = stribeck_qmax(b, load)
            c = ball_contact(b, q, "inner")
            ld = radial_load_distribution(b, 0.0, load, np.radians([0.0, 20.0]))
        except BearingsimError as exc:
            _one_line(exc)
            return
        assert _finite([c.p_max, c.a, c.b, c.delta]), (data, load)
        assert _finite([ld.ball_loads, ld.displacement]), (data, load)
        event("ran")


# ------------------------------------------------------------------ scenario schemas
RING_KEYS = {
    "rpm": numbers(1.0, 2e4),
    "fx_n": numbers(-5e3, 5e3),
    "fy_n": numbers(-5e3, 5e3),
    "defect_width_m": numbers(1e-6, 1e-2),
    "defect_depth_m": numbers(1e-7, 1e-2),
    "defect_edge_angle_deg": numbers(-400.0, 400.0),
    "mass_kg": numbers(1e-3, 10.0),
    "damping_n_s_per_m": numbers(0.0, 1e4),
    "stiffness_n_per_m1_5": numbers(1e6, 1e12),
    "clearance_m": numbers(-1e-4, 1e-4),
    "retention_factor": numbers(0.0, 1.0),
    "ball_diameter_spread_m": numbers(-1e-6, 2e-5),
    "unbalance_n": numbers(-1.0, 100.0),
    "pocket_jitter_percent": numbers(-1.0, 12.0),
    "noise_rms_m_per_s2": numbers(0.0, 10.0),
    "seed": numbers(0, 100),
    "fault": st.sampled_from(["none", "outer", "inner", "ball", 3, None]),
    "model": st.sampled_from(["vsm", "dem", "tvsm", "rotor", "lstm"]),
    "per_ball": st.one_of(st.booleans(), numbers(0, 1)),
}


@st.composite
def ring_scenarios(draw):
    d = {"duration_s": 0.003, "fs_hz": 12000.0, "fault": "outer"}
    for k in draw(st.sets(st.sampled_from(sorted(RING_KEYS)), max_size=4)):
        d[k] = draw(RING_KEYS[k])
    return d


@given(scenario=ring_scenarios())
@example(scenario={"duration_s": 0.003, "fs_hz": 12000.0, "fault": "outer", "fx_n": 9362})
def test_scenario_schema_and_simulate(scenario):
    """A generated scenario is built or refused in one line; a built one simulates to finite
    channels or is refused in one line (a budget, the bearing's capacity, a solver limit)."""
    from bearingsim import simulate
    from bearingsim.config import Scenario

    with no_hang():
        try:
            sc = Scenario.from_dict(scenario)
        except BearingsimError as exc:
            _one_line(exc)
            return
        if sc.duration_s > 0.01 or sc.model.value == "rotor":
            sc = sc.replace(duration_s=min(sc.duration_s, 0.003))
        try:
            res = simulate(sc)
        except BearingsimError as exc:
            _one_line(exc)
            return
        assert _finite(dict(res.channels)), scenario
        event("ran")


SWEEP_AXES = {
    "rpm": st.one_of(
        st.lists(numbers(1.0, 3000.0), min_size=1, max_size=3),
        st.fixed_dictionaries({"start": numbers(1, 3000), "stop": numbers(1, 3000)}),
        st.fixed_dictionaries(
            {"random": st.sampled_from(["uniform", "normal", "zipf"]), "n": numbers(0, 5)}
        ),
    ),
    "fault": st.lists(st.sampled_from(["none", "outer", "inner", "x"]), min_size=0, max_size=3),
    "fy_n": st.lists(numbers(-100.0, 100.0), min_size=1, max_size=2),
}


@given(
    axes=st.dictionaries(st.sampled_from(sorted(SWEEP_AXES)), st.just(None), max_size=3),
    data=st.data(),
)
def test_sweep_schema(axes, data):
    """A generated sweep spec is read or refused in one line, and every run of a read one has a
    valid scenario."""
    from bearingsim.sweep import SweepSpec

    drawn = {k: data.draw(SWEEP_AXES[k]) for k in axes}
    with no_hang():
        try:
            spec = SweepSpec.from_dict(
                {"base": {"model": "dem", "duration_s": 0.01}, "axes": drawn}, origin="gen.toml"
            )
            scenarios = spec.scenarios()  # every run validated (what `sweep plan/run` do)
        except BearingsimError as exc:
            _one_line(exc)
            return
        assert spec.n_runs == len(scenarios) >= 1
        assert all(sc.model.value == "dem" for sc in scenarios)
        event("ran")


# ------------------------------------------------------------------ CLI
def _cli(args: list[str]):
    """``bearingsim ARGS`` in-process: (exit code, stdout, stderr); any exception that is not the
    CLI's own exit fails the test (a traceback)."""
    import io
    from contextlib import redirect_stderr, redirect_stdout

    from bearingsim.cli import main

    out, err = io.StringIO(), io.StringIO()
    with redirect_stdout(out), redirect_stderr(err):
        try:
            main([str(a) for a in args])
            code = 0
        except SystemExit as exc:
            code = int(exc.code or 0)
    return code, out.getvalue(), err.getvalue()


def _check_cli(args: list[str]) -> None:
    with no_hang():
        code, out, err = _cli(args)
    lines = [ln for ln in err.splitlines() if ln.strip() and not ln.startswith("warning: ")]
    event("ran" if code == 0 else "refused")
    if code == 0:
        d = json.loads(out)
        assert _finite(d), (args, out[:300])
    else:
        assert code == 2, (args, code, err[-500:])
        assert len(lines) == 1 and lines[0].startswith("error: "), (args, err[-500:])


def opt(name: str, lo: float, hi: float):
    """An option and a generated value (as the shell would pass it)."""
    return st.tuples(st.just(name), numbers(lo, hi).map(str))


@given(
    options=st.lists(
        st.one_of(
            opt("--radial-load-n", 0.0, 1e5),
            opt("--ball-load-n", 0.0, 1e4),
            opt("--E-pa", 1e9, 1e12),
            opt("--nu", 0.0, 0.5),
        ),
        max_size=2,
        unique_by=lambda t: t[0],
    ),
    bearing=st.sampled_from(["6205", "6206", "NU204-ECP", "nope"]),
)
def test_cli_contact(options, bearing):
    args = ["contact", bearing, *[x for o in options for x in o], "--json"]
    if not any(o[0] in ("--radial-load-n", "--ball-load-n") for o in options):
        args[2:2] = ["--radial-load-n", "1000"]
    _check_cli(args)


@given(
    options=st.lists(
        st.one_of(
            opt("--fx-n", -1e5, 1e5),
            opt("--fy-n", -1e5, 1e5),
            opt("--clearance-m", -1e-4, 1e-4),
            opt("--cage-angle-deg", -720.0, 720.0),
        ),
        max_size=3,
        unique_by=lambda t: t[0],
    )
)
def test_cli_load(options):
    _check_cli(["load", "6205", *[x for o in options for x in o], "--json"])


@given(
    options=st.lists(
        st.one_of(
            opt("--fy-n", -1e4, 1e4),
            opt("--fz-n", -1e4, 1e4),
            opt("--outer-tilt-deg", -1.0, 1.0),
            opt("--clearance-m", -5e-5, 5e-5),
            opt("--cage-revs", 0, 3),
            opt("--rpm", 0.0, 2e4),
        ),
        max_size=3,
        unique_by=lambda t: t[0],
    )
)
def test_cli_stiffness(options):
    _check_cli(["stiffness", "6205", *[x for o in options for x in o], "--json"])


@given(
    options=st.lists(
        st.one_of(
            opt("--rpm", 0.0, 1e5),
            opt("--fx-n", -1e4, 1e4),
            opt("--fy-n", -1e4, 1e4),
            opt("--defect-width-m", 0.0, 1e-2),
            opt("--defect-depth-m", 0.0, 1e-2),
            opt("--fs-hz", 0.0, 1e6),
            opt("--duration-s", 0.0, 0.01),
            opt("--damping-n-s-per-m", -10.0, 1e4),
        ),
        max_size=3,
        unique_by=lambda t: t[0],
    ),
    model=st.sampled_from(["vsm", "dem", "tvsm"]),
)
def test_cli_simulate(options, model, tmp_path_factory):
    out = tmp_path_factory.mktemp("sim") / "r.nc"
    args = ["simulate", "--model", model, "--fault", "outer", *[x for o in options for x in o]]
    if not any(o[0] == "--duration-s" for o in options):
        args += ["--duration-s", "0.002"]
    _check_cli([*args, "-o", out, "--json"])
    if not out.exists():
        assert not list(out.parent.iterdir()), "a refused run leaves nothing behind"


@given(
    options=st.lists(
        st.one_of(
            opt("--rpm", 100.0, 1e4),
            opt("--torque-n-m", -100.0, 100.0),
            opt("--spall-width-m", 0.0, 1e-2),
            opt("--spall-angle-deg", -720.0, 720.0),
            opt("--fy-n", -1e4, 1e4),
            opt("--duration-s", 0.0, 1.0),
            opt("--dt-s", 0.0, 1e-4),
            opt("--fs-hz", 0.0, 1e6),
            opt("--skip-s", 0.0, 0.05),
        ),
        max_size=3,
        unique_by=lambda t: t[0],
    )
)
def test_cli_ias(options, tmp_path_factory):
    """IAS runs finite or is refused in one line (0.5 s runs at 600 r/min unless drawn, so that a
    run turns the shaft far enough to be analysed: the default is 10 s from rest)."""
    args = ["ias", *[x for o in options for x in o], "--initial-rpm", "600"]
    if not any(o[0] in ("--rpm", "--torque-n-m") for o in options):
        args += ["--rpm", "600"]
    if not any(o[0] == "--duration-s" for o in options):
        args += ["--duration-s", "0.5"]
    if not any(o[0] == "--skip-s" for o in options):
        args += ["--skip-s", "0"]
    if not any(o[0] == "--dt-s" for o in options):
        args += ["--dt-s", "1e-5"]
    out = tmp_path_factory.mktemp("ias") / "i.nc"
    _check_cli([*args, "-o", out, "--json"])
    if not out.exists():
        assert not list(out.parent.iterdir()), "a refused run leaves nothing behind"


@given(
    options=st.lists(
        st.one_of(
            opt("--disks", 1, 30).map(lambda t: (t[0], t[1].split(".")[0])),
            opt("--elements", 10, 200).map(lambda t: (t[0], t[1].split(".")[0])),
            opt("--shaft-length-mm", 50.0, 2000.0),
            opt("--shaft-diameter-mm", 1.0, 40.0),
            opt("--shaft-E-pa", 1e9, 1e12),
            opt("--rotor-mass-kg", 0.0, 3.0),
        ),
        max_size=3,
        unique_by=lambda t: t[0],
    )
)
@example(options=[("--shaft-length-mm", "7.023347140412655e-252")])  # was a ZeroDivisionError
@example(options=[("--rotor-mass-kg", "1e-300")])  # was a LinAlgError
def test_cli_rotor_modes(options):
    _check_cli(["rotor-modes", *[x for o in options for x in o], "--json"])


SET_VALUES = st.one_of(
    st.text(max_size=12),
    st.from_regex(r"\[{1,400}", fullmatch=True),
    numbers(-1e6, 1e6).map(str),
    st.sampled_from(["true", "[1, 2]", '"x"', "{a = 1}", "1e400", "nan", "inf", ""]),
)


@given(
    key=st.sampled_from(["rpm", "fy_n", "fault", "defect_width_m", "seed", "nope", ""]),
    value=SET_VALUES,
)
def test_cli_simulate_set(key, value, tmp_path_factory):
    """``simulate --set KEY=VALUE`` with any value: a finite run or a one-line refusal."""
    out = tmp_path_factory.mktemp("set") / "r.nc"
    args = ["simulate", "--model", "dem", "--duration-s", "0.002", "--set", f"{key}={value}"]
    _check_cli([*args, "-o", out, "--json"])
