"""The measurement chain ("rig", issue 16 item 3): a linear transfer path, background, tones and
sensor noise applied to a model's output; rig files validated with one-line errors."""

from __future__ import annotations

import re
import subprocess
import sys
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest
from numpy.testing import assert_allclose, assert_array_equal
from scipy.signal import welch

import bearingsim
from bearingsim import simulate
from bearingsim.errors import ConfigError
from bearingsim.results import load_result
from bearingsim.rig import Background, Mode, Rig, Tone, apply_rig, available_rigs, load_rig

SRC = str(Path(bearingsim.__file__).resolve().parents[1])

RIG_TOML = """
name = "test-rig"
description = "a rig written for the tests"
provenance = "written by hand for tests/test_rig.py"
input_channel = "acc_y"

[path]
gain = 0.5
provenance = "test value"

[[mode]]
frequency_hz = 3350.0
damping_ratio = 0.05
gain = 4.0
provenance = "test value"

[background]
frequency_hz = [20.0, 6000.0]
psd_m2_per_s4_per_hz = [1e-4, 1e-6]
provenance = "test value"

[[tone]]
order = 1.0
amplitude_m_per_s2 = 0.05
provenance = "test value"

[sensor]
noise_rms_m_per_s2 = 0.01
provenance = "test value"
"""


#: a model-based path gain table (rig.ModelGain)
_MG = '\n[[model_gain]]\nmodel = "rotor"\nscale = 6.5\nprovenance = "test gain"\n'
RIG_TOML += _MG
#: the fitted form of a model gain (a second table, for the VSM)
_FIT = (
    '\n[[model_gain]]\nmodel = "vsm"\npath_gain = 0.01\nmode_gains = [0.5]\n'
    'provenance = "test fit"\n'
)


@pytest.fixture()
def rig_file(tmp_path):
    p = tmp_path / "rig.toml"
    p.write_text(RIG_TOML, encoding="utf-8")
    return p


def _rig(**kw) -> Rig:
    base = dict(name="r", description="", provenance="test", gain=0.0)
    return Rig(**(base | kw))


def test_mode_resonance_gain_and_bandwidth():
    """The discretised mode keeps its natural frequency, its gain there and its half-power
    bandwidth 2 zeta f_n (the band-pass of one degree of freedom) at f_n = 0.28 fs, where a
    bilinear transform pre-warped at f_n alone narrows the band to 0.56 of it."""
    fs, fn, zeta, g = 12000.0, 3350.0, 0.05, 4.0
    rig = _rig(modes=(Mode(fn, zeta, g, "test"),))
    f = np.linspace(1000.0, 5500.0, 45001)
    h = np.abs(rig.transfer(f, fs))
    assert f[np.argmax(h)] == pytest.approx(fn, abs=0.2)
    assert h.max() == pytest.approx(g, rel=1e-6)
    above = f[h >= g / np.sqrt(2.0)]
    # iirpeak pre-warps the band edges: the digital bandwidth is the mode's (grid step 0.1 Hz)
    assert above[-1] - above[0] == pytest.approx(2 * zeta * fn, abs=0.3)


def test_identity_rig_returns_the_signal():
    x = np.random.default_rng(1).standard_normal(1000)
    rig = Rig(name="id", description="", provenance="test")  # gain 1, nothing else
    assert_array_equal(rig.apply(x, 12000.0), x)


def test_background_has_the_tabulated_psd():
    fs, n = 12000.0, 12000 * 40
    bg = Background((20.0, 6000.0), (1e-4, 1e-6), "test")
    y = bg.synthesize(n, fs, np.random.default_rng(2))
    f, p = welch(y, fs=fs, nperseg=4096)
    band = (f > 100.0) & (f < 5000.0)
    ratio = p[band] / bg.psd_at(f[band])
    assert np.median(ratio) == pytest.approx(1.0, abs=0.03)
    assert np.all((ratio > 0.6) & (ratio < 1.6))
    # the RMS is the integral of the PSD
    ff = np.linspace(20.0, 6000.0, 200001)
    assert np.std(y) == pytest.approx(np.sqrt(np.trapezoid(bg.psd_at(ff), ff)), rel=0.02)


def test_tone_and_sensor_noise_levels():
    fs, n = 12000.0, 120000
    rig = _rig(tones=(Tone(0.05, "test", order=1.0),))
    y = rig.apply(np.zeros(n), fs, shaft_hz=29.5)
    spec = np.abs(np.fft.rfft(y)) * 2 / n
    f = np.fft.rfftfreq(n, 1 / fs)
    assert f[np.argmax(spec)] == pytest.approx(29.5, abs=0.1)
    assert spec.max() == pytest.approx(0.05, rel=0.01)
    noisy = _rig(noise_rms_m_per_s2=0.01)
    assert np.std(noisy.apply(np.zeros(n), fs)) == pytest.approx(0.01, rel=0.02)


def test_a_zero_gain_mode_contributes_nothing_quietly():
    """A mode of gain 0 (allowed) is the path without it, without SciPy's warnings about a
    zero numerator (the test run turns warnings into errors)."""
    x = np.random.default_rng(4).standard_normal(2000)
    rig = _rig(gain=1.0, modes=(Mode(3000.0, 0.05, 0.0, "test"),))
    assert_array_equal(rig.apply(x, 12000.0), x)
    assert_allclose(np.abs(rig.transfer(np.array([100.0, 3000.0]), 12000.0)), 1.0)


def test_a_tiny_mode_gain_scales_its_mode():
    """A mode gain of 1e-20 (a fitted gain the fit drove to its bound) filters like gain 1
    scaled by 1e-20, without SciPy's BadCoefficients (its gain-times-numerator read as leading
    zeros below ~3e-13 and stopped apply); an ordinary gain gives the coefficients it gave."""
    from scipy.signal import iirpeak, tf2sos

    x = np.random.default_rng(5).standard_normal(2000)
    unit = _rig(gain=0.0, modes=(Mode(3000.0, 0.05, 1.0, "test"),)).apply(x, 12000.0)
    tiny = _rig(gain=0.0, modes=(Mode(3000.0, 0.05, 1e-20, "test"),)).apply(x, 12000.0)
    assert_allclose(tiny, 1e-20 * unit, rtol=1e-12, atol=0.0)
    b, a = iirpeak(3000.0, 1.0 / 0.1, fs=12000.0)
    assert_array_equal(Mode(3000.0, 0.05, 4.13, "test").sos(12000.0), tf2sos(4.13 * b, a))


def test_tones_at_or_above_nyquist():
    """A tone at a fixed frequency at or above the output's Nyquist frequency is refused in one
    line (as a mode is); one given as an order that a fast shaft puts there is left out of the
    signal, as a recorder's anti-aliasing filter removes it."""
    fixed = _rig(tones=(Tone(0.05, "test", frequency_hz=7000.0),))
    with pytest.raises(ConfigError, match=r"tone\[0\]\.frequency_hz = 7000 Hz is at or above"):
        fixed.apply(np.zeros(1000), 12000.0)
    assert np.std(fixed.apply(np.zeros(1000), 48000.0)) > 0.03
    order = _rig(tones=(Tone(0.05, "test", order=250.0),))
    assert_array_equal(order.apply(np.zeros(1000), 12000.0, shaft_hz=29.5), np.zeros(1000))
    assert np.std(order.apply(np.zeros(1000), 48000.0, shaft_hz=29.5)) > 0.03


def test_background_wholly_above_nyquist():
    """A background table that starts at or above the output's Nyquist frequency would add
    nothing: refused in one line naming the field; one reaching below it is kept."""
    high = _rig(background=Background((7000.0, 9000.0), (1e-3, 1e-3), "test"))
    with pytest.raises(ConfigError, match=r"background\.frequency_hz\[0\] = 7000 Hz"):
        high.apply(np.zeros(1000), 12000.0)
    assert np.std(high.apply(np.zeros(4000), 48000.0)) > 0.0
    low = _rig(background=Background((5000.0, 9000.0), (1e-3, 1e-3), "test"))
    assert np.std(low.apply(np.zeros(4000), 12000.0)) > 0.0


def test_seeded_and_bit_reproducible(rig_file):
    rig = load_rig(rig_file)
    x = np.sin(np.arange(6000) * 0.3)
    a = rig.apply(x, 12000.0, shaft_hz=29.0, seed=4)
    assert_array_equal(a, rig.apply(x, 12000.0, shaft_hz=29.0, seed=4))
    assert not np.array_equal(a, rig.apply(x, 12000.0, shaft_hz=29.0, seed=5))


def test_file_round_trip(rig_file):
    rig = load_rig(rig_file)
    assert rig.name == "test-rig" and len(rig.modes) == 1 and rig.gain == 0.5
    again = Rig.from_dict(rig.to_dict(), source="again")
    assert again == rig


def test_apply_to_a_simulation_and_save(rig_file, tmp_path):
    res = simulate(dict(model="vsm", duration_s=0.1, fs_hz=12000.0, fault="outer"))
    out = apply_rig(res, rig_file)
    assert "acc_sensor" in out.channels and out.units["acc_sensor"] == "m/s^2"
    assert_array_equal(out["acc_y"], res["acc_y"])  # the model's channels are untouched
    assert out.meta["rig"]["name"] == "test-rig" and out.meta["rig"]["seed"] == 0
    p = tmp_path / "r.nc"
    out.save(p)
    back = load_result(p)
    assert_allclose(back["acc_sensor"], out["acc_sensor"], rtol=0, atol=0)
    assert back.meta["rig"]["mode"][0]["frequency_hz"] == 3350.0


@pytest.mark.parametrize(
    "edit, message",
    [
        (("name = ", "colour = 1\nname = "), "unknown key 'colour'"),
        (("damping_ratio = 0.05", "damping_ratio = -0.05"), "mode[0].damping_ratio = -0.05"),
        # far below any structure's damping the resonator's design is ill-conditioned
        (("damping_ratio = 0.05", "damping_ratio = 1e-17"), "valid range [1e-06, 1)"),
        (("gain = 4.0", "gain = nan"), "mode[0].gain = nan is not finite"),
        (
            ('provenance = "written by hand for tests/test_rig.py"\n', ""),
            "rig.provenance is missing",
        ),
        (
            (
                'gain = 4.0\nprovenance = "test value"',
                "gain = 4.0",
            ),
            "mode[0].provenance is missing",
        ),  # fmt: skip
        (("[20.0, 6000.0]", "[6000.0, 20.0]"), "[1] = 20 Hz does not exceed [0] = 6000 Hz"),
        (("order = 1.0", "order = 1.0\nfrequency_hz = 60.0"), "exactly one of order and frequency"),
        ((_MG, _MG.replace('"rotor"', '"fem"')), "model_gain[0].model = 'fem' is invalid"),
        ((_MG, _MG.replace("6.5", "0.0")), "model_gain[0].scale = 0"),
        ((_MG, _MG.replace("6.5", "nan")), "model_gain[0].scale = nan is not finite"),
        # the identification rate: a positive number, and above twice every mode
        (
            ('input_channel = "acc_y"', 'input_channel = "acc_y"\nfs_hz = -12000.0'),
            "rig.fs_hz = -12000 Hz is out of range",
        ),
        (
            ('input_channel = "acc_y"', 'input_channel = "acc_y"\nfs_hz = "12000"'),
            "rig.fs_hz = '12000' is text",
        ),
        (
            ('input_channel = "acc_y"', 'input_channel = "acc_y"\nfs_hz = 6000.0'),
            "mode[0].frequency_hz = 3350 Hz is at or above the Nyquist frequency of the rig's "
            "fs_hz (3000 Hz)",
        ),
        # a channel no model has failed only when a run applied the rig (twenty-fourth session)
        (
            ('input_channel = "acc_y"', 'input_channel = "acc_z"'),
            "rig.input_channel = 'acc_z' is invalid; valid: acc_x, acc_y, acc_x_fe, acc_y_fe",
        ),
        # exploratory testing (fourteenth session): 1e308 overflowed the mode filters with a
        # traceback, 1e200 wrote an infinite RMS
        ((_MG, _MG.replace("6.5", "1e308")), "model_gain[0].scale = 1e+308 is out of range"),
        (("gain = 4.0", "gain = 1e200"), "mode[0].gain = 1e+200 is out of range"),
        (
            (_MG, _MG.replace('provenance = "test gain"\n', "")),
            "model_gain[0].provenance is missing",
        ),
        ((_MG, _MG + _MG), "model 'rotor' is given twice"),
        ((_MG, _MG.replace("scale", "gain")), "model_gain[0]: unknown key 'gain'"),
        # the fitted form (path_gain with one mode gain per [[mode]])
        (
            (_MG, _MG + _FIT.replace("[0.5]", "[0.5, 1.0]")),
            "model_gain[1].mode_gains has 2 gains; valid: one per [[mode]] (1)",
        ),
        (
            (_MG, _MG + _FIT.replace("path_gain = 0.01\n", "")),
            "model_gain[1].path_gain is missing (path_gain and mode_gains go together)",
        ),
        (
            (_MG, _MG + _FIT.replace("[0.5]", "0.5")),
            "model_gain[1].mode_gains = 0.5 is invalid; valid: a list of gains",
        ),
        ((_MG, _MG + _FIT.replace("[0.5]", "[-0.5]")), "model_gain[1].mode_gains[0] = -0.5"),
        (
            (_MG, _MG + _FIT.replace("path_gain = 0.01", "path_gain = nan")),
            "model_gain[1].path_gain = nan is not finite",
        ),
        (
            (_MG, _MG.replace("scale = 6.5", "scale = 6.5\npath_gain = 1.0\nmode_gains = [1.0]")),
            "model_gain[0]: give either scale or path_gain with mode_gains",
        ),
        (
            (_MG, _MG.replace("scale = 6.5\n", "")),
            "model_gain[0]: give either scale or path_gain with mode_gains",
        ),
    ],  # fmt: skip
)
def test_bad_rig_files_are_refused_in_one_line(tmp_path, edit, message):
    old, new = edit
    assert old in RIG_TOML
    p = tmp_path / "bad.toml"
    p.write_text(RIG_TOML.replace(old, new, 1), encoding="utf-8")
    with pytest.raises(ConfigError) as exc:
        load_rig(p)
    text = str(exc.value)
    assert message in text and "\n" not in text and text.startswith("bad.toml: ")


def test_the_identification_rate_round_trips_and_the_shipped_profiles_carry_theirs(rig_file):
    """``fs_hz``: the rate of the records a rig was identified from [Hz]; optional (a rig
    written by hand may leave it out), kept through TOML, and written by ``rig identify``
    (the shipped profiles: the rate in their names)."""
    assert load_rig(rig_file).fs_hz is None
    p = rig_file.with_name("rate.toml")
    p.write_text(RIG_TOML.replace('input_channel = "acc_y"', 'input_channel = "acc_y"\nfs_hz = '
                                  "12000.0"), encoding="utf-8")  # fmt: skip
    rig = load_rig(p)
    assert rig.fs_hz == 12000.0 and rig.to_dict()["fs_hz"] == 12000.0
    assert Rig.from_dict(rig.to_dict(), source="again") == rig
    rates = {n: load_rig(n).fs_hz for n in ("cwru-de-12k", "cwru-fe-12k", "cwru-de-48k")}
    assert rates == {"cwru-de-12k": 12000.0, "cwru-fe-12k": 12000.0, "cwru-de-48k": 48000.0}
    with pytest.raises(ConfigError, match=r"rig.fs_hz = -1 Hz is out of range"):
        _rig(fs_hz=-1.0)  # a rig built in code is held to it as well


def test_mode_above_nyquist_is_refused(rig_file):
    rig = load_rig(rig_file)
    with pytest.raises(ConfigError, match=r"mode\[0\].frequency_hz = 3350 Hz is at or above"):
        rig.apply(np.zeros(100), 6000.0)


def test_a_mode_whose_half_power_band_reaches_nyquist_is_refused(tmp_path):
    """A mode at 3450 Hz with zeta = 0.87 (inside the file's range [1e-6, 1)) at 12 kHz made a
    digital resonator with a pole outside the unit circle: `simulate` wrote a sensor signal
    of RMS 3e4 m/s^2 growing without bound, exit 0. Its half-power band reaches
    f_n (sqrt(1 + z^2) + z) = 7574 Hz, above 6 kHz: refused in one line with the damping
    range this rate allows, ((r^2 - 1) / 2r, r = 6000/3450: 0.582), before any work; the same
    mode at 48 kHz runs, and the rig's own fs_hz is held to it."""
    m = Mode(3450.0, 0.87, 3.0, "test")
    with pytest.raises(ConfigError) as e:
        _rig(modes=(m,)).apply(np.zeros(100), 12000.0)
    msg = str(e.value)
    assert "\n" not in msg and "mode[0].damping_ratio = 0.87" in msg
    assert "reaches 7574.41 Hz" in msg and "valid range [1e-06, 0.582065) at this rate" in msg
    with pytest.raises(ConfigError, match=r"mode\[0\].damping_ratio = 0.87: .* rig's fs_hz"):
        _rig(modes=(m,), fs_hz=12000.0)
    # just inside the bound the resonator is stable; at 48 kHz the mode is far from Nyquist
    zmax = ((6000.0 / 3450.0) ** 2 - 1.0) / (2.0 * 6000.0 / 3450.0)
    for z, fs in ((0.999 * zmax, 12000.0), (0.87, 48000.0), (0.99, 48000.0)):
        sos = Mode(3450.0, z, 3.0, "test").sos(fs)
        assert np.all(np.abs(np.roots(sos[0, 3:])) < 1.0), (z, fs)
        y = _rig(modes=(Mode(3450.0, z, 3.0, "t"),)).apply(np.r_[1.0, np.zeros(4095)], fs)
        assert np.all(np.isfinite(y)) and np.abs(y[-100:]).max() < 1e-6 * np.abs(y).max()
    f = tmp_path / "u.toml"
    f.write_text(
        'name = "u"\nprovenance = "p"\n[[mode]]\nfrequency_hz = 3450.0\n'
        'damping_ratio = 0.87\ngain = 3.0\nprovenance = "p"\n'
    )
    out = tmp_path / "u.nc"
    r = _cli("simulate", "--model", "vsm", "--duration-s", "0.05", "--fs-hz", "12000",
             "--rig", str(f), "-o", str(out), cwd=tmp_path)  # fmt: skip
    assert r.returncode == 2 and len(r.stderr.strip().splitlines()) == 1, r.stderr
    assert "damping_ratio = 0.87" in r.stderr and not out.exists()


def test_unknown_profile_name_lists_the_shipped_ones():
    with pytest.raises(ConfigError, match="neither a file nor a shipped profile; shipped: "):
        load_rig("no-such-rig")
    assert isinstance(available_rigs(), list)


def _cli(*args, cwd):
    import os

    env = {**os.environ, "PYTHONPATH": SRC}
    return subprocess.run([sys.executable, "-m", "bearingsim", *args], capture_output=True,
                          text=True, env=env, cwd=cwd)  # fmt: skip


def test_cli_simulate_with_a_rig(rig_file, tmp_path):
    out = tmp_path / "s.nc"
    r = _cli("simulate", "--model", "vsm", "--duration-s", "0.05", "--fs-hz", "12000",
             "--rig", str(rig_file), "-o", str(out), cwd=tmp_path)  # fmt: skip
    assert r.returncode == 0, r.stderr
    assert "through rig test-rig" in r.stdout
    assert "acc_sensor" in load_result(out).channels


def test_cli_refuses_a_bad_rig_before_any_work(rig_file, tmp_path):
    out = tmp_path / "s.nc"
    r = _cli("simulate", "--model", "vsm", "--duration-s", "0.05", "--fs-hz", "6000",
             "--rig", str(rig_file), "-o", str(out), cwd=tmp_path)  # fmt: skip
    assert r.returncode == 2
    lines = r.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("error: ")
    assert "rig.toml: mode[0].frequency_hz = 3350 Hz is at or above" in lines[0]
    assert not out.exists() and sorted(p.name for p in tmp_path.iterdir()) == ["rig.toml"]


def test_rig_as_a_scenario_key(rig_file, tmp_path):
    """The rig is a scenario key of the ring and rotor families (and so of sweeps): the result
    carries acc_sensor; a rig file named relative to the scenario file is found beside it."""
    res = simulate(dict(model="vsm", duration_s=0.05, fs_hz=12000.0, rig=str(rig_file)))
    assert "acc_sensor" in res.channels and res.meta["rig"]["name"] == "test-rig"
    sc = tmp_path / "sc.toml"
    sc.write_text('model = "vsm"\nduration_s = 0.05\nfs_hz = 12000.0\nrig = "rig.toml"\n')
    res2 = simulate(sc)
    assert_array_equal(res2["acc_sensor"], res["acc_sensor"])
    rot = simulate(dict(model="rotor", duration_s=0.02, fs_hz=12000.0, rig="cwru-de-12k"))
    assert "acc_sensor" in rot.channels
    with pytest.raises(ConfigError, match="at or above the Nyquist"):
        simulate(dict(model="vsm", duration_s=0.05, fs_hz=6000.0, rig=str(rig_file)))


def _analyze_json(files, *extra) -> list[dict]:
    import json

    r = _cli("analyze", *map(str, files), "--json", "--jobs", "1", *extra, cwd=files[0].parent)
    assert r.returncode == 0, r.stderr
    return [json.loads(line) for line in r.stdout.splitlines()]


def test_a_scenario_files_unset_rate_follows_the_rig_in_force(tmp_path):
    """A scenario file's rig gives its rate as a listed default, and a --rig option over the
    file gives its own: the file's rig (48 kHz profile) pinned 48 kHz under --rig cwru-de-12k,
    and `simulate s.toml --json` left fs_hz out of realism_defaults (it listed it with the
    option). A rate the file gives is kept."""
    import json

    base = 'model = "vsm"\nfault = "ball"\nduration_s = 0.05\nrig = "cwru-de-48k"\n'
    (tmp_path / "s.toml").write_text(base)
    (tmp_path / "t.toml").write_text(base.replace("cwru-de-48k", "cwru-de-12k"))
    (tmp_path / "f.toml").write_text(base + "fs_hz = 24000.0\n")
    # (48 kHz is also the default without a rig: not listed as a rig's default)
    twelve = ("--rig", "cwru-de-12k")
    cases = (("s.toml", (), 48000.0, False), ("s.toml", twelve, 12000.0, True),
             ("t.toml", (), 12000.0, True), ("f.toml", twelve, 24000.0, False))  # fmt: skip
    for name, extra, fs, listed in cases:
        out = tmp_path / "o.nc"
        r = _cli("simulate", name, *extra, "--json", "-o", str(out), cwd=tmp_path)
        assert r.returncode == 0, r.stderr
        real = json.loads(r.stdout).get("realism_defaults", {})
        assert ("fs_hz" in real) is listed and real.get("fs_hz", fs) == fs, (name, extra, real)
        assert load_result(out).fs_hz == fs, (name, extra)


def test_through_the_shipped_rig_analyze_reads_the_sensor(tmp_path):
    """Issue 16: a healthy simulation through the rig is diagnosed "none", a ball defect
    "ball" (ring models, 2 s at 12 kHz through cwru-de-12k, the profile identified from the
    CWRU drive-end records, with the realistic defaults a rig brings: docs/models.md,
    "Realistic defaults with a rig"; with the seeds' zero slip a VSM outer-race fault through
    the rig read "none"). `analyze` reads what the sensor records (acc_sensor) by default;
    the bare model output of the healthy bearing (`--channel y`: perfectly periodic ball
    passes, no background) is what it used to read, and that one is not "none"."""
    cases = [(m, f) for m in ("vsm", "dem", "tvsm") for f in ("none", "ball")]
    cases.append(("vsm", "outer"))  # "none" with the seed's zero slip (exactly periodic impacts)
    files, want = [], []
    for model, fault in cases:
        sc = dict(model=model, fault=fault, duration_s=2.0, fs_hz=12000.0, seed=0)
        out = tmp_path / f"{model}_{fault}.nc"
        simulate({**sc, "rig": "cwru-de-12k"}).save(out)
        files.append(out)
        want.append(fault)
    got = _analyze_json(files)
    assert [d["channel"] for d in got] == ["sensor"] * len(files)
    assert [d["diagnosis"] for d in got] == want, [(d["file"], d["diagnosis"]) for d in got]
    bare = _analyze_json([files[0]], "--channel", "y")[0]
    assert bare["channel"] == "y" and bare["diagnosis"] != "none"


def test_rotor_faults_through_the_shipped_rig_are_diagnosed(tmp_path):
    """Issue 16 for the rotor model: through cwru-de-12k (its rotor path gain identified on the
    profile's own records, docs/validation.md "A model-based gain for the rotor") a healthy
    bearing is "none" and ball, inner- and outer-race defects are their fault (1 s at 12 kHz,
    the realistic defaults of a rig). With the output-only path alone (gain 1) the rotor's
    output lay ~20x below the rig's background and every fault read "none"."""
    faults = ("none", "ball", "inner", "outer")
    files = []
    for fault in faults:
        out = tmp_path / f"rotor_{fault}.nc"
        sc = dict(model="rotor", de_fault=fault, duration_s=1.0, fs_hz=12000.0, seed=0)
        res = simulate({**sc, "rig": "cwru-de-12k"})
        assert res.meta["rig"]["applied_model_gain"]["model"] == "rotor"
        res.save(out)
        files.append(out)
    got = _analyze_json(files)
    assert [d["diagnosis"] for d in got] == list(faults), [
        (d["file"], d["confidence"]) for d in got
    ]


def test_a_model_gain_scales_only_its_models_path(rig_file):
    """A ``[[model_gain]]`` scales the path (direct gain and modes) for its own model's output
    and for no other: the rotor's sensor signal minus what the rig adds on its own is the
    scale times the unscaled one; a VSM result passes the rig bit for bit as without the
    table. The applied rig is recorded with the gain in its path and no table left."""
    from dataclasses import replace

    rig = load_rig(rig_file)
    (g,) = rig.model_gains
    assert (g.model, g.scale) == ("rotor", 6.5)
    bare = replace(rig, model_gains=())
    vsm = simulate(dict(model="vsm", fault="outer", duration_s=0.05, fs_hz=12000.0, seed=0))
    assert_array_equal(apply_rig(vsm, rig)["acc_sensor"], apply_rig(vsm, bare)["acc_sensor"])
    assert "applied_model_gain" not in apply_rig(vsm, rig).meta["rig"]
    rot = simulate(dict(model="rotor", de_fault="outer", duration_s=0.05, fs_hz=12000.0, seed=0))
    silent = replace(bare, gain=0.0, modes=())
    bg = apply_rig(rot, silent)["acc_sensor"]
    scaled, unscaled = apply_rig(rot, rig), apply_rig(rot, bare)
    assert_allclose(scaled["acc_sensor"] - bg, 6.5 * (unscaled["acc_sensor"] - bg), atol=1e-12)
    m = scaled.meta["rig"]
    assert m["applied_model_gain"] == {"model": "rotor", "scale": 6.5}
    assert "model_gain" not in m and m["path"]["gain"] == pytest.approx(0.5 * 6.5)
    assert "x 6.5 for the rotor model (test gain)" in m["path"]["provenance"]


def test_a_fitted_model_path_replaces_the_path_for_its_model_only(tmp_path):
    """The fitted form of ``[[model_gain]]`` (path_gain, mode_gains): the VSM's output passes
    the path with those gains (sensor minus what the rig adds on its own equals the output
    through gain 0.01 and the mode at 0.5); the rotor keeps its scale; the table round-trips
    through TOML and the applied gain is recorded without its provenance."""
    import tomllib
    from dataclasses import replace

    from bearingsim.rig_identify import rig_to_toml

    p = tmp_path / "fit.toml"
    p.write_text(RIG_TOML + _FIT, encoding="utf-8")
    rig = load_rig(p)
    g = rig.model_gain("vsm")
    assert (g.scale, g.path_gain, g.mode_gains) == (None, 0.01, (0.5,))
    assert g.describe() == "fitted path: direct gain 0.01, mode gains 0.5"
    applied = rig.for_model("vsm")
    assert applied.gain == 0.01 and applied.modes[0].gain == 0.5 and not applied.model_gains
    assert applied.modes[0].frequency_hz == rig.modes[0].frequency_hz
    assert rig.for_model("rotor").gain == pytest.approx(0.5 * 6.5)
    vsm = simulate(dict(model="vsm", fault="outer", duration_s=0.05, fs_hz=12000.0, seed=0,
                       defect_profile="geometric"))  # the gain's profile  # fmt: skip
    out = apply_rig(vsm, rig)
    silent = replace(rig, gain=0.0, modes=(), model_gains=())
    bg = apply_rig(vsm, silent)["acc_sensor"]
    by_hand = replace(rig, gain=0.01, modes=(replace(rig.modes[0], gain=0.5),), model_gains=())
    want = apply_rig(vsm, by_hand)["acc_sensor"] - bg
    assert_allclose(out["acc_sensor"] - bg, want, atol=1e-12)
    assert out.meta["rig"]["applied_model_gain"] == {
        "model": "vsm", "path_gain": 0.01, "mode_gains": [0.5]
    }  # fmt: skip
    again = Rig.from_dict(tomllib.loads(rig_to_toml(rig)))
    assert again.model_gains == rig.model_gains
    # a rig built in code is held to the file's rule: one gain per mode
    from bearingsim.rig import ModelGain

    with pytest.raises(ConfigError, match=r"model_gain\[0\].mode_gains has 2 gains; valid: one"):
        replace(rig, model_gains=(ModelGain("vsm", None, "t", 0.1, (1.0, 2.0)),))


def test_a_model_gain_round_trips_through_toml(rig_file):
    import tomllib

    from bearingsim.rig_identify import rig_to_toml

    rig = load_rig(rig_file)
    again = Rig.from_dict(tomllib.loads(rig_to_toml(rig)))
    assert again.model_gains == rig.model_gains and again.for_model("rotor") == rig.for_model(
        "rotor"
    )


def test_healthy_with_slip_and_rough_contacts_through_the_rig_is_none(tmp_path):
    """A healthy bearing with the slip real bearings have (1.5 %) and rough contacts
    (composite RMS roughness 0.1 um, ``contact_roughness_m``) is diagnosed "none" by the
    three ring models through cwru-de-12k. With Hertz's smooth onset (roughness 0) the DEM
    rings its contact resonance at every ball pass; with slip those impulses are no longer
    periodic, CPW and DRS keep them and they read as "outer" (docs/validation.md,
    "Simulations through the rig, diagnosed")."""
    files = []
    for model, sig in (("vsm", 1e-7), ("dem", 1e-7), ("tvsm", 1e-7), ("dem", 0.0)):
        sc = dict(model=model, fault="none", duration_s=2.0, fs_hz=12000.0, seed=0,
                  slip_percent=1.5, contact_roughness_m=sig, rig="cwru-de-12k")  # fmt: skip
        out = tmp_path / f"{model}_{sig:g}.nc"
        simulate(sc).save(out)
        files.append(out)
    got = [d["diagnosis"] for d in _analyze_json(files)]
    assert got == ["none", "none", "none", "outer"], got


def test_healthy_through_each_shipped_profile_at_its_own_rate_is_none(tmp_path):
    """Exploratory testing (nineteenth session): a healthy VSM through cwru-de-48k at its
    48 kHz read "uncertain" (2 x BPFO in 23.25-24 kHz). The profile's background table ended
    at 0.45 fs, so above 21.6 kHz the sensor signal was the model's output alone (1e-16
    (m/s^2)^2 of near-silent ball-pass content, no floor) and the kurtogram picked that band.
    The tables now reach the Nyquist frequency with the records' roll-off. Each ring model,
    healthy, 1 s at each profile's own rate (the default with a rig), reads "none"."""
    files = []
    for rig, bearing in (("cwru-de-12k", "6205-cwru"), ("cwru-fe-12k", "6203-cwru"),
                         ("cwru-de-48k", "6205-cwru")):  # fmt: skip
        for model in ("vsm", "dem"):
            out = tmp_path / f"{rig}_{model}.nc"
            simulate(dict(model=model, bearing=bearing, fault="none", rig=rig)).save(out)
            files.append(out)
    got = [d["diagnosis"] for d in _analyze_json(files)]
    assert got == ["none"] * 6, got
    for name in ("cwru-de-12k", "cwru-fe-12k", "cwru-de-48k"):
        r = load_rig(name)
        assert r.background.frequency_hz[-1] == 0.5 * r.fs_hz


@pytest.mark.parametrize("size_in", [0.021, 0.028])
def test_fused_diagnosis_of_simulated_faults_of_sizes_the_shared_records_lack(size_in):
    """The CWRU benchmark also has 0.021 and 0.028 in faults, which the shared records do not
    (the fused diagnosis was developed on 0.007 and 0.014 in). Simulated through cwru-de-12k
    with the side-by-side's realism (VSM, 1.5 % slip, geometric drop, 0.1 um roughness) at the
    CWRU load-2 speed, 1750 r/min: inner, outer @6 and ball defects of those widths are each
    diagnosed as their fault at p >= 0.8, every method reading it. An outer-race defect at @12
    lies outside the load zone of the catalogue clearance (no ball is loaded there: the sensor
    signal is the healthy one) and must not be given a fault type."""
    from bearingsim.catalog import resolve_bearing
    from bearingsim.side_by_side import CWRU_DEPTH_M, REALISM
    from bearingsim.signal.fused import diagnose_fused

    rpm, fs = 1750.0, 12000.0
    got, xs = {}, {}
    for fault, edge in (("none", 10.0), ("inner", 10.0), ("outer", 10.0), ("ball", 10.0),
                        ("outer@12", 190.0)):  # fmt: skip
        sc = dict(model="vsm", bearing="6205-cwru", fault=fault.split("@")[0], **REALISM,
                  defect_width_m=size_in * 0.0254, defect_depth_m=CWRU_DEPTH_M,
                  defect_edge_angle_deg=edge, rpm=rpm, duration_s=2.0, fs_hz=fs, seed=3,
                  rig="cwru-de-12k")  # fmt: skip
        x = xs[fault] = np.asarray(simulate(sc)["acc_sensor"], dtype=float)
        d = diagnose_fused(x, fs, resolve_bearing("6205-cwru"), rpm / 60.0)
        got[fault] = d
    for fault in ("inner", "outer", "ball"):
        d = got[fault]
        assert d.diagnosis == fault and d.confidence >= 0.8, (fault, d.diagnosis, d.confidence)
        assert all(v.names(fault) for v in d.views), (
            fault,
            [v.diagnosis.diagnosis for v in d.views],
        )
    assert got["none"].diagnosis == "none"
    assert got["outer@12"].diagnosis in ("none", "uncertain")
    assert_array_equal(xs["outer@12"], xs["none"])


def test_cli_rig_show_states_the_background_band(tmp_path):
    """`rig show` prints the band its background covers and the output rate above which
    `apply_rig` warns (RigRateWarning: the table ends below a quarter of the rate)."""
    r = _cli("rig", "show", "cwru-de-12k", cwd=tmp_path)
    assert r.returncode == 0, r.stderr
    assert "background: 45 PSD points, 10-6000 Hz" in r.stdout
    assert "above 24000 Hz gets a RigRateWarning" in r.stdout
    assert "for the rotor model's output (model-based)" in r.stdout
    assert "identified from records at 12000 Hz: a scenario with this rig and no" in r.stdout


def test_cli_simulate_json_reports_the_applied_model_gain(tmp_path):
    """`simulate --rig --json` names the model gain it applied (the rotor's on cwru-de-12k) and
    null for a model the rig has none for; the text line says it too (exploratory testing,
    fourteenth session: the JSON gave only the rig's name)."""
    import json

    gains = {}
    for model, fault in (("rotor", "--de-fault"), ("vsm", "--fault")):
        r = _cli("simulate", "--model", model, fault, "outer", "--duration-s", "0.02", "--fs-hz",
                 "12000", "--rig", "cwru-de-12k", "-o", f"{model}.nc", "--json",
                 cwd=tmp_path)  # fmt: skip
        assert r.returncode == 0, r.stderr
        gains[model] = json.loads(r.stdout)["rig_model_gain"]
    assert gains["rotor"] == pytest.approx(load_rig("cwru-de-12k").model_gain("rotor").scale)
    assert gains["vsm"] is None


@pytest.mark.parametrize(
    "field, value",
    [("noise", 1e308), ("tone", 1e300), ("psd", 1e300)],
)
def test_accelerations_beyond_any_accelerometer_are_refused(field, value):
    """Noise, tone amplitude and background PSD are bounded by 1e6 m/s^2 (1e12 (m/s^2)^2/Hz),
    beyond any accelerometer (exploratory testing: a noise of 1e308 m/s^2 wrote infinite
    samples and 'rms: null')."""
    from bearingsim import simulate
    from bearingsim.errors import ConfigError

    if field == "noise":
        with pytest.raises(ConfigError, match="noise_rms_m_per_s2"):
            simulate(dict(model="dem", duration_s=0.01, fs_hz=12000.0, noise_rms_m_per_s2=value))
        return
    d = {
        "name": "x", "description": "x", "provenance": "test",
        "tone": [{"order": 1.0, "amplitude_m_per_s2": value if field == "tone" else 1.0,
                   "provenance": "t"}],
        "background": {"frequency_hz": [10.0, 1000.0],
                       "psd_m2_per_s4_per_hz": [value if field == "psd" else 1e-6, 1e-6],
                       "provenance": "t"},
    }  # fmt: skip
    with pytest.raises(ConfigError, match="amplitude_m_per_s2" if field == "tone" else "psd"):
        Rig.from_dict(d)


@pytest.mark.parametrize(
    ("table", "key", "index"),
    [
        ("path", "gain", None),
        ("mode", "frequency_hz", 0),
        ("background", "psd_m2_per_s4_per_hz", 3),
    ],
)
def test_a_number_written_as_text_is_refused(table, key, index):
    """A rig file's number in quotes (``gain = "2"``) was read as the number; it is refused in
    one line naming the field, as the file's other wrong types are."""
    d = load_rig("cwru-de-12k").to_dict()
    t = d[table][index] if table == "mode" else d[table]
    if table == "background":
        t[key][index] = "1e-6"
    else:
        t[key] = "2"
    with pytest.raises(ConfigError, match=r"is text; valid: a number without quotes") as e:
        Rig.from_dict(d)
    assert "\n" not in str(e.value) and key in str(e.value)


def test_background_rms_is_the_tables_integral():
    """``Background.rms``: a flat PSD S over [f1, f2] has RMS sqrt(S (f2 - f1)) (within the
    2000-point quadrature); cut at f_hi, the part below it; a table wholly above f_hi, 0."""
    bg = Background((100.0, 5100.0), (2e-4, 2e-4), "test")
    assert bg.rms() == pytest.approx(np.sqrt(2e-4 * 5000.0), rel=1e-4)
    assert bg.rms(2600.0) == pytest.approx(np.sqrt(2e-4 * 2500.0), rel=1e-4)
    assert bg.rms(50.0) == 0.0


@pytest.mark.parametrize("model", ["dem", "rotor"])
def test_the_models_measurement_noise_is_added_after_the_path_and_apart_from_the_rig(model):
    # twenty-first session: a model's white measurement noise (noise_rms_m_per_s2) was the rig's
    # input, so the structure's modes rang with it (its PSD x27 at 2.77 kHz and x57 at
    # 3.30 kHz through cwru-de-12k), and it drew from default_rng(seed), the stream of the
    # rig's background (its samples were the background's Fourier coefficients)
    fs, seed = 12000.0, 3
    kw = dict(model=model, rig="cwru-de-12k", seed=seed, duration_s=1.0, fs_hz=fs)
    if model == "rotor":
        kw["dt_s"] = 1.0 / fs / 8
    clean = simulate(kw)
    noisy = simulate(dict(kw, noise_rms_m_per_s2=1.0))
    e = noisy.channels["acc_sensor"] - clean.channels["acc_sensor"]
    # the same noise on the model channel the rig reads, and nothing else added
    assert_allclose(e, noisy.channels["acc_y"] - clean.channels["acc_y"], atol=1e-9)
    assert np.std(e) == pytest.approx(1.0, rel=0.05)
    f, p = welch(e, fs, nperseg=1024)
    for mode in load_rig("cwru-de-12k").modes:  # white: no mode stands out
        k = np.argmin(np.abs(f - mode.frequency_hz))
        assert p[k] / np.median(p) < 2.5, (mode.frequency_hz, p[k] / np.median(p))
    # a stream apart from the rig's default_rng(seed)
    rig_stream = np.random.default_rng(seed).standard_normal(e.size)
    assert abs(np.corrcoef(e, rig_stream)[0, 1]) < 0.1


def test_a_results_scenario_reruns_from_any_folder_with_the_same_files(tmp_path, monkeypatch):
    # twenty-first session: the scenario stored "rig": "rig.toml" and "bearing_file":
    # "b.toml" as typed, so a rerun from another folder read that folder's files (acc_sensor
    # RMS 7.99 against 6.24 m/s^2, the stored scenarios equal) or none
    from bearingsim.config import Scenario

    a, b = tmp_path / "a", tmp_path / "b"
    a.mkdir()
    b.mkdir()
    (a / "rig.toml").write_text(RIG_TOML, encoding="utf-8")
    (b / "rig.toml").write_text(RIG_TOML.replace("gain = 4.0", "gain = 40.0"), encoding="utf-8")
    import bearingsim.catalog

    catalogue = Path(bearingsim.catalog.__file__).parent / "6205.toml"  # as a user's file
    (a / "b.toml").write_text(catalogue.read_text(encoding="utf-8"), encoding="utf-8")
    monkeypatch.chdir(a)
    sc = dict(model="vsm", fault="outer", duration_s=0.05, fs_hz=12000.0, seed=5)
    first = simulate(sc | {"rig": "rig.toml", "bearing_file": "b.toml"})
    assert first.scenario["rig"] == str(a / "rig.toml")
    assert first.scenario["bearing_file"] == str(a / "b.toml")
    monkeypatch.chdir(b)
    again = simulate(Scenario.from_dict(first.scenario))
    assert_array_equal(again.channels["acc_sensor"], first.channels["acc_sensor"])


def test_a_rig_name_with_a_control_character_is_refused(tmp_path, capsys):
    # twenty-first session: a name holding an escape or a carriage return was printed raw by
    # `rig show` and the "wrote" line, which were then no longer one line each
    p = tmp_path / "r.toml"
    p.write_text(RIG_TOML.replace('name = "test-rig"', 'name = "test\\u001b[2Jrig"'))
    with pytest.raises(ConfigError, match=r"rig.name = .* holds a control character"):
        load_rig(p)
    from bearingsim.cli import main

    rec = tmp_path / "r.csv"
    rec.write_text("t,x\n" + "".join(f"{k / 1000},{np.sin(k)}\n" for k in range(2000)))
    capsys.readouterr()
    with pytest.raises(SystemExit) as e:
        main(["rig", "identify", str(rec), "--name", "a\nb", "-o", str(tmp_path / "o.toml")])
    assert e.value.code == 2 and not (tmp_path / "o.toml").exists()
    assert "holds a control character" in capsys.readouterr().err


# ------------------------------------------------------------ model gain and defect profile
def test_a_model_gain_records_the_defect_profile_it_was_identified_with():
    """Exploratory testing (twenty-third session): a rig's model gain fitted with the geometric
    slot (the realism a rig brings) scaled pit runs without a word. A ``[[model_gain]]`` now
    records its ``defect_profile`` (written only when it is not the default, so the shipped
    files, identified with the slot, keep their bytes); a bad value is one line."""
    from bearingsim.rig import ModelGain

    g = ModelGain("rotor", 2.0, "test", defect_profile="pit")
    assert g.to_dict()["defect_profile"] == "pit" and "(pit defects)" in g.describe()
    assert ModelGain.from_dict(g.to_dict(), "model_gain[0]") == g
    plain = ModelGain("rotor", 2.0, "test")
    assert plain.defect_profile == "geometric" and "defect_profile" not in plain.to_dict()
    with pytest.raises(ConfigError) as e:
        ModelGain.from_dict(dict(g.to_dict(), defect_profile="round"), "model_gain[0]")
    assert str(e.value) == (
        "model_gain[0].defect_profile = 'round' is invalid; valid: geometric, rectangular, pit"
    )
    for name in available_rigs():  # identified with the slot
        assert all(m.defect_profile == "geometric" for m in load_rig(name).model_gains)


def test_a_run_with_another_profile_than_its_gain_is_warned():
    import warnings

    from bearingsim.rig import RigGainWarning

    base = dict(model="rotor", duration_s=0.01, rig="cwru-de-12k")
    with pytest.warns(RigGainWarning, match=r"rotor model gain was identified with "
                      r"defect_profile = 'geometric'; this run's defect is 'pit'"):  # fmt: skip
        simulate(dict(base, de_fault="outer", defect_profile="pit"))
    with warnings.catch_warnings():
        warnings.simplefilter("error", RigGainWarning)
        simulate(dict(base, de_fault="outer"))  # the gain's own profile
        simulate(dict(base, defect_profile="pit"))  # no defect: the profile is not used
        simulate(dict(model="vsm", duration_s=0.01, fault="outer", defect_profile="pit",
                      rig="cwru-de-12k"))  # no vsm gain in the profile  # fmt: skip


def test_rig_identify_takes_the_defect_profile_of_its_model_gain(run_cli, tmp_path):
    from conftest import cwru_record

    recs = [str(cwru_record(n)) for n in ("132", "107")]
    out = tmp_path / "t.toml"
    r = run_cli("rig", "identify", *recs, "--name", "t", "--channel", "DE", "--model-gain",
                "vsm", "--defect-profile", "pit", "-o", str(out))  # fmt: skip
    assert r.code == 0, r.err
    assert load_rig(str(out)).model_gain("vsm").defect_profile == "pit"
    assert "(pit defects)" in r.out
    r = run_cli("rig", "identify", *recs, "--name", "t", "--channel", "DE",
                "--defect-profile", "pit", "-o", str(tmp_path / "u.toml"))  # fmt: skip
    assert r.code == 2 and not (tmp_path / "u.toml").exists()
    assert r.err.strip() == (
        "error: --defect-profile pit is only read with --model-gain; give both or neither"
    )


@pytest.mark.parametrize("name", ["cwru-de-12k", "cwru-de-48k", "cwru-fe-12k"])
def test_a_rate_too_low_for_a_rig_names_the_rate_it_needs(name):
    """A run's rate below what a rig's modes need was refused with the rig file's range
    ("mode[0].frequency_hz = 2768.55 Hz ...; valid range (0, 1500) Hz"), not the run's remedy
    (exploratory testing, twenty-third session). The message now gives the rate needed,
    :meth:`Rig.min_rate_hz`, and the rate just above it is accepted."""
    from bearingsim.config import Scenario

    need = load_rig(name).min_rate_hz()
    Scenario.from_dict(dict(model="vsm", fault="outer", rig=name, fs_hz=need * 1.0001))
    with pytest.raises(ConfigError) as e:
        Scenario.from_dict(dict(model="vsm", fault="outer", rig=name, fs_hz=need * 0.9999))
    msg = str(e.value)
    assert msg.startswith(f"<scenario>: fs_hz = {need * 0.9999:g} Hz is too low for rig '{name}'")
    assert msg.endswith(f"; valid: fs_hz above {need:.6g} Hz, or a rig identified at this rate")
    assert "\n" not in msg


def test_a_run_far_from_the_rigs_speeds_is_warned(tmp_path):
    """Exploratory testing (twenty-third session): a healthy bearing through ``cwru-de-12k``
    at 3000 r/min was diagnosed "outer" (docs/validation.md, "Simulations through the rig,
    diagnosed"): the model's ball-pass line grows with speed while the rig's background is
    the machine's at the records' 1730-1797 r/min. A rig now records the speeds it was
    identified at (``rpm_range``), and a run more than 10 % outside them is warned."""
    import warnings

    from bearingsim.rig import RigSpeedWarning

    for name in available_rigs():  # CWRU: loads 0-3 hp, 1723-1797 r/min in the files
        lo, hi = load_rig(name).rpm_range
        assert 1700.0 <= lo <= hi <= 1800.0
    base = dict(model="vsm", duration_s=0.01, rig="cwru-de-12k")
    # the message does not name the run's speed: a sweep groups warnings by message
    # (exploratory testing, twenty-fourth session: one line per value of a speed axis)
    msg = []
    for rpm in (3000.0, 3600.0):
        with pytest.warns(RigSpeedWarning, match=r"identified at 1723-1796 r/min; this run "
                          r"turns more than 10% outside those speeds") as w:  # fmt: skip
            simulate(dict(base, rpm=rpm))
        msg.append(str(w[0].message))
    assert msg[0] == msg[1]
    with warnings.catch_warnings():
        warnings.simplefilter("error", RigSpeedWarning)
        simulate(dict(base, rpm=1796.0 * 1.09))  # within 10 % of the range
        simulate(dict(base, rpm=1600.0))
    with pytest.raises(
        ConfigError,
        match=r"^rig.rpm_range\[1\] = 1000 r/min is out of range; valid range \[1500, inf\) r/min$",
    ):
        Rig(name="x", description="", provenance="t", rpm_range=(1500.0, 1000.0))
    r = Rig(name="x", description="", provenance="t", rpm_range=(1500.0, 1600.0))
    assert Rig.from_dict(r.to_dict()) == r and r.to_dict()["rpm_range"] == [1500.0, 1600.0]


def _law(text: str, rpm_range: str = "[1000.0, 2000.0]") -> str:
    """RIG_TOML with a speed law in its [background] table (and the speeds it holds over)."""
    out = RIG_TOML.replace(
        "psd_m2_per_s4_per_hz = [1e-4, 1e-6]\n",
        "psd_m2_per_s4_per_hz = [1e-4, 1e-6]\n" + text,
    )
    if rpm_range:
        out = out.replace('input_channel = "acc_y"',
                          f'input_channel = "acc_y"\nrpm_range = {rpm_range}')  # fmt: skip
    return out


def test_a_background_speed_law_scales_its_amplitude_and_nothing_else(tmp_path):
    """A background with ``speed_exponent`` n and ``rpm_ref`` (twenty-fourth session; left for
    planning last session: a rig's background did not grow with speed) is the table at
    ``rpm_ref`` and ``(N / rpm_ref)^n`` times it in amplitude at N: the same draws, so at twice
    the reference speed with n = 2 exactly four times the samples. Without a law, and at the
    reference speed, the samples are those of before, bit for bit."""
    p = tmp_path / "law.toml"
    p.write_text(_law("speed_exponent = 2.0\nrpm_ref = 1500.0\n"), encoding="utf-8")
    law = replace(load_rig(p), modes=(), tones=(), noise_rms_m_per_s2=0.0)
    bare = replace(law, background=replace(law.background, speed_exponent=None, rpm_ref=None))
    z = np.zeros(4096)
    at_ref = law.apply(z, 12000.0, shaft_hz=25.0, seed=3)
    assert np.array_equal(at_ref, bare.apply(z, 12000.0, shaft_hz=25.0, seed=3))
    assert np.array_equal(bare.apply(z, 12000.0, shaft_hz=50.0, seed=3), at_ref)
    assert np.allclose(law.apply(z, 12000.0, shaft_hz=50.0, seed=3), 4.0 * at_ref, rtol=1e-12)
    assert np.array_equal(law.apply(z, 12000.0, seed=3), at_ref)  # no speed: the table's
    assert law.background.speed_factor(12.5) == 0.25
    assert Rig.from_dict(law.to_dict()) == law  # saved and reloaded
    assert list(law.to_dict()["background"])[-1] == "provenance"
    # a speed at which the law's level passes any accelerometer, or overflows: one line
    big = replace(law, background=replace(law.background, speed_exponent=4.0))
    for rps in (1e6, 1e300):
        with pytest.raises(ConfigError, match=r"^rig 'test-rig': at [\d.e+]+ r/min the "
                           r"background's speed law, \(N / 1500 r/min\)\^4, gives "):  # fmt: skip
            big.apply(z, 12000.0, shaft_hz=rps, seed=3)


@pytest.mark.parametrize(
    ("text", "msg"),
    [
        ("speed_exponent = 2.0\n", r"background.rpm_ref is missing \(speed_exponent is given\)"),
        ("rpm_ref = 1500.0\n", r"background.speed_exponent is missing \(rpm_ref is given\)"),
        (
            "speed_exponent = 9.0\nrpm_ref = 1500.0\n",
            r"background.speed_exponent = 9 is out of range; valid range \[-4, 4\]$",
        ),
        (
            "speed_exponent = 2.0\nrpm_ref = 0.0\n",
            r"background.rpm_ref = 0 r/min is out of range; valid range \(0, inf\) r/min$",
        ),
        ("speed_exponent = nan\nrpm_ref = 1500.0\n", r"background.speed_exponent = nan is not"),
        # exploratory testing (twenty-fourth session): rpm_ref = 1e-300 passed and the run
        # ended in an OverflowError; 25 (Hz for r/min) gave a 538 m/s^2 background. A law
        # holds over the speeds it was fitted at: rpm_ref within them, and they are given
        (
            "speed_exponent = 2.0\nrpm_ref = 25.0\n",
            r"background.rpm_ref = 25 r/min lies outside rig.rpm_range \[1000, 2000\] r/min; "
            "valid: a speed within the range the law was fitted over$",
        ),
        (
            "speed_exponent = 2.0\nrpm_ref = 1e-300\n",
            r"background.rpm_ref = 1e-300 r/min lies outside rig.rpm_range",
        ),
        (
            "speed_exponent = 2.0\nrpm_ref = 1500.0\n|",
            r"background.speed_exponent needs rig.rpm_range \(the shaft speeds the law",
        ),
    ],
)
def test_a_bad_speed_law_is_one_line(tmp_path, text, msg):
    p = tmp_path / "bad.toml"
    text, bar, _ = text.partition("|")  # a "|": the file without an rpm_range
    p.write_text(_law(text, "" if bar else "[1000.0, 2000.0]"), encoding="utf-8")
    with pytest.raises(ConfigError, match="^bad.toml: " + msg):
        load_rig(p)
    r = _cli("rig", "show", str(p), cwd=tmp_path)
    assert r.returncode == 2 and len(r.stderr.strip().splitlines()) == 1, r.stderr


def test_the_speed_warning_says_when_the_background_follows_the_speed(tmp_path):
    """Outside the rig's speeds the run is still warned (the law is an extrapolation there),
    but the warning no longer says the background stays the records'."""
    from bearingsim.rig import RigSpeedWarning

    p = tmp_path / "law.toml"
    p.write_text(_law("speed_exponent = 2.0\nrpm_ref = 1500.0\n"), encoding="utf-8")
    with pytest.warns(RigSpeedWarning, match=r"its background is scaled as speed\^2, a law "):
        simulate(dict(model="vsm", duration_s=0.01, rpm=3000.0, rig=str(p), fs_hz=12000.0))
    r = _cli("rig", "show", str(p), cwd=tmp_path)
    assert "background amplitude x (speed / 1500 r/min)^2" in r.stdout, r.stdout


def test_a_bearing_of_another_size_than_the_rigs_is_warned(tmp_path):
    """Left for planning (twenty-third session): a 6205 through ``cwru-fe-12k`` (the fan end's
    6203 housing) passed without a word. A rig now names the bearing its records were taken on
    (``bearing``; `rig identify` writes it for a CWRU end), and a run whose bearing is another
    size gets one ``RigBearingWarning``; the seed's 6205 through the drive-end rig (0.1 % from
    the CWRU 6205) and the rotor's fan-end 6203 through ``cwru-fe-12k`` do not."""
    import warnings

    from bearingsim.rig import RigBearingWarning

    assert [load_rig(n).bearing for n in ("cwru-de-12k", "cwru-de-48k", "cwru-fe-12k")] == [
        "6205-cwru", "6205-cwru", "6203-cwru"]  # fmt: skip
    base = dict(model="vsm", duration_s=0.01)
    with pytest.warns(RigBearingWarning, match=r"^rig 'cwru-fe-12k' was identified on records "
                      r"of the 6203-cwru \(pitch diameter 28\.5 mm, 8 elements of 6\.746 mm\); "
                      r"this run's bearing 6205-cwru is another size \(pitch diameter 39\.04 "
                      r"mm"):  # fmt: skip
        simulate(dict(base, bearing="6205-cwru", rig="cwru-fe-12k"))
    with pytest.warns(RigBearingWarning, match="identified on records of the 6205-cwru"):
        simulate(dict(base, bearing="6206", rig="cwru-de-12k"))
    with warnings.catch_warnings():
        warnings.simplefilter("error", RigBearingWarning)
        simulate(dict(base, bearing="6205", rig="cwru-de-12k"))
        simulate(dict(base, bearing="6203-cwru", rig="cwru-fe-12k"))
        simulate(dict(model="rotor", duration_s=0.01, rig="cwru-fe-12k"))
    p = tmp_path / "r.toml"
    p.write_text(RIG_TOML.replace('input_channel = "acc_y"',
                                  'input_channel = "acc_y"\nbearing = "6205-xyz"'))  # fmt: skip
    with pytest.raises(ConfigError, match=r"^r.toml: rig.bearing = '6205-xyz' is not a "
                       r"catalogue bearing; valid: 6203-cwru, "):  # fmt: skip
        load_rig(p)
    r = _cli("rig", "show", "cwru-fe-12k", cwd=tmp_path)
    assert "identified on records of the 6203-cwru" in r.stdout, r.stdout
    # and the speeds a RigSpeedWarning is judged by (--json had them, the text did not)
    assert "  identified at 1728-1797 r/min: a run more than 10 % outside" in r.stdout, r.stdout
    p.write_text(RIG_TOML.replace('input_channel = "acc_y"',
                                  'input_channel = "acc_y"\nbearing = 6205'))  # fmt: skip
    with pytest.raises(ConfigError, match=r"^r.toml: rig.bearing = 6205 is not text; valid: a "
                       r'catalogue id in quotes \(bearing = "6205-cwru"\), or a \[bearing\] '
                       r"table of id, n_elements, pitch_diameter_m, "
                       r"element_diameter_m$"):  # fmt: skip
        load_rig(p)
    # twenty-fifth session: a bearing outside the catalogue is a [bearing] table of its size
    good = ('[bearing]\nid = "mine"\nn_elements = 9\npitch_diameter_m = 0.039\n'
            "element_diameter_m = 0.0079\n")  # fmt: skip
    for table, message in (
        (good.replace("9", "2", 1), r"bearing.n_elements = 2 is invalid; valid range \[3, 1000\]"),
        (good.replace("9", "9.5", 1), r"bearing.n_elements = 9.5 is invalid; valid range \[3, "),
        (good.replace("0.0079", "0.02"), r"bearing.element_diameter_m = 0.02 m is out of range; "
                                         r"valid range \(0, 0.0133"),
        (good.replace('"mine"', '""'), "bearing.id = '' is invalid; valid: printable text"),
        (good.replace("n_elements = 9\n", ""), r"bearing.n_elements is missing"),
        (good + "width_m = 1\n", "bearing: unknown key 'width_m'; valid keys: id, "),
        # a catalogue id with another size (twenty-fifth session)
        (good.replace('"mine"', '"6205-cwru"').replace("9", "12", 1),
         r"bearing.id = '6205-cwru' names a catalogue bearing of another size \(6205-cwru "),
    ):  # fmt: skip
        p.write_text(RIG_TOML + "\n" + table)
        with pytest.raises(ConfigError, match=r"^r.toml: " + message):
            load_rig(p)
    p.write_text(RIG_TOML + "\n" + good.replace("9", "9.0", 1))  # as a bearing file takes it
    assert load_rig(p).bearing.n_elements == 9
    p.write_text(RIG_TOML + "\n" + good)
    with pytest.warns(RigBearingWarning, match=r"^rig '.*' was identified on records of the "
                      r"mine \(pitch diameter 39 mm, 9 elements of 7\.9 mm\)"):  # fmt: skip
        simulate(dict(base, bearing="6206", rig=str(p), fs_hz=12000.0))
    with warnings.catch_warnings():
        warnings.simplefilter("error", RigBearingWarning)
        simulate(dict(base, bearing="6205", rig=str(p), fs_hz=12000.0))
    # an element diameter alone differing printed two identical sizes (twenty-fifth session)
    p.write_text(RIG_TOML + "\n" + good.replace("0.039", "0.039040").replace("0.0079", "0.0070"))
    with pytest.warns(RigBearingWarning, match=r"9 elements of 7 mm\); this run's bearing "
                      r"6205-cwru is another size \(pitch diameter 39\.04 mm, 9 elements of "
                      r"7\.94 mm\)"):  # fmt: skip
        simulate(dict(base, bearing="6205-cwru", rig=str(p), fs_hz=12000.0))


def test_a_ring_model_without_its_own_path_through_a_rig_with_anothers_is_warned():
    """Exploratory testing (twenty-fourth session): a VSM run through a user's rig that has a
    model-based path for the DEM only passed at the output-only gain 1 (102 m/s^2 RMS against
    the records' 1.7) without a word. It now gets a RigGainWarning; a rig with only a rotor
    gain (the shipped profiles) does not warn ring-model runs, nor a DEM run its own path."""
    import warnings

    from bearingsim.rig import ModelGain, RigGainWarning

    base = load_rig("cwru-de-12k")
    dem = replace(base, model_gains=(*base.model_gains, ModelGain("dem", 0.02, "t")))
    sc = dict(duration_s=0.01, fault="none")
    res = simulate(dict(sc, model="vsm", rig="cwru-de-12k"))
    with pytest.warns(RigGainWarning, match=r"has a model-based path for dem but none for vsm"):
        apply_rig(res, dem, channel="s2")
    with warnings.catch_warnings():
        warnings.simplefilter("error", RigGainWarning)
        apply_rig(simulate(dict(sc, model="dem", rig="cwru-de-12k")), dem, channel="s2")
        apply_rig(res, base, channel="s2")


def test_a_rig_bearing_built_in_code_is_checked_as_a_files_table():
    """``RigBearing(...)`` built in code validated nothing (twenty-fifth session's note): a
    zero element diameter passed and divided by zero in ``same_size``. It now takes the
    ``[bearing]`` table's checks, one line each naming the field."""
    from bearingsim.rig import RigBearing

    ok = RigBearing(" mine ", 9.0, 0.039, 0.0079)
    assert (ok.id, ok.n_elements) == ("mine", 9) and isinstance(ok.n_elements, int)
    for args, field in (
        (("", 9, 0.039, 0.0079), "bearing.id = ''"),
        (("x", 2, 0.039, 0.0079), "bearing.n_elements = 2"),
        (("x", True, 0.039, 0.0079), "bearing.n_elements = True"),
        (("x", 9, float("nan"), 0.0079), "bearing.pitch_diameter_m = nan"),
        (("x", 9, 0.039, 0.0), "bearing.element_diameter_m = 0 m"),
        (("x", 9, 0.039, 0.02), "bearing.element_diameter_m = 0.02 m"),  # balls overlap
    ):
        with pytest.raises(ConfigError, match=re.escape(field)) as e:
            RigBearing(*args)
        assert "\n" not in str(e.value) and "valid" in str(e.value)
