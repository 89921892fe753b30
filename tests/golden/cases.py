"""Golden-regression cases: one small case per model family (seconds each), its inputs and key
outputs (summary statistics and a few samples, not whole arrays).

``tests/golden/<model>.json`` holds what the current code gave; ``tests/test_golden.py``
compares a fresh run with it. Regenerate after an intended change of results with
``python -m tests.golden.regenerate [--model M]`` and say why in the commit.

Tolerance: the cases are deterministic (fixed inputs, no random numbers, no fastmath), so a
rerun on the same machine is bit-identical. ``rtol`` allows for the compiler and library
rounding of another machine (BLAS, LAPACK, MINPACK, libm, LLVM): each case's ``why`` gives the
measured response of its outputs to a one-ulp change of every float input (``python -m
tests.golden.regenerate --sensitivity``) and ``rtol`` sits well above it (50 x for the rotor,
whose start from a static equilibrium solved to a tolerance makes it the sensitive case;
1e4 x or more for the others). ``atol`` is ``atol_rel`` times the largest magnitude of each
output, for entries that are zero or nearly so.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

import numpy as np

#: command that rewrites the golden files (written into every file)
REGENERATE = "python -m tests.golden.regenerate"

Outputs = dict[str, float | list[float]]


@dataclass(frozen=True)
class Case:
    """One golden case: ``run(inputs)`` gives the outputs, compared with ``rtol``/``atol_rel``
    (``looser``: other ``(rtol, atol_rel, why)`` for the outputs whose name starts with a key)."""

    description: str
    inputs: dict[str, Any]
    run: Callable[[dict[str, Any]], Outputs]
    rtol: float
    atol_rel: float
    why: str
    looser: dict[str, tuple[float, float, str]] = field(default_factory=dict)

    def tolerance(self, output: str) -> tuple[float, float]:
        """``(rtol, atol_rel)`` of the output named ``output``."""
        for prefix, (rtol, atol_rel, _why) in self.looser.items():
            if output.startswith(prefix):
                return rtol, atol_rel
        return self.rtol, self.atol_rel

    def tolerance_record(self) -> dict[str, Any]:
        """The tolerances as written into the golden file."""
        rec: dict[str, Any] = {"rtol": self.rtol, "atol_rel": self.atol_rel, "why": self.why}
        for prefix, (rtol, atol_rel, why) in self.looser.items():
            rec[f"outputs {prefix}*"] = {"rtol": rtol, "atol_rel": atol_rel, "why": why}
        return rec


def _floats(x) -> float | list[float]:
    a = np.asarray(x, dtype=float)
    return float(a) if a.ndim == 0 else [float(v) for v in a.ravel()]


def _summary(name: str, x, n_samples: int = 8) -> Outputs:
    """Mean, standard deviation, min, max and ``n_samples`` evenly spaced samples of ``x``."""
    x = np.asarray(x, dtype=float).ravel()
    idx = np.linspace(0, x.size - 1, n_samples).round().astype(int)
    return {
        f"{name}.mean": float(x.mean()),
        f"{name}.std": float(x.std()),
        f"{name}.min": float(x.min()),
        f"{name}.max": float(x.max()),
        f"{name}.samples": _floats(x[idx]),
    }


# ------------------------------------------------------------------ Hertz / load distribution


def _hertz(inp: dict[str, Any]) -> Outputs:
    from bearingsim.catalog import get_bearing
    from bearingsim.contact.hertz import (
        ball_contact,
        ball_stiffness,
        line_subsurface_stresses,
        roller_contact,
        subsurface_stresses,
    )
    from bearingsim.geometry import Race, characteristic_frequencies
    from bearingsim.load_distribution import radial_load_distribution, stribeck_qmax

    out: Outputs = {}
    b6206 = get_bearing(inp["contact_bearing"])
    q = stribeck_qmax(b6206, inp["contact_radial_load_n"])
    out["stribeck_qmax_n"] = float(q)
    for race in (Race.INNER, Race.OUTER):
        c = ball_contact(b6206, q, race)
        for k in ("p_max", "a", "b", "delta", "k_hertz"):
            out[f"{race.value}.{k}"] = _floats(getattr(c, k))
        if race is Race.INNER:
            s = subsurface_stresses(c, inp["poisson"])
            for k in ("tau_max", "tau_max_depth", "tau_orth", "tau_orth_depth"):
                out[f"inner.{k}"] = _floats(getattr(s, k))
    b = get_bearing(inp["distribution_bearing"])
    out["ball_stiffness"] = float(ball_stiffness(b))
    ld = radial_load_distribution(b, inp["fx_n"], inp["fy_n"], np.radians(inp["cage_angles_deg"]))
    out["fr"] = float(ld.fr)
    out["theta0"] = float(ld.theta0)
    out["psi_l"] = _floats(ld.psi_l)
    out["delta_max"] = _floats(ld.delta_max)
    out["ball_loads"] = _floats(ld.ball_loads)
    out["n_loaded"] = _floats(ld.n_loaded)
    nu = get_bearing(inp["roller_bearing"])
    rc = roller_contact(nu, inp["roller_load_n"], Race.INNER)
    for k in ("p_max", "b", "delta"):
        out[f"roller_inner.{k}"] = _floats(getattr(rc, k))
    ls = line_subsurface_stresses(rc, inp["poisson"])
    out["roller_inner.tau_max"] = _floats(ls.tau_max)
    kin = characteristic_frequencies(b, inp["rpm"] / 60)
    for k in ("bpfi_hz", "bpfo_hz", "ftf_hz", "bsf_hz"):
        out[f"kinematics.{k}"] = float(getattr(kin, k))
    return out


# ---------------------------------------------------------------------- ring VSM / DEM / TVSM


def _ring(inp: dict[str, Any]) -> Outputs:
    from bearingsim.catalog import get_bearing
    from bearingsim.config import Scenario
    from bearingsim.dynamics.ring.base import ModelInputs
    from bearingsim.dynamics.ring.trace import stiffness_trace
    from bearingsim.geometry import defect_at_edge
    from bearingsim.simulation import simulate

    out: Outputs = {}
    for run in inp["runs"]:
        r = simulate(Scenario(**run, duration_s=inp["duration_s"]))
        tag = f"{run['model']}_{run['fault']}"
        for ch in ("disp_y", "acc_y"):
            out |= _summary(f"{tag}.{ch}", r[ch])
    tr_in = inp["trace"]
    b = get_bearing(tr_in["bearing"])
    d = defect_at_edge(
        b,
        tr_in["fault"],
        tr_in["defect_width_m"],
        tr_in["defect_depth_m"],
        math.radians(tr_in["defect_angle_deg"]),
    )
    mi = ModelInputs(
        b, tr_in["fx_n"], tr_in["fy_n"], tr_in["rpm"] / 60, d, retention_factor=tr_in["gamma"]
    )
    cage = np.radians(np.linspace(*tr_in["cage_deg"]))
    tr = stiffness_trace(mi, cage)
    out |= _summary("trace.k_load", tr.k_load)
    out["trace.n_loaded"] = _floats(tr.n_loaded[:: max(1, cage.size // 8)])
    out["trace.event_angles_deg"] = [float(a) for a, _b, _k in tr.events()]
    return out


# ----------------------------------------------------------------------------------- rotor


def _rotor(inp: dict[str, Any]) -> Outputs:
    from bearingsim.dynamics.rotor.config import cwru_rotor_config
    from bearingsim.dynamics.rotor.model import rotor_modes, simulate_rotor
    from bearingsim.geometry import Defect

    out: Outputs = {}
    modes = rotor_modes(cwru_rotor_config(inp["modes_disks"]), n_modes=inp["n_modes"])
    out["modes_hz"] = _floats(modes.frequency_hz)
    cfg = cwru_rotor_config(
        inp["disks"], de_fault=Defect(inp["de_fault"]), speed_rpm=inp["speed_rpm"]
    )
    r = simulate_rotor(cfg, duration=inp["duration_s"], sample_rate=inp["sample_rate_hz"])
    out["DE.bpfo_hz"] = float(r.kinematics["DE"].bpfo_hz)
    for end in ("DE", "FE"):
        out |= _summary(f"run.{end}.acc_y", r.channel(end, "y"))
    return out


# ------------------------------------------------------------------------------------- IAS


def _ias(inp: dict[str, Any]) -> Outputs:
    from dataclasses import replace

    from bearingsim.catalog import get_bearing
    from bearingsim.dynamics.ias.model import IasParams, simulate_ias

    out: Outputs = {}
    p = IasParams(get_bearing(inp["bearing"]))  # the other parameters: seed IAS §3.1 defaults
    p = replace(
        p,
        fy=inp["fy_n"],
        torque=inp["torque_nm"],
        spall=replace(p.spall, width=inp["spall_width_m"]),
    )
    r = simulate_ias(p, inp["duration_s"], inp["dt_s"], inp["output_rate_hz"])
    k = r.constants
    for name in ("k_total", "cage_ratio", "bpfo_order", "q_max", "free_speed"):
        out[f"constants.{name}"] = float(getattr(k, name))
    out |= _summary("omega", r.omega, 12)
    out |= _summary("x", r.state[:, 0])
    out |= _summary("y", r.state[:, 1])
    out["spall_force.max"] = float(r.spall_force.max())
    out["impact_force.max"] = float(r.impact_force.max())
    return out


# ---------------------------------------------------------------------------- QS5 (5-DOF)


def _qs5(inp: dict[str, Any]) -> Outputs:
    from bearingsim.catalog import get_bearing
    from bearingsim.quasistatic.iso16281 import run_iso16281
    from bearingsim.quasistatic.jones import Misalignment, run_quasi_static
    from bearingsim.quasistatic.stiffness import stiffness_vs_cage

    out: Outputs = {}
    b = get_bearing(inp["bearing"])
    errors = np.zeros(b.n_elements)
    for j, e in inp["ball_errors_rad"].items():
        errors[int(j)] = e
    s = stiffness_vs_cage(
        b,
        fy=inp["fy_n"],
        cage_revs=inp["cage_revs"],
        points_per_rev=inp["points_per_rev"],
        misalignment=Misalignment(outer_tilt=inp["outer_tilt_rad"]),
        ball_errors=errors,
    )
    for name in ("k_radial", "k_axial", "k_tilt"):
        out |= _summary(name, getattr(s, name))
    cage = np.radians(inp["cage_angles_deg"])
    loads = dict(fy=inp["fy_n"], fz=inp["fz_n"])
    j = run_quasi_static(b, cage, **loads)
    out["jones.ball_loads"] = _floats(j.ball_loads)
    out["jones.displacement"] = _floats(j.displacement)
    out["jones.stiffness_diag"] = _floats(np.diagonal(j.stiffness_matrix, axis1=1, axis2=2))
    iso = run_iso16281(b, cage, **loads)
    out["iso16281.ball_loads"] = _floats(iso.ball_loads)
    return out


# ------------------------------------------------------------------------------------ LIFE


def _life(inp: dict[str, Any]) -> Outputs:
    from bearingsim.catalog import get_bearing
    from bearingsim.life.damage import GCR15_TORSION, fit_sn_curve, torsion_check
    from bearingsim.life.fatigue import contact_fatigue_life
    from bearingsim.life.iso281 import basic_rating_life, dynamic_load_rating, static_capacity
    from bearingsim.life.reference_life import reference_rating_life

    out: Outputs = {}
    law = fit_sn_curve(GCR15_TORSION).law
    out["kappa"] = float(law.kappa)
    out["sigma_t"] = float(law.sigma_t)
    out["torsion.cycles_predicted"] = _floats(torsion_check(law).cycles_predicted)
    b = get_bearing(inp["bearing"])
    f = inp["radial_load_n"]
    r = contact_fatigue_life(
        b, f, mesh=inp["mesh"], delta_d=inp["delta_d"], stop=inp["stop"], law=law,
        solver="direct",  # the reference solve; tests/test_block_solver.py checks "pcg"
    )  # fmt: skip
    out["fe.cycles_initiation"] = float(r.cycles_initiation)
    out["fe.steps_initiation"] = float(r.steps_initiation)
    out["fe.initiation_depth"] = float(r.initiation_depth)
    out["fe.initiation_x"] = float(r.initiation_x)
    out |= _summary("fe.damage_max", r.damage_max)
    out["iso281.c_r"] = float(dynamic_load_rating(b).c)
    out["iso281.l10_rev"] = float(basic_rating_life(b, f))
    out["iso76.c0"] = float(static_capacity(b).c0)
    out["iso16281.l10r_rev"] = float(reference_rating_life(b, f).l10r)
    return out


#: measured with ``--sensitivity`` (bearingsim 0.1.0): largest output change, relative to the
#: output's magnitude, when every float input moves by one ulp
_ULP = "a one-ulp change of every float input moves the outputs by at most {s} (relative)"

CASES: dict[str, Case] = {
    "hertz": Case(
        "Hertz point and line contact (6206 seed LIFE case, NU204 roller), subsurface stresses, "
        "discrete radial load distribution (6205 seed VSM case) and kinematics",
        {
            "contact_bearing": "6206",
            "contact_radial_load_n": 5000.0,
            "poisson": 0.3,
            "distribution_bearing": "6205",
            "fx_n": 10.0,
            "fy_n": 50.0,
            "cage_angles_deg": [0.0, 10.0, 20.0],
            "roller_bearing": "NU204-ECP",
            "roller_load_n": 500.0,
            "rpm": 1750.0,
        },
        _hertz,
        rtol=1e-9,
        atol_rel=1e-12,
        why=_ULP.format(s="4e-16") + "; closed forms and converged root finders",
    ),
    "ring": Case(
        "VSM, DEM and TVSM (seed VSM) 20 ms runs with a CWRU-size outer defect, a VSM run with "
        "an inner defect, and the quasi-static VSM stiffness trace over 80 deg of cage angle",
        {
            "duration_s": 0.02,
            "runs": [
                {"model": "vsm", "fault": "outer", "rpm": 1796.0, "defect_width_m": 1.778e-4},
                {"model": "dem", "fault": "outer", "rpm": 1796.0, "defect_width_m": 1.778e-4},
                {"model": "tvsm", "fault": "outer", "rpm": 1796.0, "defect_width_m": 1.778e-4},
                {"model": "vsm", "fault": "inner", "rpm": 1748.0, "defect_width_m": 3.556e-4},
            ],
            "trace": {
                "bearing": "6205",
                "fault": "outer",
                "defect_width_m": 1e-3,
                "defect_depth_m": 1e-3,
                "defect_angle_deg": 10.0,
                "fx_n": 10.0,
                "fy_n": 50.0,
                "rpm": 1750.0,
                "gamma": 0.38,
                "cage_deg": [0.013, 80.013, 1601],
            },
        },
        _ring,
        rtol=1e-7,
        atol_rel=1e-9,
        why=_ULP.format(s="1.4e-12")
        + ", most in the mean acceleration (a cancellation of +/-300 m/s^2); rtol 1e-7 leaves "
        "five orders of magnitude for the rounding of another machine",
    ),
    "rotor": Case(
        "CWRU rotor: pinned rotor-alone modes (3 disks) and a 50 ms run of the bearing-rotor-"
        "housing model (1 disk, drive-end outer-race defect at 6 o'clock, 1750 r/min, 12 kHz)",
        {
            "modes_disks": 3,
            "n_modes": 6,
            "disks": 1,
            "de_fault": "outer",
            "speed_rpm": 1750.0,
            "duration_s": 0.05,
            "sample_rate_hz": 12000.0,
        },
        _rotor,
        rtol=1e-9,
        atol_rel=1e-12,
        why="the modes have no float input: a dense symmetric eigenproblem (LAPACK), exact to "
        "rounding (~1e-14)",
        looser={
            "run.DE.": (
                1e-3,
                1e-2,
                _ULP.format(s="2e-5")
                + "; between two machines (same library versions) the drive-end outputs moved "
                "by up to 3.7e-3 of their largest magnitude: atol 1e-2 of it (cause not found: "
                "a tighter static solve moves the run by 1e-5 only; tests/golden/README.md)",
            ),
            "run.FE.": (
                1e-3,
                1e-1,
                _ULP.format(s="2e-5")
                + "; between two machines (same library versions) the fan-end outputs, whose "
                "balls carry little more than the rotor weight, moved by up to 4.5e-2 of their "
                "largest magnitude: atol 1e-1 of it (tests/golden/README.md)",
            ),
        },
    ),
    "ias": Case(
        "IAS model (seed IAS §3.1 case: NU204-ECP, F_y 400 N, M_z 9.54 N m, 1 mm spall), "
        "0.6 s with RK4 dt 1e-5 s, two spall crossings",
        {
            "bearing": "NU204-ECP",
            "fy_n": 400.0,
            "torque_nm": 9.54,
            "spall_width_m": 1e-3,
            "duration_s": 0.6,
            "dt_s": 1e-5,
            "output_rate_hz": 20000.0,
        },
        _ias,
        rtol=1e-9,
        atol_rel=1e-12,
        why=_ULP.format(s="6e-14") + " (RK4 with a fixed step, two spall crossings)",
    ),
    "qs5": Case(
        "Jones 5-DOF quasi-static model (seed QS5): stiffness over one cage revolution with outer "
        "misalignment and ball-distribution errors; radial + axial equilibrium by Jones and by "
        "ISO/TS 16281",
        {
            "bearing": "6205",
            "fy_n": 500.0,
            "fz_n": 200.0,
            "outer_tilt_rad": 3e-3,
            "ball_errors_rad": {"0": 0.05, "4": -0.03},
            "cage_revs": 1,
            "points_per_rev": 36,
            "cage_angles_deg": [0.0, 11.0, 25.0],
        },
        _qs5,
        rtol=1e-9,
        atol_rel=1e-12,
        why=_ULP.format(s="3.4e-14") + "; Newton solutions converged to 1e-12",
    ),
    "life": Case(
        "GCr15 S-N fit and torsion check (seed LIFE §1), damage-mechanics FE life of the 6206 at "
        "5 kN to initiation (coarse mesh, Delta_D 0.1), ISO 281 / ISO 76 / ISO/TS 16281 ratings",
        {
            "bearing": "6206",
            "radial_load_n": 5000.0,
            "mesh": "coarse",
            "delta_d": 0.1,
            "stop": "initiation",
        },
        _life,
        rtol=1e-9,
        atol_rel=1e-12,
        why=_ULP.format(s="5.3e-16") + "; direct (sparse LU) FE solves",
    ),
}

__all__ = ["CASES", "REGENERATE", "Case"]
