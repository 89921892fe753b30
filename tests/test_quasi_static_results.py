"""Quasi-static family as a result pattern (issue 13): labelled stiffness matrix, netCDF save/load
of QuasiStaticSolution, StiffnessMatrix and StiffnessResult bit for bit, enums, public API."""

from __future__ import annotations

import dataclasses
import importlib

import numpy as np
import pytest

from bearingsim.catalog import get_bearing
from bearingsim.errors import ConfigError
from bearingsim.geometry import Race
from bearingsim.quasistatic import (
    DOF_NAMES,
    Conformities,
    Method,
    Misalignment,
    QuasiStaticSolution,
    SpeedEffects,
    StiffnessMatrix,
    StiffnessResult,
    iso_geometry,
    max_tilt,
    qs_geometry,
    run_iso16281,
    run_quasi_static,
    solve_equilibrium,
    stiffness_vs_cage,
)
from bearingsim.results import Result, load_result

B6205 = get_bearing("6205")
ERRORS = np.zeros(9)
ERRORS[0], ERRORS[4] = 0.05, -0.03
_ARRAYS = (
    "cage_angle",
    "shaft_angle",
    "displacement",
    "reaction",
    "ball_angles",
    "ball_loads",
    "contact_angles",
    "deflections",
    "iterations",
    "residual",
    "applied",
    "free",
    "ball_errors",
)


def _same_array(a, b, what):
    a, b = np.asarray(a), np.asarray(b)
    assert a.dtype == b.dtype and a.shape == b.shape, what
    np.testing.assert_array_equal(a, b, err_msg=what)


def _assert_same_matrix(a: StiffnessMatrix, b: StiffnessMatrix):
    _same_array(a.values, b.values, "stiffness values")
    if a.cage_angle is None:
        assert b.cage_angle is None
    else:
        _same_array(a.cage_angle, b.cage_angle, "stiffness cage angles")
    assert a.meta == b.meta


def _assert_same_solution(a: QuasiStaticSolution, b: QuasiStaticSolution):
    for name in _ARRAYS:
        _same_array(getattr(a, name), getattr(b, name), name)
    _assert_same_matrix(a.stiffness_matrix, b.stiffness_matrix)
    assert a.geometry == b.geometry
    assert a.method is b.method
    assert a.misalignment == b.misalignment
    assert a.speed == b.speed
    assert a.bearing_id == b.bearing_id


# ---------------------------------------------------------------- labelled stiffness matrix


def test_one_position_gives_a_labelled_5x5():
    s = solve_equilibrium(B6205, fy=500.0, fz=100.0, cage_angle=0.2)
    K = s.stiffness_matrix
    assert isinstance(K, StiffnessMatrix) and not K.is_stack
    assert K.values.shape == (5, 5) and K.dofs == DOF_NAMES
    assert K.cage_angle == 0.2
    assert K["y", "y"] == K.values[1, 1] and isinstance(K["y", "y"], float)
    assert K["theta_x", "z"] == K.values[3, 2]
    assert K.unit("x", "x") == "N/m"
    assert K.unit("y", "theta_x") == "N/rad"
    assert K.unit("theta_y", "z") == "N m/m"
    assert K.unit("theta_x", "theta_y") == "N m/rad"
    assert K.units.shape == (5, 5) and K.units[4, 0] == "N m/m"
    np.testing.assert_array_equal(np.asarray(K), K.values)
    assert K.at(0) is K


def test_several_positions_give_a_stack():
    cage = np.radians([0.0, 10.0, 20.0])
    s = run_quasi_static(B6205, cage, fy=500.0)
    K = s.stiffness_matrix
    assert K.is_stack and K.values.shape == (3, 5, 5)
    np.testing.assert_array_equal(K.cage_angle, cage)
    np.testing.assert_array_equal(K["y", "y"], K.values[:, 1, 1])
    one = K.at(1)
    assert not one.is_stack and one.cage_angle == cage[1]
    np.testing.assert_array_equal(one.values, K.values[1])
    # a sequence of one cage angle is still a stack (shape follows the question)
    assert run_quasi_static(B6205, [0.0], fy=500.0).stiffness_matrix.values.shape == (1, 5, 5)
    eq = s.equilibrium(2)["stiffness_matrix"]
    assert isinstance(eq, StiffnessMatrix)
    np.testing.assert_array_equal(eq.values, K.values[2])


def test_stiffness_matrix_dataset_is_labelled():
    K = run_quasi_static(B6205, [0.0, 0.1], fy=500.0).stiffness_matrix
    ds = K.to_dataset()
    assert ds["stiffness"].dims == ("position", "dof", "dof_col")
    assert list(ds["dof"].values) == list(DOF_NAMES)
    assert list(ds["load_unit"].values) == ["N", "N", "N", "N m", "N m"]
    assert ds["stiffness_unit"].sel(dof="z", dof_col="theta_y").item() == "N/rad"
    assert ds["cage_angle"].attrs["units"] == "rad"
    one = K.at(0).to_dataset()
    assert one["stiffness"].dims == ("dof", "dof_col")


@pytest.mark.parametrize(
    ("key", "needle"),
    [(("q", "x"), "dof = 'q' is invalid; valid: x, y, z, theta_x, theta_y"), ("x", "index")],
    ids=["bad-name", "one-name"],
)
def test_stiffness_matrix_bad_index_one_line(key, needle):
    K = solve_equilibrium(B6205, fy=500.0).stiffness_matrix
    with pytest.raises(ConfigError, match=needle) as exc:
        K[key]
    assert "\n" not in str(exc.value)


def test_stiffness_matrix_bad_shape_and_position():
    with pytest.raises(ConfigError, match="shape"):
        StiffnessMatrix(np.zeros((4, 4)))
    K = run_quasi_static(B6205, [0.0, 0.1], fy=500.0).stiffness_matrix
    with pytest.raises(ConfigError, match="index = 2 is out of range"):
        K.at(2)


# --------------------------------------------------------------------------- save / load


@pytest.mark.parametrize(
    "make",
    [
        lambda: solve_equilibrium(B6205, fy=500.0, fz=50.0, mx=1.0),
        lambda: run_quasi_static(
            B6205,
            np.linspace(0, 1, 7),
            fy=500.0,
            misalignment=Misalignment(outer_tilt=3e-3, inner_tilt=1e-3, inner_azimuth=0.4),
            ball_errors=ERRORS,
            first_ball_angle=0.1,
        ),
        lambda: run_quasi_static(
            B6205, [0.0, 0.3], fy=500.0, speed=SpeedEffects(2000.0, True, True)
        ),
        lambda: run_iso16281(B6205, [0.0, 0.2], fy=500.0, fz=100.0, conformities="iso"),
    ],
    ids=["jones-single", "jones-misaligned-stack", "jones-inertia", "iso16281"],
)
def test_solution_save_load_bit_for_bit(make, tmp_path):
    s = make()
    p = s.save(tmp_path / "sol.nc")
    assert p == tmp_path / "sol.nc"
    back = QuasiStaticSolution.load(p)
    _assert_same_solution(s, back)
    _assert_same_solution(s, load_result(p))
    _assert_same_solution(s, Result.load(p))
    ds = s.to_dataset()
    assert ds.attrs["format"] == QuasiStaticSolution.FORMAT
    assert ds["displacement"].attrs["units"] == "m, m, m, rad, rad"
    assert ds["ball_loads"].attrs["units"] == "N"


def test_stiffness_matrix_save_load_bit_for_bit(tmp_path):
    for K in (
        run_quasi_static(B6205, [0.0, 0.1, 0.2], fy=500.0).stiffness_matrix,
        solve_equilibrium(B6205, fy=500.0).stiffness_matrix,
        StiffnessMatrix(np.arange(25.0).reshape(5, 5)),
    ):
        back = StiffnessMatrix.load(K.save(tmp_path / "k.nc"))
        _assert_same_matrix(K, back)
        assert back.is_stack == K.is_stack


def test_stiffness_result_is_netcdf_and_round_trips(tmp_path):
    r = stiffness_vs_cage(
        B6205,
        fy=500.0,
        cage_revs=1,
        points_per_rev=72,
        misalignment=Misalignment(inner_tilt=3e-3),
        ball_errors=ERRORS,
        n_components=7,
    )
    p = r.save(tmp_path / "r.nc")
    assert p.read_bytes()[:8] == b"\x89HDF\r\n\x1a\n", "netCDF-4 (HDF5) file"
    back = StiffnessResult.load(p)
    _assert_same_solution(r.solution, back.solution)
    for name in ("k_radial", "k_axial", "k_tilt", "radial_direction"):
        _same_array(getattr(r, name), getattr(back, name), name)
    assert (back.cage_revs, back.points_per_rev) == (r.cage_revs, r.points_per_rev)
    for name, sp in r.spectra.items():
        b = back.spectra[name]
        for f in ("order_cage", "order_shaft", "amplitude"):
            _same_array(getattr(sp, f), getattr(b, f), f"{name} {f}")
        assert b.components == sp.components and len(b.components) == 7
    assert isinstance(load_result(p), StiffnessResult)
    ds = r.to_dataset()
    assert ds["k_tilt"].attrs["units"] == "N m/rad"
    assert ds["spectrum_radial"].dims == ("order",)


def test_load_refuses_another_result(tmp_path):
    p = solve_equilibrium(B6205, fy=500.0).save(tmp_path / "sol.nc")
    with pytest.raises(ConfigError, match="is not a StiffnessResult file") as exc:
        StiffnessResult.load(p)
    assert "\n" not in str(exc.value)


def test_plots_return_figures():
    import matplotlib.pyplot as plt

    s = run_quasi_static(B6205, [0.0, 0.1], fy=500.0)
    for fig in (
        s.plot_loads(1),
        s.stiffness_matrix.plot_matrix(1),
        s.stiffness_matrix.at(0).plot_matrix(),
    ):
        assert fig.axes
        plt.close(fig)


# --------------------------------------------------------------------------------- enums


def test_conformities_enum():
    g_str, cp_str, _ = iso_geometry(B6205, conformities="iso")
    g_enum, cp_enum, _ = iso_geometry(B6205, conformities=Conformities.ISO)
    assert g_str == g_enum and cp_str == cp_enum
    with pytest.raises(ConfigError, match="conformities = 'ISO' is invalid; valid: bearing, iso"):
        iso_geometry(B6205, conformities="ISO")


def test_race_enum_for_max_tilt():
    g = qs_geometry(B6205)
    assert max_tilt(g, Race.INNER) == max_tilt(g, "inner") != max_tilt(g, Race.OUTER)
    with pytest.raises(ConfigError, match="race = 'ball' is invalid; valid: inner, outer"):
        max_tilt(g, "ball")


def test_method_enum_and_series_names():
    with pytest.raises(ConfigError, match="method = 'harris' is invalid; valid: jones, iso16281"):
        stiffness_vs_cage(B6205, fy=500.0, cage_revs=1, points_per_rev=36, method="harris")
    r = stiffness_vs_cage(B6205, fy=500.0, cage_revs=1, points_per_rev=36, method=Method.JONES)
    with pytest.raises(
        ConfigError, match="series = 'shear' is invalid; valid: radial, axial, tilt"
    ):
        r.series("shear")


# ---------------------------------------------------------------------------- public API


@pytest.mark.parametrize(
    "module",
    [
        "bearingsim.quasistatic",
        "bearingsim.quasistatic.inputs",
        "bearingsim.quasistatic.jones",
        "bearingsim.quasistatic.iso16281",
        "bearingsim.quasistatic.result",
        "bearingsim.quasistatic.stiffness",
    ],
)
def test_star_import_and_all(module):
    mod = importlib.import_module(module)
    ns: dict = {}
    exec(f"from {module} import *", ns)  # noqa: S102 - the point of the test
    assert set(mod.__all__) <= set(ns)
    assert all(not n.startswith("_") for n in mod.__all__)


def test_results_are_frozen_dataclasses_of_the_pattern():
    for cls in (QuasiStaticSolution, StiffnessMatrix, StiffnessResult):
        assert issubclass(cls, Result) and dataclasses.is_dataclass(cls)
        assert cls.FORMAT == f"bearingsim.{cls.__name__}/1"


def test_load_result_finds_the_class_in_a_fresh_process(tmp_path):
    """``load_result`` imports the module of a file's class itself (``results.RESULT_MODULES``):
    a fresh interpreter that imported nothing of the quasi-static family reads both kinds."""
    import subprocess
    import sys
    from pathlib import Path

    a = solve_equilibrium(B6205, fy=500.0).save(tmp_path / "sol.nc")
    b = stiffness_vs_cage(B6205, fy=500.0, cage_revs=1, points_per_rev=36).save(tmp_path / "r.nc")
    code = (
        "import sys\nfrom bearingsim.results import load_result\n"
        "print(type(load_result(sys.argv[1])).__name__, type(load_result(sys.argv[2])).__name__)"
    )
    src = str(Path(__file__).resolve().parents[1] / "src")
    out = subprocess.run(
        [sys.executable, "-c", code, str(a), str(b)],
        capture_output=True,
        text=True,
        env={"PYTHONPATH": src, "PATH": "/usr/bin:/bin"},
        timeout=300,
    )
    assert out.returncode == 0, out.stderr
    assert out.stdout.split() == ["QuasiStaticSolution", "StiffnessResult"]
