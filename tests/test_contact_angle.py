"""The contact angle from a line's order (geometry.contact_angle_from_order) and from a record
(signal.contact_angle): the inverse of the kinematic frequencies, a synthetic record whose
angle is known, and bad input."""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from bearingsim import ConfigError, characteristic_frequencies
from bearingsim.catalog import resolve_bearing
from bearingsim.geometry import contact_angle_from_order
from bearingsim.signal.contact_angle import estimate_contact_angle, measured_shaft_hz

B = resolve_bearing("6205-cwru")


@settings(max_examples=60, deadline=None)
@given(alpha_deg=st.floats(0.0, 45.0), line=st.sampled_from(["bpfo", "bpfi", "ftf"]))
def test_inverse_of_the_kinematic_frequencies(alpha_deg, line):
    """The angle that puts a line at the order characteristic_frequencies gives for a bearing
    at alpha is alpha (0-45 deg, the range a ball bearing's contact angle may take; to
    round-off in cos(alpha), ~1e-8 rad near 0 where acos is steep)."""
    b = replace(B, contact_angle=math.radians(alpha_deg))
    k = characteristic_frequencies(b, 1.0)
    order = {"bpfo": k.bpfo_order, "bpfi": k.bpfi_order, "ftf": k.ftf_order}[line]
    assert math.degrees(contact_angle_from_order(B, line, order)) == pytest.approx(
        alpha_deg, abs=1e-4
    )


@pytest.mark.parametrize("bid", ["6203-cwru", "6205", "6205-cwru", "6206"])
def test_a_line_at_the_alpha_zero_order_reads_zero_on_every_ball_bearing(bid):
    """Exploratory testing (twentieth session): a simulated 6203-cwru inner-race fault put its
    BPFI exactly at the alpha = 0 order, and the estimate refused it as "outside ... valid
    range [4, 4.94688]", the value its own bound (a rounding of 2 o / Z - 1 above d/D). The
    ends of each line's range read 0 and 90 deg on every catalogue ball bearing."""
    b = replace(resolve_bearing(bid), contact_angle=0.0)
    k = characteristic_frequencies(b, 1.0)
    for line, order in (("bpfo", k.bpfo_order), ("bpfi", k.bpfi_order), ("ftf", k.ftf_order)):
        assert math.degrees(contact_angle_from_order(b, line, order)) == pytest.approx(
            0.0, abs=1e-3
        )
    z = b.n_elements
    assert contact_angle_from_order(b, "bpfo", z / 2) == pytest.approx(math.pi / 2)
    assert contact_angle_from_order(b, "bpfi", z / 2) == pytest.approx(math.pi / 2)


def test_the_cwru_table_orders_are_alpha_zero():
    """The CWRU bearing table's drive-end orders (BPFO 3.5848, BPFI 5.4152) are those of a
    contact angle of 0 (within the table's 4 decimals: under 0.6 deg, where acos is steep)."""
    from bearingsim.report.published import value

    assert (
        math.degrees(contact_angle_from_order(B, "bpfo", value("cwru.drive_end.bpfo_order"))) < 0.6
    )
    assert (
        math.degrees(contact_angle_from_order(B, "bpfi", value("cwru.drive_end.bpfi_order"))) < 0.6
    )


@pytest.mark.parametrize(
    "line, order, match",
    [
        ("bpfo", 3.5, "valid range"),  # below the alpha = 0 BPFO: slip or speed, not an angle
        ("bpfo", 4.6, "valid range"),  # above Z/2
        ("bpfi", 5.5, "valid range"),  # above the alpha = 0 BPFI
        ("ftf", 0.6, "valid range"),
        ("bsf", 2.0, "not one of"),
        ("bpfo", float("nan"), "finite"),
    ],
)
def test_bad_orders_are_one_line_errors(line, order, match):
    with pytest.raises(ConfigError, match=match) as e:
        contact_angle_from_order(B, line, order)
    assert "\n" not in str(e.value)


def _record(alpha_deg: float, shaft_hz: float, fs: float = 12000.0, seconds: float = 8.0):
    """Outer-race impacts (BPFO of a bearing at ``alpha_deg``) ringing at 3 kHz, shaft
    harmonics 1-6 and white noise."""
    rng = np.random.default_rng(3)
    n = int(fs * seconds)
    t = np.arange(n) / fs
    bpfo = characteristic_frequencies(
        replace(B, contact_angle=math.radians(alpha_deg)), shaft_hz
    ).bpfo_hz
    x = 0.05 * rng.standard_normal(n)
    for k in range(1, 7):
        x += 0.2 / k * np.sin(2 * np.pi * k * shaft_hz * t + k)
    ring = np.exp(-600.0 * t[:200]) * np.sin(2 * np.pi * 3000.0 * t[:200])
    for t0 in np.arange(0.0, seconds - 0.02, 1.0 / bpfo):
        i = int(round(t0 * fs))
        x[i : i + 200] += ring[: n - i]
    return x, fs


@pytest.mark.parametrize("alpha_deg", [0.0, 6.0, 12.0, 20.0])
def test_estimate_recovers_a_known_angle_with_a_wrong_stored_speed(alpha_deg):
    """A synthetic outer-race record of a bearing at a known contact angle, analysed with a
    stored speed 0.3 % off: the shaft speed comes from the record (within 0.02 %) and the
    angle within 1 deg (0 within 2.5 deg: near alpha = 0 the order moves with alpha^2)."""
    x, fs = _record(alpha_deg, 29.2)
    est = estimate_contact_angle(x, fs, B, "outer", 29.2 * 1.003)
    assert est.shaft_hz == pytest.approx(29.2, rel=2e-4)
    assert est.shaft_lines >= 4
    assert est.contact_angle_deg == pytest.approx(alpha_deg, abs=2.5 if alpha_deg == 0 else 1.0)
    assert est.as_dict()["contact_angle_deg"] == est.contact_angle_deg


def test_no_shaft_line_is_a_one_line_error():
    x = np.random.default_rng(0).standard_normal(48000)
    with pytest.raises(ConfigError, match="shaft speed cannot be measured") as e:
        measured_shaft_hz(x, 12000.0, 29.0)
    assert "\n" not in str(e.value)
    with pytest.raises(ConfigError, match="family"):
        estimate_contact_angle(x, 12000.0, B, "ball", 29.0)


def test_one_shaft_line_does_not_set_the_speed():
    """One line near a shaft harmonic (another source's, or a lone 1x) is not a shaft speed:
    at least 3 of the 6 harmonics must stand out (the CWRU records that have one show 5-6,
    docs/validation.md); with three they do."""
    fs, n = 12000.0, 48000
    t = np.arange(n) / fs
    noise = 1e-3 * np.random.default_rng(1).standard_normal(n)
    one = noise + np.sin(2 * np.pi * 29.05 * t)
    with pytest.raises(ConfigError, match=r"1 shaft harmonic\(s\) .* fewer than 3"):
        measured_shaft_hz(one, fs, 29.0)
    three = noise + sum(np.sin(2 * np.pi * k * 29.05 * t) for k in (1, 2, 3))
    f, k = measured_shaft_hz(three, fs, 29.0)
    assert k == 3 and f == pytest.approx(29.05, rel=1e-4)


def test_a_small_axial_load_loads_every_ball():
    """Why an outer-race defect at 3 or 12 o'clock can be struck (docs/validation.md, "Contact
    angle of the CWRU bearings"): with the catalogue clearance (6 um) and the seed's 50 N radial
    load 3 of the 6205's 9 balls carry load; 10 N of axial load, which also gives the balls a
    contact angle, loads all nine (Jones model, seed QS5)."""
    from bearingsim.quasistatic.jones import run_quasi_static

    q0 = np.asarray(run_quasi_static(B, 0.0, fy=50.0, fz=0.0).ball_loads)
    sol = run_quasi_static(B, 0.0, fy=50.0, fz=10.0)
    q10 = np.asarray(sol.ball_loads)
    assert int((q0 > 1e-6).sum()) == 3
    assert int((q10 > 1.0).sum()) == 9
    assert np.degrees(np.asarray(sol.contact_angles)).max() > 8.0


@pytest.mark.parametrize("alpha_deg", [0.0, 18.0])
def test_the_line_search_follows_the_contact_angle(alpha_deg):
    """The diagnosis searches BPFO from its alpha = 0 position up to its position at
    DiagnosisRule.contact_angle_max_deg (20 deg) widened by 1 %: an outer-race series of a
    bearing at 18 deg (BPFO 1.3 % above the alpha = 0 line, outside the former ±1 %) is found
    at its true position; with the former symmetric window (contact_angle_max_deg = 0) the
    fundamental is not found there. At alpha = 0 both find it."""
    from bearingsim.signal import DiagnosisRule, diagnose

    x, fs = _record(alpha_deg, 29.2)
    true = characteristic_frequencies(replace(B, contact_angle=math.radians(alpha_deg)), 29.2)
    for rule, found in (
        (DiagnosisRule(), True),
        (DiagnosisRule(contact_angle_max_deg=0.0), alpha_deg == 0.0),
    ):
        d = diagnose(x, fs, B, 29.2, band=(2000.0, 4500.0), rule=rule)
        p = next(q for q in d.peaks if q.label == "BPFO")
        at_true = abs(p.freq_hz - true.bpfo_hz) <= 2 * d.spectrum.bin_width
        assert (p.detected and at_true) is found, (rule, p)
        if found:
            assert d.diagnosis == "outer"


def test_one_mounting_reads_one_angle():
    """The 0.014 in drive-end outer-race bearing (records 197-199, loads 0-2 hp): the same
    contact angle within 0.5 deg from each record (13.8 deg, docs/validation.md), read from a
    BPFO harmonic whose window holds no BPFI harmonic (on the 6205 3xBPFO and 2xBPFI lie 0.7 %
    apart: reading 3xBPFO gave 7.5 deg on two of them). The inner-race line these records also
    show lies at Z f_r - BPFO, i.e. at the same angle."""
    from bearingsim.io.cwru import cwru_data_dir
    from bearingsim.signal import load_signal

    names = [f"12k_Drive_End_OR014@6_{k}_{n}.mat" for k, n in ((0, 197), (1, 198), (2, 199))]
    paths = [cwru_data_dir() / n for n in names]
    if not all(p.is_file() for p in paths):
        pytest.skip("CWRU records 197-199 are not in shared/data")
    out, inn = [], []
    for p in paths:
        r = load_signal(p)
        e = estimate_contact_angle(r.x, r.fs, B, "outer", r.rpm / 60)
        assert e.harmonic in (1, 2)
        out.append(e.contact_angle_deg)
        inn.append(estimate_contact_angle(r.x, r.fs, B, "inner", r.rpm / 60).contact_angle_deg)
    assert max(out) - min(out) < 0.5 and 12.0 < min(out) < 15.0
    assert max(abs(a - b) for a, b in zip(out, inn, strict=True)) < 0.5


def test_the_slip_resolution_is_three_standard_deviations_of_the_wander():
    # module docstring step 4: the rate over N passes wanders by slip sqrt(1.2 / N) (the
    # least-squares slope of a Brownian phase); the resolution is the angle 3 of them read
    from bearingsim.signal.contact_angle import slip_resolution

    b = resolve_bearing("6205-cwru", None)
    k0 = characteristic_frequencies(replace(b, contact_angle=0.0), 1.0)
    for fam, line, o0, sign in (
        ("outer", "bpfo", k0.bpfo_hz, 1),
        ("inner", "bpfi", k0.bpfi_hz, -1),
    ):
        res = [slip_resolution(b, fam, n) for n in (100, 1000, 10000)]
        assert res[0] > res[1] > res[2] > 0.0  # finer with more passes
        rel = 3 * 0.015 * math.sqrt(1.2 / 1000)
        assert res[1] == pytest.approx(contact_angle_from_order(b, line, o0 * (1 + sign * rel)))
    assert slip_resolution(b, "outer", 1e-3) == pytest.approx(math.pi / 2)  # tells no angle
    with pytest.raises(ConfigError, match="n_passes"):
        slip_resolution(b, "outer", 0.0)


def test_simulations_at_alpha_zero_with_slip_read_below_the_resolution():
    # twenty-first session: with 1.5 % random slip, simulations at alpha = 0 read 0-6.2 deg on
    # 1 s (the twentieth session's "below ~3 deg" caveat was measured with slip that lowered
    # the pass rate by slip^2); every one must lie below the resolution the estimate gives
    from bearingsim import simulate

    b = resolve_bearing("6205-cwru", None)
    for seed in range(6):
        for fam in ("outer", "inner"):
            r = simulate(dict(model="vsm", fault=fam, bearing="6205-cwru", rig="cwru-de-12k",
                              duration_s=1.0, seed=seed, rpm=1750.0))  # fmt: skip
            e = estimate_contact_angle(
                r.channels["acc_sensor"], r.fs_hz, b, fam, 1750 / 60, measure_shaft=False
            )
            assert 9.0 < e.resolution_deg < 13.0, e.resolution_deg  # 11.2 (outer), 12.4
            assert e.contact_angle_deg < e.resolution_deg, (seed, fam, e.contact_angle_deg)
