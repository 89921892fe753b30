"""Quasi-static VSM stiffness traces vs cage angle (seed VSM §2.2–2.4, figs. 5–12, tables 2–3).

The static balance of seed VSM eq. (16) over the discrete balls (:mod:`._balance`) at a sequence
of cage angles: per-ball contact forces, deformations and secant stiffnesses, the effective
stiffness in the load direction and the load-zone events (a ball entering or leaving the zone
or the defect).

A :class:`StiffnessTrace` follows the result pattern (:class:`~bearingsim.results.Result`):
``save(path)`` writes a self-describing netCDF file (dims ``cage_angle``, ``ball``, ``axis``;
every variable with its ``units``; the inputs and ``meta`` as JSON attributes), ``load`` reads it
back losslessly; ``to_csv`` stays as a plain-text export.

What a trace refuses (one line each, before any output):

- a zero radial load (:func:`check_trace_load`): with ``P_d > 0`` the ring may sit anywhere in
  the clearance; with ``P_d = 0`` every ball touches unloaded and the secant stiffness
  ``K delta^0.5`` of each is 0, so there is nothing to trace; a preload (``P_d < 0``, where zero
  radial load is a valid state: the ring centred, every ball equally loaded) is refused whatever
  the load, the VSM's secant stiffness being measured from the concentric position
  (:meth:`.base.ModelInputs.require_clearance`; model ``dem`` or ``tvsm`` simulate it);
- a ball constant outside :data:`STIFFNESS_RANGE` (``stiffness_n_per_m1_5``), the Hertz constants
  of real point contacts with a decade of margin;
- a static balance that did not converge (:data:`TRACE_RESIDUAL_TOL`): a contact deflection
  ``(|F|/K)^(2/3)`` below what the ring position resolves in floating point (a large ``K`` under
  a small load) left the relative force residual at 1e-2..0.4 where it is ~1e-12.
"""

from __future__ import annotations

import dataclasses
import json
import math
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, ClassVar

import numpy as np
from numpy.typing import NDArray

from ...contact.capacity import check_load
from ...contact.rough import rough_mean_power
from ...errors import ConfigError, SolverError, check_range
from ...geometry import BallBearing, DefectProfile, Race, check_clearance, defect_geometry
from ...io.atomic import atomic_open
from ...load_distribution import radial_load_distribution
from ...results import Result, json_attr, read_json_attr, var_attrs
from ..budget import F8, Estimate
from . import _balance as bl
from .base import ModelInputs, static_path

#: how the load check names the radial load
_RADIAL = "|(fx_n, fy_n)|"

__all__ = [
    "STIFFNESS_RANGE",
    "TRACE_RESIDUAL_TOL",
    "StiffnessTrace",
    "check_trace_load",
    "check_trace_stiffness",
    "stiffness_trace",
    "trace_estimate",
]

#: Ball load-deflection constants ``K`` [N/m^1.5] (``Q = K delta^1.5``, seed VSM eq. (10)) a
#: trace accepts as an override (``stiffness_n_per_m1_5``): the Hertz constants of real ball
#: bearings with one decade of margin on each side. Derivation: for a point contact
#: ``delta ~ Q^(2/3) (sum rho)^(1/3) / E'^(2/3)`` (Harris & Kotzalas 2007, ch. 6), so
#: ``K = Q / delta^1.5 ~ E' (sum rho)^(-1/2)``: it grows with the modulus and with the square
#: root of the size. :func:`bearingsim.contact.hertz.ball_stiffness` over the bearings that
#: exist — balls of 0.5 mm (miniature bearings of 1 mm bore) to 100 mm (bores of a metre and
#: more), groove radii 0.505 to 0.60 of the ball diameter (the conformities of
#: :data:`bearingsim.geometry.CONFORMITY_RANGE`), rings and balls of bearing steel (207 GPa,
#: 0.3) or silicon nitride (310 GPa, 0.26) — gives ``K`` from 1.4e9 (0.5 mm steel ball in
#: 0.60 grooves) to 8.0e10 N/m^1.5 (100 mm Si3N4 ball in 0.505 grooves); the 6205's is 9.37e9
#: (``tests/test_vsm_trace_input.py`` recomputes them). The decade below keeps a fitted
#: equivalent constant (seed VSM's load zone needs 2.6e9 for the 6205) and polymer balls
#: (E ~ 3 GPa: ~1.4e8 for the 6205's size); the decade above, tungsten-carbide or diamond
#: contacts. Beyond: ring displacements of kilometres (1e-6) or contact deflections below the
#: float resolution of the ring position, where the balance does not converge (1e18, 1e25).
STIFFNESS_RANGE = (1e8, 1e12)

#: largest relative force residual ``|sum Q_j e_j - F| / |F|`` of seed VSM eq. (16) a trace
#: may report [-]: the damped Newton of :mod:`._balance` stops at ``ModelInputs.tol`` (1e-12,
#: at most 1e-6) and converged traces end at ~1e-12; one that failed ends at 1e-2..0.4
TRACE_RESIDUAL_TOL = 1e-6

#: per-ball arrays of one cage angle held at once by :func:`stiffness_trace` (angles, their sine
#: and cosine, deflections, loads, deformations, stiffnesses and the intermediate products) [-]
TRACE_BALL_ARRAYS = 16

#: array fields of :class:`StiffnessTrace`: name -> (dims, units, description)
_VARIABLES: dict[str, tuple[tuple[str, ...], str, str]] = {
    "shaft_angle": (("cage_angle",), "rad", "inner-ring rotation angle 2 pi f_s t"),
    "displacement": (("cage_angle", "axis"), "m", "static ring displacement"),
    "k_load": (("cage_angle",), "N/m", "total effective stiffness along the load"),
    "k_x": (("cage_angle",), "N/m", "total effective stiffness in x"),
    "k_y": (("cage_angle",), "N/m", "total effective stiffness in y"),
    "k_xy": (("cage_angle",), "N/m", "total effective stiffness coupling x-y"),
    "ball_load": (("cage_angle", "ball"), "N", "contact force Q_j"),
    "ball_deformation": (("cage_angle", "ball"), "m", "contact deformation (Q_j/K)^(2/3)"),
    "ball_k_load": (("cage_angle", "ball"), "N/m", "per-ball effective stiffness along the load"),
    "ball_k_x": (("cage_angle", "ball"), "N/m", "per-ball effective stiffness in x"),
    "ball_k_y": (("cage_angle", "ball"), "N/m", "per-ball effective stiffness in y"),
    "in_zone": (("cage_angle", "ball"), "1", "load-zone flag lambda_j (seed VSM eq. (14))"),
    "in_defect": (("cage_angle", "ball"), "1", "ball over the defect (seed VSM eq. (15))"),
    "residual": (("cage_angle",), "1", "relative force residual of seed VSM eq. (16)"),
}
#: scalar fields: name -> (units, description)
_SCALARS: dict[str, tuple[str, str]] = {
    "theta0": ("rad", "load direction"),
    "psi_l0": ("rad", "load-zone half angle of the intact bearing at cage angle 0 (eq. (8))"),
}
#: array entries of ``meta`` (cage angle x ball): name -> description
_META_ARRAYS: dict[str, str] = {
    "zone_margin": "load-zone margin of eq. (14): nominal deflection [m], or the angular "
    "margin to the fixed window [rad] when load_zone_half_angle is given",
    "psi": "ball azimuth psi_j",
}


@dataclass(frozen=True)
class StiffnessTrace(Result):
    """Quasi-static VSM quantities vs cage angle (seed VSM figs. 5–12, tables 2–3).

    Per-ball effective stiffnesses are the secant-matrix contributions of ball ``j``:
    ``k_j = s_j cos^2(psi_j - theta_0)`` (load direction), ``k_jx = s_j sin^2 psi_j``,
    ``k_jy = s_j cos^2 psi_j`` with ``s_j = Q_j/(u . e_j)`` [N/m] (see module docstring).

    Attributes
    ----------
    cage_angle : ndarray (m,)
        Cage angle ``theta_m`` [rad].
    shaft_angle : ndarray (m,)
        Inner-ring rotation angle ``2 pi f_s t`` [rad].
    displacement : ndarray (m, 2)
        Static ring displacement (u_x, u_y) [m].
    k_load, k_x, k_y, k_xy : ndarray (m,)
        Total effective stiffness along the load, in x, in y and the coupling [N/m].
    ball_load : ndarray (m, Z)
        Contact force Q_j [N].
    ball_deformation : ndarray (m, Z)
        Contact deformation ``(Q_j/K)^(2/3)`` [m] (what remains after the drop).
    ball_k_load, ball_k_x, ball_k_y : ndarray (m, Z)
        Per-ball effective stiffness [N/m].
    in_zone : ndarray (m, Z) of bool
        Load-zone flag ``lambda_j`` (eq. (14)): nominal deflection > 0.
    in_defect : ndarray (m, Z) of bool
        Ball over the defect (eq. (15)).
    residual : ndarray (m,)
        Relative force residual of eq. (16) [-].
    theta0 : float
        Load direction [rad].
    psi_l0 : float
        Load-zone half angle ``arccos(P_d / (2 delta_r))`` of the intact bearing at cage angle
        0 (eq. (8)) [rad].
    label : str
        Description (fault, retention factor, stiffness used).
    meta : dict
        The inputs (``inputs``: bearing, loads, defect, overrides, as in
        :class:`~.base.ModelInputs`), the defect and ball-frame scalars used by :meth:`events`,
        the ball constant ``stiffness`` [N/m^1.5] and the arrays ``zone_margin`` (m, Z) and
        ``psi`` (m, Z) [rad].
    """

    FORMAT: ClassVar[str] = "bearingsim.StiffnessTrace/1"

    cage_angle: NDArray[np.float64]
    shaft_angle: NDArray[np.float64]
    displacement: NDArray[np.float64]
    k_load: NDArray[np.float64]
    k_x: NDArray[np.float64]
    k_y: NDArray[np.float64]
    k_xy: NDArray[np.float64]
    ball_load: NDArray[np.float64]
    ball_deformation: NDArray[np.float64]
    ball_k_load: NDArray[np.float64]
    ball_k_x: NDArray[np.float64]
    ball_k_y: NDArray[np.float64]
    in_zone: NDArray[np.bool_]
    in_defect: NDArray[np.bool_]
    residual: NDArray[np.float64]
    theta0: float
    psi_l0: float
    label: str = ""
    meta: dict = field(default_factory=dict)

    @property
    def n_loaded(self) -> NDArray[np.int64]:
        """Number of balls in the load zone [-]."""
        return self.in_zone.sum(axis=1)

    def events(self) -> list[tuple[float, int, str]]:
        """Load-zone and defect events ``(cage angle [deg], ball (1-based), kind)`` with kind in
        ``enters_zone``, ``leaves_zone``, ``enters_defect``, ``leaves_defect``; angles by linear
        interpolation of the nominal deflection (zone) or the sample of the change (defect,
        refined to the exact kinematic crossing)."""
        deg = np.degrees(self.cage_angle)
        out: list[tuple[float, int, str]] = []
        z = self.in_zone.astype(int)
        dz = np.diff(z, axis=0)
        for i, j in zip(*np.nonzero(dz), strict=True):
            kind = "enters_zone" if dz[i, j] > 0 else "leaves_zone"
            a0, a1 = self._margin[i, j], self._margin[i + 1, j]
            f = a0 / (a0 - a1) if a0 != a1 else 0.5
            out.append((float(deg[i] + f * (deg[i + 1] - deg[i])), int(j) + 1, kind))
        dd = np.diff(self.in_defect.astype(int), axis=0)
        for i, j in zip(*np.nonzero(dd), strict=True):
            kind = "enters_defect" if dd[i, j] > 0 else "leaves_defect"
            out.append((float(self._defect_crossing(i, j, kind)), int(j) + 1, kind))
        return sorted(out)

    @property
    def _margin(self) -> NDArray[np.float64]:
        return self.meta["zone_margin"]

    def _defect_crossing(self, i: int, j: int, kind: str) -> float:
        """Exact kinematic crossing of a defect edge between samples i and i+1 [deg]: the
        ball-to-edge angle is linear in the cage angle. A ball enters an outer defect at its
        left edge; the faster inner defect catches the ball with its right edge."""
        m = self.meta
        th = self.cage_angle[i : i + 2]
        psi = th + m["alpha0"] + 2 * math.pi * j / m["Z"]
        inner = m["fault"] == "inner"
        edge = m["beta0"] + (th / m["cage_per_shaft"] if inner else 0.0)
        enters = kind == "enters_defect"
        target = m["delta_beta"] if enters == inner else 0.0
        r = psi - edge - target
        r = r - 2 * math.pi * np.round(r[0] / (2 * math.pi))
        f = r[0] / (r[0] - r[1]) if r[0] != r[1] else 0.5
        return math.degrees(th[0] + f * (th[1] - th[0]))

    # ------------------------------------------------------------------------ files
    def to_dataset(self):
        """The trace as an :class:`xarray.Dataset`: dims ``cage_angle`` (coordinate [rad]),
        ``ball`` (1..Z) and ``axis`` (x, y); every array with its ``units`` (the arrays of
        ``meta`` as ``meta_<name>``); ``label`` and the other ``meta`` entries (inputs included)
        as JSON attributes."""
        import xarray as xr

        m = self.meta
        fixed = (m.get("inputs") or {}).get("load_zone_half_angle") is not None
        data: dict[str, Any] = {}
        for name, (dims, units, desc) in _VARIABLES.items():
            data[name] = (dims, np.asarray(getattr(self, name)), var_attrs(units, desc))
        for name, (units, desc) in _SCALARS.items():
            data[name] = ((), float(getattr(self, name)), var_attrs(units, desc))
        arrays = [k for k, v in m.items() if isinstance(v, np.ndarray)]
        for k in arrays:
            units = "rad" if k == "psi" or (k == "zone_margin" and fixed) else "m"
            data[f"meta_{k}"] = (
                ("cage_angle", "ball"),
                np.asarray(m[k]),
                var_attrs(units, _META_ARRAYS.get(k, k)),
            )
        coords = {
            "cage_angle": ("cage_angle", np.asarray(self.cage_angle), var_attrs("rad", "theta_m")),
            "ball": ("ball", np.arange(1, self.ball_load.shape[1] + 1)),
            "axis": ("axis", ["x", "y"]),
        }
        # the arrays keep their place in meta_json as null (key order survives)
        scalars = {k: (None if k in arrays else v) for k, v in m.items()}
        attrs = self._base_attrs(
            model="vsm-trace (seed VSM, Guo et al. 2025)",
            label=self.label,
            meta_json=json_attr(scalars),
            meta_arrays_json=json.dumps(arrays),
        )
        return xr.Dataset(data, coords=coords, attrs=attrs)

    @classmethod
    def from_dataset(cls, ds) -> StiffnessTrace:
        """Inverse of :meth:`to_dataset`."""
        cls.check_format(ds)
        meta = read_json_attr(ds, "meta_json")
        for k in read_json_attr(ds, "meta_arrays_json"):
            meta[k] = np.asarray(ds[f"meta_{k}"].values)
        kw = {name: np.asarray(ds[name].values) for name in _VARIABLES}
        kw.update({name: float(ds[name].values) for name in _SCALARS})
        return cls(
            cage_angle=np.asarray(ds["cage_angle"].values),
            label=str(ds.attrs.get("label", "")),
            meta=meta,
            **kw,
        )

    def to_csv(self, path: str | Path) -> None:
        """Write the trace as CSV (one row per cage angle; SI units, angles in deg), atomically.

        Columns: ``cage_angle_deg``, ``shaft_angle_deg``, ``u_x_m``, ``u_y_m``,
        ``k_load_n_per_m``, ``k_x_n_per_m``, ``k_y_n_per_m``, ``k_xy_n_per_m`` [N/m],
        ``n_loaded``, ``residual``, then per ball ``Q<j>_n`` [N], ``delta<j>_m`` [m] and
        ``k<j>_load_n_per_m`` [N/m] (formerly ``_n_m``, which the unit rule reads N m)."""
        Z = self.ball_load.shape[1]
        # stiffnesses in N/m end in _n_per_m (docs/cli.md unit rule; the former _n_m reads N m)
        cols = [
            "cage_angle_deg",
            "shaft_angle_deg",
            "u_x_m",
            "u_y_m",
            "k_load_n_per_m",
            "k_x_n_per_m",
            "k_y_n_per_m",
            "k_xy_n_per_m",
            "n_loaded",
            "residual",
        ]
        cols += [f"Q{j + 1}_n" for j in range(Z)]
        cols += [f"delta{j + 1}_m" for j in range(Z)]
        cols += [f"k{j + 1}_load_n_per_m" for j in range(Z)]
        data = np.column_stack(
            [
                np.degrees(self.cage_angle),
                np.degrees(self.shaft_angle),
                self.displacement,
                self.k_load,
                self.k_x,
                self.k_y,
                self.k_xy,
                self.n_loaded,
                self.residual,
                self.ball_load,
                self.ball_deformation,
                self.ball_k_load,
            ]
        )
        import json

        from ...io.jsonable import to_jsonable

        inputs = json.dumps(to_jsonable(self.meta.get("inputs", {})), separators=(",", ":"))
        with atomic_open(path, "w", encoding="utf-8") as fh:
            # the inputs as JSON (SI) on the label's line, so the export says what it is a trace
            # of and stays one comment line before the header (twenty-first session: the label
            # alone was written)
            fh.write(f"# bearingsim vsm-trace: {self.label}; inputs: {inputs}\n")
            np.savetxt(fh, data, delimiter=",", header=",".join(cols), comments="", fmt="%.17g")

    def plot_total(self, ax=None):
        """Total effective stiffness vs cage angle (seed VSM figs. 5–8); returns the Figure."""
        from ...plotting import FULL_WIDTH, new_figure

        if ax is None:
            fig, axs = new_figure(3, 1, width=FULL_WIDTH, row_height=2.0, sharex=True)
        else:
            axs = ax
            fig = axs[0].figure
        deg = np.degrees(self.cage_angle)
        for a, k, lab in zip(
            axs,
            (self.k_load, self.k_x, self.k_y),
            ("k_eq,r (load direction)", "k_eq,x", "k_eq,y"),
            strict=True,
        ):
            a.plot(deg, k / 1e6, lw=1)
            a.set_ylabel(f"{lab} [MN/m]")
        axs[-1].set_xlabel("cage angle θ_m [deg]")
        axs[0].set_title(f"VSM total effective stiffness: {self.label}")
        return fig

    def plot_ball(self, ball: int):
        """Effective stiffness, contact force and deformation of one ball (seed figs. 9, 11)."""
        from ...plotting import FULL_WIDTH, new_figure

        j = ball - 1
        deg = np.degrees(self.cage_angle)
        fig, axs = new_figure(3, 1, width=FULL_WIDTH, row_height=2.0, sharex=True)
        axs[0].plot(deg, self.ball_k_load[:, j] / 1e6)
        axs[0].set_ylabel("stiffness k_j [MN/m]")
        axs[1].plot(deg, self.ball_load[:, j])
        axs[1].set_ylabel("contact force Q_j [N]")
        axs[2].plot(deg, self.ball_deformation[:, j] * 1e6)
        axs[2].set_ylabel("deformation δ_j [µm]")
        axs[2].set_xlabel("cage angle θ_m [deg]")
        axs[0].set_title(f"ball {ball}: {self.label}")
        return fig

    def plot_balls(self, balls: list[int]):
        """Contact force and deformation of several balls (seed figs. 10, 12)."""
        from ...plotting import FULL_WIDTH, legend_outside, new_figure

        deg = np.degrees(self.cage_angle)
        fig, axs = new_figure(2, 1, width=FULL_WIDTH, row_height=2.2, sharex=True)
        for b in balls:
            axs[0].plot(deg, self.ball_load[:, b - 1], label=f"ball {b}")
            axs[1].plot(deg, self.ball_deformation[:, b - 1] * 1e6, label=f"ball {b}")
        axs[0].set_ylabel("contact force Q_j [N]")
        axs[1].set_ylabel("deformation δ_j [µm]")
        axs[1].set_xlabel("cage angle θ_m [deg]")
        legend_outside(axs[0])
        axs[0].set_title(self.label)
        return fig


def check_trace_load(
    bearing: BallBearing, fx: float, fy: float, clearance: float | None = None
) -> None:
    """Refuse, in one line naming ``fx_n``, ``fy_n`` and ``clearance_m``, the loads a VSM trace
    cannot trace (module docstring): a zero radial load with ``P_d >= 0``, and a preload
    ``P_d < 0`` whatever the load.

    Parameters
    ----------
    bearing : BallBearing
        The bearing (its clearance unless ``clearance`` is given).
    fx, fy : float
        Radial load components [N].
    clearance : float, optional
        Diametral clearance P_d [m] (default the bearing's).
    """
    if not isinstance(bearing, BallBearing):
        raise ConfigError(
            f"bearing = {getattr(bearing, 'id', bearing)!r} is not a ball bearing; the VSM "
            "stiffness trace needs a ball bearing"
        )
    fx = check_range("fx_n", fx, unit="N")
    fy = check_range("fy_n", fy, unit="N")
    pd = bearing.diametral_clearance
    if clearance is not None:
        pd = check_clearance(
            bearing, clearance, name="clearance_m", hi=0.5 * bearing.element_diameter
        )
    if pd < 0.0:
        raise ConfigError(
            f"clearance_m = {pd:.6g} m (a preload) is out of range for the VSM stiffness trace: "
            "its secant stiffness is measured from the concentric position, where a preloaded "
            "ball already carries load (with a preload even fx_n = fy_n = 0 N is a valid state, "
            "every ball equally loaded); valid range [0, inf) m (simulate a preloaded bearing "
            "with model dem or tvsm)"
        )
    if math.hypot(fx, fy) > 0.0:
        return
    if pd > 0.0:
        why = (
            f"with clearance_m = {pd:.6g} m > 0 the ring position within the clearance is "
            "undetermined"
        )
    else:
        why = (
            "with clearance_m = 0 m every ball touches unloaded and its secant stiffness "
            "K delta^0.5 is 0: there is no stiffness to trace"
        )
    raise ConfigError(
        f"radial load |(fx_n, fy_n)| = 0 N (fx_n = {fx:g} N, fy_n = {fy:g} N): {why}; valid "
        "range |(fx_n, fy_n)| > 0 N"
    )


def check_trace_stiffness(inputs: ModelInputs) -> None:
    """Refuse an overriding ball constant (``stiffness_n_per_m1_5``) outside
    :data:`STIFFNESS_RANGE`, in one line with the bearing's Hertz value."""
    if inputs.stiffness is None:
        return
    lo, hi = STIFFNESS_RANGE
    if not lo <= inputs.stiffness <= hi:
        from ...contact.hertz import element_stiffness

        hertz = element_stiffness(inputs.bearing)[0]
        raise ConfigError(
            f"stiffness_n_per_m1_5 = {inputs.stiffness:.6g} N/m^1.5 is out of range; valid "
            f"range [{lo:g}, {hi:g}] N/m^1.5 (the Hertz constants of steel and ceramic ball "
            f"contacts from 0.5 to 100 mm balls, with a decade of margin; {inputs.bearing.id}: "
            f"{hertz:.3g})"
        )


def _check_residual(inputs: ModelInputs, cage: NDArray, res: NDArray, K: float) -> None:
    """Refuse a trace whose static balance did not converge (:data:`TRACE_RESIDUAL_TOL`)."""
    bad = ~(res <= TRACE_RESIDUAL_TOL)
    if not np.any(bad):
        return
    i = int(np.argmax(np.where(bad, np.nan_to_num(res, nan=np.inf), -np.inf)))
    f = math.hypot(inputs.fx, inputs.fy)
    delta = (f / K) ** (2.0 / 3.0)
    raise SolverError(
        f"the static balance of seed VSM eq. (16) did not converge: residual_max = "
        f"{res[i]:.3g} (relative force residual) at cage angle {math.degrees(cage[i]):.4g} deg, "
        f"above {TRACE_RESIDUAL_TOL:g}; the contact deflection (|F|/K)^(2/3) = {delta:.3g} m "
        f"under |(fx_n, fy_n)| = {f:.6g} N with K = {K:.3g} N/m^1.5 is below what the ring "
        f"position (P_d/2 = {0.5 * inputs.diametral_clearance:.3g} m) resolves; valid: a larger "
        "radial load or a smaller stiffness_n_per_m1_5"
    )


def trace_estimate(inputs: ModelInputs, n_points: int) -> Estimate:
    """Memory [B] of :func:`stiffness_trace` over ``n_points`` cage angles: the table of the
    quasi-static solution and :data:`TRACE_BALL_ARRAYS` arrays per ball and angle (no
    integration steps)."""
    z = inputs.bearing.n_elements
    per_point = (bl.NCOL + 4 + TRACE_BALL_ARRAYS * z) * F8
    return Estimate(f"vsm-trace: {n_points} cage angles x {z} balls", float(n_points) * per_point)


def stiffness_trace(
    inputs: ModelInputs,
    cage_angle: NDArray[np.float64] | None = None,
    *,
    cage_revs: float = 1.0,
    n_points: int = 3601,
    allow_overload: bool | None = False,
) -> StiffnessTrace:
    """Quasi-static VSM trace vs cage angle (seed VSM §2.2–2.4, figs. 5–12, tables 2–3).

    Parameters
    ----------
    inputs : ModelInputs
        Bearing, load, defect, speed (only the shaft/cage speed ratio matters here), optional
        stiffness/clearance/retention overrides; a preload, an axial load and a ball constant
        outside :data:`STIFFNESS_RANGE` are refused, and so is a result whose static balance
        did not converge (:data:`TRACE_RESIDUAL_TOL`; :class:`~bearingsim.errors.SolverError`).
    cage_angle : ndarray, optional
        Cage angles [rad]; default ``n_points`` over ``cage_revs`` revolutions.
    cage_revs : float
        Number of cage revolutions [-] (used without ``cage_angle``).
    n_points : int
        Number of samples (used without ``cage_angle``).
    allow_overload : bool or None
        The radial load is checked against the static capacity first
        (:func:`bearingsim.contact.capacity.check_load`: a warning above ``C_0``, refused above
        ``2 C_0``); ``True`` runs an overload anyway, ``None`` skips the check.
    """
    check_load(inputs.bearing, math.hypot(inputs.fx, inputs.fy), allow_overload, name=_RADIAL)
    inputs.require_clearance("the VSM stiffness trace")
    check_trace_stiffness(inputs)
    if cage_angle is None:
        if not (isinstance(n_points, int) and n_points >= 2):
            raise ConfigError(f"n_points = {n_points!r} is invalid; valid range [2, inf) integer")
        if not (0.0 < cage_revs <= 1000.0):
            raise ConfigError(f"cage_revs = {cage_revs!r} is out of range; valid range (0, 1000]")
        cage_angle = np.linspace(0.0, 2 * math.pi * cage_revs, n_points)
    cage = np.ascontiguousarray(cage_angle, dtype=float)
    w_cage = 2 * math.pi * inputs.cage_hz
    times = cage / w_cage
    table, res = static_path(inputs, times)
    p = inputs.header()
    _check_residual(inputs, cage, res, float(p[bl.P_K]))
    Z = inputs.bearing.n_elements
    psi = cage[:, None] + inputs.first_ball_angle + 2 * math.pi * np.arange(Z)[None, :] / Z
    sn, cs = np.sin(psi), np.cos(psi)
    ux, uy = table[:, bl.C_UX : bl.C_UX + 1], table[:, bl.C_UY : bl.C_UY + 1]
    ue = ux * sn + uy * cs
    dev = inputs.ball_deviations()  # a larger ball closes its gap by its whole excess
    nominal = ue - p[bl.P_CLR] + (dev[None, :] if dev.size else 0.0)
    defect = inputs.defect
    shaft = times * 2 * math.pi * inputs.shaft_hz
    beta0 = 0.0
    drop = np.full_like(psi, p[bl.P_DOFF])
    if defect is None:
        over = np.zeros_like(psi, dtype=bool)
    else:  # the kernels' window: the defect's extent (a pit's widened by the contact's length)
        beta0 = defect_geometry(inputs.bearing, defect).edge_angle
        w0, wext = p[bl.P_BETA0], p[bl.P_DBETA]
        if defect.race is Race.BALL:  # ball 1's spin angle past the defect edge (_balance)
            spin = np.mod(p[bl.P_SPIN] * (psi[:, 0] - inputs.first_ball_angle) + w0, 2 * math.pi)
            outer = spin < wext
            inner = np.mod(spin + math.pi, 2 * math.pi) < wext
            over = np.zeros_like(psi, dtype=bool)
            over[:, 0] = outer | inner
            drop[:, 0] = np.where(inner, p[bl.P_DOFFI], p[bl.P_DOFF])
        else:
            edge = w0 + (shaft[:, None] if defect.race is Race.INNER else 0.0)
            over = np.mod(psi - edge, 2 * math.pi) < wext
    off = np.where(over, drop, 0.0)
    fac = np.where(over, p[bl.P_DFAC], 1.0)
    th0 = inputs.theta0
    if inputs.load_zone_half_angle is None:
        margin = nominal  # eq. (14) decided by contact
    else:  # seed's literal eq. (14): fixed window theta_0 +/- psi_L
        rel = np.mod(psi - th0 + math.pi, 2 * math.pi) - math.pi
        margin = inputs.load_zone_half_angle - np.abs(rel)
        fac = np.where(margin >= 0, fac, 0.0)
    comp = nominal - off
    K = p[bl.P_K]
    if inputs.defect is not None and inputs.profile is not DefectProfile.RECTANGULAR:
        # the drop (geometric) or share (pit) varies across the defect: the kernels' own ball
        # loads at the solved displacements (point values), as simulate's per-ball output
        Q = np.empty_like(psi)
        buf = np.empty(2 * Z)
        for i in range(times.size):
            bl.per_ball(float(times[i]), p, float(ux[i, 0]), float(uy[i, 0]), buf, 0, True)
            Q[i] = buf[:Z]
    elif inputs.roughness > 0.0:  # the rough load law (contact.rough), as the kernels use it
        sig = inputs.roughness
        Q = fac * K * sig**1.5 * rough_mean_power(comp / sig, 1.5)
    else:
        Q = np.where(comp > 0, fac * K * np.maximum(comp, 0.0) ** 1.5, 0.0)
    s = np.where(Q > 0, Q / np.where(Q > 0, ue, 1.0), 0.0)
    ldh = radial_load_distribution(
        inputs.bearing,
        inputs.fx,
        inputs.fy,
        0.0,
        clearance=inputs.diametral_clearance,
        stiffness=K,
        first_element_angle=inputs.first_ball_angle,
        allow_overload=None,  # checked above
    )
    fault = "none" if defect is None else defect.race.value
    label = f"fault {fault}"
    if defect is not None:
        label += f", b {inputs.defect.width * 1e3:.3g} mm, " + (
            f"gamma {inputs.retention_factor:g}"
            if inputs.retention_factor is not None
            else f"pit, r {0.5e3 * inputs.defect.width:.3g} mm"
            if inputs.profile is DefectProfile.PIT
            else f"h_min {p[bl.P_DOFF] * 1e6:.3g} um (eq. 11 implicit"
            + (", geometric)" if inputs.profile is DefectProfile.GEOMETRIC else ")")
        )
    label += f", K {K:.3g} N/m^1.5, psi_L0 {math.degrees(float(ldh.psi_l[0])):.1f} deg"
    if inputs.load_zone_half_angle is not None:
        label += f", fixed zone +/-{math.degrees(inputs.load_zone_half_angle):.1f} deg"
    meta = {
        "zone_margin": margin,
        "psi": psi,
        "fault": fault,
        "alpha0": inputs.first_ball_angle,
        "beta0": beta0,
        "Z": Z,
        "delta_beta": float(p[bl.P_DBETA]),
        "cage_per_shaft": inputs.cage_hz / inputs.shaft_hz,
        "stiffness": float(K),
        "inputs": _inputs_dict(inputs),
    }
    return StiffnessTrace(
        cage_angle=cage,
        shaft_angle=shaft,
        displacement=table[:, :2].copy(),
        k_load=(s * np.cos(psi - th0) ** 2).sum(1),
        k_x=table[:, bl.C_SXX].copy(),
        k_y=table[:, bl.C_SYY].copy(),
        k_xy=table[:, bl.C_SXY].copy(),
        ball_load=Q,
        ball_deformation=np.where(Q > 0, (Q / K) ** (2.0 / 3.0), 0.0),
        ball_k_load=s * np.cos(psi - th0) ** 2,
        ball_k_x=s * sn**2,
        ball_k_y=s * cs**2,
        in_zone=margin > 0,
        in_defect=over,
        residual=res,
        theta0=th0,
        psi_l0=float(ldh.psi_l[0]),
        label=label,
        meta=meta,
    )


def _inputs_dict(inputs: ModelInputs) -> dict[str, Any]:
    """The inputs as plain JSON types (bearing and defect spelled out, enums by value)."""
    d: dict[str, Any] = {f.name: getattr(inputs, f.name) for f in dataclasses.fields(inputs)}
    d["bearing"] = dataclasses.asdict(inputs.bearing)
    d["profile"] = inputs.profile.value
    dfc = inputs.defect
    if dfc is not None:
        d["defect"] = {
            "race": dfc.race.value,
            "width": dfc.width,
            "depth": dfc.depth,
            "angle": dfc.angle,
        }  # the ring models' drop profile is the inputs' own ("profile" above): the defect's
        # field is the rotor model's, and recorded here it contradicted the one in force
    return json.loads(json_attr(d))
