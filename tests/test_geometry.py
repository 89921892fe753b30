"""Catalogue, geometry validation and kinematic frequencies (SPEC §0.1–0.2)."""

from __future__ import annotations

import math

import numpy as np
import pytest
from numpy.testing import assert_allclose

from bearingsim import BallBearing, ConfigError, characteristic_frequencies, get_bearing
from bearingsim.catalog import bearing_from_dict, list_bearings, load_bearing_file
from bearingsim.report.published import value


def test_catalogue_has_required_entries_with_sources():
    ids = {b.id for b in list_bearings()}
    assert {"6205", "6205-cwru", "6203-cwru", "6206", "NU204-ECP"} <= ids
    for b in list_bearings():
        assert b.source.strip(), f"catalogue entry {b.id} names no source"


@pytest.mark.parametrize(
    "bid, z, d_mm, D_mm",
    [
        ("6205", 9, 7.94, 39.0),  # seed VSM table 1
        ("6205-cwru", 9, 7.94, 39.04),  # CWRU bearing table (0.3126 in, 1.537 in)
        ("6203-cwru", 8, 6.746, 28.499),  # CWRU bearing table (0.2656 in, 1.122 in)
        ("6206", 9, 9.525, 46.005),  # seed LIFE table 1
        ("NU204-ECP", 11, 7.94, 34.0),  # seed IAS table 1
    ],
)
def test_catalogue_values(bid, z, d_mm, D_mm):
    b = get_bearing(bid)
    assert b.n_elements == z
    assert_allclose(b.element_diameter * 1e3, d_mm, rtol=2e-4, err_msg=f"{bid} d vs SPEC §0.1")
    assert_allclose(b.pitch_diameter * 1e3, D_mm, rtol=2e-4, err_msg=f"{bid} D vs SPEC §0.1")


def test_seed_raceway_radii():
    b = get_bearing("6205")
    assert_allclose(b.inner_raceway_radius, 15.53e-3, rtol=1e-9, err_msg="r_i vs seed VSM table 1")
    assert_allclose(b.outer_raceway_radius, 23.47e-3, rtol=1e-9, err_msg="r_o vs seed VSM table 1")
    b = get_bearing("6206")
    assert_allclose(b.inner_raceway_radius, 18.24e-3, rtol=1e-4, err_msg="vs seed LIFE table 1")
    assert_allclose(b.outer_raceway_radius, 27.765e-3, rtol=1e-4, err_msg="vs seed LIFE table 1")


@pytest.mark.parametrize(
    "rpm, key, published, source",
    [
        (1748, "bpfi_hz", value("vsm.eq20.bpfi_6205_1748rpm"), "seed VSM eq (20), 1748 r/min"),
        (1796, "bpfo_hz", value("vsm.eq21.bpfo_6205_1796rpm"), "seed VSM eq (21), 1796 r/min"),
    ],
)
def test_seed_vsm_fault_frequencies(rpm, key, published, source):
    k = characteristic_frequencies(get_bearing("6205"), rpm / 60).as_dict()
    assert_allclose(k[key], published, rtol=1e-3, err_msg=f"{key} vs {source}")


#: CWRU bearing-table defect orders (BPFI, BPFO, FTF, 2xBSF) of each end
CWRU_ORDERS = {
    end: [value(f"cwru.{end}.{k}_order") for k in ("bpfi", "bpfo", "ftf", "2xbsf")]
    for end in ("drive_end", "fan_end")
}


@pytest.mark.parametrize(
    "bid, bpfi, bpfo, ftf, two_bsf",
    [
        ("6205-cwru", *CWRU_ORDERS["drive_end"]),  # CWRU drive-end defect orders
        ("6203-cwru", *CWRU_ORDERS["fan_end"]),  # CWRU fan-end defect orders
    ],
)
def test_cwru_defect_orders(bid, bpfi, bpfo, ftf, two_bsf):
    k = characteristic_frequencies(get_bearing(bid), 1.0)
    got = [k.bpfi_order, k.bpfo_order, k.ftf_order, 2 * k.bsf_order]
    assert_allclose(
        got, [bpfi, bpfo, ftf, two_bsf], rtol=1e-3, err_msg=f"{bid} orders vs CWRU bearing table"
    )


def test_nu204_bpfo_order():
    k = characteristic_frequencies(get_bearing("NU204-ECP"), 1.0)
    assert_allclose(
        k.bpfo_order,
        value("ias.eq36.bpfo_order"),
        rtol=2e-3,
        err_msg="NU204 BPFO order vs seed IAS eq (36)",
    )


def test_frequency_identities():
    """BPFO + BPFI = Z f_s and FTF = BPFO / Z for any geometry (definitions, SPEC §0.2)."""
    for b in list_bearings():
        k = characteristic_frequencies(b, 25.0)
        assert_allclose(k.bpfo_hz + k.bpfi_hz, b.n_elements * 25.0, rtol=1e-12)
        assert_allclose(k.ftf_hz * b.n_elements, k.bpfo_hz, rtol=1e-12)
        assert_allclose(k.bpfo_order * 25.0, k.bpfo_hz, rtol=1e-12)


GOOD = dict(
    id="user-1",
    type="ball",
    n_elements=9,
    element_diameter_m=7.94e-3,
    pitch_diameter_m=39e-3,
    contact_angle_rad=0.0,
    diametral_clearance_m=6e-6,
    inner_groove_radius_m=4.089e-3,
    outer_groove_radius_m=4.169e-3,
    youngs_modulus_pa=207e9,
    poisson_ratio=0.3,
)


def test_user_file_roundtrip(tmp_path):
    p = tmp_path / "b.toml"
    lines = [f"{k} = {v!r}" if isinstance(v, str) else f"{k} = {v}" for k, v in GOOD.items()]
    p.write_text("\n".join(lines).replace("'", '"'))
    b = load_bearing_file(p)
    assert isinstance(b, BallBearing)
    assert b.id == "user-1"
    assert_allclose(b.inner_conformity, 4.089 / 7.94, rtol=1e-12)


@pytest.mark.parametrize(
    "change, field",
    [
        ({"element_diameter_m": -1e-3}, "element_diameter_m"),
        ({"element_diameter_m": 0.0}, "element_diameter_m"),
        ({"pitch_diameter_m": 5e-3}, "element_diameter_m"),  # d >= D
        ({"n_elements": 2}, "n_elements"),
        ({"n_elements": 9.5}, "n_elements"),
        ({"inner_groove_radius_m": 3.9e-3}, "inner_groove_radius_m"),  # conformity < 0.5
        ({"outer_groove_radius_m": 3.97e-3}, "outer_groove_radius_m"),  # conformity = 0.5
        ({"youngs_modulus_pa": float("nan")}, "youngs_modulus_pa"),
        ({"poisson_ratio": 0.6}, "poisson_ratio"),
        ({"colour": "red"}, "colour"),
        ({"type": "tapered"}, "type"),
        ({"n_elements": 40}, "element_diameter_m"),  # balls overlap
    ],
)
def test_bad_bearing_data(change, field):
    with pytest.raises(ConfigError) as ei:
        bearing_from_dict({**GOOD, **change}, "user.toml")
    msg = str(ei.value)
    assert field in msg and "\n" not in msg


def test_missing_key():
    d = dict(GOOD)
    d.pop("outer_groove_radius_m")
    with pytest.raises(ConfigError, match="outer_groove_radius_m"):
        bearing_from_dict(d)


def test_unknown_id():
    with pytest.raises(ConfigError, match="not in the catalogue"):
        get_bearing("6299")


def test_bad_speed():
    for bad in (0.0, -1.0, math.inf, np.nan):
        with pytest.raises(ConfigError, match="shaft_hz"):
            characteristic_frequencies(get_bearing("6205"), bad)
