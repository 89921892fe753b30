"""Two-parameter Weibull view of fatigue lives: test scatter, rating lives and a predicted life.

Bearing fatigue lives scatter along a two-parameter Weibull distribution
``F(L) = 1 - exp(-(L/eta)^beta)`` (Lundberg & Palmgren 1947; ISO 281 rests on it). A handful of
tests is plotted at Bernard's median ranks ``F_i = (i - 0.3)/(n + 0.4)`` on Weibull paper
(``ln ln 1/(1 - F)`` against ``ln L``, where the distribution is a straight line of slope
``beta``); the line through them is the maximum-likelihood fit
(:func:`scipy.stats.weibull_min.fit`, location fixed at 0).

Nothing here calibrates a model: a predicted life is placed on the tests' distribution
(:meth:`WeibullFit.probability_at`) and shown beside it, whatever it shows.
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass

import numpy as np

from ..errors import ConfigError

__all__ = [
    "LP_SLOPE_POINT",
    "median_ranks",
    "rating_life_ratio",
    "weibull_fit",
    "WeibullFit",
]

#: Weibull slope of ball-bearing (point-contact) lives in Lundberg & Palmgren's theory [-]; the
#: exponent ``e = 10/9`` of ISO/TS 16281's life summation (``reference_life``)
LP_SLOPE_POINT = 10.0 / 9.0


def median_ranks(n: int) -> np.ndarray:
    """Bernard's approximation of the median ranks of ``n`` ordered failures [-]."""
    if n < 1:
        raise ConfigError(f"n = {n} failures; valid: n >= 1")
    i = np.arange(1, n + 1)
    return (i - 0.3) / (n + 0.4)


def rating_life_ratio(f: float, beta: float = LP_SLOPE_POINT) -> float:
    """``L_F / L_10`` for a Weibull population of slope ``beta`` [-]: e.g. ``f = 0.5`` gives the
    median life in units of L10 (5.45 for ``beta = 10/9``)."""
    if not 0.0 < f < 1.0:
        raise ConfigError(f"failure probability f = {f!r}; valid range (0, 1)")
    return (math.log(1.0 / (1.0 - f)) / math.log(1.0 / 0.9)) ** (1.0 / beta)


@dataclass(frozen=True)
class WeibullFit:
    """Weibull fit of a set of lives.

    Attributes
    ----------
    lives : tuple of float
        The lives, ascending [cycles or rev, as given].
    ranks : tuple of float
        Their median ranks (failure probabilities) [-].
    beta : float
        Weibull slope [-].
    eta : float
        Characteristic life (63.2 % failed) [same unit as ``lives``].
    """

    lives: tuple[float, ...]
    ranks: tuple[float, ...]
    beta: float
    eta: float

    def life_at(self, f: float) -> float:
        """Life by which a fraction ``f`` has failed [unit of ``lives``]."""
        if not 0.0 < f < 1.0:
            raise ConfigError(f"failure probability f = {f!r}; valid range (0, 1)")
        return self.eta * (-math.log1p(-f)) ** (1.0 / self.beta)

    def probability_at(self, life: float) -> float:
        """Fraction of the population failed by ``life`` [-]."""
        if not life >= 0.0:
            raise ConfigError(f"life = {life!r}; valid range [0, inf)")
        return -math.expm1(-((life / self.eta) ** self.beta))

    @property
    def l10(self) -> float:
        """The 10 % life of the fitted distribution [unit of ``lives``]."""
        return self.life_at(0.1)

    @property
    def l50(self) -> float:
        """The median life of the fitted distribution [unit of ``lives``]."""
        return self.life_at(0.5)

    def plot(
        self,
        marks: Mapping[str, float] | None = None,
        unit: str = "cycles",
        title: str = "",
        line_label: str | None = None,
        points: bool = True,
    ):
        """Weibull-paper plot: the lives at their median ranks (``points``), the fitted line
        (``line_label``, default "Weibull fit of the tests") and vertical lines at ``marks``
        (label -> life, e.g. a predicted life, L10); returns the figure."""
        from ..plotting import ANNOTATION_PT, legend_outside, new_figure

        def y_of(f):
            return np.log(-np.log1p(-np.asarray(f, dtype=float)))

        fig, ax = new_figure(width=9.0, height=4.4)
        lives = np.asarray(self.lives)
        vals = [lives.min(), lives.max(), *(marks or {}).values()]
        vals = [v for v in vals if math.isfinite(v) and v > 0]
        lo = 10 ** math.floor(math.log10(min(vals)) - 0.3)
        hi = 10 ** math.ceil(math.log10(max(vals)) + 0.3)
        x = np.geomspace(lo, hi, 200)
        f_line = -np.expm1(-((x / self.eta) ** self.beta))
        ok = (f_line > 1e-4) & (f_line < 0.9999)
        lab = line_label or "Weibull fit of the tests"
        ax.plot(x[ok], y_of(f_line[ok]), "k-", lw=1.2,
                label=f"{lab}: β {self.beta:.2f}, η {self.eta:.3g}")  # fmt: skip
        if points:
            ax.plot(lives, y_of(self.ranks), "ko", ms=7, mfc="white", mew=1.5,
                    label="tests at median ranks")  # fmt: skip
        styles = ["-", "--", "-.", ":", (0, (5, 1, 1, 1))]
        colours = ["C3", "C0", "C2", "C1", "C4"]
        for k, (lab, v) in enumerate((marks or {}).items()):
            if math.isfinite(v) and v > 0:
                ax.axvline(v, color=colours[k % 5], ls=styles[k % 5], lw=1.6,
                           label=f"{lab}: {v:.3g} {unit}")  # fmt: skip
        ax.set_xscale("log")
        ax.set_xlim(lo, hi)
        ticks = np.array([0.01, 0.05, 0.1, 0.2, 0.3, 0.5, 0.632, 0.8, 0.9, 0.99])
        ax.set_yticks(y_of(ticks), [f"{100 * t:g}" for t in ticks])
        ax.set_ylim(y_of(0.005), y_of(0.995))
        ax.set_xlabel(f"life [{unit}]")
        ax.set_ylabel("failed, Weibull scale [%]")
        ax.grid(True, which="both", alpha=0.3)
        legend_outside(ax, fontsize=ANNOTATION_PT)
        if title:
            ax.set_title(title)
        return fig


def weibull_fit(lives: Sequence[float]) -> WeibullFit:
    """Maximum-likelihood two-parameter Weibull fit of ``lives`` (at least 2, all > 0)."""
    from scipy.stats import weibull_min

    arr = np.sort(np.asarray(lives, dtype=float))
    if arr.size < 2 or not np.all(np.isfinite(arr)) or np.any(arr <= 0):
        raise ConfigError(f"lives = {list(lives)!r}; valid: at least 2 finite values > 0")
    beta, _loc, eta = weibull_min.fit(arr, floc=0.0)
    return WeibullFit(
        tuple(arr.tolist()), tuple(median_ranks(arr.size).tolist()), float(beta), float(eta)
    )
