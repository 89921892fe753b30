"""Issue 14, item 1 (bearings): what is not a bearing is refused in one line naming the field,
its value and the valid range with its source — in Python and on every command that reads a
bearing file — and a boolean is never a number."""

from __future__ import annotations

import math

import numpy as np
import pytest

from bearingsim.catalog import bearing_from_dict, get_bearing, list_bearings
from bearingsim.config import Scenario
from bearingsim.errors import ConfigError, check_positive, check_range
from bearingsim.geometry import (
    ISO5753_GROUP5_BALL,
    ISO5753_GROUP5_ROLLER,
    clearance_range,
    max_clearance,
)
from bearingsim.load_distribution import radial_load_distribution

#: a valid user bearing (the 6205 of seed VSM table 1), SI keys of the bearing files
GOOD = dict(
    id="user-1",
    type="ball",
    n_elements=9,
    element_diameter_m=7.94e-3,
    pitch_diameter_m=39e-3,
    diametral_clearance_m=6e-6,
    inner_groove_radius_m=4.089e-3,
    outer_groove_radius_m=4.169e-3,
    bore_m=25e-3,
    outer_diameter_m=52e-3,
)


def _toml(d: dict) -> str:
    return "\n".join(f'{k} = "{v}"' if isinstance(v, str) else f"{k} = {v!r}" for k, v in d.items())


def one_line_error(r) -> str:
    """The single ``error:`` line of a refused command (exit 2, nothing on stdout)."""
    assert r.code == 2, (r.code, r.out, r.err)
    lines = r.err.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("error: "), r.err
    assert "Traceback" not in r.err
    return lines[0]


# ------------------------------------------------------------------------------- booleans
@pytest.mark.parametrize("value", [True, False, np.True_, np.bool_(False)])
def test_booleans_are_not_numbers(value):
    with pytest.raises(ConfigError, match=r"rpm = .* is not a number; valid range \(0, inf\)"):
        check_positive("rpm", value, "r/min")
    with pytest.raises(ConfigError, match="is not a number"):
        check_range("fy_n", value, unit="N")
    assert check_range("fy_n", np.float64(2.5)) == 2.5  # NumPy numbers still are


def test_scenario_rpm_true_is_refused_not_one_rpm(run_cli, tmp_path):
    """Issue 14: 'a scenario with rpm = true runs at 1 r/min'."""
    with pytest.raises(ConfigError, match=r"rpm = True is not a number; valid range \(0, inf\)"):
        Scenario(model="vsm", rpm=True)
    sc = tmp_path / "s.toml"
    sc.write_text('model = "vsm"\nrpm = true\nduration_s = 0.01\n')
    out = tmp_path / "r.nc"
    line = one_line_error(run_cli("simulate", sc, "-o", out))
    assert "rpm = True is not a number" in line
    assert not out.exists()


def test_bearing_file_number_as_text():
    """A number in quotes (``pitch_diameter_m = "0.039"``) was read as the number; refused in
    one line naming the key (the id and source stay text)."""
    with pytest.raises(ConfigError, match=r"user.toml: pitch_diameter_m = '0.039' is text"):
        bearing_from_dict({**GOOD, "pitch_diameter_m": "0.039"}, "user.toml")
    bearing_from_dict({**GOOD, "id": "mine", "source": "a catalogue"}, "user.toml")


def test_bearing_file_boolean(tmp_path):
    with pytest.raises(ConfigError, match="pitch_diameter_m = True is not a number"):
        bearing_from_dict({**GOOD, "pitch_diameter_m": True})


# ------------------------------------------------------------------- what a bearing can be
@pytest.mark.parametrize(
    "change, needle",
    [
        # issue 14: 'a bearing file with a 1e30 m groove radius is accepted by six commands'
        ({"outer_groove_radius_m": 1e30}, "outer_groove_radius_m = 1e+30 m gives conformity"),
        ({"inner_groove_radius_m": 0.7 * 7.94e-3}, "conformity in (0.5, 0.6]"),
        ({"inner_groove_radius_m": 0.5 * 7.94e-3}, "inner_groove_radius_m"),
        # issue 14: '-3.9 mm (inside the documented +/- d/2) gives an 808 kN ball load'
        ({"diametral_clearance_m": -3.9e-3}, "diametral_clearance_m = -0.0039 m is out of range"),
        ({"diametral_clearance_m": 1e-3}, "ISO 5753-1, group 5, for a 25 mm bore"),
        ({"pitch_diameter_m": 1e30}, "pitch_diameter_m = 1e+30 m is out of range"),
        ({"pitch_diameter_m": 1.0, "bore_m": 0.9, "outer_diameter_m": 1.1}, "gamma = d cos"),
        ({"element_diameter_m": 1e-4}, "gamma"),
        ({"contact_angle_rad": math.radians(60)}, "contact_angle_rad = 1.0472 rad"),
        ({"youngs_modulus_pa": 1e30}, "youngs_modulus_pa = 1e+30 Pa is out of range"),
        ({"youngs_modulus_pa": 1e3}, "valid range [1e+09, 1.2e+12] Pa"),
        ({"poisson_ratio": -0.5}, "poisson_ratio = -0.5 is out of range; valid range [0, 0.5)"),
        ({"density_kg_m3": 1e30}, "density_kg_m3 = 1e+30 kg/m^3 is out of range"),
        ({"bore_m": 0.032}, "bore_m = 0.032 m is not inside the inner raceway"),
        ({"outer_diameter_m": 0.045}, "outer_diameter_m = 0.045 m is not outside"),
        ({"n_elements": 2**80}, "n_elements = 1208925819614629174706176 is out of range"),
    ],
    ids=[
        "groove-1e30",
        "conformity-0.7",
        "conformity-0.5",
        "clearance-minus-3.9mm",
        "clearance-1mm",
        "pitch-1e30",
        "gamma-small",
        "gamma-tiny-ball",
        "contact-angle-60",
        "E-1e30",
        "E-1kPa",
        "nu-negative",
        "density-1e30",
        "bore",
        "outside-diameter",
        "huge-count",
    ],
)
def test_not_a_bearing_is_refused(change, needle):
    with pytest.raises(ConfigError) as ei:
        bearing_from_dict({**GOOD, **change}, "user.toml")
    msg = str(ei.value)
    assert needle in msg, msg
    assert msg.startswith("user.toml: ") and "\n" not in msg and "valid" in msg


def test_roller_length_and_huge_integers():
    nu = dict(
        id="nu",
        type="cylindrical_roller",
        n_elements=11,
        element_diameter_m=7.94e-3,
        pitch_diameter_m=34e-3,
        roller_length_m=9e-3,
    )
    bearing_from_dict(nu)
    with pytest.raises(ConfigError, match=r"roller_length_m = 2.5e\+296 m is out of range"):
        bearing_from_dict({**nu, "roller_length_m": 2.5e296})  # found by the property below
    with pytest.raises(ConfigError, match=r"fy_n = 10{400} is out of range"):
        check_range("fy_n", 10**400)  # an integer beyond the float range


def test_catalogue_bearings_are_plausible():
    """Every catalogue entry passes the checks (they run when it loads) with its clearance well
    inside the ISO 5753-1 limit."""
    for b in list_bearings():
        lo, hi = clearance_range(b)
        assert lo < b.diametral_clearance < hi, b.id


@pytest.mark.parametrize(
    "bid, c5_um",
    # ISO 5753-1 group 5 upper limits: 6205 and 6206 bores (25, 30 mm) are in the 24-30 mm row
    # of the deep-groove table (53 um); the 6203 (17 mm) in the 10-18 mm row (45 um); the NU204
    # (20 mm) in the first row of the cylindrical-roller table (up to 24 mm: 90 um)
    [("6205", 53.0), ("6206", 53.0), ("6203-cwru", 45.0), ("NU204-ECP", 90.0)],
)
def test_max_clearance_is_the_iso5753_group5_limit(bid, c5_um):
    assert max_clearance(get_bearing(bid)) == pytest.approx(c5_um * 1e-6, rel=1e-12)


def test_max_clearance_without_bore_and_beyond_the_table():
    from dataclasses import replace

    b = get_bearing("6205")
    # no bore: the inner raceway diameter (31.06 mm, the 30-40 mm row) bounds any bore
    assert max_clearance(replace(b, bore=None)) == pytest.approx(64e-6, rel=1e-12)
    # tables are nondecreasing; above the last row the limit grows in proportion to the bore
    for rows in (ISO5753_GROUP5_BALL, ISO5753_GROUP5_ROLLER):
        assert all(a[1] <= b_[1] for a, b_ in zip(rows, rows[1:], strict=False))
    big = bearing_from_dict(
        {
            **GOOD,
            "element_diameter_m": 0.04,
            "pitch_diameter_m": 0.5,
            "n_elements": 20,
            "inner_groove_radius_m": 0.0206,
            "outer_groove_radius_m": 0.021,
            "bore_m": 0.4,
            "outer_diameter_m": 0.6,
        }
    )
    assert max_clearance(big) == pytest.approx(120e-6 * 400 / 100, rel=1e-12)


def test_clearance_override_is_bounded_too(run_cli):
    """``load --clearance-m -3.9e-3`` gave 808 kN per ball under 5 kN (issue 14)."""
    with pytest.raises(ConfigError, match=r"clearance_m = -0.0039 m is out of range"):
        radial_load_distribution(get_bearing("6205"), 0.0, 5000.0, clearance=-3.9e-3)
    line = one_line_error(run_cli("load", "6205", "--fy-n", "5000", "--clearance-m", "-3.9e-3"))
    assert "clearance_m = -0.0039 m is out of range; valid range [-5.3e-05, 5.3e-05] m" in line
    assert "ISO 5753-1" in line
    # within the range it still runs (a preload of 20 um)
    r = run_cli("load", "6205", "--fy-n", "5000", "--clearance-m", "-2e-5", "--json")
    assert r.code == 0 and max(r.json()["ball_loads_n"]) < 5000


GROOVE_1E30 = _toml({**GOOD, "outer_groove_radius_m": 1e30})


@pytest.mark.parametrize(
    "args",
    [
        ["info", "--rpm", "1000"],
        ["contact", "--ball-load-n", "100"],
        ["load", "--fy-n", "100"],
        ["stiffness", "--fy-n", "100", "--cage-revs", "1"],
        ["life", "--radial-load-n", "1000", "-o", "OUT"],
        ["simulate", "--duration-s", "0.01", "-o", "OUT"],
        ["vsm-trace", "--json"],
    ],
    ids=lambda a: a[0],
)
def test_groove_radius_1e30_refused_by_every_command(run_cli, tmp_path, args):
    """Issue 14: the 1e30 m groove radius was accepted by six commands."""
    f = tmp_path / "bad.toml"
    f.write_text(GROOVE_1E30)
    out = tmp_path / "out.nc"
    args = [str(out) if a == "OUT" else a for a in args]
    line = one_line_error(run_cli(args[0], "--bearing-file", f, *args[1:]))
    assert "outer_groove_radius_m = 1e+30 m gives conformity" in line
    assert not out.exists()


# ------------------------------------------------------------------- any bearing file at all
def test_bearing_schema_property():
    """Any bearing file (Hypothesis: plausible and absurd values of every key, booleans, strings,
    NaN, huge integers) is either a bearing whose derived quantities are finite — static
    capacity, clearance range, kinematic frequencies — or refused in one line naming the file."""
    hyp = pytest.importorskip("hypothesis", reason="Hypothesis runs the property tests")
    st = pytest.importorskip("hypothesis.strategies")
    from bearingsim.contact.capacity import static_capacity
    from bearingsim.geometry import characteristic_frequencies

    def mostly(good, other):
        """``good`` nine times in ten, else ``other``."""
        return st.integers(0, 9).flatmap(lambda k: good if k < 9 else other)

    def near(v: float):
        """Around a real value, or anything."""
        wild = st.one_of(
            st.floats(allow_nan=True, allow_infinity=True),
            st.integers(-(2**70), 2**70),
            st.booleans(),
            st.text(max_size=4),
            st.none(),
        )
        # mostly plausible values (so that bearings are built and checked), now and then anything
        return mostly(st.one_of(st.just(v), st.floats(0.8 * v, 1.25 * v)), wild)

    ball = {
        "id": mostly(st.just("h"), st.one_of(st.text(max_size=3), st.integers())),
        "type": mostly(st.sampled_from(["ball", "cylindrical_roller"]), st.text(max_size=8)),
        "n_elements": mostly(
            st.integers(3, 14), st.one_of(st.integers(-5, 2000), st.floats(), st.booleans())
        ),
        "element_diameter_m": near(7.94e-3),
        "pitch_diameter_m": near(39e-3),
        "inner_groove_radius_m": near(4.089e-3),
        "outer_groove_radius_m": near(4.169e-3),
        "roller_length_m": near(9e-3),
    }
    optional = {
        "contact_angle_rad": near(0.2),
        "diametral_clearance_m": near(6e-6),
        "youngs_modulus_pa": near(207e9),
        "poisson_ratio": near(0.3),
        "density_kg_m3": near(7850.0),
        "bore_m": near(25e-3),
        "outer_diameter_m": near(52e-3),
    }

    @hyp.settings(max_examples=300, deadline=None, derandomize=True, database=None)
    @hyp.given(st.fixed_dictionaries(ball, optional=optional))
    def check(d):
        if d["type"] == "ball":
            d.pop("roller_length_m")
        else:
            d.pop("inner_groove_radius_m")
            d.pop("outer_groove_radius_m")
        try:
            b = bearing_from_dict(d, "h.toml")
        except ConfigError as exc:
            msg = str(exc)
            assert msg.startswith("h.toml: ") and "\n" not in msg, msg
            return
        assert 0 < static_capacity(b).c0 < math.inf
        lo, hi = clearance_range(b)
        assert -math.inf < lo < 0 < hi < math.inf
        f = characteristic_frequencies(b, 10.0)
        assert all(math.isfinite(v) and v > 0 for v in f.as_dict().values())
        built.append(b.kind)

    built: list[str] = []
    check()
    assert {"ball", "cylindrical_roller"} <= set(built), "the property saw no bearing built"
