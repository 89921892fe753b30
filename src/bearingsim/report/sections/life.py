"""Report section for SPEC §4 (seed LIFE): damage-mechanics contact-fatigue life of the 6206,
beside the ISO 281 and ISO/TS 16281-style ratings."""

from __future__ import annotations

import math

import numpy as np

from ...catalog import get_bearing
from ...contact.hertz import ball_contact, subsurface_stresses
from ...geometry import Race
from ...life.analytic import mcewen_stresses
from ...life.damage import GCR15_TORSION, fit_sn_curve, torsion_check
from ...life.fatigue import contact_fatigue_life, inner_contact
from ...life.fe import ShearMeasure, contact_section, section_spec
from ...life.iso281 import (
    basic_rating_life,
    dynamic_load_rating,
    inner_race_cycles_per_revolution,
)
from ...life.reference_life import reference_rating_life
from ...life.validation import validate_against_hertz
from ...life.weibull import rating_life_ratio, weibull_fit
from .. import Context, Section, compare, info, judge, kind_of
from ..figures import HALF_WIDTH, new_figure, save_figure
from ..published import entry, value

__all__ = ["TITLE", "run"]

TITLE = "LIFE (SPEC §4): damage-mechanics contact-fatigue life of the 6206; ISO 281 / ISO/TS 16281"

#: seed LIFE table 4: predicted life and the three test bearings [cycles], the seed's errors [%]
SEED_PREDICTED = value("life.table4.predicted_life")
SEED_TESTS = value("life.table4.test_lives")
SEED_ERRORS_PCT = value("life.table4.relative_errors")
#: tolerance of the table-3 maximum-shear rows [-]: the seed's 459 MPa is a 3-D value (its
#: p_max is its 3-D FE's 2904 MPa, 0.5 % above Hertz); half the 3-D and the plane-strain Tresca
#: shears differ by 4.5 % (0.313 vs 0.300 p_max), so 2 % tells the two apart
TRESCA_TOL = 0.02


def _fe_figure(section, st):
    """tau_xz vs depth under the orthogonal-shear peak: FE element averages vs McEwen."""
    b, p0 = section.b, section.p_max
    k0 = int(np.argmin(np.abs(section.positions)))
    cx, cz = section.centroids
    fig, ax = new_figure(width=HALF_WIDTH, height=4.6)
    for xb, mk in ((-0.87, "o"), (0.87, "s")):
        col = np.isclose(cx, cx[np.argmin(np.abs(cx - xb * b))], rtol=0, atol=1e-9)
        sel = col & (cz < 3 * b)
        order = np.argsort(cz[sel])
        z = cz[sel][order]
        ax.plot(
            st.tau_xz[sel, k0][order] / p0,
            z / b,
            mk,
            ms=3,
            mfc="none",
            label=f"FE, x = {cx[sel][0] / b:+.2f} b",
        )
        zz = np.linspace(0.01, 3, 300) * b
        ax.plot(mcewen_stresses(cx[sel][0], zz, p0, b).tau_xz / p0, zz / b, "k-", lw=1)
    ax.plot([], [], "k-", label="McEwen (Johnson eq. 4.75)")
    ax.invert_yaxis()
    ax.set_xlabel("orthogonal shear τ_xz / p_max [-]")
    ax.set_ylabel("depth z / b [-]")
    fig.legend(loc="outside lower center", ncols=2)
    ax.set_title("undamaged section, load at x = 0")
    return fig


def run(ctx: Context) -> Section:
    sec = Section("life", TITLE)
    rows = sec.rows
    out = ctx.out_dir
    # ---------------------------------------------------------------- §1.1 damage law fit
    fit = fit_sn_curve(GCR15_TORSION)
    law = fit.law
    rows.append(
        compare(
            "kappa from the GCr15 torsional S-N fit [-]",
            "seed LIFE §1.1",
            value("life.s1_1.kappa"),
            law.kappa,
            0.05 / value("life.s1_1.kappa"),
            kind=kind_of("life.s1_1.kappa"),
        )
    )
    rows.append(
        compare(
            "sigma_t from the GCr15 torsional S-N fit [MPa]",
            "seed LIFE §1.1",
            value("life.s1_1.sigma_t"),
            law.sigma_t / 1e6,
            5e-3,
            kind=kind_of("life.s1_1.sigma_t"),
        )
    )
    save_figure(fit.plot(GCR15_TORSION), out / "life_sn_fit.png")
    sec.figures.append(
        (
            "life_sn_fit.png",
            "Seed LIFE fig. 1 analogue: GCr15 torsional S-N "
            "curve (eq. (5)) and the integrated damage law (eq. (6)) fitted to it",
        )
    )
    # ---------------------------------------------------------------- §1.2 torsion check
    tc = torsion_check(law)
    for i in (0, -1):
        ta = tc.tau_amplitude[i] / 1e6
        rows.append(
            compare(
                f"torsion life at shear amplitude {ta:.0f} MPa [cycles]",
                "seed LIFE §1.2 / eq. (5) S-N curve",
                float(tc.cycles_sn[i]),
                float(tc.cycles_predicted[i]),
                0.01,
                kind="paper",
            )
        )
    save_figure(tc.plot(), out / "life_torsion.png")
    sec.figures.append(
        (
            "life_torsion.png",
            "Seed LIFE fig. 3 analogue: torsion 1000 → 400 MPa "
            "by 50 MPa; the damage law (blocks ΔD = 0.001) against the S-N "
            "curve. The seed compares with the scattered test points (not "
            "available); against its own fitted curve the law agrees to the "
            "block error ΔD (κ+1)/2 = 0.6 %.",
        )
    )
    # ---------------------------------------------------------------- §2.1 contact
    b6206 = get_bearing("6206")
    c = inner_contact(b6206, 5000.0)
    rows.append(
        compare(
            "6206 inner p_max at 5 kN used by the FE [MPa]",
            "seed LIFE table 3 (ABAQUS)",
            value("life.table3.pmax"),
            c.p_max / 1e6,
            0.01,
            "ours is Hertz theory with Stribeck Q_max = 4.37 F_r/Z = 2428 N; it "
            "matches the seed's own theory value 2890 MPa (table 2)",
            kind=kind_of("life.table3.pmax"),
            verified_by="tests/test_deviations.py::test_seed_fe_pmax_differs_from_its_own_hertz_value",
        )
    )
    rows.append(
        compare(
            "6206 inner contact semi-axis b (along rolling) [mm]",
            "seed LIFE table 3",
            value("life.table3.semi_axis_b"),
            c.b * 1e3,
            0.03,
            f"Hertz gives b = {c.b * 1e3:.3f} mm (a = {c.a * 1e3:.2f} mm) for "
            "Q = 2428 N; b = 0.23 mm would need 1.77 x that load (b ~ Q^(1/3)); the "
            "seed does not say how its 0.23 mm was obtained",
            kind=kind_of("life.table3.semi_axis_b"),
            verified_by="tests/test_deviations.py::test_seed_b_needs_177_times_the_stribeck_load",
        )
    )
    # ---------------------------------------------------------------- FE validation
    spec = section_spec(c.b, "default")
    fe = contact_section(b6206.material, c.p_max, c.b, spec)
    st = fe.solve()
    v = validate_against_hertz(fe, st)
    rows.append(
        compare(
            "FE max orthogonal shear |tau_xz| (default mesh) [MPa]",
            "McEwen / Johnson (1985) §4.2: 0.25 p_max",
            v.tau_max_exact / 1e6,
            v.tau_max_fe / 1e6,
            0.03,
            kind="paper",
        )
    )
    rows.append(
        compare(
            "FE depth of max |tau_xz| (default mesh) [µm]",
            "McEwen / Johnson (1985) §4.2: 0.5 b",
            v.depth_exact * 1e6,
            v.depth_fe * 1e6,
            0.03,
            kind="paper",
        )
    )
    # the seed's "maximum shear stress" (table 3): half the 3-D Hertz Tresca shear, the
    # amplitude of the 0 -> tau_max -> 0 cycle as the ball passes
    ss = subsurface_stresses(ball_contact(b6206, c.q, Race.INNER), b6206.material.poisson_ratio)
    rows.append(
        compare(
            "6206 max shear amplitude at 5 kN: half the 3-D Hertz max (Tresca) shear [MPa]",
            "seed LIFE table 3 ('maximum shear stress')",
            value("life.table3.max_shear"),
            0.5 * ss.tau_max / 1e6,
            TRESCA_TOL,
            kind=kind_of("life.table3.max_shear"),
        )
    )
    tresca_fe = float(st.shear_range(ShearMeasure.MAX_SHEAR).max())
    rows.append(
        compare(
            "6206 max shear amplitude at 5 kN: half the FE in-plane Tresca range, the damage "
            "driver (default mesh) [MPa]",
            "seed LIFE table 3 ('maximum shear stress')",
            value("life.table3.max_shear"),
            0.5 * tresca_fe / 1e6,
            TRESCA_TOL,
            f"the plane-strain section carries the line-contact field, in-plane Tresca "
            f"0.300 p_max, plus the finite 12 x 4 mm section's sigma_x: "
            f"{tresca_fe / c.p_max:.4f} p_max, against {ss.tau_max / c.p_max:.4f} p_max of the "
            f"3-D ellipse (a/b = {c.a / c.b:.1f})",
            kind=kind_of("life.table3.max_shear"),
        )
    )
    save_figure(_fe_figure(fe, st), out / "life_fe_vs_mcewen.png")
    fe_caption = (
        f"Undamaged plane-strain section (default mesh, {fe.n_elements} "
        f"elements, h = b/10): τ_xz vs depth in the element columns nearest x = ±0.87 b (where "
        "τ_xz peaks; their centroids at ±0.85 b) against the McEwen line-contact field there"
    )
    # ---------------------------------------------------------------- damage life
    dd, dds = (0.01, 0.05) if ctx.quick else (0.001, 0.1)
    res = contact_fatigue_life(
        b6206, 5000.0, mesh="default", delta_d=dd, delta_d_spall=dds, law=law
    )
    life = res.cycles_spall
    variant = (
        f"default mesh (h = b/10), ΔD = {dd:g}"
        + (" (quick variant; the seed's 0.001 in the full report)" if ctx.quick else "")
        + f", ΔD = {dds:g} after initiation; Δτ = range of the in-plane Tresca shear"
    )
    u = inner_race_cycles_per_revolution(b6206)
    l10 = basic_rating_life(b6206, 5000.0)
    ref = reference_rating_life(b6206, 5000.0)
    l10c, l10rc = l10 * u, ref.l10r * u
    uniform_fe = float(law.cycles_to_failure(tresca_fe))
    uniform_seed = float(law.cycles_to_failure(2 * entry("life.table3.max_shear").si))
    rows.append(
        compare(
            "6206 life at 5 kN, first surface element failed (spall) [cycles]",
            "seed LIFE table 4 (predicted)",
            SEED_PREDICTED,
            life,
            0.1,
            f"same law and criterion; a uniformly stressed element lives {uniform_fe:.3g} cycles "
            f"at our Δτ = {tresca_fe / 1e6:.0f} MPa and {uniform_seed:.3g} at the seed's "
            f"2 x 459 = 918 MPa: our FE life is {life / uniform_fe:.2f} x its uniform-element "
            f"value, the seed's {SEED_PREDICTED / uniform_seed:.2f} x — the seed's damage "
            "redistribution (or its unstated 3-D/plane-stress details) gains more life than "
            "ours; not verified, so a mismatch. Ours: " + variant + ". No calibration factor.",
            kind=kind_of("life.table4.predicted_life"),
        )
    )
    rows.append(
        info(
            "6206 life at 5 kN, first element failed (initiation) [cycles]",
            "ours (" + variant + ")",
            res.cycles_initiation,
            f"initiation at depth {res.initiation_depth * 1e6:.0f} µm = "
            f"{res.initiation_depth / c.b:.2f} b after {res.steps_initiation} blocks; "
            f"spall after {res.steps_spall} blocks",
        )
    )
    fit = weibull_fit(SEED_TESTS)
    for k, (t, e) in enumerate(zip(SEED_TESTS, SEED_ERRORS_PCT, strict=True), start=1):
        rows.append(
            compare(
                f"test bearing {k} life [cycles]",
                "seed LIFE table 4 (test)",
                t,
                life,
                0.5,
                f"the damage life lies at {100 * fit.probability_at(life):.0f} % failed on the "
                f"tests' Weibull fit (beta {fit.beta:.2f}, eta {fit.eta:.3g} cycles)",
                kind=kind_of("life.table4.test_lives"),
            )
        )
        rows.append(
            compare(
                f"seed's relative error, bearing {k} [%]",
                "seed LIFE table 4 (recomputed from its lives)",
                e,
                100 * abs(SEED_PREDICTED - t) / t,
                2e-3,
                kind=kind_of("life.table4.relative_errors"),
            )
        )
    rows.append(
        compare(
            "6206 life at 5 kN vs the median of the tests' Weibull fit [cycles]",
            "seed LIFE table 4 (tests), Weibull ML fit",
            fit.l50,
            life,
            0.5,
            f"L50 of the three tests (beta {fit.beta:.2f}); the damage life lies at "
            f"{100 * fit.probability_at(life):.0f} % failed",
            kind="measured",
        )
    )
    deep = res.initiation_depth > 0 and not res.surface[np.argmax(res.damage_initiation)]
    rows.append(
        judge(
            "damage initiation site",
            "seed LIFE fig. 15",
            "below the surface",
            f"depth {res.initiation_depth / c.b:.2f} b",
            deep,
            kind="paper",
        )
    )
    # uniform-element estimates per Δτ definition (from the undamaged default mesh)
    est = []
    for m in ShearMeasure:
        dt = float(st.shear_range(m).max())
        est.append(
            f"{m.value}: Δτ {dt / 1e6:.0f} MPa -> {float(law.cycles_to_failure(dt)):.3g} cycles"
        )
    rows.append(
        info(
            "uniform-element life eq. (6) with the seed's table-3 shear amplitude "
            "459 MPa (Δτ = 918 MPa) [cycles]",
            "derived from seed LIFE table 3",
            uniform_seed,
            "the order of magnitude of the seed's 2.72e8 follows from its 459 MPa; "
            "Hertz-field estimates per Δτ definition: " + "; ".join(est),
        )
    )
    save_figure(res.plot_damage_field("final"), out / "life_damage_field.png")
    sec.figures.append(
        (
            "life_damage_field.png",
            "Seed LIFE fig. 15 analogue: damage field when the first surface element "
            f"fails ({variant}); white squares = failed elements",
        )
    )
    save_figure(res.plot_damage_field("initiation"), out / "life_damage_initiation.png")
    sec.figures.append(
        ("life_damage_initiation.png", "damage field at the first failure (subsurface initiation)")
    )
    save_figure(res.plot_damage_curve(), out / "life_damage_curve.png")
    sec.figures.append(
        (
            "life_damage_curve.png",
            "Largest element damage and failed elements vs load cycles; right: the failed "
            "elements after the first failure (initiation and spall are close on the left)",
        )
    )
    marks = {
        "damage life (spall), ours": life,
        "seed's damage life (table 4)": SEED_PREDICTED,
        "ISO 281 L10": l10c,
        "ISO/TS 16281 L10r": l10rc,
    }
    save_figure(
        fit.plot(marks, title="6206 at 5 kN: inner-race cycles (tests: seed LIFE table 4)"),
        out / "life_weibull.png",
    )
    sec.figures.append(
        (
            "life_weibull.png",
            "The three fatigue tests of seed LIFE table 4 on Weibull paper (median ranks, "
            "maximum-likelihood line) with our damage life, the seed's, ISO 281 L10 and the "
            f"ISO/TS 16281 L10r ({u:.3f} inner-race over-rollings per revolution); no "
            "calibration",
        )
    )
    # after the damage figures: the two damage fields share a row of the page
    sec.figures.append(("life_fe_vs_mcewen.png", fe_caption))
    # ---------------------------------------------------------------- ISO 281 / 16281
    for bid in ("6206", "6205"):
        nsk, skf = value(f"catalogue.nsk.{bid}.c_r"), value(f"catalogue.skf.{bid}.c_r")
        r = dynamic_load_rating(get_bearing(bid))
        rows.append(
            compare(
                f"{bid} ISO 281 C_r from geometry [kN]",
                "NSK catalogue (ISO 281)",
                nsk,
                r.c / 1e3,
                0.01,
                kind=kind_of(f"catalogue.nsk.{bid}.c_r"),
            )
        )
        rows.append(
            compare(
                f"{bid} ISO 281 C_r from geometry [kN]",
                "SKF catalogue",
                skf,
                r.c / 1e3,
                0.01,
                f"SKF lists {skf / nsk:.3f} x the plain ISO 281 value that NSK lists and we "
                "compute (their steel and manufacturing quality)",
                kind=kind_of(f"catalogue.skf.{bid}.c_r"),
                verified_by="tests/test_deviations.py::test_skf_ratings_exceed_plain_iso281",
            )
        )
    ratio = rating_life_ratio(0.5)
    rows.append(
        judge(
            "6206 damage life / ISO 281 L10 at 5 kN [-]",
            "ISO 281 L10 (inner-race cycles); a median-type life lies in [1, L50/L10]",
            f"1 to {ratio:.2f}",
            f"{life / l10c:.3g}",
            1.0 <= life / l10c <= ratio,
            f"L10 = {l10:.3g} rev x u_i = Z(1+gamma)/2 = {u:.3f} = {l10c:.3g} cycles; "
            f"L50/L10 = {ratio:.2f} for the Weibull slope 10/9 of ball bearings (Lundberg & "
            f"Palmgren); {sum(t < l10c for t in SEED_TESTS)} of the 3 tests fall below L10",
            kind="standard",
        )
    )
    rows.append(
        info(
            "6206 ISO/TS 16281-style L10r at 5 kN [cycles]",
            "ours (zero clearance)",
            l10rc,
            f"{ref.l10r:.3g} rev; L10 (ISO 281) = {l10:.3g} rev; L10r is higher because the "
            f"seed's grooves (f_i {b6206.inner_conformity:.3f}, f_e "
            f"{b6206.outer_conformity:.3f}) are tighter than ISO's reference 0.52/0.53",
        )
    )
    sec.text = (
        "Plane-strain idealisation (the seed calls its 2-D model plane stress, §2.3; the in-plane "
        "stresses of the Hertz field are the same in both): the elliptical ball/race contact is "
        "represented by its central strip, a 12 x 4 mm section in the rolling plane loaded by "
        "p(x) = p_max sqrt(1 - (x/b)^2) with the point-contact p_max and b from Hertz theory; "
        "the pressure moves across the surface (+/-2 b in steps of h), one pass = one cycle; "
        "Δτ = range of the in-plane maximum (Tresca) shear over a pass (the seed's "
        "table-3 driver; the orthogonal tau_xz range is an option). "
        f"Damage run: {res.meta['n_core_elements']} core elements, "
        f"{res.meta['n_positions']} load positions, {res.meta['n_steps']} blocks in "
        f"{res.wall_s:.1f} s ({1e3 * res.meta['time_per_step_s']:.1f} ms per block). "
        f"Units: u_i = {u:.3f} inner-race cycles per revolution; spall at "
        f"{res.cycles_spall / u:.3g} rev. ISO: C_r = {dynamic_load_rating(b6206).c:.0f} N, "
        f"L10 = {l10:.3g} rev, L10r = {ref.l10r:.3g} rev."
    )
    s_l = f"{life:.3g}"
    sec.text += (
        f" Life beside the measurements: the damage life {s_l} cycles is "
        + ", ".join(f"{life / t:.2f}" for t in SEED_TESTS)
        + f" x the three tests, {life / l10c:.2f} x ISO 281 L10 and {life / l10rc:.2f} x L10r."
    )
    if not math.isfinite(res.cycles_spall):
        sec.text += " The spall criterion was not reached within the block limit."
    return sec
