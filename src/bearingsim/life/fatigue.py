"""Contact-fatigue life by damage mechanics on the plane-strain race section (seed LIFE §2.3).

Semi-decoupled damage integration (seed LIFE eqs. (7)–(8)):

1. solve the FE model of the current damage state for one load pass (all load positions) and
   get ``Delta_tau`` per element (:class:`~bearingsim.life.fe.ShearMeasure`);
2. damage rates ``(dD/dN)_j = [Delta_tau_j / (sigma_t (1 - D_j))]^kappa`` (eq. (4));
3. cycle block ``Delta_N_i = Delta_D / max_j (dD/dN)_j`` (eq. (7)), ``D_j += Delta_N_i (dD/dN)_j``
   for every element (eq. (8)), so the fastest element gains exactly ``Delta_D``;
4. update the stiffness ``E (1 - D_j)`` per element (eq. (2)) and repeat.

``cycles_initiation`` is the cycle count when the first element reaches ``D = 1``;
``cycles_spall`` when the first failed element touches the contact surface (the seed's life
criterion, §1.1 end: "the first representative volume element at the contact surface reaching
D = 1"). Failed elements keep a residual stiffness fraction (default ``1e-3``) so the stiffness
matrix stays regular; the same floor enters the effective stress ``Delta_tau/(1 - D)``.

The section outside the fine zone is condensed onto it once (static condensation, see
:class:`~bearingsim.life.fe.CoreSubstructure`) and assumed undamaged; the largest undamaged
damage rate outside relative to inside is reported (``outer_rate_ratio``).

:class:`LifeResult` follows the result pattern (:class:`~bearingsim.results.Result`): ``save``
writes a self-describing netCDF file (damage curve on ``step``, damage field and element
geometry on ``element``, units on every variable, every input including the damage law and the
mesh specification in ``meta_json``), ``load`` reads it back losslessly.
"""

from __future__ import annotations

import dataclasses
import enum
import json
import math
import time
import warnings
from dataclasses import dataclass, field
from typing import Any, ClassVar

import numpy as np
from numpy.typing import NDArray

from .._version import __version__
from ..errors import ConfigError, SolverError, check_positive, check_range
from ..geometry import BallBearing, Bearing
from ..results import Result, json_attr, read_json_attr, var_attrs
from .damage import GCR15_TORSION, DamageLaw, fit_sn_curve
from .fe import DEFAULT_MEASURE, ShearMeasure, contact_section, core_substructure, section_spec
from .validation import validate_against_hertz

#: smallest contact semi-width ``b`` the model takes [m]: smooth-surface Hertz contact needs a
#: contact much wider than the surface roughness, of the order of 0.1 um on ground and honed
#: raceways; the FE section, graded from ``b/n`` up to its 12 mm, also loses the load position in
#: double precision below ~10 nm (radial_load_n = 1e-30 N: "the load reaches outside the fine
#: zone"; 1e-300 N: a mesh graded over 200 decades that never finished)
MIN_CONTACT_HALF_WIDTH_M = 1e-7

__all__ = [
    "ContactLoad",
    "ElementLoadMethod",
    "LifeResult",
    "contact_fatigue_life",
    "default_damage_law",
    "inner_contact",
]


class ElementLoadMethod(enum.Enum):
    """How the most loaded rolling element's load is obtained."""

    #: Stribeck ``Q_max = 4.37 F_r / (Z cos alpha)`` (seed LIFE §2.1, zero clearance; 4.08 for
    #: roller bearings, :func:`bearingsim.load_distribution.stribeck_qmax`)
    STRIBECK = "stribeck"
    #: largest element load of the discrete-element distribution with the bearing's clearance,
    #: over cage angles spanning one element pitch
    DISTRIBUTION = "distribution"


def default_damage_law() -> DamageLaw:
    """kappa and sigma_t fitted to the GCr15 torsional S–N curve (seed LIFE eqs. (5)–(6))."""
    return fit_sn_curve(GCR15_TORSION).law


@dataclass(frozen=True)
class ContactLoad:
    """Most loaded inner contact: element load ``q`` [N], Hertz ``p_max`` [Pa] and the
    semi-width ``b`` along rolling [m] (plus ``a`` across rolling [m], equal to half the roller
    length for line contact)."""

    q: float
    p_max: float
    b: float
    a: float
    method: ElementLoadMethod


def inner_contact(
    bearing: Bearing, radial_load: float, method: ElementLoadMethod | str = "stribeck"
) -> ContactLoad:
    """Hertz contact of the most loaded element with the inner race (seed LIFE §2.1, table 3).

    Parameters
    ----------
    bearing : BallBearing or RollerBearing
        Geometry and material.
    radial_load : float
        Radial load F_r [N].
    method : ElementLoadMethod
        Stribeck (seed) or the discrete distribution.
    """
    from ..contact.hertz import ball_contact, roller_contact
    from ..geometry import Race
    from ..load_distribution import radial_load_distribution, stribeck_qmax

    fr = check_positive("radial_load_n", radial_load, "N")
    method = ElementLoadMethod(method)
    if method is ElementLoadMethod.STRIBECK:
        q = stribeck_qmax(bearing, fr)
    else:
        cage = 2 * math.pi / bearing.n_elements * np.linspace(0, 1, 17)[:-1]
        # the load was checked against C0 by check_static_load (no override in this family)
        ld = radial_load_distribution(bearing, 0.0, fr, cage, allow_overload=None)
        q = float(ld.ball_loads.max())
    if isinstance(bearing, BallBearing):
        c = ball_contact(bearing, q, Race.INNER)
        return ContactLoad(q, float(c.p_max), float(c.b), float(c.a), method)
    c = roller_contact(bearing, q, Race.INNER)
    return ContactLoad(q, float(c.p_max), float(c.b), 0.5 * bearing.roller_length, method)


#: array fields of :class:`LifeResult`: name -> (dims, units, description)
_LIFE_VARIABLES: dict[str, tuple[tuple[str, ...], str, str]] = {
    "cycles": (("step",), "1", "cumulative load cycles after each damage block"),
    "damage_max": (("step",), "1", "largest element damage after each block"),
    "n_failed": (("step",), "1", "number of failed elements after each block"),
    "centroids": (("axis", "element"), "m", "core element centroid (x rolling, z depth)"),
    "element_size": (("axis", "element"), "m", "core element width (x) and height (z)"),
    "surface": (("element",), "1", "core element with an edge on the contact surface"),
    "delta_tau0": (("element",), "Pa", "undamaged shear range Delta_tau"),
    "damage_initiation": (("element",), "1", "damage field when the first element failed"),
    "damage_final": (("element",), "1", "damage field at the end (spall or step limit)"),
}
#: scalar fields of :class:`LifeResult`: name -> (units, description)
_LIFE_SCALARS: dict[str, tuple[str, str]] = {
    "cycles_initiation": ("1", "load cycles to the first failed element"),
    "cycles_spall": ("1", "load cycles to the first failed surface element"),
    "initiation_depth": ("m", "depth of the first failed element's centroid"),
    "initiation_x": ("m", "x of the first failed element's centroid"),
    "steps_initiation": ("1", "damage blocks to initiation (-1: not reached)"),
    "steps_spall": ("1", "damage blocks to the spall (-1: not reached)"),
}


@dataclass
class LifeResult(Result):
    """Result of :func:`contact_fatigue_life` (SI arrays plus metadata).

    Attributes
    ----------
    cycles : ndarray, shape (n_steps + 1,)
        Cumulative load cycles after each damage block [cycles].
    damage_max : ndarray, shape (n_steps + 1,)
        Largest element damage after each block [-].
    n_failed : ndarray, shape (n_steps + 1,)
        Number of failed elements (``D = 1``) after each block [-].
    centroids : ndarray, shape (2, n_core)
        ``(x, z)`` of the core elements [m] (``z`` depth).
    element_size : ndarray, shape (2, n_core)
        Width and height of the core elements [m].
    surface : ndarray of bool, shape (n_core,)
        Core elements with an edge on the contact surface.
    delta_tau0 : ndarray, shape (n_core,)
        Undamaged ``Delta_tau`` per core element [Pa].
    damage_initiation : ndarray, shape (n_core,)
        Damage field when the first element failed [-] (zeros if never).
    damage_final : ndarray, shape (n_core,)
        Damage field at the end (spall, or the step limit) [-].
    cycles_initiation : float
        Cycles to the first failed element [cycles] (``nan`` if not reached).
    cycles_spall : float
        Cycles to the first failed element at the surface [cycles] (``nan`` if not reached).
    initiation_depth, initiation_x : float
        Depth and x of the first failed element's centroid [m].
    steps_initiation, steps_spall : int
        Damage blocks to initiation / spall (``-1`` if not reached).
    meta : dict
        Inputs and derived scalars: bearing (id) and bearing_data (the geometry and material),
        radial_load_n, load_method, q_n, p_max_pa, b_m, kappa, sigma_t_pa, law_source,
        delta_d, delta_d_spall, measure, mesh (elements per b), element_size_m, order,
        traverse_m, section_length_m, section_height_m, stop, max_steps, n_elements,
        n_core_elements, n_positions, residual_stiffness, outer_rate_ratio, fe validation,
        solver, n_factorizations, n_preconditioner, n_iterations, n_accepted, wall_s, version.
    """

    FORMAT: ClassVar[str] = "bearingsim.LifeResult/1"

    cycles: NDArray[np.float64]
    damage_max: NDArray[np.float64]
    n_failed: NDArray[np.int64]
    centroids: NDArray[np.float64]
    element_size: NDArray[np.float64]
    surface: NDArray[np.bool_]
    delta_tau0: NDArray[np.float64]
    damage_initiation: NDArray[np.float64]
    damage_final: NDArray[np.float64]
    cycles_initiation: float
    cycles_spall: float
    initiation_depth: float
    initiation_x: float
    steps_initiation: int
    steps_spall: int
    meta: dict = field(default_factory=dict)

    @property
    def wall_s(self) -> float:
        """Wall time of the damage computation [s]."""
        return float(self.meta.get("wall_s", math.nan))

    # ------------------------------------------------------------------ files
    _ARRAYS = tuple(_LIFE_VARIABLES)
    _SCALARS = tuple(_LIFE_SCALARS)

    def to_dataset(self):
        """The result as an :class:`xarray.Dataset`: the damage curve on ``step`` (0..n_steps),
        the core elements' damage fields, shear ranges and geometry on ``element`` (with
        ``axis`` = x, z for centroids and sizes), the outcome scalars as 0-d variables (NaN when
        not reached), every variable with its ``units``; ``meta`` as a JSON attribute."""
        import xarray as xr

        data: dict[str, Any] = {}
        for name, (dims, units, desc) in _LIFE_VARIABLES.items():
            data[name] = (dims, np.asarray(getattr(self, name)), var_attrs(units, desc))
        for name, (units, desc) in _LIFE_SCALARS.items():
            data[name] = ((), getattr(self, name), var_attrs(units, desc))
        coords = {
            "step": ("step", np.arange(self.cycles.size)),
            "element": ("element", np.arange(self.damage_final.size)),
            "axis": ("axis", ["x", "z"]),
        }
        attrs = self._base_attrs(
            model="contact-fatigue life (seed LIFE, damage mechanics)",
            meta_json=json_attr(self.meta),
        )
        return xr.Dataset(data, coords=coords, attrs=attrs)

    @classmethod
    def from_dataset(cls, ds) -> LifeResult:
        """Inverse of :meth:`to_dataset`."""
        cls.check_format(ds)
        arrays = {k: np.asarray(ds[k].values) for k in _LIFE_VARIABLES}
        scal: dict[str, Any] = {k: ds[k].values.item() for k in _LIFE_SCALARS}
        return cls(**arrays, **scal, meta=read_json_attr(ds, "meta_json"))

    # ------------------------------------------------------------------ plots
    def plot_damage_field(self, which: str = "final", zoom_b: float = 4.0):
        """Damage field on the stressed zone (seed LIFE fig. 15 analogue); returns the Figure.

        Parameters
        ----------
        which : {"final", "initiation"}
            Field at the end (spall) or when the first element failed.
        zoom_b : float
            Half-width and depth of the window in units of ``b`` [-].
        """
        from matplotlib.collections import PolyCollection

        from ..plotting import HALF_WIDTH, new_figure

        D = self.damage_final if which == "final" else self.damage_initiation
        cx, cz = self.centroids
        w, h = self.element_size
        x0, x1, z0, z1 = cx - w / 2, cx + w / 2, cz - h / 2, cz + h / 2
        verts = np.stack([np.c_[x0, z0], np.c_[x1, z0], np.c_[x1, z1], np.c_[x0, z1]], axis=1)
        b = float(self.meta["b_m"])
        depth = min(zoom_b, float(cz.max() + h.max()) / b)
        # height for the equal-aspect box (about 3.8 in of the width) plus title and x axis
        fig, ax = new_figure(width=HALF_WIDTH, height=1.1 + 3.8 * depth / (2 * zoom_b))
        pc = PolyCollection(verts / b, array=D, cmap="jet", edgecolors="face", linewidths=0.1)
        pc.set_clim(0.0, 1.0)
        ax.add_collection(pc)
        failed = D >= 1.0
        if np.any(failed):
            ax.plot(cx[failed] / b, cz[failed] / b, "ws", ms=2, mfc="none", mew=0.5)
        ax.set_xlim(-zoom_b, zoom_b)
        ax.set_ylim(depth, 0)
        ax.set_aspect("equal")
        ax.set_xlabel("x / b [-]")
        ax.set_ylabel("depth z / b [-]")
        fig.colorbar(pc, ax=ax, label="damage D [-]")
        n = (
            self.cycles_spall
            if which == "final" and np.isfinite(self.cycles_spall)
            else (self.cycles_initiation if which != "final" else float(self.cycles[-1]))
        )
        ax.set_title(f"{self.meta.get('bearing', '')} damage field ({which}),\nN = {n:.4g} cycles")
        return fig

    def plot_damage_curve(self):
        """Largest damage and number of failed elements vs load cycles [10^6 cycles] (left) and,
        when the run went on after the first failure, the failed elements against the cycles
        after it (right: initiation and spall are often too close to tell apart on the left);
        returns the Figure."""
        from matplotlib.ticker import MaxNLocator

        from ..plotting import FULL_WIDTH, new_figure

        init, spall = self.cycles_initiation, self.cycles_spall
        after = np.isfinite(init) & (self.cycles >= init)
        two = int(np.count_nonzero(after)) > 1
        fig, axs = new_figure(1, 2 if two else 1, width=FULL_WIDTH, height=3.6, squeeze=False)
        ax = axs[0, 0]
        ax.plot(self.cycles / 1e6, self.damage_max, "b-", label="largest damage D")
        ax.set_xlabel("load cycles N [10⁶ cycles]")
        ax.set_ylabel("largest element damage D [-]", color="b")
        ax2 = ax.twinx()
        ax2.plot(self.cycles / 1e6, self.n_failed, "r-", label="failed elements")
        ax2.set_ylabel("failed elements [-]", color="r")
        ax2.yaxis.set_major_locator(MaxNLocator(integer=True))
        for val, lab, st in ((init, "initiation", "--"), (spall, "spall", ":")):
            if np.isfinite(val):
                ax.axvline(val / 1e6, color="k", ls=st, lw=1, label=f"{lab}, N = {val:.4g}")
        ax.set_title("damage evolution (semi-decoupled, seed LIFE eqs. (7)-(8))")
        if two:
            a = axs[0, 1]
            a.step(self.cycles[after] - init, self.n_failed[after], "r-", where="post")
            if np.isfinite(spall):
                a.axvline(spall - init, color="k", ls=":", lw=1)
            a.set_xlabel("load cycles after the first failure N - N_init [cycles]")
            a.set_ylabel("failed elements [-]")
            a.yaxis.set_major_locator(MaxNLocator(integer=True))
            a.set_title("after initiation")
        handles = ax.get_legend_handles_labels()[0] + ax2.get_legend_handles_labels()[0]
        fig.legend(handles=handles, loc="outside lower center", ncols=len(handles))
        return fig


def contact_fatigue_life(
    bearing: Bearing,
    radial_load: float,
    *,
    mesh: str | float = "default",
    element_size: float | None = None,
    delta_d: float = 0.001,
    delta_d_spall: float | None = 0.1,
    law: DamageLaw | None = None,
    measure: ShearMeasure | str = DEFAULT_MEASURE,
    load_method: ElementLoadMethod | str = ElementLoadMethod.STRIBECK,
    stop: str = "spall",
    max_steps: int = 20000,
    residual_stiffness: float = 1e-3,
    length: float = 12e-3,
    height: float = 4e-3,
    traverse_b: float = 2.0,
    order: int = 1,
    solver: str = "pcg",
    progress: bool = False,
) -> LifeResult:
    """Contact-fatigue life of the most loaded inner-race contact (seed LIFE §2.3, eqs. (2),
    (4), (7)–(9)); see the module docstring.

    Parameters
    ----------
    bearing : BallBearing or RollerBearing
        Geometry and material (E, nu of the race).
    radial_load : float
        Radial load F_r [N]; refused above twice the static capacity, warned above it.
    mesh : {"coarse", "default", "fine", "finer"} or float
        Fine-zone elements per contact semi-width b [-] (5, 10, 16, 24).
    element_size : float, optional
        Explicit fine element size [m] (must be <= b/4).
    delta_d : float
        Damage increment of the fastest element per block, Delta_D [-] (seed: 0.001).
    delta_d_spall : float or None
        Block size after initiation (growth of the failed zone to the surface) [-]; ``None``
        uses ``delta_d``. Default 0.1: the cycles spent between initiation and spall are
        2.5e-7 of the life, and on the default mesh 0.1, 0.01 and 0.001 fail the same elements
        and give the same spall life to 2.3e-7 (6206 at 5 kN, docs/validation.md), while with
        0.001 the growth to the surface takes 16 000 blocks (0.01: 1600; 0.1: 170). On the
        coarse mesh (Tresca measure) 0.03 and above fail 24 elements instead of 26: use
        0.01 there when the shape of the failed zone matters.
    law : DamageLaw, optional
        kappa [-], sigma_t [Pa]; default the seed's GCr15 fit (11.1, 5979 MPa).
    measure : ShearMeasure or str
        Which shear range drives damage (default ``max_shear``: the range of the in-plane
        Tresca shear, the seed's table-3 damage driver; see :class:`ShearMeasure` for why);
        an unknown name is refused with the valid ones.
    load_method : ElementLoadMethod
        Most-loaded element load: Stribeck 4.37 F_r/Z (seed; 4.08 for roller bearings) or the
        discrete distribution.
    stop : {"spall", "initiation"}
        Stop at the first failed surface element, or at the first failed element.
    max_steps : int
        Limit on damage blocks [-]; at least ``1 / delta_d``, the blocks the fastest element
        needs to fail (refused otherwise, before any work).
    residual_stiffness : float
        Stiffness fraction kept by failed elements [-], in (0, 0.1].
    length, height : float
        Section size [m] (seed: 12 mm x 4 mm).
    traverse_b : float
        Half-length of the load traverse in units of b [-].
    order : int
        Element order (1 bilinear, 2 biquadratic).
    solver : {"pcg", "direct"}
        How each block's FE system is solved: ``"pcg"`` (default) conjugate gradients from the
        extrapolation of the previous blocks' displacements (accepted without iterating when
        it already meets the tolerance), preconditioned by the factorization of an earlier
        block, on the load positions ``x_c <= 0`` (the others are their mirror images:
        :class:`~bearingsim.life.fe.CoreSubstructure`); residual below 1e-5 of the load
        (:class:`~bearingsim.life.block_solver.BlockSolver`); ``"direct"``: a new sparse LU
        factorization every block, all positions (the reference).
    progress : bool
        Show a progress bar on stderr.
    """
    from tqdm import tqdm

    from .iso281 import STATIC_LIMIT_FACTOR, check_static_load

    fr = check_positive("radial_load_n", radial_load, "N")
    dd = check_range("delta_d", delta_d, 0.0, 0.1, lo_open=True)
    dd_sp = (
        dd
        if delta_d_spall is None
        else check_range("delta_d_spall", delta_d_spall, 0.0, 0.1, lo_open=True)
    )
    dd_now = dd
    res_k = check_range("residual_stiffness", residual_stiffness, 0.0, 0.1, lo_open=True)
    if stop not in ("spall", "initiation"):
        raise ConfigError(f"stop = {stop!r} is invalid; valid values 'spall', 'initiation'")
    max_steps = int(check_range("max_steps", max_steps, 1, 10_000_000))
    if dd * max_steps < 1.0:  # the fastest element gains delta_d per block, from D = 0 to 1
        fix = f"max_steps >= {math.ceil(1.0 / dd - 1e-9):.6g}"
        if max_steps >= 10:  # else no delta_d <= 0.1 fails an element within max_steps
            fix = f"delta_d in [{1.0 / max_steps:.6g}, 0.1], or " + fix
        raise ConfigError(
            f"delta_d = {dd:.6g} needs at least {1.0 / dd:.6g} damage blocks to fail an element, "
            f"more than max_steps = {max_steps}; valid: delta_d * max_steps >= 1 ({fix})"
        )
    measure = ShearMeasure.parse(measure)
    if solver not in ("pcg", "direct"):
        raise ConfigError(f"solver = {solver!r} is invalid; valid values 'pcg', 'direct'")
    law = law if law is not None else default_damage_law()
    cap = check_static_load(bearing, fr)
    contact = inner_contact(bearing, fr, load_method)
    if contact.b < MIN_CONTACT_HALF_WIDTH_M:
        # Hertz: b grows as Q^(1/3) (point contact) or Q^(1/2) (line contact), Q ~ F_r
        e = 3.0 if isinstance(bearing, BallBearing) else 2.0
        f_min = fr * (MIN_CONTACT_HALF_WIDTH_M / contact.b) ** e
        raise ConfigError(
            f"radial_load_n = {fr:.6g} N gives a contact semi-width b = {contact.b:.3g} m, below "
            f"the {MIN_CONTACT_HALF_WIDTH_M:g} m (the raceway roughness) under which the "
            f"smooth-surface Hertz contact and the FE section do not apply; valid range "
            f"[{f_min:.3g}, {STATIC_LIMIT_FACTOR * cap.c0:.6g}] N"
        )
    spec = section_spec(
        contact.b,
        mesh,
        length=length,
        height=height,
        traverse_b=traverse_b,
        order=order,
        element_size=element_size,
    )
    t0 = time.perf_counter()
    section = contact_section(bearing.material, contact.p_max, contact.b, spec)
    core = core_substructure(section)
    # undamaged full model: validation against Hertz and the outer-region rate check
    st_full = section.solve()
    val = validate_against_hertz(section, st_full)
    dtau_full = st_full.shear_range(measure)
    outer = np.ones(section.n_elements, dtype=bool)
    outer[core.elements] = False
    rate_in = float(np.max(dtau_full[core.elements]))
    rate_out = float(np.max(dtau_full[outer])) if np.any(outer) else 0.0
    with np.errstate(over="ignore", under="ignore"):  # a float's range checked just below
        outer_ratio = float(np.float64(rate_out / rate_in) ** law.kappa) if rate_in > 0 else 0.0
        rate0 = float(np.float64(rate_in / law.sigma_t) ** law.kappa)  # seed LIFE eq. (4), D = 0
    if not 0.0 < rate0 < math.inf:
        # constants that put the first block's rate outside the float range (kappa = 1e6
        # underflowed to 0, sigma_t = 1e-300 Pa overflowed to inf: "no element is being damaged")
        raise ConfigError(
            f"kappa = {law.kappa:.6g} and sigma_t_pa = {law.sigma_t:.6g} Pa give the most "
            f"stressed element (shear range {rate_in:.6g} Pa) a damage rate "
            f"(delta_tau/sigma_t)^kappa = {rate0:.3g} per cycle; valid: constants whose rate is "
            "finite and > 0 (the defaults: the GCr15 fit, seed LIFE eqs. (5)-(6))"
        )
    t_setup = time.perf_counter() - t0

    n = core.n_elements
    cx, cz = section.centroids[:, core.elements]
    pts = section.mesh.p[:, section.mesh.t[:, core.elements]]
    width = pts[0].max(axis=0) - pts[0].min(axis=0)
    hgt = pts[1].max(axis=0) - pts[1].min(axis=0)
    surf = section.surface[core.elements]
    D = np.zeros(n)
    failed = np.zeros(n, dtype=bool)
    N = 0.0
    cyc, dmax, nfail = [0.0], [0.0], [0]
    d_init = np.zeros(n)
    n_init = n_spall = math.nan
    s_init = s_spall = -1
    z_init = x_init = math.nan
    dtau0 = None
    blocks = core.block_solver() if solver == "pcg" else None
    bar = tqdm(desc="damage blocks", unit="block", disable=not progress, leave=False)
    t1 = time.perf_counter()
    try:
        for step in range(1, max_steps + 1):
            fac = np.maximum(1.0 - D, res_k)
            if blocks is None:
                dtau = core.solve(fac).shear_range(measure)
            else:
                dtau = core.shear_range_from(blocks.solve(fac), fac, measure)
            if dtau0 is None:
                dtau0 = dtau.copy()
            rate = (dtau / (law.sigma_t * fac)) ** law.kappa  # seed LIFE eq. (4)
            rate[failed] = 0.0
            j = int(np.argmax(rate))
            if not rate[j] > 0.0:
                raise SolverError("contact_fatigue_life: no element is being damaged")
            dN = dd_now / rate[j]  # seed LIFE eq. (7)
            D += dN * rate  # seed LIFE eq. (8)
            N += dN
            # an element within 1e-3 Delta_D of D = 1 is failed: it would reach 1 in the next
            # block in a vanishing number of cycles (its rate grows as (1 - D)^-kappa)
            newly = (D >= 1.0 - 1e-3 * dd_now) & ~failed
            D[newly] = 1.0
            failed |= newly
            cyc.append(N)
            dmax.append(float(D.max()))
            nfail.append(int(failed.sum()))
            bar.update(1)
            if progress and step % 50 == 0:
                bar.set_postfix_str(f"N={N:.3g} Dmax={D.max():.3f} failed={failed.sum()}")
            if np.any(newly) and s_init < 0:
                s_init, n_init = step, N
                d_init = D.copy()
                first = np.flatnonzero(newly)
                k = first[np.argmax(dtau0[first])]
                z_init, x_init = float(cz[k]), float(cx[k])
                dd_now = dd_sp
                if stop == "initiation":
                    break
            if np.any(newly & surf):
                s_spall, n_spall = step, N
                break
    finally:
        bar.close()
    wall = time.perf_counter() - t1
    if s_init < 0:
        warnings.warn(
            f"contact_fatigue_life: no element failed within max_steps = {max_steps}",
            RuntimeWarning,
            stacklevel=2,
        )
    elif stop == "spall" and s_spall < 0:
        warnings.warn(
            f"contact_fatigue_life: the failed zone did not reach the surface within "
            f"max_steps = {max_steps}",
            RuntimeWarning,
            stacklevel=2,
        )
    meta = {
        "bearing": bearing.id,
        "bearing_data": json.loads(json_attr(dataclasses.asdict(bearing))),
        "radial_load_n": fr,
        "q_n": contact.q,
        "load_method": contact.method.value,
        "p_max_pa": contact.p_max,
        "b_m": contact.b,
        "a_m": contact.a,
        "kappa": law.kappa,
        "sigma_t_pa": law.sigma_t,
        "law_source": law.source,
        "delta_d": dd,
        "delta_d_spall": dd_sp,
        "measure": measure.value,
        "mesh": mesh if element_size is None else "custom",
        "element_size_m": spec.element_size,
        "order": spec.order,
        "traverse_m": spec.traverse,
        "section_length_m": spec.length,
        "section_height_m": spec.height,
        "n_elements": section.n_elements,
        "n_core_elements": n,
        "n_core_dofs": core.n_dofs,
        "n_positions": section.n_positions,
        "residual_stiffness": res_k,
        "stop": stop,
        "max_steps": max_steps,
        "outer_rate_ratio": outer_ratio,
        "fe_tau_max_pa": val.tau_max_fe,
        "fe_tau_depth_m": val.depth_fe,
        "fe_tau_error": val.tau_error,
        "fe_depth_error": val.depth_error,
        "solver": solver,
        "n_factorizations": len(cyc) - 1 if blocks is None else blocks.n_factorizations,
        "n_preconditioner": 0 if blocks is None else blocks.n_preconditioner,
        "n_iterations": 0 if blocks is None else blocks.n_iterations,
        "n_accepted": 0 if blocks is None else blocks.n_accepted,
        "n_steps": len(cyc) - 1,
        "setup_s": t_setup,
        "wall_s": wall,
        "time_per_step_s": wall / max(1, len(cyc) - 1),
        "version": __version__,
    }
    return LifeResult(
        cycles=np.asarray(cyc),
        damage_max=np.asarray(dmax),
        n_failed=np.asarray(nfail, dtype=np.int64),
        centroids=np.vstack([cx, cz]),
        element_size=np.vstack([width, hgt]),
        surface=surf,
        delta_tau0=dtau0 if dtau0 is not None else np.zeros(n),
        damage_initiation=d_init,
        damage_final=D,
        cycles_initiation=float(n_init),
        cycles_spall=float(n_spall),
        initiation_depth=z_init,
        initiation_x=x_init,
        steps_initiation=int(s_init),
        steps_spall=int(s_spall),
        meta=meta,
    )
