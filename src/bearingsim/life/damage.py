"""Continuum-damage law for shear-driven high-cycle fatigue and its fit to S–N data.

Seed LIFE (Zhang, Chen et al., J. Aerospace Power 2019, §1.1):

- damage evolution (eq. (4)): ``dD/dN = [Delta_tau / (sigma_t (1 - D))]^kappa`` with ``Delta_tau``
  the *range* of the damaging shear stress (twice its amplitude) and ``D`` in [0, 1];
- integrated from ``D = 0`` to ``D = 1`` at constant nominal stress (eq. (6)):
  ``N_f = (sigma_t / Delta_tau)^kappa / (kappa + 1)``, i.e.
  ``Delta_tau = sigma_t (kappa + 1)^(-1/kappa) N_f^(-1/kappa)``;
- the GCr15 torsional S–N curve of Shimizu, Tsuchiya & Tosha (Tribol. Trans. 52(6) 2009) fitted as
  the power law ``Delta_tau/2 = 2.3879 GPa N^-0.090092`` (eq. (5)), which gives
  ``kappa = 11.1`` and ``sigma_t = 5979 MPa``.

The fit works for any S–N data: a power law ``tau_a = A N^-m`` maps exactly onto eq. (6)
(``kappa = 1/m``, ``sigma_t = 2 A (kappa+1)^(1/kappa)``), and a set of points is fitted by linear
least squares on ``log Delta_tau = log(sigma_t (kappa+1)^(-1/kappa)) - (1/kappa) log N``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ..errors import ConfigError, check_positive, check_range

__all__ = [
    "cycles_to_failure",
    "damage_rate",
    "DamageLaw",
    "fit_sn_curve",
    "GCR15_TORSION",
    "integrate_uniform",
    "SNCurve",
    "SNFit",
    "torsion_check",
    "TorsionCheck",
]


@dataclass(frozen=True)
class DamageLaw:
    """Parameters of the damage law ``dD/dN = [Delta_tau/(sigma_t (1-D))]^kappa`` (seed LIFE
    eq. (4)).

    Parameters
    ----------
    kappa : float
        Damage exponent kappa [-], > 0.
    sigma_t : float
        Damage resistance sigma_t [Pa], > 0.
    source : str
        Where the values come from.
    """

    kappa: float
    sigma_t: float
    source: str = ""

    def __post_init__(self) -> None:
        object.__setattr__(self, "kappa", check_positive("kappa", self.kappa))
        object.__setattr__(self, "sigma_t", check_positive("sigma_t_pa", self.sigma_t, "Pa"))

    def rate(self, delta_tau: ArrayLike, damage: ArrayLike = 0.0) -> NDArray[np.float64]:
        """Damage rate per cycle ``dD/dN`` [1/cycle] (seed LIFE eq. (4)).

        Parameters
        ----------
        delta_tau : array_like
            Shear-stress range Delta_tau [Pa] (>= 0).
        damage : array_like
            Current damage D [-] in [0, 1); broadcast against ``delta_tau``.
        """
        return damage_rate(delta_tau, damage, self.kappa, self.sigma_t)

    def cycles_to_failure(self, delta_tau: ArrayLike) -> NDArray[np.float64]:
        """Cycles from ``D = 0`` to ``D = 1`` at constant nominal ``Delta_tau`` [cycles]
        (seed LIFE eq. (6))."""
        return cycles_to_failure(delta_tau, self.kappa, self.sigma_t)

    def stress_range(self, n_cycles: ArrayLike) -> NDArray[np.float64]:
        """Shear-stress range that fails in ``n_cycles`` cycles [Pa] (seed LIFE eq. (6))."""
        n = np.asarray(n_cycles, dtype=float)
        return self.sigma_t * (self.kappa + 1.0) ** (-1.0 / self.kappa) * n ** (-1.0 / self.kappa)


def damage_rate(
    delta_tau: ArrayLike, damage: ArrayLike, kappa: float, sigma_t: float
) -> NDArray[np.float64]:
    """``dD/dN = [Delta_tau / (sigma_t (1 - D))]^kappa`` [1/cycle] (seed LIFE eq. (4)).

    Parameters
    ----------
    delta_tau : array_like
        Range of the damaging shear stress [Pa].
    damage : array_like
        Damage D [-], in [0, 1).
    kappa : float
        Damage exponent [-].
    sigma_t : float
        Damage resistance [Pa].
    """
    dt = np.abs(np.asarray(delta_tau, dtype=float))
    d = np.asarray(damage, dtype=float)
    return (dt / (sigma_t * (1.0 - d))) ** kappa


def cycles_to_failure(delta_tau: ArrayLike, kappa: float, sigma_t: float) -> NDArray[np.float64]:
    """Cycles to ``D = 1`` at constant nominal range ``Delta_tau`` [cycles]:
    ``N_f = (sigma_t/Delta_tau)^kappa / (kappa + 1)`` (seed LIFE eq. (6), integral of eq. (4))."""
    dt = np.asarray(delta_tau, dtype=float)
    with np.errstate(divide="ignore"):
        return (sigma_t / dt) ** kappa / (kappa + 1.0)


@dataclass(frozen=True)
class SNCurve:
    """Power-law S–N curve of the shear-stress *amplitude*: ``tau_a = A N^-m``.

    Parameters
    ----------
    coefficient : float
        ``A`` [Pa] (amplitude at N = 1).
    exponent : float
        ``m`` [-], > 0.
    source : str
        Origin of the curve.
    n_range : tuple of float
        Range of cycles [cycles] over which the curve was fitted to tests (for plots).
    """

    coefficient: float
    exponent: float
    source: str = ""
    n_range: tuple[float, float] = (1e5, 1e9)

    def __post_init__(self) -> None:
        check_positive("sn_coefficient_pa", self.coefficient, "Pa")
        check_positive("sn_exponent", self.exponent)

    def amplitude(self, n_cycles: ArrayLike) -> NDArray[np.float64]:
        """Shear amplitude tau_a = A N^-m [Pa] at ``n_cycles`` [cycles]."""
        return self.coefficient * np.asarray(n_cycles, dtype=float) ** (-self.exponent)

    def cycles(self, amplitude: ArrayLike) -> NDArray[np.float64]:
        """Cycles to failure [cycles] at shear amplitude ``amplitude`` [Pa]."""
        return (np.asarray(amplitude, dtype=float) / self.coefficient) ** (-1.0 / self.exponent)


#: GCr15 (AISI 52100) torsional S–N curve, shear amplitude [Pa] vs cycles: seed LIFE eq. (5),
#: the seed's power-law fit to the alternating-torsion tests of Shimizu, Tsuchiya & Tosha (2009).
GCR15_TORSION = SNCurve(
    coefficient=2.3879e9,
    exponent=0.090092,
    source=(
        "seed LIFE eq. (5): power-law fit of the GCr15 alternating-torsion S-N data of "
        "Shimizu, Tsuchiya & Tosha, Tribol. Trans. 52(6):807-816 (2009)"
    ),
    n_range=(1e5, 1e9),
)


@dataclass(frozen=True)
class SNFit:
    """Result of :func:`fit_sn_curve`.

    Attributes
    ----------
    law : DamageLaw
        Fitted kappa [-] and sigma_t [Pa].
    n_cycles, delta_tau : ndarray
        Data used [cycles], [Pa] (ranges, twice the amplitudes).
    residual_rms : float
        RMS of the residual of ``log10 Delta_tau`` [-] (0 for an exact power law).
    """

    law: DamageLaw
    n_cycles: NDArray[np.float64] = field(repr=False)
    delta_tau: NDArray[np.float64] = field(repr=False)
    residual_rms: float = 0.0

    def plot(self, curve: SNCurve | None = None):
        """The S–N data and the fitted integrated law (seed LIFE fig. 1 analogue); returns the
        Figure."""
        from ..plotting import HALF_WIDTH, new_figure

        fig, ax = new_figure(width=HALF_WIDTH, height=4.4)
        lo, hi = float(self.n_cycles.min()), float(self.n_cycles.max())
        n = np.logspace(math.log10(lo), math.log10(hi), 200)
        if curve is not None:
            lab = f"S-N curve ({curve.source.split(':')[0]})"
            ax.semilogx(n, curve.amplitude(n) / 1e6, "k-", lw=2, label=lab)
        ax.semilogx(self.n_cycles, self.delta_tau / 2e6, "o", ms=4, label="data (amplitude)")
        ax.semilogx(
            n,
            self.law.stress_range(n) / 2e6,
            "r--",
            label=f"damage law eq. (6): κ = {self.law.kappa:.3f}, "
            f"σ_t = {self.law.sigma_t / 1e6:.0f} MPa",
        )
        ax.set_xlabel("cycles to failure N [cycles]")
        ax.set_ylabel("shear stress amplitude [MPa]")
        ax.grid(True, which="both", alpha=0.3)
        fig.legend(loc="outside lower center")
        ax.set_title("GCr15 torsional S-N curve and damage-law fit\n(seed LIFE fig. 1)")
        return fig


def fit_sn_curve(
    curve: SNCurve | None = None,
    *,
    n_cycles: ArrayLike | None = None,
    tau_amplitude: ArrayLike | None = None,
    source: str = "",
) -> SNFit:
    """Fit kappa and sigma_t of the damage law to S–N data through its integral (seed LIFE
    eqs. (5)–(6)).

    Give either a power-law ``curve`` (exact mapping ``kappa = 1/m``,
    ``sigma_t = 2 A (kappa + 1)^(1/kappa)``) or points ``n_cycles``/``tau_amplitude`` (least
    squares on ``log Delta_tau = log(sigma_t (kappa+1)^(-1/kappa)) - log(N)/kappa``).

    Parameters
    ----------
    curve : SNCurve, optional
        Power-law amplitude curve ``tau_a = A N^-m``.
    n_cycles : array_like, optional
        Cycles to failure of each test [cycles], > 0.
    tau_amplitude : array_like, optional
        Shear-stress amplitude of each test [Pa], > 0 (``Delta_tau = 2 tau_a``).
    source : str
        Label of the data.

    Returns
    -------
    SNFit
    """
    if curve is not None:
        if n_cycles is not None or tau_amplitude is not None:
            raise ConfigError("fit_sn_curve: give either a curve or points, not both")
        kappa = 1.0 / curve.exponent
        sigma_t = 2.0 * curve.coefficient * (kappa + 1.0) ** (1.0 / kappa)
        lo, hi = curve.n_range
        n = np.logspace(math.log10(lo), math.log10(hi), 9)
        return SNFit(
            DamageLaw(kappa, sigma_t, source or curve.source), n, 2.0 * curve.amplitude(n), 0.0
        )
    if n_cycles is None or tau_amplitude is None:
        raise ConfigError("fit_sn_curve: give a curve or both n_cycles and tau_amplitude")
    n = np.asarray(n_cycles, dtype=float).ravel()
    ta = np.asarray(tau_amplitude, dtype=float).ravel()
    if n.size != ta.size:
        raise ConfigError(
            f"fit_sn_curve: n_cycles has {n.size} values but tau_amplitude has {ta.size}"
        )
    if n.size < 2:
        raise ConfigError(f"fit_sn_curve: {n.size} S-N points; valid range [2, inf) points")
    for name, arr, unit in (("n_cycles", n, "cycles"), ("tau_amplitude_pa", ta, "Pa")):
        if not np.all(np.isfinite(arr)) or np.any(arr <= 0):
            bad = arr[~(np.isfinite(arr) & (arr > 0))][0]
            check_positive(name, bad, unit)
    if np.ptp(np.log(n)) == 0.0:
        raise ConfigError("fit_sn_curve: all n_cycles are equal; the slope is undetermined")
    dt = 2.0 * ta
    A = np.c_[np.ones_like(n), np.log(n)]
    coef, *_ = np.linalg.lstsq(A, np.log(dt), rcond=None)
    intercept, slope = float(coef[0]), float(coef[1])
    if slope >= 0.0:
        raise ConfigError(
            f"fit_sn_curve: S-N slope d(log tau)/d(log N) = {slope:.4g} >= 0; valid range (-inf, 0)"
        )
    kappa = -1.0 / slope
    sigma_t = math.exp(intercept) * (kappa + 1.0) ** (1.0 / kappa)
    res = (np.log(dt) - A @ coef) / math.log(10.0)
    return SNFit(DamageLaw(kappa, sigma_t, source), n, dt, float(np.sqrt(np.mean(res**2))))


def integrate_uniform(
    law: DamageLaw, delta_tau: float, delta_d: float = 0.001
) -> tuple[float, NDArray[np.float64], NDArray[np.float64]]:
    """Semi-decoupled block integration of eq. (4) for one element at constant nominal
    ``Delta_tau`` (seed LIFE eqs. (7)–(8) with a single element).

    Each block adds ``Delta_D`` with the rate frozen at the block start:
    ``Delta_N_i = Delta_D / (dD/dN)(D_i)``. This is the left Riemann sum of the exact integral
    (eq. (6)) and converges to it as ``Delta_D -> 0`` (over-estimate ~ ``Delta_D (kappa+1)/2``
    relative).

    Parameters
    ----------
    law : DamageLaw
        kappa [-], sigma_t [Pa].
    delta_tau : float
        Shear-stress range [Pa], > 0.
    delta_d : float
        Damage increment per block [-], in (0, 1].

    Returns
    -------
    cycles : float
        Cycles to ``D = 1`` [cycles].
    n_history, d_history : ndarray
        Cumulative cycles [cycles] and damage [-] after each block (starting at 0).
    """
    dt = check_positive("delta_tau_pa", delta_tau, "Pa")
    dd = check_range("delta_d", delta_d, 0.0, 1.0, lo_open=True)
    n_blocks = int(math.ceil(1.0 / dd - 1e-9))
    d = np.minimum(np.arange(n_blocks + 1) * dd, 1.0)
    rates = law.rate(dt, d[:-1])
    dn = np.diff(d) / rates
    n_hist = np.concatenate([[0.0], np.cumsum(dn)])
    return float(n_hist[-1]), n_hist, d


@dataclass(frozen=True)
class TorsionCheck:
    """Seed LIFE §1.2 torsion check: predicted vs S–N lives over a range of shear amplitudes.

    Attributes
    ----------
    tau_amplitude : ndarray
        Shear amplitudes [Pa].
    cycles_predicted : ndarray
        Cycles to ``D = 1`` from the block-integrated damage law [cycles].
    cycles_exact : ndarray
        Exact integral of eq. (4) (eq. (6)) [cycles].
    cycles_sn : ndarray
        Cycles from the S–N curve [cycles].
    law : DamageLaw
        Law used.
    delta_d : float
        Block size [-].
    curve : SNCurve
        S–N curve compared with.
    """

    tau_amplitude: NDArray[np.float64]
    cycles_predicted: NDArray[np.float64]
    cycles_exact: NDArray[np.float64]
    cycles_sn: NDArray[np.float64]
    law: DamageLaw
    delta_d: float
    curve: SNCurve

    def plot(self):
        """Predicted vs S–N lives (seed LIFE fig. 3 analogue); returns the Figure."""
        from ..plotting import HALF_WIDTH, new_figure

        fig, ax = new_figure(width=HALF_WIDTH, height=4.4)
        ta = self.tau_amplitude / 1e6
        n = np.logspace(
            math.log10(self.cycles_sn.min() / 3), math.log10(self.cycles_sn.max() * 3), 200
        )
        ax.semilogx(n, self.curve.amplitude(n) / 1e6, "k-", label="S-N curve (seed eq. (5))")
        ax.semilogx(
            self.cycles_predicted,
            ta,
            "rs",
            mfc="none",
            label=f"damage law, blocks ΔD = {self.delta_d:g}",
        )
        ax.semilogx(self.cycles_exact, ta, "b+", label="damage law, exact eq. (6)")
        ax.set_xlabel("cycles to failure N [cycles]")
        ax.set_ylabel("shear stress amplitude [MPa]")
        ax.grid(True, which="both", alpha=0.3)
        fig.legend(loc="outside lower center")
        ax.set_title("GCr15 torsion: predicted vs S-N life\n(seed LIFE fig. 3)")
        return fig


def torsion_check(
    law: DamageLaw,
    curve: SNCurve = GCR15_TORSION,
    tau_amplitudes: ArrayLike | None = None,
    delta_d: float = 0.001,
) -> TorsionCheck:
    """The seed's torsion check (seed LIFE §1.2, fig. 3): fully reversed uniform shear with
    amplitude 1000 → 400 MPa in 50 MPa steps, life from the damage law vs the S–N curve.

    A uniformly stressed torsion specimen has no stress redistribution, so each amplitude is one
    element integrated with the semi-decoupled blocks of eqs. (7)–(8); ``Delta_tau = 2 tau_a``.

    Parameters
    ----------
    law : DamageLaw
        kappa [-], sigma_t [Pa].
    curve : SNCurve
        S–N curve to compare with.
    tau_amplitudes : array_like, optional
        Shear amplitudes [Pa]; default 1000 → 400 MPa by 50 MPa (seed LIFE §1.2).
    delta_d : float
        Damage block size [-].
    """
    if tau_amplitudes is None:
        ta = np.arange(1000.0, 399.0, -50.0) * 1e6
    else:
        ta = np.atleast_1d(np.asarray(tau_amplitudes, dtype=float))
    pred = np.array([integrate_uniform(law, 2.0 * t, delta_d)[0] for t in ta])
    return TorsionCheck(
        tau_amplitude=ta,
        cycles_predicted=pred,
        cycles_exact=law.cycles_to_failure(2.0 * ta),
        cycles_sn=curve.cycles(ta),
        law=law,
        delta_d=delta_d,
        curve=curve,
    )
