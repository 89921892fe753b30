"""Report section for SPEC §2 (seed ROTOR, Liu et al. 2021): the rotor alone against beam
theory, the simulated CWRU record 132 (drive-end outer-race fault, 1750 r/min, 12 kHz; seed
figs. 5–6) and the fault-frequency amplitude against the number of disks (seed fig. 7)."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
from scipy.signal import find_peaks

from ...catalog import resolve_bearing
from ...config import HOUSING_DAMPING_N_S_M, HOUSING_MASS_KG, HOUSING_STIFFNESS_N_M
from ...dynamics.rotor.config import (
    BAND_TUNED_HOUSING,
    Armature,
    Shaft,
    ShaftMassModel,
    cwru_rotor_config,
    housing_from_frequency,
)
from ...dynamics.rotor.fe import Disk, assemble_rotor, complex_modes
from ...dynamics.rotor.model import rotor_modes, simulate_rotor
from ...geometry import Defect, contact_angle_from_order
from ...io.cwru import cwru_data_dir
from ...signal import amplitude_spectrum, envelope, envelope_spectrum, load_signal
from ...signal.contact_angle import measured_shaft_hz
from .. import Context, Row, Section, compare, info, judge, kind_of
from ..figures import ACC, FULL_WIDTH, HALF_WIDTH, mark_lines, new_figure, save_figure
from ..published import value

__all__ = ["TITLE", "run"]

TITLE = "ROTOR: bearing–rotor–housing system with a multi-disk rotor (SPEC §2, seed ROTOR)"

#: envelope band at 12 kHz (shared/data/cwru/SOURCES.md sanity check: 2–5 kHz)
BAND = (2000.0, 5000.0)
FS = 12000.0
#: seed ROTOR §3: fault-frequency amplitude from the highest to the lowest disk case [%]
SEED_DROP_PCT = value("rotor.s3.amplitude_drop")
RECORD = "12k_Drive_End_OR007@6_2_132.mat"


def _record_path() -> Path | None:
    p = cwru_data_dir() / RECORD
    return p if p.is_file() else None


def _near(spec, f0: float, tol: float = 0.01) -> tuple[float, float]:
    """(frequency [Hz], amplitude) of the largest line within ``f0 (1 +/- tol)``."""
    sel = np.flatnonzero((spec.freq >= f0 * (1 - tol)) & (spec.freq <= f0 * (1 + tol)))
    i = sel[np.argmax(spec.amplitude[sel])]
    return float(spec.freq[i]), float(spec.amplitude[i])


def _impacts(x: np.ndarray, fs: float, period: float, t0=0.10, t1=0.20) -> int:
    """Envelope peaks in [t0, t1] s above 30 % of the largest, >= 0.6 fault periods apart."""
    e = envelope(x, fs, BAND)[int(t0 * fs) : int(t1 * fs)]
    pk, _ = find_peaks(e, distance=int(0.6 * period * fs), height=0.3 * e.max())
    return int(pk.size)


def _rotor_alone(sec: Section) -> None:
    # seed rotor, one disk at mid-span of the massless shaft: a Jeffcott rotor
    cfg = cwru_rotor_config(1)
    sh = cfg.shaft
    fa = math.sqrt(48 * sh.ei / (cfg.armature.mass * sh.length**3)) / (2 * math.pi)
    sec.rows.append(
        compare(
            "rotor alone, 1 disk, pinned: 1st natural frequency [Hz]",
            "Jeffcott rotor sqrt(48 EI/(m L^3)) (Friswell et al. 2010 eq. 3.4)",
            fa,
            float(rotor_modes(cfg).frequency_hz[0]),
            1e-6,
            kind="paper",
        )
    )
    # shaft and rotor mass distributed: a pinned Rayleigh beam
    cfg = cwru_rotor_config(
        shaft=Shaft(mass_model=ShaftMassModel.DISTRIBUTED),
        armature=Armature(distributed=True),
        n_elements=32,
    )
    arm = cfg.armature
    rho_a = (sh.mass + arm.mass) / sh.length
    rho_i = (
        sh.mass / sh.length * sh.diameter**2 / 16
        + arm.mass / sh.length * (arm.diameter**2 + sh.diameter**2) / 16
    )
    f = rotor_modes(cfg, n_modes=6).frequency_hz[::2]
    for n in (1, 2, 3):
        k = n * math.pi / sh.length
        sec.rows.append(
            compare(
                f"rotor alone, distributed mass, pinned: mode {n} [Hz]",
                "Rayleigh beam w^2 = EI k^4/(rhoA + rhoI k^2) (Han, Benaroya & Wei 1999)",
                math.sqrt(sh.ei * k**4 / (rho_a + rho_i * k**2)) / (2 * math.pi),
                float(f[n - 1]),
                0.01,
                kind="paper",
            )
        )
    # mesh convergence (distributed shaft mass, 3 disks)
    f8, f64 = (
        rotor_modes(
            cwru_rotor_config(3, shaft=Shaft(mass_model="distributed"), n_elements=ne), n_modes=6
        ).frequency_hz[4]
        for ne in (8, 64)
    )
    sec.rows.append(
        compare(
            "rotor alone, 3 disks + distributed shaft: 3rd mode, 8 vs 64 elements [Hz]",
            "mesh convergence (64 elements as reference)",
            float(f64),
            float(f8),
            1e-3,
            kind="paper",
        )
    )
    # gyroscopics: Friswell et al. (2010) Example 5.9.1 at 4000 r/min, computed by ROSS
    E, rho, d, L = 211e9, 7810.0, 0.05, 1.5
    A, ia = math.pi * d**2 / 4, math.pi * d**4 / 64

    def disk(z, do, t=0.07, di=0.05):
        return Disk.from_geometry(z, rho * math.pi * (do**2 - di**2) / 4 * t, do, di, t)

    r = assemble_rotor(np.linspace(0, L, 7), E * ia, rho * A, rho * ia,
                       [disk(0.5, 0.28), disk(1.0, 0.35)])  # fmt: skip
    K = r.K.copy()
    for nd in (0, 6):
        K[r.dof(nd, "x"), r.dof(nd, "x")] += 1e6
        K[r.dof(nd, "y"), r.dof(nd, "y")] += 1e6
    m = complex_modes(r.M, K, r.G, 4000 * math.pi / 30)
    ross_4000 = value("friswell.ex5_9_1.ross_4000rpm")
    for i in (0, 1, 3):
        ross = ross_4000[i]
        sec.rows.append(
            compare(
                f"Friswell Example 5.9.1 at 4000 r/min, mode {i + 1} [rad/s]",
                "Friswell et al. 2010 Ex. 5.9.1 via ROSS (Timoshenko elements)",
                ross,
                float(m.frequency_hz[i] * 2 * math.pi),
                3e-3,
                kind=kind_of("friswell.ex5_9_1.ross_4000rpm"),
            )
        )


def _psd_peak_hz(x: np.ndarray, fs: float) -> float:
    """Frequency of the Welch PSD maximum (1024-sample segments) [Hz]: where the signal rings."""
    from scipy.signal import welch

    f, p = welch(x, fs, nperseg=1024)
    return float(f[np.argmax(p)])


def _sim132(**kw) -> tuple[np.ndarray, float]:
    """Simulated DE y acceleration of the record-132 case (9 disks, about 1 s) and its BPFO."""
    cfg = cwru_rotor_config(9, de_fault=Defect("outer"), **kw)
    bpfo = cfg.kinematics()["DE"].bpfo_hz
    # a whole number of fault periods (about 1 s) puts the simulated BPFO on a spectral bin
    dur = round(bpfo * 1.0) / bpfo
    return simulate_rotor(cfg, duration=dur, sample_rate=FS).channel("DE", "y"), bpfo


def _band_tuned(sec: Section, meas: dict[str, float]) -> None:
    """Rows of the alternative, non-literature housing tuned to the record's resonance band
    (``meas``: the measured values of :func:`_cwru`)."""
    h = housing_from_frequency(*BAND_TUNED_HOUSING)
    xs, bpfo = _sim132(housing_de=h, housing_fe=h)
    why = (
        "not the default: 1 kg at 3.3 kHz, 5 % damping, chosen from the measured 2.5-3.5 kHz "
        "band of this record (BAND_TUNED_HOUSING); shows how much the unpublished housing "
        "sets the level and the ringing frequency"
    )
    tag = "band-tuned housing (not literature)"
    f_m, f_s = meas["meas_psd_hz"], _psd_peak_hz(xs, FS)
    sec.rows += [
        info(f"{tag}: DE ringing frequency, Welch PSD maximum [Hz]",
             "identified from CWRU 132 DE (not a comparison)", f_s,
             f"the record rings at {f_m:.5g} Hz; equal by construction: this housing's mount "
             "frequency was chosen from this record's resonance band; not a validation"),
        compare(f"{tag}: DE acceleration RMS, 1 s [m/s²]", "CWRU 132 DE",
                meas["meas_rms"], float(np.std(xs)), 0.5, why, kind="measured"),
        compare(f"{tag}: DE envelope amplitude at BPFO (2-5 kHz band) [m/s²]", "CWRU 132 DE",
                meas["meas_env"], _near(envelope_spectrum(xs, FS, BAND), bpfo)[1], 0.5, why,
                kind="measured"),
    ]  # fmt: skip


def _cwru(ctx: Context, sec: Section) -> dict[str, float]:
    xs, bpfo = _sim132()
    path = _record_path()
    out = {"sim_rms": float(np.std(xs)), "sim_peak": float(np.abs(xs).max())}
    es_s = envelope_spectrum(xs, FS, BAND)
    rec = load_signal(path) if path else None
    if rec is None:
        sec.text += f" CWRU record {RECORD} not found: measured rows skipped."
        return out
    xm = rec.x[: int(FS)]  # 1 s of the record, as in the seed's figures
    es_m = envelope_spectrum(xm, rec.fs, BAND)
    res = max(es_m.resolution, es_s.resolution)
    fm, am = _near(es_m, bpfo)
    fsim, asim = _near(es_s, bpfo)
    out |= {"meas_rms": float(np.std(xm)), "meas_peak": float(np.abs(xm).max()),
            "meas_psd_hz": _psd_peak_hz(xm, rec.fs),
            "meas_env": am, "sim_env": asim}  # fmt: skip
    # the whole record (10 s, 0.1 Hz bins) locates the measured fault line precisely
    es_all = envelope_spectrum(rec.x, rec.fs, BAND)
    order_m = _near(es_all, bpfo, 0.02)[0] / (rec.rpm / 60)
    bpfo_order = value("cwru.drive_end.bpfo_order")
    # the record's own shaft harmonics give its speed: the offset is not a speed error
    shaft_m, _n = measured_shaft_hz(rec.x, rec.fs, rec.rpm / 60)
    alpha = math.degrees(
        contact_angle_from_order(
            resolve_bearing("6205-cwru"), "bpfo", order_m * rec.rpm / 60 / shaft_m
        )
    )
    speed_note = (
        f"the measured line is at order {order_m:.4f} of the stored {rec.rpm:g} r/min (whole "
        f"record), {100 * (order_m / bpfo_order - 1):.2f} % above the CWRU BPFO order 3.5848; "
        f"the record's shaft harmonics put its speed at {60 * shaft_m:.1f} r/min, so the offset "
        f"is not speed: it is a contact angle of about {alpha:.1f} deg (an axial load on the "
        "deep-groove bearing; the inner-race records of this size sit as far below BPFI; "
        "docs/validation.md, 'Contact angle of the CWRU bearings'); the model runs at the "
        "stored speed and alpha = 0"
    )
    sec.rows.append(
        compare(
            "measured 132 fault frequency as an order of the stored speed [-]",
            "CWRU bearing table BPFO order 3.5848",
            bpfo_order,
            order_m,
            1e-3,
            speed_note,
            kind=kind_of("cwru.drive_end.bpfo_order"),
            verified_by="tests/test_deviations.py::test_record_132_fault_line_is_above_the_table_order",
        )
    )
    sec.rows.append(
        compare(
            "DE outer fault: fault frequency, simulated vs measured 132 [Hz]",
            f"CWRU 132 envelope spectrum (1 s, bin {res:.3g} Hz; seed figs. 5-6)",
            fm,
            fsim,
            res / fm,
            speed_note,
            kind="measured",
        )
    )
    for h in (2, 3):
        fmh, _ = _near(es_m, h * bpfo)
        fsh, _ = _near(es_s, h * bpfo)
        sec.rows.append(
            compare(
                f"DE outer fault: envelope harmonic {h} x BPFO, simulated vs measured [Hz]",
                "CWRU 132 (seed fig. 6: 'harmonics close'), 1 s",
                fmh,
                fsh,
                res / fmh,
                speed_note,
                kind="measured",
            )
        )
    n_m = _impacts(rec.x, rec.fs, 1 / bpfo)
    n_s = _impacts(xs, FS, 1 / bpfo)
    sec.rows.append(
        compare(
            "impacts between 0.10 s and 0.20 s [-]",
            "CWRU 132 DE (seed fig. 5a vs 6a: 'same number')",
            float(n_m),
            float(n_s),
            0.0,
            kind="measured",
        )
    )
    why = (
        "the literature housing (Sawalhi & Randall 2008 pedestal, 240 Hz mount) has no mode in "
        "the record's 2.5-3.5 kHz ringing band, which carries most of the measured energy; the "
        "seed gives no housing or contact damping; the only radial load is the rotor weight "
        "(20 N); the motor structure, coupling and dynamometer are not modelled "
        "(docs/validation.md)"
    )
    sec.rows.append(
        compare(
            "DE ringing frequency, Welch PSD maximum [Hz]",
            "CWRU 132 DE",
            out["meas_psd_hz"],
            _psd_peak_hz(xs, FS),
            0.05,
            why,
            kind="measured",
        )
    )
    for lab, key in (("RMS", "rms"), ("peak", "peak")):
        sec.rows.append(
            compare(
                f"DE acceleration {lab}, 1 s [m/s²]",
                "CWRU 132 DE",
                out[f"meas_{key}"],
                out[f"sim_{key}"],
                0.5,
                why,
                kind="measured",
            )
        )
    sp_m = amplitude_spectrum(xm, rec.fs, ACC)
    sp_s = amplitude_spectrum(xs, FS, ACC)
    sec.rows.append(
        compare(
            "DE raw-spectrum amplitude at BPFO, 1 s [m/s²]",
            "CWRU 132 DE",
            _near(sp_m, bpfo)[1],
            _near(sp_s, bpfo)[1],
            0.5,
            "with only the rotor weight (20 N) as radial load the model's DE housing moves "
            "little at BPFO itself; the rig's structure (motor frame, base, coupling) that "
            "carries the measured low-frequency response is not modelled",
            kind="measured",
        )
    )
    sec.rows.append(
        compare(
            "DE envelope amplitude at BPFO (2-5 kHz band) [m/s²]",
            "CWRU 132 DE",
            am,
            asim,
            0.5,
            why,
            kind="measured",
        )
    )
    _band_tuned(sec, out)
    # figures: seed figs. 5 and 6 analogues (acceleration in m/s², as everywhere in the report)
    fig, axs = new_figure(3, 2, width=FULL_WIDTH, row_height=2.5)
    for j, (lab, x, fs) in enumerate((("measured CWRU 132", xm, rec.fs),
                                      ("simulated, 9 disks", xs, FS))):  # fmt: skip
        t = np.arange(x.size) / fs
        sel = (t >= 0.10) & (t <= 0.20)
        axs[0, j].plot(t[sel], x[sel], lw=0.6)
        axs[0, j].set_title(f"{lab}: DE acceleration")
        axs[0, j].set_xlabel("time [s]")
        axs[0, j].set_ylabel(f"acceleration [{ACC}]")
        sp = amplitude_spectrum(x, fs, ACC)
        axs[1, j].plot(sp.freq / 1e3, sp.amplitude, lw=0.5)
        axs[1, j].set_title(f"{lab}: amplitude spectrum")
        axs[1, j].set_xlabel("frequency [kHz]")
        axs[1, j].set_ylabel(f"amplitude [{ACC}]")
        es = envelope_spectrum(x, fs, BAND)
        sel = es.freq <= 500
        axs[2, j].plot(es.freq[sel], es.amplitude[sel], lw=0.7)
        mark_lines(axs[2, j], bpfo * np.arange(1, 5), f"BPFO = {bpfo:.2f} Hz and harmonics"
                   if j == 0 else None)  # fmt: skip
        axs[2, j].set_title(f"{lab}: envelope spectrum (2-5 kHz band)")
        axs[2, j].set_xlabel("envelope frequency [Hz]")
        axs[2, j].set_ylabel(f"envelope amplitude [{ACC}]")
    fig.legend(loc="outside lower center")
    save_figure(fig, ctx.out_dir / "rotor_fig5_6_cwru132.png")
    sec.figures.append(
        (
            "rotor_fig5_6_cwru132.png",
            "Seed ROTOR figs. 5-6 analogue: CWRU record 132 (DE, outer race 0.007 in at 6 o'clock, "
            "1750 r/min) beside the simulated DE housing acceleration (9 disks): waveform "
            "0.10-0.20 s, amplitude spectrum, envelope spectrum (2-5 kHz band); all in m/s². "
            "Each panel has its own axis, so the shapes can be compared; the levels are not "
            f"those of the record: the simulated RMS is {out['sim_rms'] / out['meas_rms']:.3g}"
            f"× and its BPFO envelope line {asim / am:.3g}× the record's (the rows above).",
        )
    )
    return out


def _disks(ctx: Context, sec: Section, cwru: dict[str, float]) -> None:
    from ...plotting import log_if_wide

    bpfo0 = cwru_rotor_config(1).kinematics()["DE"].bpfo_hz
    dur = round(bpfo0 * (0.5 if ctx.quick else 1.0)) / bpfo0  # BPFO on a spectral bin
    cases: list[tuple[str, Armature]] = [(f"{n}", Armature(n_disks=n)) for n in (1, 2, 3, 5, 9)]
    if not ctx.quick:
        cases.append(("17", Armature(n_disks=17)))
    cases.append(("FE limit", Armature(distributed=True)))
    env, raw, fpk = {}, {}, {}
    fig, axs = new_figure(len(cases), 1, width=FULL_WIDTH, row_height=1.7, sharex=True)
    bpfo = res = math.nan
    for ax, (lab, arm) in zip(axs, cases, strict=True):
        r = simulate_rotor(cwru_rotor_config(armature=arm, de_fault=Defect("outer")),
                           duration=dur, sample_rate=FS)  # fmt: skip
        x = r.channel("DE", "y")
        bpfo = r.kinematics["DE"].bpfo_hz
        es = envelope_spectrum(x, FS, BAND)
        res = es.resolution
        fpk[lab], env[lab] = _near(es, bpfo)
        sp = amplitude_spectrum(x, FS, ACC)
        raw[lab] = _near(sp, bpfo)[1]
        sel = sp.freq <= 1000
        ax.plot(sp.freq[sel], sp.amplitude[sel], lw=0.6)
        ax.set_ylabel(f"amplitude [{ACC}]")
        name = {"FE limit": "distributed rotor mass (FE limit)", "1": "1 disk"}.get(
            lab, f"{lab} disks"
        )
        ax.set_title(name, loc="left")
        mark_lines(ax, bpfo * np.arange(1, 4),
                   f"BPFO = {bpfo:.2f} Hz and harmonics" if ax is axs[0] else None)  # fmt: skip
    fig.legend(loc="outside lower center")
    axs[-1].set_xlabel("frequency [Hz]")
    save_figure(fig, ctx.out_dir / "rotor_fig7_spectra.png")
    labs = list(env)
    fig2, ax = new_figure(width=HALF_WIDTH, height=4.0)
    xs = np.arange(len(labs))
    ax.plot(xs, [env[k] for k in labs], "o-", label="simulated (envelope at BPFO)")
    vals = list(env.values())
    if "meas_env" in cwru:
        ax.axhline(cwru["meas_env"], color="k", ls="--", label="measured CWRU 132")
        vals.append(cwru["meas_env"])
    if log_if_wide(ax, vals):
        ax.set_ylim(min(vals) / 2, max(vals) * 2)
    ax.set_xticks(xs, labs)
    ax.set_xlabel("number of disks [-]")
    ax.set_ylabel(f"envelope amplitude at BPFO [{ACC}]")
    ax.set_title("DE envelope amplitude at BPFO, 2-5 kHz band")
    ax.grid(True, alpha=0.3)
    fig2.legend(loc="outside lower center", ncols=2)
    save_figure(fig2, ctx.out_dir / "rotor_fig7_amplitude.png")
    sec.figures += [
        ("rotor_fig7_spectra.png", "Seed ROTOR fig. 7 analogue: DE amplitude spectra (0-1 kHz) "
         f"for 1, 2, 3, 5, 9{'' if ctx.quick else ', 17'} disks and the distributed rotor mass "
         f"(converged FE limit), {dur:.4g} s each."),
        ("rotor_fig7_amplitude.png", "DE envelope amplitude at BPFO (2-5 kHz band) against the "
         "number of disks, with the measured CWRU 132 value"
         + (f" (log scale: the record's is {cwru['meas_env'] / max(env.values()):.3g}× the "
            "largest simulated)." if "meas_env" in cwru and max(env.values()) > 0 else ".")),
    ]  # fmt: skip
    spread = max(fpk.values()) - min(fpk.values())
    sec.rows.append(
        Row(
            "fault frequency over 1, 2, 3, 5, 9 disks and the FE limit: spread [Hz]",
            "seed ROTOR §3: 'does not change'",
            0.0,
            spread,
            None,
            "match" if spread <= res else "mismatch",
            f"envelope peak frequencies {sorted(set(round(v, 3) for v in fpk.values()))} Hz, "
            f"bin {res:.3g} Hz",
            res,
            reference_kind="paper",
        )
    )
    for name, amp in (("envelope", env), ("raw-spectrum", raw)):
        hi, lo = max(amp.values()), min(amp.values())
        sec.rows.append(
            compare(
                f"{name} amplitude at BPFO, highest to lowest disk case [%]",
                "seed ROTOR §3",
                SEED_DROP_PCT,
                100 * (lo - hi) / hi,
                0.1,
                "the impacts excite the bearing node and ball contacts at 1-5 kHz, where "
                "the shaft's flexibility isolates the disks from the bearing, so the "
                "rotor's mass distribution changes little; see docs/validation.md",
                kind=kind_of("rotor.s3.amplitude_drop"),
            )
        )
    two = env["2"] > env["1"]
    sec.rows.append(
        judge(
            "envelope amplitude at BPFO: 2 disks above 1 disk",
            "seed ROTOR §3",
            "yes",
            "yes" if two else "no",
            two,
            "" if two else f"{env['2']:.4g} vs {env['1']:.4g} m/s²; see docs/validation.md",
            kind="paper",
        )
    )
    if "meas_env" in cwru:
        trend = env["FE limit"] < env["1"]
        closer = abs(env["FE limit"] - cwru["meas_env"]) < abs(env["1"] - cwru["meas_env"])
        sec.rows.append(
            judge(
                "more disks bring the amplitude towards the measured one",
                "seed ROTOR §3",
                "yes",
                "yes" if closer else f"no (trend {'down' if trend else 'up'}, but below test)",
                closer,
                ""
                if closer
                else "our simulated amplitude is below the measured one for "
                "every disk count, so the (small) decrease moves it away",
                kind="paper",
            )
        )
    sec.text += (
        " Disk study, DE envelope amplitude at BPFO [m/s²]: "
        + ", ".join(f"{k}: {v:.4g}" for k, v in env.items())
        + "; raw spectrum at BPFO [m/s²]: "
        + ", ".join(f"{k}: {v:.3g}" for k, v in raw.items())
        + "."
    )


def run(ctx: Context) -> Section:
    sec = Section("rotor", TITLE)
    _rotor_alone(sec)
    cwru = _cwru(ctx, sec)
    _disks(ctx, sec, cwru)
    sec.text = (
        "Beam finite elements with lumped disks and nonlinear ball bearings (docs/models.md, "
        f"ROTOR); housings {HOUSING_MASS_KG:g} kg on {HOUSING_STIFFNESS_N_M:g} "
        f"N/m and {HOUSING_DAMPING_N_S_M:g} N s/m (Sawalhi & Randall 2008 pedestal, as "
        "used for the CWRU 6205 by Ruan et al. 2022); gravity is the only radial load; "
        "anti-aliased 12 kHz output." + sec.text
    )
    return sec
