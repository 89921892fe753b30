"""Results of the quasi-static 5-DOF family: the labelled stiffness matrix
(:class:`StiffnessMatrix`) and the equilibria at one or more cage angles
(:class:`QuasiStaticSolution`), both following the result pattern of :mod:`bearingsim.results`
(``to_dataset``/``from_dataset``, atomic netCDF-4 ``save``, format-checked ``load``).

DOF vector of the inner ring ``u = (x, y, z, theta_x, theta_y)`` [m, m, m, rad, rad] and its
conjugate load ``(Fx, Fy, Fz, Mx, My)`` [N, N, N, N m, N m]; the tangent stiffness
``K_ij = dF_i/du_j`` therefore has the entry units ``N/m`` (force per translation), ``N/rad``
(force per tilt), ``N m/m`` (moment per translation) and ``N m/rad`` (moment per tilt).
"""

from __future__ import annotations

import math
from dataclasses import asdict, dataclass, field
from typing import Any, ClassVar

import numpy as np
from numpy.typing import NDArray

from ..errors import ConfigError
from ..results import Result, json_attr, read_json_attr
from .inputs import (
    Method,
    Misalignment,
    QSGeometry,
    SpeedEffects,
    _ball_azimuths,
    _Case,
)

__all__ = [
    "DOF_NAMES",
    "DOF_UNITS",
    "LOAD_NAMES",
    "LOAD_UNITS",
    "STIFFNESS_UNITS",
    "QuasiStaticSolution",
    "StiffnessMatrix",
]

#: names of the five inner-ring degrees of freedom, in vector order
DOF_NAMES = ("x", "y", "z", "theta_x", "theta_y")
#: unit of each degree of freedom
DOF_UNITS = ("m", "m", "m", "rad", "rad")
#: the load conjugate to each degree of freedom (rows of the stiffness matrix)
LOAD_NAMES = ("Fx", "Fy", "Fz", "Mx", "My")
#: unit of each load
LOAD_UNITS = ("N", "N", "N", "N m", "N m")
#: unit of each stiffness entry ``K_ij = dF_i/du_j``: load unit of row i / DOF unit of column j
STIFFNESS_UNITS = tuple(tuple(f"{lu}/{du}" for du in DOF_UNITS) for lu in LOAD_UNITS)

_MATRIX_UNITS = "per entry: load_unit(dof) / dof_unit(dof_col), see coordinate stiffness_unit"


def _dof_coords() -> dict[str, Any]:
    """Coordinates naming the DOFs, their loads and the units of every vector and matrix entry."""
    return {
        "dof": ("dof", list(DOF_NAMES)),
        "dof_col": ("dof_col", list(DOF_NAMES)),
        "dof_unit": ("dof", list(DOF_UNITS)),
        "load": ("dof", list(LOAD_NAMES)),
        "load_unit": ("dof", list(LOAD_UNITS)),
        "stiffness_unit": (("dof", "dof_col"), np.array(STIFFNESS_UNITS)),
    }


def _dof_index(name: object) -> int:
    if name in DOF_NAMES:
        return DOF_NAMES.index(name)
    raise ConfigError(f"dof = {name!r} is invalid; valid: " + ", ".join(DOF_NAMES))


@dataclass(frozen=True, eq=False)
class StiffnessMatrix(Result):
    """Tangent stiffness ``K = dF/du`` of the inner ring, labelled (rows: loads
    ``Fx, Fy, Fz, Mx, My``; columns: DOFs ``x, y, z, theta_x, theta_y``).

    One 5x5 matrix for one position, a stack (positions x 5 x 5) when several cage angles were
    asked for. Index by DOF names: ``K["y", "y"]`` is the radial stiffness along y [N/m],
    ``K["theta_x", "theta_x"]`` the tilting stiffness [N m/rad] (a float for one position, an
    array over the positions for a stack). ``numpy.asarray(K)`` gives :attr:`values`.

    Parameters
    ----------
    values : ndarray, shape (5, 5) or (m, 5, 5)
        Entries [N/m, N/rad, N m/m, N m/rad by block, :data:`STIFFNESS_UNITS`].
    cage_angle : float or ndarray, shape (m,), optional
        Cage angle of each position [rad].
    meta : dict
        Where it comes from (bearing, method), JSON-serialisable.
    """

    FORMAT: ClassVar[str] = "bearingsim.StiffnessMatrix/1"
    #: DOF names of the rows and columns
    dofs: ClassVar[tuple[str, ...]] = DOF_NAMES

    values: NDArray[np.float64]
    cage_angle: float | NDArray[np.float64] | None = None
    meta: dict[str, Any] = field(default_factory=dict)

    def __post_init__(self) -> None:
        v = np.asarray(self.values, dtype=float)
        if v.ndim not in (2, 3) or v.shape[-2:] != (5, 5):
            raise ConfigError(
                f"stiffness matrix shape = {v.shape} is invalid; valid: (5, 5) or (m, 5, 5)"
            )
        object.__setattr__(self, "values", v)
        if self.cage_angle is None:
            return
        if v.ndim == 2:
            object.__setattr__(self, "cage_angle", float(self.cage_angle))
            return
        c = np.asarray(self.cage_angle, dtype=float)
        if c.shape != v.shape[:1]:
            raise ConfigError(
                f"cage_angle has shape {c.shape}; valid: one angle per matrix, {v.shape[:1]}"
            )
        object.__setattr__(self, "cage_angle", c)

    @property
    def is_stack(self) -> bool:
        """True for several positions (``values`` of shape (m, 5, 5))."""
        return self.values.ndim == 3

    @property
    def stack(self) -> NDArray[np.float64]:
        """The entries with a leading position axis, shape (m, 5, 5) (m = 1 for one matrix)."""
        return self.values if self.is_stack else self.values[None]

    @property
    def units(self) -> NDArray[np.str_]:
        """Unit of every entry, shape (5, 5)."""
        return np.array(STIFFNESS_UNITS)

    def unit(self, row: str, col: str) -> str:
        """Unit of the entry ``(row, col)`` named by DOFs (e.g. ``("x", "theta_y")`` -> N/rad)."""
        return STIFFNESS_UNITS[_dof_index(row)][_dof_index(col)]

    def __getitem__(self, key: tuple[str, str]) -> float | NDArray[np.float64]:
        if not (isinstance(key, tuple) and len(key) == 2):
            raise ConfigError(
                f"index = {key!r} is invalid; valid: two DOF names, e.g. K['y', 'y'], from "
                + ", ".join(DOF_NAMES)
            )
        i, j = _dof_index(key[0]), _dof_index(key[1])
        out = self.values[..., i, j]
        return float(out) if out.ndim == 0 else out

    def __array__(self, dtype: Any = None, copy: bool | None = None) -> NDArray:
        a = self.values if dtype is None else self.values.astype(dtype)
        return a.copy() if copy else a

    def __str__(self) -> str:
        if self.is_stack:
            return f"StiffnessMatrix: {self.values.shape[0]} positions x 5 x 5 (SI)"
        w = 12
        rows = [" " * 4 + "".join(f"{d:>{w}}" for d in DOF_NAMES)]
        for i, load in enumerate(LOAD_NAMES):
            cells = "".join(f"{v:>{w}.4g}" for v in self.values[i])
            rows.append(f"{load:<4}{cells}   [{LOAD_UNITS[i]}/(m, rad)]")
        return "\n".join(rows)

    def at(self, index: int) -> StiffnessMatrix:
        """The 5x5 matrix of position ``index`` (a one-position matrix is its own position 0)."""
        if not self.is_stack:
            if index not in (0, -1):
                raise ConfigError(f"index = {index!r} is out of range; valid: 0 (one position)")
            return self
        m = self.values.shape[0]
        if not -m <= index < m:
            raise ConfigError(f"index = {index!r} is out of range; valid range [0, {m - 1}]")
        c = None if self.cage_angle is None else float(self.cage_angle[index])
        return StiffnessMatrix(self.values[index], c, dict(self.meta))

    # ------------------------------------------------------------------------------ files
    def to_dataset(self):
        """The matrix as an :class:`xarray.Dataset`: variable ``stiffness`` over
        ``(position,) dof, dof_col`` with the DOF names, loads and units as coordinates."""
        import xarray as xr

        dims = ("position", "dof", "dof_col") if self.is_stack else ("dof", "dof_col")
        coords = _dof_coords()
        if self.cage_angle is not None:
            coords["cage_angle"] = (dims[:-2], self.cage_angle, {"units": "rad"})
        var = {"units": _MATRIX_UNITS, "long_name": "tangent stiffness dF/du"}
        return xr.Dataset(
            {"stiffness": (dims, self.values, var)},
            coords=coords,
            attrs={"format": self.FORMAT, "meta_json": json_attr(self.meta)},
        )

    @classmethod
    def from_dataset(cls, ds) -> StiffnessMatrix:
        """Inverse of :meth:`to_dataset`."""
        cls.check_format(ds)
        c = ds["cage_angle"].values if "cage_angle" in ds.coords else None
        return cls(np.asarray(ds["stiffness"].values), c, read_json_attr(ds, "meta_json"))

    # ------------------------------------------------------------------------------ plots
    def plot_matrix(self, index: int = 0):
        """Entries of position ``index`` as a colour map of ``log10 |K_ij|`` with the values and
        units written in; returns the Figure."""
        from ..plotting import ANNOTATION_PT, FULL_WIDTH, new_figure

        K = self.stack[index]
        fig, ax = new_figure(width=FULL_WIDTH * 0.75, height=6.0)
        with np.errstate(divide="ignore"):
            im = ax.imshow(np.log10(np.abs(K)), cmap="viridis")
        for i in range(5):
            for j in range(5):
                ax.text(
                    j,
                    i,
                    f"{K[i, j]:.3g}\n{STIFFNESS_UNITS[i][j]}",
                    ha="center",
                    va="center",
                    fontsize=ANNOTATION_PT,
                    color="w",
                )
        ax.set_xticks(range(5), DOF_NAMES)
        ax.set_yticks(range(5), LOAD_NAMES)
        ax.set_xlabel("displacement or rotation u_j [m or rad]")
        ax.set_ylabel("force or moment F_i [N or N m]")
        fig.colorbar(im, ax=ax, label="log10 |K_ij| of the SI value [-]")
        title = "tangent stiffness dF/du"
        if self.cage_angle is not None:
            c = self.cage_angle if not self.is_stack else self.cage_angle[index]
            title += f" at cage angle {math.degrees(c):.1f} deg"
        ax.set_title(title)
        return fig


@dataclass(frozen=True)
class QuasiStaticSolution(Result):
    """Equilibria of the inner ring at one or more cage angles (leading axis: cage angle).

    Attributes
    ----------
    cage_angle : ndarray, shape (m,)
        Cage angles [rad].
    shaft_angle : ndarray, shape (m,)
        Inner-ring (shaft) angles ``cage_angle / cage_ratio`` [rad].
    displacement : ndarray, shape (m, 5)
        ``(x [m], y [m], z [m], theta_x [rad], theta_y [rad])`` of the inner ring.
    stiffness_matrix : StiffnessMatrix
        Tangent stiffness ``dF/du``, labelled: one 5x5 matrix [N/m, N/rad, N m/m, N m/rad] when
        one cage angle was asked for, a stack (m, 5, 5) otherwise.
    reaction : ndarray, shape (m, 5)
        Resultant of the ball forces on the inner ring ``(Fx, Fy, Fz [N], Mx, My [N m])``; equals
        the applied load on the free DOFs; on held tilts it is the reaction moment.
    ball_angles : ndarray, shape (m, Z)
        Ball azimuths psi_j [rad] (seed eq. (1)).
    ball_loads : ndarray, shape (m, Z)
        Inner-contact loads Q_j [N].
    contact_angles : ndarray, shape (m, Z)
        Inner contact angles alpha_j [rad].
    deflections : ndarray, shape (m, Z)
        Total contact deformation delta_j (negative = gap) [m].
    iterations : ndarray, shape (m,)
        Newton iterations (Jones) or function evaluations (ISO) [-].
    residual : ndarray, shape (m,)
        Relative force residual at the solution [-].
    applied : ndarray, shape (5,)
        Applied ``(Fx, Fy, Fz, Mx, My)`` [N, N m].
    free : ndarray of bool, shape (5,)
        Which DOFs were solved (the others were held at 0).
    geometry : QSGeometry
        Derived geometry used.
    method : Method
        Load-distribution method.
    misalignment : Misalignment
        Ring misalignments.
    ball_errors : ndarray, shape (Z,)
        Ball-distribution errors e_j [rad].
    speed : SpeedEffects
        Inertia-load options.
    bearing_id : str
        Catalogue id.
    """

    FORMAT: ClassVar[str] = "bearingsim.QuasiStaticSolution/1"

    cage_angle: NDArray[np.float64]
    shaft_angle: NDArray[np.float64]
    displacement: NDArray[np.float64]
    stiffness_matrix: StiffnessMatrix
    reaction: NDArray[np.float64]
    ball_angles: NDArray[np.float64]
    ball_loads: NDArray[np.float64]
    contact_angles: NDArray[np.float64]
    deflections: NDArray[np.float64]
    iterations: NDArray[np.int64]
    residual: NDArray[np.float64]
    applied: NDArray[np.float64]
    free: NDArray[np.bool_]
    geometry: QSGeometry
    method: Method
    misalignment: Misalignment
    ball_errors: NDArray[np.float64]
    speed: SpeedEffects = field(default_factory=SpeedEffects)
    bearing_id: str = ""

    @classmethod
    def _build(
        cls,
        case: _Case,
        geometry: QSGeometry,
        method: Method,
        speed: SpeedEffects,
        bearing_id: str,
        stiffness: NDArray[np.float64],
        **arrays: NDArray,
    ) -> QuasiStaticSolution:
        """A solution of the validated inputs ``case``: the ball azimuths and shaft angles from
        the inputs, the stiffness stack (m, 5, 5) labelled (one 5x5 when ``case.single``);
        ``arrays`` are the other per-position fields."""
        return cls(
            cage_angle=case.cage,
            shaft_angle=case.cage / geometry.cage_ratio,
            stiffness_matrix=_labelled(stiffness, case.cage, case.single, bearing_id, method),
            ball_angles=_ball_azimuths(case.cage, case.first_ball_angle, case.ball_errors),
            applied=case.applied,
            free=case.free,
            geometry=geometry,
            method=method,
            misalignment=case.misalignment,
            ball_errors=case.ball_errors,
            speed=speed,
            bearing_id=bearing_id,
            **arrays,
        )

    @property
    def delta_r(self) -> NDArray[np.float64]:
        """Radial displacement ``|(x, y)|`` [m]."""
        return np.hypot(self.displacement[:, 0], self.displacement[:, 1])

    @property
    def delta_max(self) -> NDArray[np.float64]:
        """``delta_r - P_d/2``: radial deflection on the displacement line [m] (SPEC §0.4)."""
        return self.delta_r - 0.5 * self.geometry.clearance

    @property
    def psi_l(self) -> NDArray[np.float64]:
        """Load-zone half angle ``arccos(P_d / (2 delta_r))`` [rad] (SPEC §0.4)."""
        dr = self.delta_r
        with np.errstate(divide="ignore", invalid="ignore"):
            ratio = np.where(dr > 0, 0.5 * self.geometry.clearance / np.where(dr > 0, dr, 1.0), 0)
        return np.arccos(np.clip(ratio, -1.0, 1.0))

    def equilibrium(self, index: int = 0) -> dict[str, object]:
        """Plain-dict summary of the state at cage angle ``index`` (SI); the stiffness is the
        labelled 5x5 :class:`StiffnessMatrix` of that position."""
        u = self.displacement[index]
        return {
            "cage_angle_rad": float(self.cage_angle[index]),
            "displacement": dict(
                zip(("x_m", "y_m", "z_m", "theta_x_rad", "theta_y_rad"), map(float, u), strict=True)
            ),
            "stiffness_matrix": self.stiffness_matrix.at(index),
            "reaction": dict(
                zip(
                    ("fx_n", "fy_n", "fz_n", "mx_nm", "my_nm"),
                    map(float, self.reaction[index]),
                    strict=True,
                )
            ),
            "ball_angles_rad": self.ball_angles[index],
            "ball_loads_n": self.ball_loads[index],
            "contact_angles_rad": self.contact_angles[index],
            "deflections_m": self.deflections[index],
            "iterations": int(self.iterations[index]),
            "residual_rel": float(self.residual[index]),
        }

    # ------------------------------------------------------------------------------ files
    def to_dataset(self):
        """The solution as an :class:`xarray.Dataset`: per-position arrays over ``position``
        (coordinate ``cage_angle``), ``dof`` (names and units as coordinates) and ``ball``; the
        inputs and the derived geometry as JSON attributes."""
        import xarray as xr

        pos, dof, ball = ("position",), ("position", "dof"), ("position", "ball")
        coords = _dof_coords()
        coords["cage_angle"] = (pos, self.cage_angle, {"units": "rad"})
        coords["ball"] = ("ball", np.arange(1, self.ball_loads.shape[1] + 1))
        data = {
            "shaft_angle": (pos, self.shaft_angle, {"units": "rad"}),
            "displacement": (dof, self.displacement, {"units": ", ".join(DOF_UNITS)}),
            "reaction": (dof, self.reaction, {"units": ", ".join(LOAD_UNITS)}),
            "stiffness_matrix": (
                ("position", "dof", "dof_col"),
                self.stiffness_matrix.stack,
                {"units": _MATRIX_UNITS, "long_name": "tangent stiffness dF/du"},
            ),
            "ball_angles": (ball, self.ball_angles, {"units": "rad"}),
            "ball_loads": (ball, self.ball_loads, {"units": "N"}),
            "contact_angles": (ball, self.contact_angles, {"units": "rad"}),
            "deflections": (ball, self.deflections, {"units": "m"}),
            "iterations": (pos, self.iterations, {"units": "1"}),
            "residual": (pos, self.residual, {"units": "1"}),
        }
        inputs = {
            "applied": self.applied,
            "free": self.free,
            "misalignment": asdict(self.misalignment),
            "ball_errors_rad": self.ball_errors,
            "speed": asdict(self.speed),
        }
        attrs = {
            "format": self.FORMAT,
            "bearing_id": self.bearing_id,
            "method": self.method.value,
            "stiffness_single": int(not self.stiffness_matrix.is_stack),
            "inputs_json": json_attr(inputs),
            "geometry_json": json_attr(asdict(self.geometry)),
        }
        return xr.Dataset(data, coords=coords, attrs=attrs)

    @classmethod
    def from_dataset(cls, ds) -> QuasiStaticSolution:
        """Inverse of :meth:`to_dataset`."""
        cls.check_format(ds)
        return cls._read(ds)

    @classmethod
    def _read(cls, ds) -> QuasiStaticSolution:
        """The solution held in ``ds`` (also inside a :class:`~.stiffness.StiffnessResult`)."""
        inp = read_json_attr(ds, "inputs_json")
        method = Method(ds.attrs["method"])
        bearing_id = str(ds.attrs["bearing_id"])
        cage = np.asarray(ds["cage_angle"].values)
        single = bool(int(ds.attrs["stiffness_single"]))
        H = np.asarray(ds["stiffness_matrix"].values)

        def arr(name: str) -> NDArray:
            return np.asarray(ds[name].values)

        return cls(
            cage_angle=cage,
            shaft_angle=arr("shaft_angle"),
            displacement=arr("displacement"),
            stiffness_matrix=_labelled(H, cage, single, bearing_id, method),
            reaction=arr("reaction"),
            ball_angles=arr("ball_angles"),
            ball_loads=arr("ball_loads"),
            contact_angles=arr("contact_angles"),
            deflections=arr("deflections"),
            iterations=arr("iterations"),
            residual=arr("residual"),
            applied=np.array(inp["applied"], dtype=float),
            free=np.array(inp["free"], dtype=bool),
            geometry=QSGeometry(**read_json_attr(ds, "geometry_json")),
            method=method,
            misalignment=Misalignment(**inp["misalignment"]),
            ball_errors=np.array(inp["ball_errors_rad"], dtype=float),
            speed=SpeedEffects(**inp["speed"]),
            bearing_id=bearing_id,
        )

    # ------------------------------------------------------------------------------ plots
    def plot_loads(self, index: int = 0):
        """Polar bar plot of the ball loads at cage position ``index``; returns the Figure."""
        from ..plotting import HALF_WIDTH, new_figure

        fig, ax = new_figure(width=HALF_WIDTH, height=5.0, polar=True)
        ax.set_theta_zero_location("N")
        ax.set_theta_direction(-1)
        ax.bar(self.ball_angles[index], self.ball_loads[index], width=0.15, alpha=0.8)
        ax.set_ylabel("ball load Q [N]", labelpad=28)
        ax.set_title(
            f"ball loads at their angles (0° at the top),\n"
            f"cage angle {math.degrees(self.cage_angle[index]):.1f}°"
        )
        return fig


def _labelled(
    H: NDArray[np.float64],
    cage: NDArray[np.float64],
    single: bool,
    bearing_id: str,
    method: Method,
) -> StiffnessMatrix:
    """The stack ``H`` (m, 5, 5) as a :class:`StiffnessMatrix`, one 5x5 when ``single``."""
    meta = {"bearing_id": bearing_id, "method": method.value}
    if single:
        return StiffnessMatrix(H[0], float(cage[0]), meta)
    return StiffnessMatrix(H, cage, meta)
