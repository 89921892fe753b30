"""Rolling-element (ball) defects in the ring and rotor models (issue 16, item 2).

One ball carries a slot of width b and depth h_d. The ball rolls on the fixed outer race, so its
spin angle advances BSF/FTF times the cage angle; the slot meets the outer race once and the
inner race once per spin revolution (2×BSF), and the ball carries it through the load zone once
per cage revolution (FTF modulation). The loss of approach at each contact follows the same
chord rule as a raceway defect (seed VSM eq. (2), with the roles of ball and raceway swapped).
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from bearingsim import get_bearing
from bearingsim.config import Scenario
from bearingsim.dynamics.ring import _balance as bl
from bearingsim.errors import ConfigError
from bearingsim.geometry import Defect, Race, characteristic_frequencies, defect_geometry
from bearingsim.signal import diagnose
from bearingsim.signal.benchmark import squared_envelope_spectrum
from bearingsim.signal.peaks import match_peaks
from bearingsim.simulation import simulate

B = get_bearing("6205")
#: CWRU 0.014 in slot across the ball, EDM depth 0.011 in [m] (SOURCES.md)
WIDTH = 0.014 * 0.0254
DEPTH = 0.011 * 0.0254


def _ball_lines_db(x, fs, fr, bearing) -> dict[str, float]:
    """SNR [dB] of FTF, 2×BSF and its ±FTF sidebands in the squared envelope (2-20 kHz)."""
    k = characteristic_frequencies(bearing, fr)
    es = squared_envelope_spectrum(x, fs, (2000.0, 20000.0))
    targets = [
        ("FTF", k.ftf_hz),
        ("2xBSF", 2 * k.bsf_hz),
        ("2xBSF-FTF", 2 * k.bsf_hz - k.ftf_hz),
        ("2xBSF+FTF", 2 * k.bsf_hz + k.ftf_hz),
    ]
    return {p.label: p.snr_db for p in match_peaks(es, targets, fr)}


def test_ball_defect_geometry_is_the_chord_rule_with_roles_swapped():
    """Seed VSM eq. (2): h_s = [r - sqrt(r^2 - b^2/4)] -/+ [r_race - sqrt(r_race^2 - b^2/4)];
    at the outer race (concave) the raceway enters the slot less, at the inner race (convex)
    more; the slot spans 2 arcsin(b/d) of the ball."""
    g = defect_geometry(B, Defect("ball", WIDTH, DEPTH, 0.0))
    r = 0.5 * B.element_diameter
    half = 0.5 * WIDTH
    chord = r - math.sqrt(r * r - half * half)
    ro, ri = B.outer_raceway_radius, B.inner_raceway_radius
    assert g.race is Race.BALL
    assert g.h_min == pytest.approx(chord - (ro - math.sqrt(ro * ro - half * half)), rel=1e-12)
    assert g.h_min_inner == pytest.approx(
        chord + (ri - math.sqrt(ri * ri - half * half)), rel=1e-12
    )
    assert g.h_min < g.h_min_inner < DEPTH  # a 0.36 mm slot is not touched at its bottom
    assert g.delta_beta == pytest.approx(2 * math.asin(WIDTH / B.element_diameter), rel=1e-12)


def test_a_ball_defects_result_records_both_races_drops():
    # twenty-first session: meta["defect"] held only the outer-race drop of a ball defect
    res = simulate(
        dict(model="vsm", fault="ball", duration_s=0.05, fs_hz=12000.0, bearing="6205",
             defect_width_m=WIDTH, defect_depth_m=DEPTH)
    )  # fmt: skip
    g = defect_geometry(B, Defect("ball", WIDTH, DEPTH, 0.0))
    assert res.meta["defect"]["h_min_m"] == g.h_min
    assert res.meta["defect"]["h_min_inner_m"] == g.h_min_inner
    assert res.meta["defect"]["race_radius_m"] == 0.5 * B.element_diameter


def test_only_ball_one_carries_the_defect_and_it_meets_both_races():
    """The compiled indicator: ball 0 over the slot facing the outer race (drop h_o) at spin
    angle in [0, dpsi), facing the inner race (drop h_i) half a turn later; other balls never."""
    dpsi, ho, hi = 0.2, 1e-6, 2e-6
    p = np.zeros(bl.HEADER)  # P_PROFILE 0: the rectangular drop
    f, d = bl.defect_fraction(0, 0.1, 0.0, 3, dpsi, ho, hi, p)
    assert (f, d) == (1.0, ho)
    f, d = bl.defect_fraction(0, math.pi + 0.1, 0.0, 3, dpsi, ho, hi, p)
    assert (f, d) == (1.0, hi)
    assert bl.defect_fraction(0, 0.5 * math.pi, 0.0, 3, dpsi, ho, hi, p)[0] == 0.0
    for j in range(1, 9):
        assert bl.defect_fraction(j, 0.1, 0.0, 3, dpsi, ho, hi, p)[0] == 0.0
    # a raceway defect: every ball, one drop
    assert bl.defect_fraction(5, 0.1, 0.0, 1, dpsi, ho, hi, p) == (1.0, ho)


@pytest.mark.parametrize("model", ["vsm", "dem", "tvsm"])
def test_ball_fault_signature_and_diagnosis(model):
    """A 0.014 in ball defect at 1797 r/min with 1 % slip and CWRU-97-level noise (0.713 m/s^2,
    tests/test_analyze.py): the squared envelope shows 2×BSF with ±FTF sidebands and the FTF
    line (>= 12 dB, the detection threshold of bearingsim.signal.diagnosis), and the
    diagnosis says ball (a BPFO line may remain: the varying compliance of the ball passes,
    strongest in the DEM)."""
    s = simulate(
        Scenario(
            model=model, fault="ball", rpm=1797.0, duration_s=1.0, defect_width_m=WIDTH,
            noise_rms_m_per_s2=0.713, seed=1, slip_percent=1.0,
        )
    )  # fmt: skip
    x, fs, fr = s["acc_y"], s.fs_hz, s.shaft_hz
    got = _ball_lines_db(x, fs, fr, B)
    for lab in ("FTF", "2xBSF", "2xBSF-FTF", "2xBSF+FTF"):
        assert got[lab] >= 12.0, (lab, got)
    assert diagnose(x, fs, B, fr).diagnosis == "ball"


def test_contacts_refuse_a_ball_race():
    """Contacts are between a ball and a raceway: 'ball' is a defect site, not a raceway."""
    from bearingsim.contact.hertz import ball_contact

    with pytest.raises(ConfigError, match="race = 'ball' is invalid; valid: inner, outer"):
        ball_contact(B, 1000.0, "ball")


def test_rotor_ball_fault_signature():
    """Rotor model (seed ROTOR system, CWRU 6205 at the drive end), 0.014 in slot on ball 1,
    0.5 s: the drive-end housing acceleration's squared envelope (2-20 kHz) shows 2×BSF with
    ±FTF sidebands and FTF (>= 12 dB), and the fused diagnosis says ball."""
    from bearingsim.signal.fused import diagnose_fused

    s = simulate(
        Scenario(
            model="rotor", de_fault="ball", duration_s=0.5, defect_width_m=WIDTH,
            noise_rms_m_per_s2=0.05, seed=1,
        )
    )  # fmt: skip
    x, fs, fr = s["acc_y"], s.fs_hz, s.shaft_hz
    b = get_bearing("6205-cwru")
    got = _ball_lines_db(x, fs, fr, b)
    for lab, v in got.items():
        assert v >= 12.0, (lab, got)
    assert diagnose_fused(x, fs, b, fr).diagnosis == "ball"


def test_the_slots_spin_angle_means_the_same_in_the_ring_and_rotor_models():
    """Exploratory testing (twenty-fifth session): the slot's spin angle (0 = facing the outer
    race, advancing as the ball spins) was taken with the opposite sign by the rotor model, so
    at 90 deg its first strike was on the outer race and the DEM's on the inner. Both now reach
    the inner race after a quarter spin turn (the slot at 90 deg, 90 deg from the inner
    contact) and the outer race after three quarters: ball 1's load drops at T/4 and 3T/4 (T
    = 1/BSF), deeper at the inner race (convex: the chord rule's loss is larger there,
    test_ball_defect_geometry_is_the_chord_rule_with_roles_swapped). Preloaded (-10 um), so
    ball 1 is loaded at both."""
    common = dict(duration_s=0.03, fs_hz=48000.0, per_ball=True, defect_width_m=WIDTH)
    for sc, name in (
        (dict(model="dem", fault="ball", defect_edge_angle_deg=90.0, clearance_m=-1e-5),
         "ball_load"),
        (dict(model="rotor", de_fault="ball", de_defect_angle_deg=90.0, de_clearance_m=-1e-5),
         "ball_load_inner_de"),
    ):  # fmt: skip
        r = simulate(sc | common)
        q, t = np.asarray(r[name])[:, 0], r.time
        period = 1.0 / r.meta["kinematics"]["bsf_hz"]
        base = np.median(q[t < period])

        def drop(lo, hi, q=q, t=t, period=period, base=base):
            m = (t >= lo * period) & (t < hi * period)
            return base - q[m].min(), t[m][np.argmin(q[m])] / period

        (d_in, at_in), (d_out, at_out) = drop(0.125, 0.375), drop(0.625, 0.875)
        assert at_in == pytest.approx(0.25, abs=0.01) and at_out == pytest.approx(0.75, abs=0.01)
        assert d_in > d_out > 0.0, (sc["model"], d_in, d_out)


def test_healthy_and_race_faults_unchanged_by_the_ball_branch():
    """The raceway-defect and healthy paths are the golden cases (tests/test_golden.py); here
    the scenario keys: 'ball' is a fault of the ring and rotor families."""
    assert Scenario(model="vsm", fault="ball").fault == "ball"
    assert Scenario(model="rotor", fe_fault="ball").fe_fault == "ball"
    with pytest.raises(ConfigError, match="fault"):
        Scenario(model="vsm", fault="cage")
    np.testing.assert_equal(bl.defect_rate(np.zeros(bl.HEADER)), 0.0)


def test_a_ball_defect_deeper_than_the_ball_radius_is_named_once(run_cli, tmp_path):
    """The refusal names the ball radius (exploratory testing: 'the ball ball radius')."""
    r = run_cli("simulate", "--model", "vsm", "--fault", "ball", "--defect-depth-m", "0.1",
                "--duration-s", "0.01", "-o", tmp_path / "b.nc")  # fmt: skip
    line = r.refused("defect_depth_m = 0.1 m is not less than the ball radius 0.00397 m of 6205")
    assert "ball ball" not in line
