"""The ring models' round pit (``defect_profile = "pit"``): a pit narrower than the ball's
contact ellipse takes only part of the contact's load (:mod:`bearingsim.dynamics.defect_pit`).

Reference values: the Hertz pressure ``p0 sqrt(1 - x^2/b^2 - y^2/a^2)`` of an elliptical contact
(Johnson 1985, *Contact Mechanics*, eq. (4.32); Harris & Kotzalas 2007, ch. 6), integrated here
by brute force over the pit's disc with NumPy, and the Hertz semi-axes of
:func:`bearingsim.contact.hertz.ball_contact` (Hamrock & Brewe 1983).
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from bearingsim import simulate
from bearingsim.catalog import get_bearing
from bearingsim.contact.hertz import ball_contact, ball_stiffness
from bearingsim.dynamics.defect_pit import (
    pit_contact,
    pit_lost_share,
    pit_share,
    strip_share,
)
from bearingsim.dynamics.ring.base import ModelInputs
from bearingsim.errors import ConfigError
from bearingsim.geometry import Defect, Race

B = get_bearing("6205-cwru")
INCH = 0.0254


def _brute_share(xc, rh, a, b, n=1601):
    """Share of the Hertz load on the disc of radius ``rh`` centred ``xc`` along the track from
    the contact's centre: the pressure summed on an n x n grid over the ellipse."""
    x = np.linspace(-b, b, n)
    y = np.linspace(-a, a, n)
    X, Y = np.meshgrid(x, y, indexing="ij")
    p = np.sqrt(np.clip(1.0 - (X / b) ** 2 - (Y / a) ** 2, 0.0, None))
    on = (X - xc) ** 2 + Y**2 < rh * rh
    return float(p[on].sum() / p.sum())


def test_strip_share_is_the_hertz_line_load_across_the_track():
    """A strip |y| < t a of the ellipse carries 1.5 t - 0.5 t^3 of the load."""
    a, b = 1.0, 0.15
    x = np.linspace(-b, b, 1201)
    y = np.linspace(-a, a, 1201)
    X, Y = np.meshgrid(x, y, indexing="ij")
    p = np.sqrt(np.clip(1.0 - (X / b) ** 2 - (Y / a) ** 2, 0.0, None))
    for t in (0.1, 0.3, 0.6, 0.9):
        assert strip_share(t) == pytest.approx(p[np.abs(Y) < t * a].sum() / p.sum(), abs=2e-3)
    assert strip_share(1.0) == 1.0 and strip_share(3.0) == 1.0


@pytest.mark.parametrize(
    ("xc", "rh", "a", "b"),
    [
        (0.0, 0.089, 0.341, 0.054),  # 0.007 in under a 25 N outer-race contact, centred
        (0.06, 0.089, 0.341, 0.054),  # ... entering
        (0.12, 0.089, 0.341, 0.054),  # ... the contact's edge over the pit's rim
        (0.0, 0.178, 0.341, 0.054),  # 0.014 in
        (0.0, 0.178, 0.541, 0.2),  # a long contact
        (0.1, 0.3, 0.25, 0.05),  # the pit wider than the contact
        (0.0, 0.005, 0.34, 0.054),  # a 10 um pit under a 25 N contact
        (0.03, 0.005, 0.34, 0.054),  # ... off its centre
    ],
)
def test_pit_share_is_the_hertz_pressure_on_the_pit(xc, rh, a, b):
    """The 12-point quadrature against the pressure summed over the disc (within 0.01)."""
    assert pit_lost_share(xc, rh, a, b) == pytest.approx(_brute_share(xc, rh, a, b), abs=0.01)
    assert pit_lost_share(-xc, rh, a, b) == pit_lost_share(xc, rh, a, b)


def test_pit_share_limits():
    # off the pit, and a contact of no length (the strip at its centre)
    assert pit_lost_share(0.2, 0.089, 0.3, 0.1) == 0.0
    assert pit_lost_share(0.0, 0.089, 0.3, 0.0) == pytest.approx(strip_share(0.089 / 0.3))
    # one contact: rho = g; a contact not under load carries nothing
    a2, b2 = 0.06, 0.0015
    d = 2e-6
    f = pit_lost_share(0.0, 1e-4, math.sqrt(a2 * d), math.sqrt(b2 * d))
    assert pit_share(d, 0.0, 1e-4, a2, b2, 1.0, 1.5, False)[0] == pytest.approx(1.0 - f)
    # no approach (a rough contact's asperities): nothing over the pit, all beside it
    assert pit_share(0.0, 0.0, 1e-4, a2, b2, 0.5, 1.5, True) == (0.0, 0.0)
    assert pit_share(-1e-8, 3e-4, 1e-4, a2, b2, 0.5, 1.5, True) == (1.0, 0.0)
    assert pit_share(1e-12, 3e-4, 1e-4, a2, b2, 0.5, 1.5, False)[0] == 1.0
    # two contacts in series: the constant K rho is the series of g k_p and k_q
    w, g = 0.52, 1.0 - f
    kp, kq = 1.0, (1.0 / w - 1.0) ** -1.5  # k^(-2/3) shares w and 1 - w
    series = (1.0 / (g * kp) ** (2 / 3) + 1.0 / kq ** (2 / 3)) ** -1.5
    intact = (1.0 / kp ** (2 / 3) + 1.0 / kq ** (2 / 3)) ** -1.5
    rho = pit_share(d, 0.0, 1e-4, a2, b2, w, 1.5, False)[0]
    assert rho == pytest.approx(series / intact, rel=1e-12)


def test_pit_share_slope_is_its_derivative():
    a2, b2, w = 0.06, 0.0015, 0.52
    for d in (0.5e-6, 2e-6, 5e-6):
        for xc in (0.0, 5e-5):
            rho, slope = pit_share(d, xc, 8.89e-5, a2, b2, w, 1.5, True)
            h = 1e-3 * d
            up = pit_share(d + h, xc, 8.89e-5, a2, b2, w, 1.5, False)[0]
            dn = pit_share(d - h, xc, 8.89e-5, a2, b2, w, 1.5, False)[0]
            assert slope == pytest.approx((up - dn) / (2 * h), rel=1e-3)
            assert slope > 0.0  # the ball sinks: the contact grows past the pit


@pytest.mark.parametrize("race", [Race.OUTER, Race.INNER])
def test_semi_axes_follow_the_approach_as_hertz(race):
    """a^2 = A d and b^2 = B d give Hertz's semi-axes at the load K d^1.5 of both contacts."""
    K = ball_stiffness(B)
    a2, b2, w, margin = pit_contact(B, race)
    A, Bc = a2 * K ** (2.0 / 3.0), b2 * K ** (2.0 / 3.0)
    for q in (5.0, 50.0, 500.0):
        d = (q / K) ** (2.0 / 3.0)
        c = ball_contact(B, q, race)
        assert math.sqrt(A * d) == pytest.approx(float(c.a), rel=1e-9)
        assert math.sqrt(Bc * d) == pytest.approx(float(c.b), rel=1e-9)
    ko = ball_contact(B, 1.0, race).k_hertz
    assert 0.4 < w < 0.6  # the two contacts of a 6205 share the compliance about equally
    # the window's margin: the contact's length at 4.2 GPa (ISO 76)
    c = ball_contact(B, 1.0, race)
    q42 = (4.2e9 / float(c.p_max)) ** 3
    assert margin == pytest.approx(float(ball_contact(B, q42, race).b), rel=1e-9)
    assert ko > 0


def _run(profile, width_in=0.007, fault="outer", **kw):
    sc = dict(model="vsm", bearing="6205-cwru", fault=fault, rpm=1797.0, duration_s=0.3,
              fs_hz=12000.0, antialias=True, per_ball=True, defect_width_m=width_in * INCH,
              defect_profile=profile)  # fmt: skip
    return simulate({**sc, **kw})


def test_a_pit_unloads_the_ball_less_than_a_slot_of_its_width():
    """0.014 in: the slot's drop (3.3 um at the centre) exceeds the ball's approach at the
    seed's load, so the ball over it carries nothing; the groove beside a pit of that diameter
    still carries it (about half its load, pit_share)."""
    geo, pit = _run("geometric", 0.014), _run("pit", 0.014)
    lg = np.asarray(geo["ball_load"])
    lp = np.asarray(pit["ball_load"])
    heavy = lg.max(axis=0) > 0.8 * lg.max()  # balls that pass through the load zone's middle
    assert heavy.any()
    # the least load of a ball in the load zone's middle: the slot empties it, the pit does not
    top_g = [lg[lg[:, j] > 0, j] for j in np.flatnonzero(heavy)]
    assert min(float(v.min()) for v in top_g) < 0.05 * lg.max()
    loaded = lp[:, heavy]
    assert loaded[loaded > 0.5 * lp.max()].size
    assert float(np.asarray(pit["acc_y"]).std()) < 0.7 * float(np.asarray(geo["acc_y"]).std())


@pytest.mark.parametrize("model", ["vsm", "dem", "tvsm"])
def test_the_level_grows_with_the_pit(model):
    """A tiny pit is nearly the healthy bearing; the response grows with the diameter up to
    0.014 in. The DEM and TVSM then ring their 6 kHz contact mode less as the pit's passage
    lengthens (0.3 s, 1797 r/min: 15.8, 38.7, 31.2 m/s^2 for 0.007, 0.014, 0.021 in), so only
    the quasi-static VSM grows throughout."""
    rms = [
        float(np.asarray(_run("pit", w, model=model, per_ball=False)["acc_y"]).std())
        for w in (0.0005, 0.007, 0.014, 0.021)
    ]
    healthy = float(
        np.asarray(_run("pit", fault="none", model=model, per_ball=False)["acc_y"]).std()
    )
    assert rms[0] < 1.5 * healthy
    assert rms[0] < rms[1] < rms[2]
    assert rms[3] > 100.0 * healthy
    if model == "vsm":
        assert rms[2] < rms[3]


@pytest.mark.parametrize("fault", ["inner", "ball"])
def test_inner_race_and_ball_pits_run(fault):
    r = _run("pit", fault=fault, per_ball=False)
    a = np.asarray(r["acc_y"])
    assert np.all(np.isfinite(a))
    assert a.std() < np.asarray(_run("geometric", fault=fault, per_ball=False)["acc_y"]).std()
    if fault == "inner":
        assert r.meta["static_residual_max"] < 1e-9


def test_pit_is_refused_with_gamma():
    with pytest.raises(ConfigError, match=r"^defect_profile = 'pit' with retention_factor"):
        ModelInputs(B, 10.0, 50.0, 29.0, Defect("outer"), retention_factor=0.4, profile="pit")


@pytest.mark.parametrize("inertia", [True, False])
@pytest.mark.parametrize("fault", ["outer", "inner", "ball"])
def test_rotor_pit(fault, inertia):
    """The rotor model's balls (massive, or quasi-static with the two contacts in series) over
    a pit: a 0.0005 in pit is the healthy bearing to 1 %, the response grows with the pit's
    diameter, and a 0.014 in pit shakes the housing less than the geometric slot of that width
    (0.3 s at 12 kHz; measured 0.25 against 0.34 m/s^2 for the outer race)."""

    def rms(profile, width_in, f=fault):
        sc = dict(model="rotor", de_fault=f, duration_s=0.3, fs_hz=12000.0,
                  defect_width_m=width_in * INCH, ball_inertia=inertia,
                  defect_profile=profile)  # fmt: skip
        return float(np.asarray(simulate(sc)["acc_y"]).std())

    healthy = rms("geometric", 0.007, "none")
    tiny, small, mid, big = (rms("pit", w) for w in (0.0005, 0.007, 0.014, 0.021))
    assert tiny == pytest.approx(healthy, rel=0.01)
    assert healthy < small < mid < big
    assert mid < 0.9 * rms("geometric", 0.014)


# ---- found by exploratory testing of the pit (twenty-second session), one test each


def test_rough_contacts_beside_a_pit_keep_their_load():
    """A rough contact carries load before the surfaces meet (d <= 0); the pit's window took
    it all away, even 0.3 mm off a 10 um pit (found by exploratory testing). The contact's
    size now comes from the load it carries: beside the pit nothing is lost, over it a share."""
    from bearingsim.dynamics.ring import _balance as bl

    mi = ModelInputs(B, 10.0, 50.0, 29.0, Defect("outer", width=1e-5), profile="pit",
                     roughness=1e-6)  # fmt: skip
    p = mi.header()
    clr, _doff, dfac, K, n = bl.constants(p)
    for d in (-2e-6, -1e-8, 1e-6):
        intact = bl.ball_load(clr + d, 0.0, 1.0, clr, 0.0, dfac, K, n, p, True, True)[0]
        assert intact > 0.0
        beside = bl.ball_load_pit(clr + d, 1.0, 1.0, clr, 3e-4, dfac, K, n, p, True, True, True)[0]
        assert beside == intact
        over = bl.ball_load_pit(clr + d, 1.0, 1.0, clr, 0.0, dfac, K, n, p, True, True, True)[0]
        assert 0.0 < over < intact
    # a 10 um pit: its passages add less than 2 % of the 0.007 in pit's RMS to the sensor
    sc = dict(model="vsm", bearing="6205-cwru", rpm=1797.0, duration_s=0.2, fs_hz=12000.0,
              contact_roughness_m=1e-6, fault="outer", defect_profile="pit")  # fmt: skip
    healthy = np.asarray(simulate({**sc, "fault": "none"})["acc_y"])
    tiny = np.asarray(simulate({**sc, "defect_width_m": 1e-5})["acc_y"])
    pit = np.asarray(simulate({**sc, "defect_width_m": 0.007 * INCH})["acc_y"])
    assert (tiny - healthy).std() < 0.02 * pit.std()


def test_a_pit_shallower_than_the_ball_sinks_is_refused():
    """The model holds the ball beside the pit, clear of its bottom: a 1 nm deep pit was
    simulated as a deep one. Refused in one line, ring and rotor."""
    w = 0.014 * INCH
    for sc in (
        dict(model="vsm", fault="outer", defect_width_m=w),
        dict(model="dem", fault="ball", defect_width_m=w),
        dict(model="rotor", de_fault="inner", defect_width_m=w),
    ):
        end = r"de_fault = 'inner' on the DE bearing \(6205-cwru\): " if "de_fault" in sc else ""
        with pytest.raises(ConfigError, match=rf"^{end}defect_depth_m = 1e-09 m is not deeper "
                           r"than a ball sinks into a pit .* valid range \("):  # fmt: skip
            simulate({**sc, "duration_s": 0.01, "defect_profile": "pit", "defect_depth_m": 1e-9})
    # the same depth is a valid (shallow) slot
    simulate(dict(model="vsm", fault="outer", defect_width_m=w, duration_s=0.01,
                  defect_profile="geometric", defect_depth_m=1e-9))  # fmt: skip


def test_vsm_trace_ball_loads_follow_the_pit():
    """The trace's per-ball loads took the rectangle's constant drop for every profile (0 N
    over a 0.014 in pit); they are now the kernels' own, about half the intact load at the
    pit's centre, and the geometric slot's follow its drop."""
    from bearingsim.dynamics.ring.trace import stiffness_trace

    w = 0.014 * INCH
    traces = {}
    for prof in ("rectangular", "geometric", "pit"):
        d = Defect("outer", w, 0.011 * INCH, math.atan2(10.0, 50.0))  # under the load
        mi = ModelInputs(B, 10.0, 50.0, 1797.0 / 60.0, d, profile=prof)
        traces[prof] = stiffness_trace(mi, n_points=2001)
    pit = traces["pit"]
    over = pit.in_defect
    assert over.any()
    q_over = pit.ball_load[over]
    assert q_over.max() > 0.0
    # least load over the pit: about half the heaviest intact ball's (pit_share: 0.47-0.54)
    intact = pit.ball_load[~over].max()
    assert 0.3 * intact < q_over[q_over > 0.1 * intact].min() < 0.8 * intact
    rect = traces["rectangular"]
    assert rect.ball_load[rect.in_defect].min() < 0.5 * q_over[q_over > 0.1 * intact].min()
    # the trace's ball loads balance the ring's load at every point (its own displacements)
    f = np.hypot(*(np.sum(pit.ball_load * t(pit.meta["psi"]), axis=1) for t in (np.sin, np.cos)))
    np.testing.assert_allclose(f, math.hypot(10.0, 50.0), rtol=1e-6)


def test_sweep_plan_refuses_a_profile_with_gamma():
    """The check lived in the model inputs: `sweep plan` passed and one run failed later."""
    from bearingsim.config import RingScenario

    with pytest.raises(ConfigError, match=r"^defect_profile = 'pit' with retention_factor"):
        RingScenario(fault="outer", defect_profile="pit", retention_factor=0.5)
    RingScenario(fault="none", defect_profile="pit", retention_factor=0.5)  # no defect: unused


def test_pit_meta_records_the_pit_not_a_slot():
    r = simulate(
        dict(model="vsm", bearing="6205-cwru", fault="outer", duration_s=0.01, defect_profile="pit")
    )
    geo = r.meta["defect"]
    assert geo["profile"] == "pit" and "h_min_m" not in geo
    assert geo["pit_radius_m"] == pytest.approx(0.5 * 0.007 * INCH)
    # the window: the pit's extent plus the contact's length at 4.2 GPa on each side
    margin = pit_contact(B, Race.OUTER)[3]
    assert geo["window_rad"] * geo["race_radius_m"] == pytest.approx(
        2 * math.asin(0.5 * 0.007 * INCH / geo["race_radius_m"]) * geo["race_radius_m"]
        + 2 * margin,
        rel=1e-9,
    )


def test_pit_under_an_axial_load_and_a_preload():
    """The pit's out-of-line paths take the axial geometry only when there is an axial load
    (a copy once passed it always: a division by zero with rough contacts)."""
    sc = dict(model="dem", bearing="6205-cwru", fault="outer", duration_s=0.1, fs_hz=12000.0,
              defect_profile="pit", contact_roughness_m=1e-7)  # fmt: skip
    plain = np.asarray(simulate(sc)["acc_y"])
    axial = np.asarray(simulate({**sc, "axial_load_n": 200.0})["acc_y"])
    pre = np.asarray(simulate({**sc, "clearance_m": -5e-6})["acc_y"])
    for a in (plain, axial, pre):
        assert np.all(np.isfinite(a)) and a.std() > 0.0
    assert not np.array_equal(plain, axial)


def test_rotor_results_record_their_defects():
    """The rotor's results carried no meta['defect'] (found by exploratory testing): now one
    entry per bearing, as the ring models record theirs, and saved and reloaded with it."""
    r = simulate(dict(model="rotor", de_fault="outer", fe_fault="ball", duration_s=0.01,
                      defect_profile="pit"))  # fmt: skip
    de, fe = r.meta["defect"]["DE"], r.meta["defect"]["FE"]
    assert de["race"] == "outer" and de["profile"] == "pit"
    assert de["pit_radius_m"] == pytest.approx(0.5 * 0.007 * INCH)
    assert fe["race"] == "ball"
    g = simulate(dict(model="rotor", de_fault="inner", duration_s=0.01))
    assert g.meta["defect"]["FE"] == {}
    assert (
        g.meta["defect"]["DE"]["profile"] == "geometric" and g.meta["defect"]["DE"]["h_min_m"] > 0
    )


@pytest.mark.parametrize("profile", ["geometric", "pit"])
@pytest.mark.parametrize("race", ["outer", "ball"])
def test_ring_and_rotor_record_a_defect_with_the_same_keys(profile, race):
    """The ring and rotor results built ``meta["defect"]`` in two places with different keys
    (the ring no race, size or angle, the rotor no surface radius or pit window; left for
    planning, twenty-second session): one function now records both."""
    from bearingsim.dynamics.defect_meta import defect_meta
    from bearingsim.geometry import Defect

    ring = simulate(dict(model="vsm", bearing="6205-cwru", fault=race, duration_s=0.002,
                         defect_profile=profile)).meta["defect"]  # fmt: skip
    rotor = simulate(dict(model="rotor", de_fault=race, duration_s=0.002,
                          defect_profile=profile)).meta["defect"]["DE"]  # fmt: skip
    assert set(ring) == set(rotor)
    common = {"race", "width_m", "depth_m", "angle_rad", "profile", "race_radius_m"}
    assert common <= set(ring)
    assert (ring["race"], ring["profile"], rotor["race"], rotor["profile"]) == (
        race, profile, race, profile,
    )  # fmt: skip
    assert ring["width_m"] == rotor["width_m"] == pytest.approx(0.007 * INCH)
    extra = {"pit_radius_m", "window_rad"} if profile == "pit" else {
        "h_s_m", "h_min_m", "delta_beta_rad", *(["h_min_inner_m"] if race == "ball" else [])
    }  # fmt: skip
    assert set(ring) == common | extra
    d = Defect(race, 0.007 * INCH, 0.011 * INCH, 1.0, profile)
    assert defect_meta(B, d)["angle_rad"] == 1.0 and defect_meta(B, None) == {}


def test_a_rotor_defect_error_names_its_end():
    """The rotor's two bearings differ (6205 DE, 6203 FE), so a defect valid at one end may
    not be at the other; the error did not say which end it was about (exploratory testing,
    twenty-third session)."""
    with pytest.raises(ConfigError) as e:
        simulate(dict(model="rotor", duration_s=0.01, fe_fault="outer", defect_profile="pit",
                      defect_depth_m=8.5e-7))  # fmt: skip
    assert str(e.value).startswith(
        "fe_fault = 'outer' on the FE bearing (6203-cwru): defect_depth_m = 8.5e-07 m is not "
        "deeper than a ball sinks into a pit"
    )
    simulate(dict(model="rotor", duration_s=0.01, de_fault="outer", defect_profile="pit",
                  defect_depth_m=8.5e-7 * 2))  # fmt: skip
