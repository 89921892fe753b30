"""Every figure of the package meets one standard (issue 15, part 3; :mod:`bearingsim.plotting`):
constrained layout, at most page width, no text below 7 pt (9 px in the report), every axis that
shows numbers labelled with a quantity and a unit in brackets, no overlapping tick labels or
data labels, nothing sticking out of the figure; and the report page shows every figure at the
size the standard plans, linked to its full-size PNG.

The plot methods are drawn on small results (a few seconds in all); the report page is checked
on a hand-made section (no simulation)."""

from __future__ import annotations

import math
import re
from dataclasses import replace

import matplotlib

matplotlib.use("Agg")

import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import pytest  # noqa: E402

from bearingsim import get_bearing  # noqa: E402
from bearingsim.config import Scenario  # noqa: E402
from bearingsim.plotting import (  # noqa: E402
    CSS_PX_PER_IN,
    MIN_FONT_PT,
    figure_problems,
    label_points,
    mark_lines,
    new_figure,
)

B6205 = get_bearing("6205")


@pytest.fixture(scope="module")
def made():
    """One small result of every kind that has plot methods."""
    from bearingsim.dynamics.ias import IasParams, simulate_ias
    from bearingsim.dynamics.ring.base import ModelInputs
    from bearingsim.dynamics.ring.trace import stiffness_trace
    from bearingsim.dynamics.rotor.config import cwru_rotor_config
    from bearingsim.dynamics.rotor.model import simulate_rotor
    from bearingsim.geometry import Defect, defect_at_edge
    from bearingsim.life.damage import GCR15_TORSION, fit_sn_curve, torsion_check
    from bearingsim.life.fatigue import contact_fatigue_life
    from bearingsim.life.fe import contact_section, section_spec
    from bearingsim.life.weibull import weibull_fit
    from bearingsim.load_distribution import radial_load_distribution
    from bearingsim.quasistatic import Misalignment, run_quasi_static, stiffness_vs_cage
    from bearingsim.signal import diagnose, fast_kurtogram
    from bearingsim.simulation import simulate

    sim = simulate(Scenario(fault="outer", rpm=1796.0, duration_s=0.3, noise_rms_m_per_s2=0.5))
    d = defect_at_edge(B6205, "outer", 1e-3, 1e-3, math.radians(10.0))
    ias_p = IasParams(get_bearing("NU204-ECP"))
    ias = simulate_ias(ias_p, 2.0, 1e-5, 20_000.0)
    fit = fit_sn_curve(GCR15_TORSION)
    b6206 = get_bearing("6206")
    life = contact_fatigue_life(b6206, 5000.0, mesh="coarse", delta_d=0.05, stop="initiation")
    from bearingsim.life.fatigue import inner_contact

    c = inner_contact(b6206, 5000.0)
    return {
        "sim": sim,
        "diag": diagnose(sim["acc_y"], sim.fs_hz, B6205, sim.shaft_hz),
        "kurtogram": fast_kurtogram(sim["acc_y"], sim.fs_hz, min_bandwidth_hz=600.0),
        "trace": stiffness_trace(
            ModelInputs(B6205, 10.0, 50.0, 1750 / 60, d, retention_factor=0.38),
            np.radians(np.arange(0, 360, 0.5)),
        ),
        "rotor": simulate_rotor(cwru_rotor_config(1, de_fault=Defect("outer")), duration=0.05),
        "ias": ias,
        "ias_summary": ias.analyze(),
        "ias_healthy": simulate_ias(replace(ias_p, spall=None), 0.5, 1e-5, 20_000.0),
        "load": radial_load_distribution(B6205, 10.0, 50.0, 0.0),
        "qs": run_quasi_static(B6205, 0.0, 10.0, 500.0),
        "stiffness": stiffness_vs_cage(
            B6205,
            0.0,
            500.0,
            misalignment=Misalignment(outer_tilt=3e-3),
            cage_revs=2,
            points_per_rev=90,
        ),  # fmt: skip
        "fit": fit,
        "torsion": torsion_check(fit.law),
        "life": life,
        "weibull": weibull_fit([2.1e8, 2.64e8, 5.57e8]),
        "section": contact_section(b6206.material, c.p_max, c.b, section_spec(c.b, "coarse")),
    }


#: every public plot method of the package: (id, figure maker)
PLOTS = {
    "SimulationResult.plot_time": lambda m: m["sim"].plot_time(t_range=(0.0, 0.05)),
    "SimulationResult.plot_stiffness": lambda m: m["sim"].plot_stiffness(),
    "SimulationResult.plot_envelope": lambda m: m["sim"].plot_envelope(),
    "Diagnosis.plot": lambda m: m["diag"].plot(unit="m/s^2"),
    "Diagnosis.plot (unit unknown)": lambda m: m["diag"].plot(),
    "Kurtogram.plot": lambda m: m["kurtogram"].plot(),
    "Spectrum.plot": lambda m: m["diag"].spectrum.plot(500.0, marks=[107.3, 214.6]),
    "StiffnessTrace.plot_total": lambda m: m["trace"].plot_total(),
    "StiffnessTrace.plot_ball": lambda m: m["trace"].plot_ball(5),
    "StiffnessTrace.plot_balls": lambda m: m["trace"].plot_balls([4, 5, 6]),
    "RotorResponse.plot_waveform": lambda m: m["rotor"].plot_waveform(t0=0.0, t1=0.05),
    "RotorResponse.plot_spectrum": lambda m: m["rotor"].plot_spectrum(),
    "IasResult.plot_ias": lambda m: m["ias"].plot_ias(revs=2),
    "IasResult.plot_order_spectrum": lambda m: m["ias"].plot_order_spectrum(),
    "AngleSignal.plot": lambda m: m["ias_summary"].signal.plot(),
    "SpallEstimate.plot": lambda m: m["ias_summary"].estimate.plot(),
    "IasResult.plot_ias (healthy)": lambda m: m["ias_healthy"].plot_ias(),
    "LoadDistribution.plot": lambda m: m["load"].plot(0),
    "QuasiStaticSolution.plot_loads": lambda m: m["qs"].plot_loads(0),
    "StiffnessMatrix.plot_matrix": lambda m: m["qs"].stiffness_matrix.plot_matrix(0),
    "StiffnessResult.plot": lambda m: m["stiffness"].plot(),
    "StiffnessResult.plot_series": lambda m: m["stiffness"].plot_series(),
    "StiffnessResult.plot_spectra": lambda m: m["stiffness"].plot_spectra(),
    "SNFit.plot": lambda m: m["fit"].plot(),
    "TorsionCheck.plot": lambda m: m["torsion"].plot(),
    "LifeResult.plot_damage_field": lambda m: m["life"].plot_damage_field("initiation"),
    "LifeResult.plot_damage_curve": lambda m: m["life"].plot_damage_curve(),
    "WeibullFit.plot": lambda m: m["weibull"].plot({"damage life": 1e8, "ISO 281 L10": 3.2e8}),
    "ContactSection.plot_mesh": lambda m: m["section"].plot_mesh(zoom=1e-3),
}


@pytest.mark.parametrize("name", list(PLOTS))
def test_plot_methods_meet_the_figure_standard(made, name):
    fig = PLOTS[name](made)
    try:
        assert figure_problems(fig) == []
    finally:
        plt.close(fig)


def test_every_plot_method_is_checked():
    """A new ``def plot...`` in the package must be added to PLOTS (by its method name)."""
    from pathlib import Path

    src = Path(__file__).resolve().parents[1] / "src" / "bearingsim"
    found = set()
    for p in src.rglob("*.py"):
        if "report" in p.parts or "cli" in p.parts:
            continue
        found |= set(re.findall(r"^    def (plot\w*)\(", p.read_text(), flags=re.M))
    checked = {k.split(".")[1].split(" ")[0] for k in PLOTS}
    assert found - checked == set()


def _bad_figure():
    """A figure breaking the standard in every checked way."""
    fig, ax = plt.subplots(figsize=(14, 3))  # not constrained, too wide
    ax.plot([1, 2, 3], [1e-3, 2.0, 3.0])
    ax.set_xlabel("12.0-24.0 kHz")  # a band, no quantity [unit]
    ax.set_xticks([1.0, 1.001, 1.002], ["1000000000", "1000000001", "1000000002"])
    ax.annotate("BPFO", (2, 2), fontsize=5)
    ax.annotate("2xBPFO", (2.001, 2))
    ax.text(3.2, 3.0, "far out of the figure", transform=ax.transData, clip_on=False)
    ax.set_ylim(0, 3)
    ax.set_xlim(0.9, 3.1)
    ax.text(1e3, 0.5, "x" * 10)
    return fig


def test_the_check_can_fail():
    fig = _bad_figure()
    got = " | ".join(figure_problems(fig))
    plt.close(fig)
    for part in (
        "layout is not constrained",
        "width 14.00 in",
        "x label '12.0-24.0 kHz' has no quantity [unit]",
        "y label '' has no quantity [unit]",
        "x tick labels overlap",
        "'BPFO' overlaps '2xBPFO'",
        "5.0 pt < 7.0 pt",
        "sticks out of the figure",
    ):
        assert part in got, part


def test_label_helpers_leave_out_overlapping_labels():
    fig, ax = new_figure()
    ax.plot(np.arange(100.0), np.ones(100))
    ax.set_xlim(0, 100)
    n = label_points(ax, [10, 11, 50, 52, 90], [1, 1, 1, 1, 1], ["a", "b", "c", "d", "e"])
    assert n == 3  # b (1 % of the width from a) and d (2 %) left out
    mark_lines(ax, [20, 21, 60], "harmonics", texts=["1x", "2x", "3x"])
    ax.set_xlabel("frequency [Hz]")
    ax.set_ylabel("amplitude [m/s²]")
    assert figure_problems(fig) == []
    assert [t.get_text() for t in ax.texts] == ["a", "c", "e", "1x", "3x"]
    plt.close(fig)


def test_envelope_plot_labels_the_diagnosed_family_first(made):
    """A line of another family beside a harmonic of the diagnosed one (the 6205's 2xBPFI lies
    0.7 % above 3xBPFO) does not take the label of the line that made the verdict."""
    from dataclasses import replace

    d = made["diag"]
    assert d.diagnosis == "outer"
    by = {p.label: p for p in d.peaks}
    h3 = by["3xBPFO"]
    assert h3.detected
    near = replace(by["2xBPFI"], detected=True, freq_hz=h3.freq_hz * 1.007, amplitude=h3.amplitude)
    d2 = replace(d, peaks=[near if p.label == "2xBPFI" else p for p in d.peaks])
    fig = d2.plot()
    texts = [t.get_text() for t in fig.axes[0].texts]
    assert "3xBPFO" in texts and "2xBPFI" not in texts, texts
    plt.close(fig)


def test_strict_save_refuses_a_figure_off_the_standard(tmp_path, monkeypatch):
    from bearingsim.report.figures import STRICT_ENV, save_figure

    monkeypatch.setenv(STRICT_ENV, "1")
    with pytest.raises(ValueError, match="bad.png breaks the figure standard: .*no quantity"):
        save_figure(_bad_figure(), tmp_path / "bad.png")
    assert not (tmp_path / "bad.png").exists()
    fig, _ax = plt.subplots()  # no layout engine, no axis labels
    with pytest.raises(ValueError, match="layout is not constrained"):
        save_figure(fig, tmp_path / "plain.png")
    monkeypatch.setenv(STRICT_ENV, "0")  # outside the tests: written as it is
    fig, _ax = plt.subplots()
    assert save_figure(fig, tmp_path / "plain.png").is_file()


def test_min_font_is_9_px_in_the_report():
    """The report shows figures at 96 CSS px per inch: the smallest font is 9 px or more."""
    assert MIN_FONT_PT * CSS_PX_PER_IN / 72.0 >= 9.0


def test_report_page_links_every_figure_at_the_planned_size(tmp_path):
    from bearingsim.report import Section
    from bearingsim.report.figures import DPI, save_figure
    from bearingsim.report.html import write_html

    fig, ax = new_figure(2, 1)
    for a in ax:
        a.plot([0, 1], [0, 1])
        a.set_xlabel("time [s]")
        a.set_ylabel("acceleration [m/s²]")
    save_figure(fig, tmp_path / "wide.png")
    fig, ax = new_figure()
    ax.plot([0, 1], [0, 1])
    ax.set_xlabel("frequency [Hz]")
    ax.set_ylabel("amplitude [m/s²]")
    save_figure(fig, tmp_path / "half.png")
    sec = Section("s", "a section", figures=[("wide.png", "two panels"), ("half.png", "one")])
    write_html(tmp_path / "report.html", [sec], quick=True)
    page = (tmp_path / "report.html").read_text()
    figs = re.findall(r"<figure style='width:(\d+)px'><a href='([^']+)'[^>]*><img src='([^']+)'",
                      page)  # fmt: skip
    assert [(h, s) for _w, h, s in figs] == [("wide.png", "wide.png"), ("half.png", "half.png")]
    assert page.count("<img") == 2
    from bearingsim.report.html import png_size

    for w, _h, src in figs:
        px = png_size(tmp_path / src)[0]
        # shown at 96 CSS px per inch of figure (the PNG is DPI dots per inch)
        assert int(w) == round(px * CSS_PX_PER_IN / DPI), src
    wide, half = (int(w) for w, _h, _s in figs)
    assert 1000 <= wide <= 1070 and half <= 525  # page width, and two per row in 1088 px
