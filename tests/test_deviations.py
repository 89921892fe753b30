"""The quantitative reasons behind the report's ``deviates`` rows.

A report row may be ``deviates`` (outside its tolerance against a paper or a standard) only
when its note gives a quantitative reason and a test verifies it: the row's ``verified_by`` names
one of these tests (or another test id). Each test checks the numbers the reason states, so a
change that breaks the reason fails here, and ``test_every_verified_by_names_a_test`` fails if
a row names a test that does not exist.
"""

from __future__ import annotations

import ast
import math
import re
from pathlib import Path

import numpy as np
import pytest
from numpy.testing import assert_allclose
from scipy.optimize import brentq

from bearingsim.catalog import get_bearing
from bearingsim.contact.hertz import ball_contact
from bearingsim.geometry import Race
from bearingsim.load_distribution import radial_load_distribution, stribeck_qmax
from bearingsim.report.published import value

ROOT = Path(__file__).resolve().parents[1]
B6205, B6206 = get_bearing("6205"), get_bearing("6206")


def _psi_deg(stiffness=None) -> float:
    """psi_L of the seed VSM §2.1 case (6205, F_rx 10 N, F_ry 50 N, cage angle 0) [deg]."""
    ld = radial_load_distribution(B6205, 10.0, 50.0, 0.0, stiffness=stiffness)
    return math.degrees(float(ld.psi_l[0]))


def test_seed_fe_pmax_differs_from_its_own_hertz_value():
    """Seed LIFE table 2 prints for the same 6206 contacts at 5 kN a Hertz-theory p_max and its
    3-D ABAQUS p_max. Ours is Hertz theory: within 1 % of the seed's own theory values; the
    seed's FE sits +0.5 % (inner) and -2.1 % (outer) from its theory, which is why the outer
    FE row deviates by more than its 1 % tolerance."""
    q = stribeck_qmax(B6206, 5000.0)
    for race, key in ((Race.INNER, "inner"), (Race.OUTER, "outer")):
        ours = float(ball_contact(B6206, q, race).p_max) / 1e6
        theory = value(f"life.table2.{key}_pmax_theory")
        assert_allclose(ours, theory, rtol=0.01, err_msg=f"{key}: ours vs seed theory")
    fe_off = value("life.table2.outer_pmax_fe") / value("life.table2.outer_pmax_theory") - 1
    assert -0.025 < fe_off < -0.015  # the seed's outer FE 2.1 % below its own Hertz value
    assert (
        abs(value("life.table2.inner_pmax_fe") / value("life.table2.inner_pmax_theory") - 1) < 0.01
    )


def test_psi_l_68_deg_needs_k_028_hertz():
    """Seed VSM §2.1: psi_L = 68.2 deg. Our Hertz K of the 6205 gives 56.03 deg; the paper's
    angle needs a ball constant of 0.28 x the Hertz K (the seed does not state its K)."""
    k_hertz = radial_load_distribution(B6205, 10.0, 50.0, 0.0).stiffness
    assert_allclose(_psi_deg(), 56.03, atol=0.02)
    pub = value("vsm.s2_1.load_zone_half_angle")
    k_needed = brentq(lambda k: _psi_deg(k) - pub, 1e8, k_hertz)
    assert_allclose(k_needed / k_hertz, 0.28, atol=0.01)


def test_hertz_k_narrows_the_zone_of_table2_and_fig5():
    """With our Hertz K (psi_L 56.0 deg) the zone is narrower than the paper's 68.2 deg: in the
    table-2 case ball 5 enters the zone about 10 deg later than the paper's 143.1 deg, and the
    healthy bearing carries 2 or 3 balls instead of fig. 5's 3 or 4; with K = 0.28 x Hertz
    (psi_L 68.2 deg) both come back (zone entry within 2 deg, 3/4 balls)."""
    from bearingsim.dynamics.ring.base import ModelInputs
    from bearingsim.dynamics.ring.trace import stiffness_trace
    from bearingsim.geometry import defect_at_edge

    pub = value("vsm.s2_1.load_zone_half_angle")
    k_hertz = radial_load_distribution(B6205, 10.0, 50.0, 0.0).stiffness
    k_paper = brentq(lambda k: _psi_deg(k) - pub, 1e8, k_hertz, xtol=1e-3)
    cage = np.radians(np.arange(0.0, 360.0 + 1e-9, 0.02))

    def inputs(loc, **kw):
        d = None if loc == "none" else defect_at_edge(B6205, loc, 1e-3, 1e-3, math.radians(10))
        return ModelInputs(B6205, 10.0, 50.0, 1750 / 60, d, retention_factor=0.38, **kw)

    published = {(b, k): a for a, b, k in _table2()}[(5, "enters_zone")]

    def entry_angle(**kw):
        tr = stiffness_trace(inputs("outer", **kw), cage)
        ev = [a for a, b, k in tr.events() if b == 5 and k == "enters_zone" and 130 <= a <= 170]
        return ev[0]

    ours = entry_angle()
    assert 8.0 < ours - published < 12.0  # about 10 deg later
    assert abs(entry_angle(stiffness=k_paper) - published) < 2.0
    balls = stiffness_trace(inputs("none"), cage).n_loaded
    balls_paper = stiffness_trace(inputs("none", stiffness=k_paper), cage).n_loaded
    assert set(np.unique(balls)) == {2, 3}
    assert set(np.unique(balls_paper)) == {3, 4}


def _table2():
    from bearingsim.report.published import entry

    return entry("vsm.table2.outer_defect_events").rows("ball", "event")


def test_record_132_fault_line_is_above_the_table_order():
    """CWRU record 132 (outer race, 0.007 in, stored speed 1750 r/min): over the whole 10 s
    record (0.1 Hz bins) the envelope line near BPFO sits at order 3.597 of the stored speed,
    0.3-0.5 % above the CWRU table's 3.5848. Not a speed error: the record's own shaft
    harmonics put its speed at the stored 1750 r/min (within 0.05 %). A contact angle of
    8-11 deg puts BPFO there (an axial load on the deep-groove bearing); record 107 (inner race,
    the same size and load) has its BPFI as far *below* the table order, which a contact angle
    does and a speed error cannot (it would move both up)."""
    from bearingsim.catalog import resolve_bearing
    from bearingsim.geometry import contact_angle_from_order
    from bearingsim.io.cwru import cwru_data_dir
    from bearingsim.signal import envelope_spectrum, load_signal
    from bearingsim.signal.contact_angle import estimate_contact_angle, measured_shaft_hz

    path = cwru_data_dir() / "12k_Drive_End_OR007@6_2_132.mat"
    inner = cwru_data_dir() / "12k_Drive_End_IR007_2_107.mat"
    if not (path.is_file() and inner.is_file()):
        pytest.skip("CWRU records 132 and 107 are not in shared/data")
    rec = load_signal(path)
    table = value("cwru.drive_end.bpfo_order")
    es = envelope_spectrum(rec.x, rec.fs, (2000.0, 5000.0))
    f0 = table * rec.rpm / 60
    sel = np.flatnonzero((es.freq >= 0.98 * f0) & (es.freq <= 1.02 * f0))
    f_line = float(es.freq[sel[np.argmax(es.amplitude[sel])]])
    order = f_line / (rec.rpm / 60)
    assert 0.003 < order / table - 1 < 0.005
    shaft, n = measured_shaft_hz(rec.x, rec.fs, rec.rpm / 60)
    assert n >= 4
    assert abs(60 * shaft / rec.rpm - 1) < 5e-4  # the stored speed is right
    b = resolve_bearing("6205-cwru")
    alpha = math.degrees(contact_angle_from_order(b, "bpfo", f_line / shaft))
    assert 8.0 < alpha < 11.0
    r107 = load_signal(inner)
    est = estimate_contact_angle(r107.x, r107.fs, b, "inner", r107.rpm / 60)
    assert est.order < value("cwru.drive_end.bpfi_order") * (1 - 0.002)
    assert 8.0 < est.contact_angle_deg < 11.0


def test_seed_b_needs_177_times_the_stribeck_load():
    """Seed LIFE table 3: b = 0.23 mm. Hertz theory gives b = 0.190 mm for the Stribeck
    Q = 4.37 F_r/Z = 2428 N of the 6206 at 5 kN; b grows as Q^(1/3), so 0.23 mm needs
    (0.23/0.190)^3 = 1.77 x that load."""
    q = stribeck_qmax(B6206, 5000.0)
    b = float(ball_contact(B6206, q, Race.INNER).b)
    assert_allclose(b * 1e3, 0.1901, rtol=2e-3)
    target = value("life.table3.semi_axis_b") * 1e-3
    factor = brentq(lambda f: float(ball_contact(B6206, f * q, Race.INNER).b) - target, 1.0, 3.0)
    assert_allclose(factor, 1.77, atol=0.01)


def test_skf_ratings_exceed_plain_iso281():
    """Our ISO 281 C_r from geometry equals the plain ISO 281 values NSK lists (1 %); SKF lists
    4-6 % more for the 6206 and 6205 (its steel and manufacturing quality)."""
    from bearingsim.life.iso281 import dynamic_load_rating

    for bid in ("6206", "6205"):
        c = dynamic_load_rating(get_bearing(bid)).c / 1e3
        nsk, skf = value(f"catalogue.nsk.{bid}.c_r"), value(f"catalogue.skf.{bid}.c_r")
        assert_allclose(c, nsk, rtol=0.01)
        assert 1.03 < skf / nsk < 1.07
        assert skf / c > 1.01  # outside the 1 % tolerance of the SKF row


# ------------------------------------------------------------------------------ the meta check


def _verified_by_ids() -> set[str]:
    """Every test id the report sections name as ``verified_by`` (string literals)."""
    ids: set[str] = set()
    for path in (ROOT / "src" / "bearingsim" / "report" / "sections").glob("*.py"):
        for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
            if isinstance(node, ast.Constant) and isinstance(node.value, str):
                if re.fullmatch(r"tests/test_\w+\.py::test_\w+", node.value):
                    ids.add(node.value)
    return ids


def test_every_verified_by_names_a_test():
    """Each ``tests/x.py::test_y`` a report section names exists as a test function, and the
    sections name at least the deviations listed in docs/validation.md."""
    ids = _verified_by_ids()
    assert len(ids) >= 6, ids
    for tid in sorted(ids):
        file, name = tid.split("::")
        tree = ast.parse((ROOT / file).read_text(encoding="utf-8"))
        names = {n.name for n in ast.walk(tree) if isinstance(n, ast.FunctionDef)}
        assert name in names, f"{tid}: no such test"
