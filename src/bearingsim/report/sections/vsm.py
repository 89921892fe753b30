"""Report section for SPEC §1: the VSM with its DEM and TVSM baselines, envelope diagnosis and
the measured CWRU records (seed VSM figs. 5–15, tables 2–3)."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
from scipy.optimize import brentq

from ...catalog import get_bearing
from ...config import Scenario
from ...dynamics.ring.base import ModelInputs
from ...dynamics.ring.trace import stiffness_trace
from ...geometry import characteristic_frequencies, defect_at_edge
from ...io.cwru import cwru_data_dir
from ...load_distribution import radial_load_distribution
from ...signal import diagnose, envelope_spectrum, fast_kurtogram, load_signal
from ...simulation import simulate
from .. import Context, Section, compare, info, judge, kind_of
from ..figures import ACC, FULL_WIDTH, new_figure, save_figure
from ..published import entry, value

__all__ = ["TITLE", "run"]

TITLE = "VSM / DEM / TVSM fault dynamics and CWRU diagnosis (SPEC §1, seed VSM)"

B6205 = get_bearing("6205")
#: the test verifying that our Hertz K (psi_L 56.0 deg) moves the zone events and ball counts
PSI_TEST = "tests/test_deviations.py::test_hertz_k_narrows_the_zone_of_table2_and_fig5"
FX, FY = 10.0, 50.0  # seed VSM table 1
#: seed VSM table 2, ball 5 (outer defect, b = 1 mm, gamma = 0.38): (angle [deg], ball, event)
TABLE2 = entry("vsm.table2.outer_defect_events").rows("ball", "event")
#: CWRU records (SOURCES.md) and their labels
RECORDS = {
    "109": "inner",
    "107": "inner",
    "135": "outer",
    "132": "outer",
    "97": "none",
    "122": "ball",
    "120": "ball",
}
#: RMS of the CWRU normal baseline 97 drive-end signal [m/s^2]: noise added to the simulations
NOISE_97 = value("cwru.record97.de_rms")


def _record(num: str) -> Path | None:
    m = sorted(cwru_data_dir().glob(f"*_{num}.mat"))
    return m[0] if m else None


def k_paper() -> float:
    """Ball constant K reproducing the paper's psi_L = 68.2 deg at cage angle 0 [N/m^1.5]."""

    def f(k):
        ld = radial_load_distribution(B6205, FX, FY, 0.0, stiffness=k)
        return math.degrees(float(ld.psi_l[0])) - value("vsm.s2_1.load_zone_half_angle")

    return brentq(f, 1e8, 9.4e9, xtol=1e-3)


def _inputs(loc, gamma=0.38, **kw):
    return ModelInputs(
        B6205,
        FX,
        FY,
        1750 / 60,
        None if loc == "none" else defect_at_edge(B6205, loc, 1e-3, 1e-3, math.radians(10.0)),
        retention_factor=gamma,
        **kw,
    )


def _traces(ctx: Context, sec: Section) -> None:
    from ...plotting import legend_outside

    step = 0.05 if ctx.quick else 0.01
    cage = np.radians(np.arange(0.0, 360.0 + 1e-9, step))
    kp = k_paper()
    # ---- table 2 with the paper's psi_L (eq. 14 fixed window) and ours
    psi_pub = entry("vsm.s2_1.load_zone_half_angle").si
    fixed = stiffness_trace(_inputs("outer", load_zone_half_angle=psi_pub), cage)
    contact_kp = stiffness_trace(_inputs("outer", stiffness=kp), cage)
    ours = stiffness_trace(_inputs("outer"), cage)

    def ev(tr, lo=140.0, hi=285.0):
        return {(b, k): a for a, b, k in tr.events() if lo <= a <= hi}

    e_fixed, e_kp, e_ours = ev(fixed), ev(contact_kp), ev(ours, 140.0, 300.0)
    for pub, ball, kind in TABLE2:
        got = e_fixed.get((ball, kind), math.nan)
        sec.rows.append(
            compare(
                f"table 2: ball {ball} {kind.replace('_', ' ')} [deg], "
                "psi_L = 68.2 deg (eq. 14 window)",
                "seed VSM table 2",
                pub,
                got,
                0.5 / pub,
                kind=kind_of("vsm.table2.outer_defect_events"),
            )
        )
    note_kp = (
        "contact-defined zone with K tuned to psi_L = 68.2 deg at cage angle 0: the "
        "discrete-ball zone is wider (about 69.6 deg) when a ball sits on its edge"
    )
    for pub, ball, kind in TABLE2[:2]:
        sec.rows.append(
            compare(
                f"table 2: ball {ball} {kind.replace('_', ' ')} [deg], contact zone, K = {kp:.3g}",
                "seed VSM table 2",
                pub,
                e_kp.get((ball, kind), math.nan),
                0.5 / pub,
                note_kp,
                kind=kind_of("vsm.table2.outer_defect_events"),
                verified_by="tests/test_vsm_trace.py::test_table2_contact_zone_with_paper_stiffness",
            )
        )
    note_ours = (
        "our Hertz K = 9.37e9 N/m^1.5 gives psi_L = 56.0 deg (foundation row), so the "
        "zone is 24 deg narrower and ball 5 enters 10 deg later"
    )
    pub = TABLE2[0][0]  # ball 5 enters the zone
    sec.rows.append(
        compare(
            "table 2: ball 5 enters the zone [deg], ours (Hertz K, contact)",
            "seed VSM table 2",
            pub,
            e_ours.get((5, "enters_zone"), math.nan),
            0.5 / pub,
            note_ours,
            kind=kind_of("vsm.table2.outer_defect_events"),
            verified_by=PSI_TEST,
        )
    )
    # ---- healthy ball count (fig. 5)
    healthy_kp = stiffness_trace(_inputs("none", stiffness=kp), cage)
    healthy = stiffness_trace(_inputs("none"), cage)
    for tr, lab, note in (
        (healthy_kp, "K for psi_L 68.2", ""),
        (
            healthy,
            "ours, Hertz K",
            "psi_L = 56.0 deg: the zone holds 2 or 3 balls (see foundation psi_L row)",
        ),
    ):
        got = "/".join(str(v) for v in sorted(set(tr.n_loaded.tolist())))
        sec.rows.append(
            judge(
                f"fig. 5: loaded balls alternate ({lab})",
                "seed VSM §2.2",
                "3/4",
                got,
                got == "3/4",
                note,
                kind="paper",
                verified_by=PSI_TEST,
            )
        )
    # ---- figures 5-8
    fig, axs = new_figure(3, 1, width=FULL_WIDTH, row_height=2.3, sharex=True)
    deg = np.degrees(cage)
    axs[0].plot(deg, healthy_kp.k_load / 1e6, label=f"K = {kp:.3g} N/m^1.5 (ψ_L 68.2°)")
    axs[0].plot(deg, healthy.k_load / 1e6, label="Hertz K (ψ_L 56.0°)")
    axs[0].set_title("fig. 5: healthy, total effective (secant) stiffness along the load")
    for g in (0.8, 0.38, 0.0):
        tr = stiffness_trace(_inputs("outer", gamma=g, stiffness=kp), cage)
        axs[1].plot(deg, tr.k_load / 1e6, label=f"γ = {g:g}")
    axs[1].set_title("figs. 6-7: outer defect b = 1 mm at 10°, drops every 40°")
    inner = stiffness_trace(_inputs("inner", stiffness=kp), cage)
    axs[2].plot(deg, inner.k_load / 1e6, label="γ = 0.38")
    axs[2].set_title("fig. 8: inner defect, drops of varying depth")
    for a in axs:
        a.set_ylabel("k_load [MN/m]")
        legend_outside(a)
    axs[-1].set_xlabel("cage angle [deg]")
    save_figure(fig, ctx.out_dir / "vsm_stiffness_figs5-8.png")
    sec.figures.append(
        (
            "vsm_stiffness_figs5-8.png",
            "Total effective stiffness along the load vs cage angle "
            "(seed VSM figs. 5-8); secant definition (docs/models.md)",
        )
    )
    fig = contact_kp.plot_balls([4, 5, 6])
    fig.axes[0].set_xlim(140, 285)
    save_figure(fig, ctx.out_dir / "vsm_balls_fig10.png")
    sec.figures.append(
        (
            "vsm_balls_fig10.png",
            "Contact force and deformation of balls 4, 5, 6 "
            "(seed VSM figs. 9-10): the load shed by a ball in the defect is taken "
            "up by its neighbours",
        )
    )


def _envelope_peaks(x, fs, shaft, kin, band=None):
    band = band or fast_kurtogram(x, fs, min_bandwidth_hz=3 * kin.bpfi_hz + shaft).band
    return envelope_spectrum(x, fs, band), band


def _near(es, f, tol=0.01):
    sel = (es.freq >= f * (1 - tol)) & (es.freq <= f * (1 + tol))
    i = np.flatnonzero(sel)
    return float(es.freq[i[np.argmax(es.amplitude[i])]]) if i.size else math.nan


def _dynamics(ctx: Context, sec: Section) -> None:
    dur = 0.5 if ctx.quick else 2.0
    cases = {
        "outer": ({"fault": "outer", "rpm": 1796.0, "defect_width_m": 1.778e-4}, "135"),
        "inner": ({"fault": "inner", "rpm": 1748.0, "defect_width_m": 3.556e-4}, "107"),
    }
    amp: dict[str, dict[str, float]] = {}
    for fault, (kw, rec_id) in cases.items():
        sims = {
            m: simulate(Scenario(model=m, duration_s=dur, **kw)) for m in ("vsm", "dem", "tvsm")
        }
        path = _record(rec_id)
        rec = load_signal(path) if path else None
        kin = characteristic_frequencies(
            get_bearing("6205-cwru"), (rec.rpm if rec else kw["rpm"]) / 60
        )
        fig, axs = new_figure(4, 2, width=FULL_WIDTH, row_height=2.2, sharex="col")
        rows = [("test", rec.x if rec else None, rec.fs if rec else 48000.0)]
        rows += [(m.upper(), s["acc_y"], s.fs_hz) for m, s in sims.items()]
        amp[fault] = {}
        for i, (lab, x, fs) in enumerate(rows):
            if x is None:
                continue
            if rec is not None and lab != "test" and rec.fs < fs:
                # compare at the record's bandwidth: decimate the 48 kHz simulation (FIR,
                # zero phase) to the record's sample rate
                from scipy.signal import decimate

                q = int(round(fs / rec.fs))
                amp[fault][lab + "_at_record_fs"] = float(
                    np.max(np.abs(decimate(x, q, ftype="fir", zero_phase=True)))
                )
            n = int(0.05 * fs)
            t = np.arange(n) / fs
            name = f"CWRU {rec_id}" if lab == "test" else lab
            axs[i, 0].plot(t * 1e3, x[:n], lw=0.6)
            axs[i, 0].set_ylabel(f"acceleration [{ACC}]")
            axs[i, 0].set_title(f"{name}: acceleration, first 50 ms", loc="left")
            es, band = _envelope_peaks(x, fs, kin.shaft_hz, kin)
            sel = es.freq <= 500
            axs[i, 1].plot(es.freq[sel], es.amplitude[sel], lw=0.7)
            axs[i, 1].set_ylabel(f"envelope amplitude [{ACC}]")
            axs[i, 1].set_title(
                f"{name}: envelope spectrum, band {band[0] / 1e3:.1f}-{band[1] / 1e3:.1f} kHz",
                loc="left",
            )
            amp[fault][lab] = float(np.max(np.abs(x - x.mean())))
            amp[fault][lab + "_rms"] = float(np.std(x))
        axs[-1, 0].set_xlabel("time [ms]")
        axs[-1, 1].set_xlabel("envelope frequency [Hz]")
        fig.suptitle(
            f"{fault} race defect: measured and simulated acceleration, envelope spectra in the "
            "kurtogram band"
        )
        name = "vsm_fig14_outer.png" if fault == "outer" else "vsm_fig15_inner.png"
        save_figure(fig, ctx.out_dir / name)
        sec.figures.append(
            (
                name,
                f"Seed VSM fig. {14 if fault == 'outer' else 15} style: CWRU "
                f"record {rec_id} (drive end) beside the VSM, DEM and TVSM "
                f"({kw['rpm']:g} r/min, defect {kw['defect_width_m'] * 1e3:.4g} mm "
                "x 0.2794 mm"
                + (
                    ", the paper's 0.014 in; CWRU 107 has a 0.007 in fault, the paper's record "
                    "is not in shared/data"
                    if fault == "inner"
                    else ""
                )
                + "). The simulations are drawn at their 48 kHz, their envelopes in their own "
                "kurtogram bands (which may lie above the record's Nyquist frequency); the "
                "peak rows compare them decimated to the record's rate, and each panel has its "
                "own axis: the table gives the levels.",
            )
        )
        # published envelope peaks (seed VSM §2.5) vs the measured record and the VSM
        if rec is not None:
            es, _b = _envelope_peaks(rec.x, rec.fs, kin.shaft_hz, kin)
            pubs = value(f"vsm.s2_5.{fault}_envelope_peaks")
            for f0 in pubs:
                note = (
                    ""
                    if fault == "outer"
                    else "the paper's inner record (0.014 in, 48 kHz) is "
                    "not in shared/data; CWRU 107 (0.007 in, 1748 r/min, 12 kHz) has the same "
                    "speed"
                )
                sec.rows.append(
                    compare(
                        f"{fault}: envelope peak near {f0:g} Hz, CWRU {rec_id} [Hz]",
                        "seed VSM §2.5 (test data)",
                        f0,
                        _near(es, f0),
                        0.005,
                        note,
                        kind=kind_of(f"vsm.s2_5.{fault}_envelope_peaks"),
                    )
                )
        es_v, _b = _envelope_peaks(sims["vsm"]["acc_y"], sims["vsm"].fs_hz, kin.shaft_hz, kin)
        f_pub = value(f"vsm.s2_5.{fault}_envelope_peaks")[0]
        f_th = kin.bpfo_hz if fault == "outer" else kin.bpfi_hz
        sec.rows.append(
            compare(
                f"{fault}: VSM envelope peak near {f_pub:g} Hz [Hz]",
                "seed VSM §2.5",
                f_pub,
                _near(es_v, f_th, 0.02),
                0.01,
                "simulation runs at the nominal speed (no slip): its line sits at "
                f"the kinematic {f_th:.2f} Hz; {dur:g} s resolution "
                f"{1 / dur:.2g} Hz",
                kind=kind_of(f"vsm.s2_5.{fault}_envelope_peaks"),
            )
        )
    # amplitude comparison (figs 14-15 claims)
    o, i = amp["outer"], amp["inner"]
    if "test" in o:
        _peak_rows(sec, "fig. 14: outer (0.1778 mm, 1796 r/min, 48 kHz)", "135", o["test"], o)
        r = o["VSM"] / o["test"]
        sec.rows.append(
            judge(
                "fig. 14: outer, VSM peak / test peak [-]",
                "seed VSM §2.5: 'VSM close to test'",
                "close (0.5-2)",
                f"{r:.3g}",
                0.5 <= r <= 2,
                kind="paper",
            )
        )
        for m in ("DEM", "TVSM"):
            r = o[m] / o["test"]
            sec.rows.append(
                judge(
                    f"fig. 14: outer, {m} peak / test peak [-]",
                    "seed VSM §2.5: 'DEM and TVSM too small'",
                    "< 1",
                    f"{r:.3g}",
                    r < 1,
                    "our DEM/TVSM use the same defect drop h_min "
                    "as the VSM but the tangent (stiffer) Hertz stiffness: the ring "
                    "rings at ~4 kHz instead of ~2 kHz with a larger force step "
                    "(docs/validation.md)",
                    kind="paper",
                )
            )
    order = sorted(("VSM", "TVSM", "DEM"), key=lambda m: i[m])
    got = " < ".join(order)
    sec.rows.append(
        judge(
            "fig. 15: inner, peak order of the models",
            "seed VSM §2.5",
            "VSM < TVSM < DEM",
            got,
            got == "VSM < TVSM < DEM",
            kind="paper",
        )
    )
    if "test" in i:
        at_fs = {m: i.get(m + "_at_record_fs", i[m]) for m in ("VSM", "TVSM", "DEM")}
        _peak_rows(
            sec,
            "fig. 15: inner (0.3556 mm, 1748 r/min, decimated to 12 kHz)",
            "107",
            i["test"],
            at_fs,
            "CWRU 107 is a 0.007 in (0.1778 mm) fault standing in for the paper's 0.014 in "
            "record at its speed (that record is not in shared/data); ",
        )
        lo = min(at_fs.values()) / i["test"]
        sec.rows.append(
            judge(
                "fig. 15: inner (0.3556 mm, 1748 r/min, decimated to 12 kHz), "
                "smallest model peak / CWRU 107 peak [-]",
                "seed VSM §2.5: 'all too large'",
                "> 1",
                f"{lo:.3g}",
                lo > 1,
                kind="paper",
            )
        )
    # same size, speed and sample rate as a record we have: CWRU 109 (0.007 in, 1796, 48 kHz)
    path = _record("109")
    if path is not None:
        rec = load_signal(path)
        test_pk = float(np.max(np.abs(rec.x - rec.x.mean())))
        pk = {}
        for m in ("vsm", "tvsm", "dem"):
            s = simulate(
                Scenario(
                    model=m, fault="inner", rpm=1796.0, defect_width_m=1.778e-4, duration_s=dur
                )
            )
            pk[m.upper()] = float(np.max(np.abs(s["acc_y"])))
        order = " < ".join(sorted(pk, key=pk.get))
        _peak_rows(
            sec, "inner at CWRU 109 conditions (0.1778 mm, 1796 r/min, 48 kHz)", "109", test_pk, pk
        )
        sec.rows.append(
            judge(
                "inner at CWRU 109 conditions (0.1778 mm, 1796 r/min, 48 kHz): "
                "order of the model peaks",
                "seed VSM §2.5",
                "VSM < TVSM < DEM",
                order,
                order == "VSM < TVSM < DEM",
                kind="paper",
            )
        )
        sec.rows.append(
            judge(
                "inner at CWRU 109 conditions: smallest model peak / test peak [-]",
                "seed VSM §2.5: 'all too large'",
                "> 1",
                f"{min(pk.values()) / test_pk:.3g}",
                min(pk.values()) > test_pk,
                kind="paper",
            )
        )
        sec.text += (
            f" CWRU 109 peak {test_pk:.3g} m/s²; simulated at its conditions: "
            + ", ".join(f"{k} {v:.3g}" for k, v in pk.items())
            + "."
        )
    sec.text += (
        " Peak |acceleration| [m/s²] — outer: "
        + ", ".join(f"{k} {v:.3g}" for k, v in o.items() if not k.endswith("_rms"))
        + "; inner: "
        + ", ".join(f"{k} {v:.3g}" for k, v in i.items() if not k.endswith("_rms"))
        + "."
    )


#: tolerance of a simulated peak acceleration against a measured one [-]: the seed gives no
#: damping, transfer path or sensor mounting for the CWRU rig, so only the order of magnitude
#: is in reach; +/-50 %, the same as the rotor's amplitude rows
PEAK_TOL = 0.5


def _peak_rows(
    sec: Section, case: str, record: str, test_pk: float, peaks, stand_in: str = ""
) -> None:
    """One row per model: its peak |acceleration| against the measured record's [m/s²];
    ``stand_in``: why that record stands in for the paper's, said first in the note."""
    for m in ("VSM", "TVSM", "DEM"):
        sec.rows.append(
            compare(
                f"{case}: {m} peak |acceleration| vs CWRU {record} [m/s²]",
                f"CWRU {record} drive end (measured)",
                test_pk,
                peaks[m],
                PEAK_TOL,
                stand_in + "the seed's own models miss the tests too (§2.5); the ring's "
                "stiffness and damping and the rig's transfer path set the level "
                "(docs/validation.md)",
                kind="measured",
            )
        )


def _diagnosis(ctx: Context, sec: Section) -> None:
    # the CWRU records themselves are judged once, in the diagnosis section: their rows here
    # repeated those, and counted each verdict twice in the summary (a helper's review of
    # the report, twenty-fifth session)
    sec.rows.append(
        info(
            "CWRU records " + ", ".join(sorted(RECORDS, key=int)) + " (drive end): diagnosis",
            "CWRU labels (measured)",
            "judged in the diagnosis section (each record once)",
        )
    )
    for m in ("vsm", "dem", "tvsm"):
        for fault, kw in (
            ("outer", {"rpm": 1796.0, "defect_width_m": 1.778e-4}),
            ("inner", {"rpm": 1748.0, "defect_width_m": 3.556e-4}),
            ("none", {"rpm": 1796.0}),
        ):
            s = simulate(
                Scenario(
                    model=m, fault=fault, duration_s=0.5, noise_rms_m_per_s2=NOISE_97, seed=1, **kw
                )
            )
            d = diagnose(s["acc_y"], s.fs_hz, B6205, s.shaft_hz)
            sec.rows.append(
                judge(
                    f"{m.upper()} {fault} simulation + CWRU-97-level noise: diagnosis",
                    "simulated fault (the input of the simulation)",
                    fault,
                    d.diagnosis,
                    d.diagnosis == fault,
                    kind="paper",
                )
            )


def run(ctx: Context) -> Section:
    sec = Section("vsm", TITLE)
    kin1796 = characteristic_frequencies(B6205, 1796 / 60)
    kin1748 = characteristic_frequencies(B6205, 1748 / 60)
    sec.rows.append(
        compare(
            "6205 BPFO at 1796 r/min [Hz]",
            "seed VSM eq. (21)",
            value("vsm.eq21.bpfo_6205_1796rpm"),
            kin1796.bpfo_hz,
            1e-3,
            kind=kind_of("vsm.eq21.bpfo_6205_1796rpm"),
        )
    )
    sec.rows.append(
        compare(
            "6205 BPFI at 1748 r/min [Hz]",
            "seed VSM eq. (20)",
            value("vsm.eq20.bpfi_6205_1748rpm"),
            kin1748.bpfi_hz,
            1e-3,
            kind=kind_of("vsm.eq20.bpfi_6205_1748rpm"),
        )
    )
    _traces(ctx, sec)
    _dynamics(ctx, sec)
    _diagnosis(ctx, sec)
    sec.text = (
        "Stiffness: secant (VSM), tangent (TVSM), nonlinear Hertz (DEM); simulations "
        "start at the static equilibrium; acceleration = mean over each 1/fs interval. "
        "Diagnosis rule: docs/validation.md." + sec.text
    )
    return sec
