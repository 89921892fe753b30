"""``bearingsim life``: damage-mechanics contact-fatigue life beside ISO 281 / ISO/TS 16281."""

from __future__ import annotations

import dataclasses
import math
import time
import warnings
from typing import Any

import click

from ..errors import ConfigError, check_positive, check_range
from ..geometry import Bearing, check_speed_limit
from .common import (
    Number,
    bearing_options,
    check_outputs,
    cli,
    deprecated,
    emit_json,
    json_option,
    output_option,
)

__all__ = [
    "life_cmd",
]


@cli.command("life")
@bearing_options()
@click.option(
    "--radial-load-n",
    "radial_load",
    type=Number(
        valid="[F_min, 2 C0] N, F_min the load of a 0.1 um contact semi-width, C0 the static "
        "capacity (ISO 76)"
    ),
    required=True,
    help="Radial load F_r [N].",
)
@deprecated("--radial-load", "--radial-load-n")
@click.option(
    "--rpm",
    type=Number(0.0, lo_open=True, unit="r/min"),
    default=None,
    show_default="lives in revolutions only",
    help="Shaft speed [r/min]; adds the lives in hours.",
)
@click.option(
    "--mesh",
    type=click.Choice(["coarse", "default", "fine", "finer"]),
    default="default",
    help="Fine-zone elements per contact semi-width b: 5, 10, 16, 24.",
)
@click.option(
    "--element-size-um",
    type=Number(valid="[b/200, b/4] um, b the contact half-width"),
    default=None,
    show_default="from --mesh",
    help="Explicit fine element size [um] instead of --mesh (must be <= b/4).",
)
@click.option(
    "--delta-d",
    type=Number(valid="[1/max_steps, 0.1]"),
    default=0.001,
    help="Damage block: increment of the fastest element [-] (seed LIFE eq. (7)).",
)
@click.option(
    "--delta-d-spall",
    type=Number(0.0, 0.1, lo_open=True),
    default=0.1,
    help="Damage block after initiation, growth of the failed zone to the surface [-].",
)
@click.option(
    "--measure",
    type=click.Choice(["max_shear", "orthogonal", "critical_plane"]),
    default="max_shear",
    help="Shear range driving damage: max_shear = range of the in-plane Tresca shear (the "
    "seed's table-3 driver), orthogonal = range of tau_xz in the rolling plane.",
)
@click.option(
    "--load-method",
    type=click.Choice(["stribeck", "distribution"]),
    default="stribeck",
    help="Most-loaded element: Stribeck 4.37 F_r/Z (seed; 4.08 for roller bearings) or "
    "discrete distribution.",
)
@click.option(
    "--kappa",
    type=Number(0.0, lo_open=True),
    default=None,
    show_default="GCr15 fit, seed LIFE eqs. (5)-(6)",
    help="Damage exponent kappa [-].",
)
@click.option(
    "--sigma-t-pa",
    type=Number(0.0, lo_open=True, unit="Pa"),
    default=None,
    show_default="GCr15 fit, seed LIFE eqs. (5)-(6)",
    help="Damage resistance sigma_t [Pa].",
)
@click.option(
    "--stop",
    type=click.Choice(["spall", "initiation"]),
    default="spall",
    help="Stop at the spall or at the first failed element.",
)
@click.option(
    "--solver",
    type=click.Choice(["pcg", "direct"]),
    default="pcg",
    help="FE solve per damage block: pcg = conjugate gradients reusing the earlier blocks' "
    "work (same answer to 1e-5); direct = a new factorization every block (the reference, "
    "several times slower).",
)
@click.option(
    "--max-steps",
    type=Number(1, 10_000_000, integer=True),
    default=20000,
    help="Limit on damage blocks.",
)
@click.option(
    "--plot",
    type=click.Path(dir_okay=False),
    default=None,
    help="Write the damage-field PNG (seed LIFE fig. 15 analogue).",
)
@click.option(
    "--plot-curve",
    type=click.Path(dir_okay=False),
    default=None,
    help="Write the damage-vs-cycles PNG.",
)
@click.option(
    "--plot-weibull",
    type=click.Path(dir_okay=False),
    default=None,
    help="Write the Weibull-paper PNG: the damage life beside ISO 281 L10, ISO/TS 16281 L10r "
    "and, for the seed's case (6206 at 5000 N), its three fatigue tests.",
)
@output_option(
    "Result file (netCDF .nc, lossless; LifeResult.load reads it).", required=True, dest="out"
)
@deprecated("--out", "--output")
@json_option
def life_cmd(
    bearing: Bearing,
    radial_load: float,
    rpm: float | None,
    mesh: str,
    element_size_um: float | None,
    delta_d: float,
    delta_d_spall: float,
    measure: str,
    load_method: str,
    kappa: float | None,
    sigma_t_pa: float | None,
    stop: str,
    solver: str,
    max_steps: int,
    plot: str | None,
    plot_curve: str | None,
    plot_weibull: str | None,
    out: str,
    as_json: bool,
) -> None:
    """Contact-fatigue life of BEARING by damage mechanics, beside ISO 281 and ISO/TS 16281.

    Damage mechanics on a plane-strain FE section of the most loaded inner contact (seed LIFE),
    with ISO 281 L10 and the ISO/TS 16281-style L10r."""
    check_outputs(
        ("-o/--output", out),
        ("--plot", plot),
        ("--plot-curve", plot_curve),
        ("--plot-weibull", plot_weibull),
    )
    from ..life.damage import DamageLaw
    from ..life.fatigue import contact_fatigue_life, default_damage_law
    from ..life.iso281 import (
        basic_rating_life,
        dynamic_load_rating,
        inner_race_cycles_per_revolution,
        revolutions_to_hours,
    )
    from ..life.reference_life import reference_rating_life

    fr = check_positive("radial_load_n", radial_load, "N")
    if rpm is not None:
        rpm = check_speed_limit(bearing, check_positive("rpm", rpm, "r/min"))
    h = None
    if element_size_um is not None:
        h = 1e-6 * check_positive("element_size_um", element_size_um, "um")
    check_range("delta_d", delta_d, 0.0, 0.1, lo_open=True)
    if max_steps < 1:
        raise ConfigError(f"max_steps = {max_steps} is out of range; valid range [1, inf)")
    base = default_damage_law()
    if kappa is not None or sigma_t_pa is not None:
        law = DamageLaw(
            base.kappa if kappa is None else kappa,
            base.sigma_t if sigma_t_pa is None else sigma_t_pa,
            "user",
        )
    else:
        law = base
    t0 = time.perf_counter()
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        res = contact_fatigue_life(
            bearing,
            fr,
            mesh=mesh,
            element_size=h,
            delta_d=delta_d,
            delta_d_spall=delta_d_spall,
            law=law,
            measure=measure,
            load_method=load_method,
            stop=stop,
            max_steps=max_steps,
            solver=solver,
            progress=not as_json,
        )
        rating = dynamic_load_rating(bearing)
        l10 = basic_rating_life(bearing, fr)
        l10r = reference_rating_life(bearing, fr).l10r
    wall = time.perf_counter() - t0
    for w in caught:
        click.echo(f"warning: {' '.join(str(w.message).split())}", err=True)
    u = inner_race_cycles_per_revolution(bearing)
    tests = _tests_beside(bearing, fr, res.cycles_spall, l10 * u, l10r * u)
    # the file records what the printed lives rest on: the ratings beside it and the speed of
    # the hours (twenty-first session: --rpm was not recorded, so the hours could not be
    # recovered from the file)
    extra = {"l10_iso281_cycles": l10 * u, "l10r_iso16281_cycles": l10r * u}
    if rpm is not None:
        extra["rpm"] = rpm
    res = dataclasses.replace(res, meta={**res.meta, **extra})
    res.save(
        out, field="-o/--output"
    )  # the data before its figures: a failed write leaves no figure of it
    if plot_weibull:
        from ..report.figures import save_figure

        save_figure(_weibull_figure(bearing, fr, res.cycles_spall, l10 * u, l10r * u), plot_weibull)
    if plot:
        from ..report.figures import save_figure

        save_figure(res.plot_damage_field("final"), plot)
    if plot_curve:
        from ..report.figures import save_figure

        save_figure(res.plot_damage_curve(), plot_curve)
    m = res.meta
    d: dict[str, Any] = {
        "p_max_pa": m["p_max_pa"],
        "b_m": m["b_m"],
        "kappa": m["kappa"],
        "sigma_t_pa": m["sigma_t_pa"],
        "cycles_initiation": res.cycles_initiation,
        "cycles_spall": res.cycles_spall,
        "initiation_depth_m": res.initiation_depth,
        "l10_iso281_rev": l10,
        "l10r_iso16281_rev": l10r,
        "wall_s": wall,
        # extras
        "bearing": bearing.id,
        "radial_load_n": fr,
        "q_max_n": m["q_n"],
        "c_iso281_n": rating.c,
        "cycles_per_rev": u,
        "l10_iso281_cycles": l10 * u,
        "l10r_iso16281_cycles": l10r * u,
        "life_over_l10": res.cycles_spall / (l10 * u),
        "life_over_l10r": res.cycles_spall / (l10r * u),
        "tests": tests,
        "rev_initiation": res.cycles_initiation / u,
        "rev_spall": res.cycles_spall / u,
        "steps_initiation": res.steps_initiation,
        "steps_spall": res.steps_spall,
        "measure": m["measure"],
        "solver": m["solver"],
        "mesh": m["mesh"],
        "element_size_m": m["element_size_m"],
        "n_core_elements": m["n_core_elements"],
        "loop_s": res.wall_s,
        "time_per_step_s": m["time_per_step_s"],
        "fe_tau_error": m["fe_tau_error"],
        "fe_depth_error": m["fe_depth_error"],
        "out": out,
    }
    if rpm is not None:
        d["rpm"] = rpm
        d["l10_iso281_h"] = revolutions_to_hours(l10, rpm)
        d["l10r_iso16281_h"] = revolutions_to_hours(l10r, rpm)
        for k in ("initiation", "spall"):
            rev = d[f"rev_{k}"]
            d[f"hours_{k}"] = revolutions_to_hours(rev, rpm) if math.isfinite(rev) else math.nan
    if as_json:
        emit_json(d)
        return
    click.echo(
        f"{bearing.id}: F_r = {fr:g} N, Q_max = {m['q_n']:.1f} N, "
        f"p_max = {m['p_max_pa'] / 1e6:.0f} MPa, b = {m['b_m'] * 1e6:.1f} µm; "
        f"kappa = {m['kappa']:.3f}, "
        f"sigma_t = {m['sigma_t_pa'] / 1e6:.0f} MPa; measure {m['measure']}"
    )
    spalled = math.isfinite(res.cycles_spall)
    spall = (
        f"spall {res.cycles_spall:.4g} cycles ({res.steps_spall} blocks)"
        if spalled
        else "spall not computed (--stop initiation)"
    )
    click.echo(
        f"  damage life: initiation {res.cycles_initiation:.4g} cycles "
        f"({res.steps_initiation} blocks, depth {res.initiation_depth * 1e6:.1f} µm), "
        f"{spall}; {wall:.1f} s"
    )
    click.echo(
        f"  ISO 281: C = {rating.c / 1e3:.2f} kN, L10 = {l10:.4g} rev = {l10 * u:.4g} cycles "
        f"({u:.3f} cycles/rev); ISO/TS 16281-style L10r = {l10r:.4g} rev"
    )
    if rpm is not None:
        hours = f"initiation {d['hours_initiation']:.4g} h" + (
            f", spall {d['hours_spall']:.4g} h" if spalled else ""
        )
        click.echo(
            f"  at {rpm:g} r/min: L10 = {d['l10_iso281_h']:.4g} h, L10r = "
            f"{d['l10r_iso16281_h']:.4g} h; damage life {hours}"
        )
    if not spalled:  # the ratios and the tests' comparison are of the spall life
        click.echo(f"  wrote {out}")
        return
    click.echo(
        f"  damage life (spall) = {d['life_over_l10']:.3g} x L10 = {d['life_over_l10r']:.3g} x L10r"
    )
    if tests is not None:
        click.echo(
            f"  tests ({tests['source']}): "
            + ", ".join(f"{c:.3g}" for c in tests["cycles"])
            + " cycles; the damage life is "
            + ", ".join(f"{r:.3g}" for r in tests["life_over_tests"])
            + f" x each, at {100 * tests['life_failed_fraction']:.1f} % failed on their Weibull "
            "fit "
            f"(beta {tests['weibull_beta']:.2f}, eta {tests['weibull_eta_cycles']:.3g} cycles)"
        )
    click.echo(f"  wrote {out}")


def _seed_tests(bearing: Bearing, fr: float) -> tuple[tuple[float, ...], str] | None:
    """The fatigue-test lives measured for this bearing and load [inner-race cycles], if any:
    seed LIFE table 4 (three 6206 at 5 kN)."""
    from ..report.published import entry

    if bearing.id != "6206" or not math.isclose(fr, 5000.0, rel_tol=1e-9):
        return None
    e = entry("life.table4.test_lives")
    return tuple(float(v) for v in e.si), e.source  # type: ignore[union-attr]


def _tests_beside(
    bearing: Bearing, fr: float, life: float, l10: float, l10r: float
) -> dict[str, Any] | None:
    """The measured lives of this case beside the damage life and the ratings (cycles)."""
    from ..life.weibull import weibull_fit

    found = _seed_tests(bearing, fr)
    if found is None:
        return None
    cycles, source = found
    fit = weibull_fit(cycles)
    ok = math.isfinite(life)
    return {
        "source": source,
        "cycles": list(cycles),
        "weibull_beta": fit.beta,
        "weibull_eta_cycles": fit.eta,
        "weibull_l10_cycles": fit.l10,
        "weibull_l50_cycles": fit.l50,
        "life_over_tests": [life / c for c in cycles],
        "life_failed_fraction": fit.probability_at(life) if ok else math.nan,
        "l10_failed_fraction": fit.probability_at(l10),
        "l10r_failed_fraction": fit.probability_at(l10r),
        "tests_below_l10": sum(c < l10 for c in cycles),
    }


def _weibull_figure(bearing: Bearing, fr: float, life: float, l10: float, l10r: float):
    """Weibull-paper figure of this case (the tests when there are, else the ratings alone)."""
    from ..life.weibull import LP_SLOPE_POINT, WeibullFit, median_ranks, weibull_fit

    marks = {
        "damage life (spall)": life,
        "ISO 281 L10": l10,
        "ISO/TS 16281 L10r": l10r,
    }
    found = _seed_tests(bearing, fr)
    title = f"{bearing.id} at {fr:g} N: inner-race cycles"
    if found is not None:
        return weibull_fit(found[0]).plot(marks, title=title + " (tests: " + found[1] + ")")
    # no tests: the ISO 281 population itself (Weibull slope 10/9 through L10)
    eta = l10 / (-math.log(0.9)) ** (1.0 / LP_SLOPE_POINT)
    pop = WeibullFit((l10,), tuple(median_ranks(1).tolist()), LP_SLOPE_POINT, eta)
    return pop.plot(
        marks, title=title, line_label="ISO 281 population (slope 10/9 through L10)", points=False
    )
