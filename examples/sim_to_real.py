"""Sim-to-real: train a fault classifier on simulated signals only and label measured records
(issue 16, item 6; first version).

    python examples/sim_to_real.py --predict FILE... [--json] [--cache DIR] [--rpm R]
        [--fs-hz F] [--channel CH] [--bearing ID|FILE.toml]
    python examples/sim_to_real.py --evaluate [--data ../shared/data/cwru] [--path-fit]

1. **Dataset** (cached in a Zarr group, so a second call trains in seconds): DEM simulations of
   every condition of a grid -- healthy, inner and outer race (at CWRU's @6, @3 and @12: in
   the load zone and 90 and 180 deg from it, the last two only in runs whose preload or axial
   load loads a ball there) and ball faults x shaft speeds
   (the CWRU loads' 1730-1797 r/min) x defect widths (0.007, 0.014, 0.021 in) x random slip
   (1-2 %, three seeds) x the shipped rig profiles (``cwru-de-12k``, ``cwru-fe-12k``,
   ``cwru-de-48k``; the drive end's 6205, the fan end's 6203) -- each passed through its rig
   (``acc_sensor``). Each run draws the machine facts CWRU does not publish: the ball diameter
   spread (0 and ISO 3290-1 grades G10, G20, G40: unequal ball loads modulate a race fault's
   impacts at the cage frequency), the rotor unbalance (0-50 % of the static load, turning
   with the shaft: modulation at the shaft frequency) and the operating clearance (the
   catalogue's 6 um, 0, and preloads of 5 and 10 um: every ball loaded, so an inner-race
   defect strikes at every pass), the contacts' composite RMS roughness (0.05, 0.1, 0.2 um:
   a ball entering the load zone takes up its load smoothly, without ringing the contact
   resonance as Hertz's smooth onset does) and an axial spring preload (none, or SKF's
   0.005-0.01 kN per mm of bore for small electric motors: the balls run at a contact angle,
   every ball loaded, the fault lines where an axially loaded bearing has them).
2. **Features** (the same function on simulated and measured signals): the squared-envelope
   spectrum in the fast-kurtogram band, its levels at the characteristic frequencies of the
   bearing at the record's speed (BPFO, BPFI and their 2nd harmonics, BPFI +/- shaft, 2 x BSF and
   its +/- FTF sidebands, FTF and 2 x FTF, the shaft's 1st and 2nd harmonics), each over the
   spectrum's median in 20-600 Hz [dB], and the
   signal's log kurtosis. Ratios and levels relative to the record's own floor: the absolute
   level of a model is not what the classifier sees.
3. **Classifier**: scikit-learn's random forest (an optional dependency: ``pip install
   bearingsim[ml]``), trained on the simulated set only. Labels ``none``, ``inner``, ``outer``,
   ``ball`` (the ring models' ball defect, issue 16 item 2).

``--predict`` prints one JSON object per line, ``{"file", "predicted", "probabilities",
"rpm", "rpm_source", "fs_hz", "fs_source", "channel", "bearing", "bearing_source"}`` (and
``"warning"`` when the speed lies outside the trained ones, ...), ``--fs-hz``, ``--channel``
and ``--bearing`` passed to the reader (:func:`_record`); a
record longer than the simulations is cut into pieces of their length (``DURATION_S``) and the
pieces' class probabilities are averaged (:func:`segments`).
``--evaluate`` labels every record of the CWRU folder, prints the accuracy per class and
overall beside ``bearingsim analyze``'s verdicts on the same records, twice:

* with the **shipped** rigs, which were identified from every record of their mounting -- the
  judged records included (system identification on the judged data);
* **held out**: each record judged by a classifier trained on simulations through rigs
  identified from the records of the *other* fault size (:data:`HELD_OUT`,
  ``bearingsim.side_by_side.rig_without_size``; the leave-one-mounting-out split of the
  side-by-side comparison). A mounting with no record of another size (the fan end here) has
  no held-out rig: its runs leave that training set and its records are not judged. The
  healthy record, which no held-out rig uses, is judged by both held-out classifiers.
"""

from __future__ import annotations

import argparse
import json
import math
import os
import shutil
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

LABELS = ("none", "inner", "outer", "ball")
#: the simulated grid (see the module docstring)
RPMS = (1730.0, 1750.0, 1772.0, 1797.0)
SIZES_IN = (0.007, 0.014, 0.021)
SLIPS = (1.0, 1.5, 2.0)
#: how the slip acts: "walk", the cage-speed random walk (``slip_percent``), or "jitter", the
#: balls wandering in their pockets with the phase locked to the cage
#: (``pocket_jitter_percent``; ``--slip-form jitter``, an experiment: the CWRU records' fault
#: orders scatter far less than the walk lets them, docs/validation.md)
SLIP_FORM = "walk"
#: how a ball loses support over a defect: ``"geometric"``, a slot across the track on whose
#: nearer edge the ball rests, or ``"pit"`` (``--defect-profile pit``, an experiment): a round
#: pit narrower than the contact, as CWRU's EDM faults are (docs/models.md "Drop profile")
DEFECT_PROFILE = "geometric"
#: the model simulated: the DEM (its Hertz contact takes a preload; the VSM's secant does not)
MODEL = "dem"
#: Machine facts the CWRU data do not publish, drawn per run (uniformly from these sets):
#: ball diameter spread [m]: identical balls and the ISO 3290-1 lot diameter variation of
#: grades G10, G20, G40 (the grades deep-groove ball bearings are made with);
SPREADS_M = (0.0, 0.5e-6, 1.0e-6, 2.0e-6)
#: rotor unbalance [share of the static load, 51 N]: the seed ROTOR's CWRU rotor (2.04 kg:
#: armature 1.361 kg, shaft 0.68 kg) balanced to ISO 21940-11 G2.5-G16 at 1800 r/min gives
#: 1.0-6.2 N (2-12 %); the draw reaches beyond it (25, 50 %), a deliberately wide range for the
#: once-per-turn forces the CWRU data do not give (a heavier rotor, a coupling);
UNBALANCE = (0.0, 0.1, 0.25, 0.5)
#: operating diametral clearance [m]: the catalogue's 6 um, none, and preloads of 5 and 10 um
#: (a motor's wave spring: ~150 N axially loads every ball of a 6205 by ~100 N, about 5 um
#: of contact deflection; a 2-D ring model takes it as a negative clearance).
CLEARANCES_M = (6e-6, 0.0, -5e-6, -10e-6)
#: axial spring preload [kN per mm of bore] (``axial_load_n`` = this x the bore in mm x 1000):
#: none, and SKF's range for the wave springs of small electric motors, F = k d with k =
#: 0.005-0.01 (SKF, "Preloading with springs"): 125-250 N on the 6205, 85-170 N on the 6203.
#: The CWRU records' own contact angles (2.5-14 deg, docs/validation.md) show axial loads
AXIAL_K = (0.0, 0.005, 0.01)
#: composite RMS roughness of the ball-raceway contacts [m] (``contact_roughness_m``): half,
#: once and twice the 0.1 um of ground and honed raceways with grade <= G20 balls
#: (bearingsim.side_by_side.CONTACT_ROUGHNESS_M)
ROUGHNESS_M = (0.05e-6, 0.1e-6, 0.2e-6)
PROFILES = {
    "cwru-de-12k": ("6205-cwru", 12000.0),
    "cwru-fe-12k": ("6203-cwru", 12000.0),
    "cwru-de-48k": ("6205-cwru", 48000.0),
}
DURATION_S = 1.0
#: outer-race defect positions simulated, by the azimuth of the defect's left edge from the load
#: direction [deg] (the DEM's ``defect_edge_angle_deg``; CWRU: @6 in the load zone, @3 and @12
#: at 90 and 180 deg from it). A defect outside the load zone is struck only when every ball is
#: loaded (a preload or an axial load); runs where no ball loads it are left out (their sensor
#: signal is the healthy one, bit for bit)
OUTER_POSITIONS = {"@6": 10.0, "@3": 100.0, "@12": 190.0}
#: the rig sets a dataset can be built through: the shipped profiles, and the same mountings
#: identified without one CWRU fault size (the held-out evaluation; manifest spelling)
HELD_OUT = ("0.007", "0.014")
#: the ring models' default radial load (seed VSM table 1) [N]
SEED_FX_N, SEED_FY_N = 10.0, 50.0
FEATURES = (
    *("bpfo", "2bpfo", "bpfi", "2bpfi", "bpfi-fs", "bpfi+fs", "2bsf", "2bsf-ftf", "2bsf+ftf"),
    *("ftf", "2ftf", "fs", "2fs", "logkurt"),
)
DATA = Path(__file__).resolve().parents[2] / "shared" / "data" / "cwru"
CACHE = Path(os.environ.get("XDG_CACHE_HOME", Path.home() / ".cache")) / "bearingsim"


def features(x: np.ndarray, fs: float, rpm: float, bearing) -> np.ndarray:
    """The feature vector of a signal [m/s^2] at ``fs`` [Hz] and shaft speed ``rpm`` of
    ``bearing`` (a catalogue id or a Bearing)."""
    from scipy.stats import kurtosis

    from bearingsim.catalog import as_bearing
    from bearingsim.geometry import characteristic_frequencies
    from bearingsim.signal.envelope import EnvelopeKind, envelope_spectrum
    from bearingsim.signal.kurtogram import fast_kurtogram

    a = np.asarray(x, dtype=float) - float(np.mean(x))
    fsh = rpm / 60.0
    kin = characteristic_frequencies(as_bearing(bearing), fsh)
    k = fast_kurtogram(a, fs, min_bandwidth_hz=max(4.0 * kin.bpfi_hz, 400.0))
    s = envelope_spectrum(a, fs, k.band, EnvelopeKind.SQUARED)
    f, amp = s.freq, s.amplitude
    floor = float(np.median(amp[(f >= 20.0) & (f <= 600.0)])) or 1e-300
    targets = (
        kin.bpfo_hz,
        2 * kin.bpfo_hz,
        kin.bpfi_hz,
        2 * kin.bpfi_hz,
        kin.bpfi_hz - fsh,
        kin.bpfi_hz + fsh,
        2 * kin.bsf_hz,
        2 * kin.bsf_hz - kin.ftf_hz,
        2 * kin.bsf_hz + kin.ftf_hz,
        kin.ftf_hz,
        2 * kin.ftf_hz,
        fsh,
        2 * fsh,
    )
    out = []
    for ft in targets:
        half = max(0.015 * ft, 1.5 * (f[1] - f[0]))  # +/- 1.5 %, at least the line spacing
        w = (f >= ft - half) & (f <= ft + half)
        out.append(10.0 * math.log10(max(float(amp[w].max()), 1e-300) / floor))
    out.append(math.log(max(float(kurtosis(a, fisher=False)), 1e-3)))
    return np.array(out)


def _grid():
    faults = [("none", 0.0, "")]
    for f in ("inner", "outer", "ball"):
        for d in SIZES_IN:
            faults += [(f, d, pos) for pos in (OUTER_POSITIONS if f == "outer" else ("",))]
    for i_rig, (rig, (bearing, fs)) in enumerate(PROFILES.items()):
        for i_rpm, rpm in enumerate(RPMS):
            for seed, slip in enumerate(SLIPS):
                for fault, size, pos in faults:
                    # the unpublished machine facts, drawn per run (a stream of its own; the
                    # other outer-race positions have streams of their own too)
                    key = [i_rig, i_rpm, seed, LABELS.index(fault), round(size * 1e4)]
                    if pos not in ("", "@6"):
                        key.append(list(OUTER_POSITIONS).index(pos))
                    rng = np.random.default_rng(key)
                    c = dict(
                        rig=rig,
                        bearing=bearing,
                        fs=fs,
                        rpm=rpm,
                        fault=fault,
                        size=size,
                        slip=slip,
                        seed=seed,
                        spread=SPREADS_M[rng.integers(len(SPREADS_M))],
                        unbalance=UNBALANCE[rng.integers(len(UNBALANCE))],
                        clearance=CLEARANCES_M[rng.integers(len(CLEARANCES_M))],
                        roughness=ROUGHNESS_M[rng.integers(len(ROUGHNESS_M))],
                        axial_k=AXIAL_K[rng.integers(len(AXIAL_K))],
                    )
                    if pos:
                        c["edge_deg"] = OUTER_POSITIONS[pos]
                        # outside the load zone only a preload or an axial load loads a ball
                        if pos != "@6" and not (c["clearance"] < 0.0 or c["axial_k"] > 0.0):
                            continue
                    yield c


def _bore_mm(bearing: str) -> float:
    """Bore diameter of a catalogue bearing [mm]."""
    from bearingsim.catalog import get_bearing

    return get_bearing(bearing).bore * 1000.0


def _end(bearing: str) -> str:
    """The CWRU bearing's end: the fan end carries the 6203."""
    return "FE" if bearing.startswith("6203") else "DE"


def rig_set(name: str, data: Path | None = None, path_fit: bool = False) -> dict:
    """The rigs of one set by profile name: ``"shipped"`` (:func:`bearingsim.rig.load_rig`) or
    ``"without-<size>"`` (each profile's mounting identified from the records of ``data``
    without that fault size; None where it has none). ``path_fit``: each rig's gains fitted
    with the :data:`MODEL`'s output as the known input on the fault records it was identified
    from (:func:`bearingsim.side_by_side.model_path_fit`; an experiment, off by default,
    docs/validation.md "Sim-to-real")."""
    from bearingsim.rig import load_rig
    from bearingsim.side_by_side import rig_without_size

    if name == "shipped":
        rigs = {p: load_rig(p) for p in PROFILES}
    else:
        size = name.removeprefix("without-")
        if size == name or size not in HELD_OUT:
            valid = ", ".join(["shipped", *(f"without-{s}" for s in HELD_OUT)])
            raise ValueError(f"rig set {name!r} is unknown; valid: {valid}")
        if data is None or not (Path(data) / "manifest.csv").is_file():
            raise FileNotFoundError(f"rig set {name!r} needs the CWRU folder (--data): {data}")
        rigs = {
            p: rig_without_size(Path(data), _end(bearing), fs, size)
            for p, (bearing, fs) in PROFILES.items()
        }
    return _fit_paths(rigs, name, data) if path_fit else rigs


def _fit_paths(rigs: dict, name: str, data: Path | None) -> dict:
    """``rigs`` with each path fitted to the :data:`MODEL` on its identification records: the
    CWRU fault records of its end and rate (the shipped profiles were identified from all of
    them; a held-out set's from those of the other size)."""
    from bearingsim.side_by_side import _other_size_records, model_path_fit

    if data is None or not (Path(data) / "manifest.csv").is_file():
        raise FileNotFoundError(f"--path-fit needs the CWRU folder (--data): {data}")
    left_out = name.removeprefix("without-") if name != "shipped" else None
    out = {}
    for p, rig in rigs.items():
        if rig is None:
            out[p] = None
            continue
        bearing, fs = PROFILES[p]
        names = _other_size_records(Path(data), _end(bearing), fs, left_out)
        recs = [Path(data) / f for f in names]
        out[p] = model_path_fit(rig, recs, model=MODEL, progress=sys.stderr.isatty())[0]
    return out


def _code_key() -> str:
    """SHA-256 of the installed bearingsim's source and data files (``*.py``, ``*.toml``) and of
    this example: the code that made the features. A dataset cached by other code is rebuilt
    (twenty-first session: the key held the grid and the rigs only, so a model fixed since,
    e.g. random slip's pass rate, was still read from the cache)."""
    import hashlib

    import bearingsim

    root = Path(bearingsim.__file__).resolve().parent
    h = hashlib.sha256()
    for f in sorted(root.rglob("*")):
        if f.suffix in (".py", ".toml") and "__pycache__" not in f.parts:
            h.update(str(f.relative_to(root)).encode() + b"\0" + f.read_bytes() + b"\0")
    h.update(Path(__file__).read_bytes())  # this example's own features and grid
    return h.hexdigest()


def _set_key(grid_key: str, rigs: dict) -> str:
    """Cache key of one set: the grid, every rig's full table (a changed profile or record
    rebuilds it) and the code (:func:`_code_key`)."""
    import hashlib

    tables = {p: (None if r is None else r.to_dict()) for p, r in rigs.items()}
    blob = grid_key + json.dumps(tables, sort_keys=True, default=str) + _code_key()
    return hashlib.sha256(blob.encode()).hexdigest()


def build_dataset(cache: Path, progress: bool = True):
    """Simulate the grid, compute the features through the shipped rigs and cache them (Zarr);
    returns ``(X, y, meta)``."""
    sets, meta = build_datasets(cache, ("shipped",), progress=progress)
    X, y = sets["shipped"]
    return X, y, meta


def build_datasets(
    cache: Path, names=("shipped",), data: Path | None = None, progress=True, path_fit=False
):
    """The features of the grid through each rig set of ``names`` (:func:`rig_set`, with
    ``path_fit``): each run
    is simulated once and passed through every set's rig of its profile. Cached (Zarr, one
    array per set, keyed by the grid and the rigs' tables); a set without a rig for a profile
    drops that profile's runs. A damaged cache (:func:`read_cache`) is rebuilt, with a warning
    on stderr; an unwritable cache location is a :class:`CacheLocationError` before any
    simulation. Returns ``({name: (X, y)}, meta)``; ``meta["rigs"]`` holds the sets' rigs."""
    import zarr

    # one store per variant of the grid: an experiment (--defect-profile pit, --slip-form
    # jitter) no longer replaces the default dataset, which took minutes to rebuild
    variant = "".join(
        f"-{v}" for v, d in ((DEFECT_PROFILE, "geometric"), (SLIP_FORM, "walk")) if v != d
    )
    path = Path(cache) / f"sim_to_real{variant}.zarr"
    grid = [MODEL, RPMS, SIZES_IN, SLIPS, SPREADS_M, UNBALANCE, CLEARANCES_M, ROUGHNESS_M]
    grid += [AXIAL_K]
    grid += [PROFILES]
    if set(OUTER_POSITIONS) != {"@6"}:  # the shipped grid's key stays as it was
        grid += [OUTER_POSITIONS]
    grid += [DURATION_S, FEATURES, "antialias", DEFECT_PROFILE]
    if SLIP_FORM != "walk":  # the shipped grid's key stays as it was
        grid += [SLIP_FORM]
    grid_key = json.dumps(grid)
    names = list(dict.fromkeys(["shipped", *names]))
    rigs = {n: rig_set(n, data, path_fit) for n in names}
    keys = {n: _set_key(grid_key, rigs[n]) for n in names}
    runs = list(_grid())
    try:
        got = read_cache(path, names, keys, len(runs))
    except CacheDamaged as exc:
        print(f"warning: cache {path} is damaged ({exc}); rebuilding", file=sys.stderr)
        got = None
    if got is not None:
        out, attrs = got
        return out, attrs | {"rigs": rigs}
    check_cache_location(Path(cache), path)  # before minutes of simulation, not after them
    print(
        f"building the training set: {len(runs)} simulations through {len(names)} rig set(s) "
        f"(minutes; cached at {path})",
        file=sys.stderr,
        flush=True,
    )
    t0 = time.perf_counter()
    X, y, mask = simulate_runs(runs, names, rigs, progress)
    for n in names:  # a run without finite features trains nothing (and reads as damage)
        mask[n] &= np.all(np.isfinite(X[n]), axis=1)
        X[n][~mask[n]] = np.nan
    gen_s = time.perf_counter() - t0
    cache = Path(cache)
    cache.mkdir(parents=True, exist_ok=True)
    tmp = Path(tempfile.mkdtemp(dir=cache, prefix=".sim_to_real."))
    try:
        g = zarr.open_group(str(tmp / "g.zarr"), mode="w")
        arrays = {"y": y} | {f"X_{n}": X[n] for n in names} | {f"mask_{n}": mask[n] for n in names}
        for k, a in arrays.items():
            g.create_array(k, data=a)
        g.attrs.update(
            {
                "sha256": _digest(arrays),
                "grid": grid_key,
                "keys": keys,
                "sets": names,
                "features": list(FEATURES),
                "labels": list(LABELS),
                "n_runs": len(runs),
                "generation_s": gen_s,
            }
        )
        if path.is_symlink() or path.is_file():  # a damaged cache may be anything
            path.unlink()
        elif path.exists():
            shutil.rmtree(path)
        (tmp / "g.zarr").rename(path)
    except OSError as exc:  # the dataset is made: use it uncached rather than lose it
        from bearingsim.errors import exception_text

        print(
            f"warning: cache {path} could not be written ({exception_text(exc)}); the dataset "
            "is used without caching",
            file=sys.stderr,
        )
    finally:
        shutil.rmtree(tmp, ignore_errors=True)
    size = sum(p.stat().st_size for p in path.rglob("*") if p.is_file()) if path.is_dir() else 0
    print(
        f"dataset: {len(runs)} simulations through {len(names)} rig set(s) "
        f"({', '.join(names)}) in {gen_s:.1f} s, {size / 1e3:.0f} kB at {path}",
        file=sys.stderr,
    )
    out = {n: (X[n][mask[n]], y[mask[n]]) for n in names}
    meta = {"n_runs": len(runs), "generation_s": gen_s, "grid": grid_key, "keys": keys}
    return out, meta | {"rigs": rigs}


def simulate_runs(runs: list, names: list, rigs: dict, progress: bool = True):
    """Simulate each run of the grid once and take its features through every set's rig of its
    profile. Returns ``(X, y, mask)``: ``X`` and ``mask`` by set name (NaN rows and False where
    a set has no rig for the run's profile), ``y`` the label indices."""
    from tqdm import tqdm

    from bearingsim import simulate
    from bearingsim.rig import apply_rig

    X = {n: np.full((len(runs), len(FEATURES)), np.nan) for n in names}
    mask = {n: np.zeros(len(runs), dtype=bool) for n in names}
    y = np.empty(len(runs), dtype=np.int64)
    for i, c in enumerate(tqdm(runs, desc="simulate", disable=not progress, file=sys.stderr)):
        sc = dict(
            model=MODEL,
            bearing=c["bearing"],
            fault=c["fault"],
            rpm=c["rpm"],
            duration_s=DURATION_S,
            fs_hz=c["fs"],
            seed=c["seed"],
            **{"slip_percent" if SLIP_FORM == "walk" else "pocket_jitter_percent": c["slip"]},
            ball_diameter_spread_m=c["spread"],
            antialias=True,  # through a measurement chain: its anti-aliasing filter
            defect_profile=DEFECT_PROFILE,  # a slot (the ball on its nearer edge) or a pit
            contact_roughness_m=c["roughness"],
        )
        sc["unbalance_n"] = c["unbalance"] * math.hypot(SEED_FX_N, SEED_FY_N)
        sc["clearance_m"] = c["clearance"]
        if c["axial_k"] > 0.0:  # a spring preload: k [kN/mm] x bore [mm] x 1000 [N/kN]
            sc["axial_load_n"] = c["axial_k"] * _bore_mm(c["bearing"]) * 1000.0
        if c["fault"] != "none":
            sc["defect_width_m"] = c["size"] * 0.0254
        if "edge_deg" in c and c["edge_deg"] != OUTER_POSITIONS.get("@6"):
            sc["defect_edge_angle_deg"] = c["edge_deg"]
        bare = simulate(sc)
        y[i] = LABELS.index(c["fault"])
        for n in names:
            rig = rigs[n][c["rig"]]
            if rig is None:
                continue
            r = apply_rig(bare, rig, seed=c["seed"])
            X[n][i] = features(r["acc_sensor"], c["fs"], c["rpm"], c["bearing"])
            mask[n][i] = True
    return X, y, mask


class CacheDamaged(Exception):
    """The cached dataset cannot be trusted (the message says why); it is rebuilt."""


class CacheLocationError(Exception):
    """The cache location cannot hold the dataset (one line naming it)."""


def _digest(arrays: dict) -> str:
    """SHA-256 of the named arrays (name, dtype, shape and bytes, in name order): a changed
    byte of a chunk (the store's compressor keeps no checksum) must not train silently."""
    import hashlib

    h = hashlib.sha256()
    for k in sorted(arrays):
        a = np.ascontiguousarray(arrays[k])
        h.update(f"{k}|{a.dtype.str}|{a.shape}|".encode())
        h.update(a.tobytes())
    return h.hexdigest()


def check_cache_location(cache: Path, store: Path | None = None) -> None:
    """Raise :class:`CacheLocationError` unless ``cache`` is, or can be created as, a writable
    folder, in which a folder can be made, and an old ``store`` there can be replaced (checked
    before any simulation: the failure would otherwise come minutes later). Creates ``cache``."""
    cache = Path(cache)
    probe = cache
    while not probe.exists():  # the nearest existing ancestor must be a writable folder
        if probe.parent == probe:
            break
        probe = probe.parent
    if probe.exists() and not probe.is_dir():
        raise CacheLocationError(
            f"--cache = {str(cache)!r} is not creatable: {str(probe)!r} is not a folder; "
            "valid: a writable folder (or one that can be created)"
        )
    if not os.access(probe, os.W_OK | os.X_OK):
        raise CacheLocationError(
            f"--cache = {str(cache)!r} is not writable ({str(probe)!r} denies it); valid: a "
            "writable folder (or one that can be created)"
        )
    from bearingsim.errors import exception_text

    try:  # what the write will do: a folder (e.g. /sys passes the access test, refuses this)
        cache.mkdir(parents=True, exist_ok=True)
        Path(tempfile.mkdtemp(dir=cache, prefix=".sim_to_real.probe.")).rmdir()
    except OSError as exc:
        raise CacheLocationError(
            f"--cache = {str(cache)!r} is not writable ({exception_text(exc)}); valid: a "
            "writable folder (or one that can be created)"
        ) from None
    if store is not None and store.is_dir() and not store.is_symlink():
        locked = [q for q in (store, *store.rglob("*")) if q.is_dir()
                  and not os.access(q, os.W_OK | os.X_OK)]  # fmt: skip
        if locked:
            raise CacheLocationError(
                f"--cache = {str(cache)!r}: the old dataset {str(store)!r} cannot be replaced "
                f"({str(locked[0])!r} is not writable); valid: a cache whose dataset this user "
                "may replace (or another --cache)"
            )


def read_cache(path: Path, names: list, keys: dict, n_runs: int):
    """The cached sets ``({name: (X, y)}, attrs)``, or None when there is no cache or it was
    built for another grid or other rigs (its keys differ). Raises :class:`CacheDamaged` when
    the store cannot be read or its arrays are not what :func:`build_datasets` writes: every
    chunk present (zarr fills a missing one with zeros), ``X`` of shape ``(n_runs, features)``
    finite exactly where ``mask`` is set, labels from :data:`LABELS` with more than one class
    among the kept runs."""
    import zarr

    path = Path(path)
    if not (path.exists() or path.is_symlink()):
        return None
    try:
        g = zarr.open_group(str(path), mode="r")
        stored = g.attrs.get("keys", {})
        if not isinstance(stored, dict):
            raise CacheDamaged(f"attribute keys = {type(stored).__name__}; valid: a mapping")
        if not all(stored.get(n) == keys[n] for n in names):
            return None  # another grid or other rigs: rebuilt silently, as always
        sets = g.attrs.get("sets", names)  # every set written: the digest covers them all
        if not isinstance(sets, list) or not set(names) <= set(sets):
            raise CacheDamaged(f"attribute sets = {sets!r}; valid: a list naming {names}")
        arrays = {}
        for name in ["y", *(f"{k}_{n}" for n in sets for k in ("X", "mask"))]:
            if name not in g:
                raise CacheDamaged(f"array {name!r} is missing")
            a = g[name]
            if a.nchunks_initialized != a.nchunks:
                raise CacheDamaged(
                    f"array {name!r} has {a.nchunks_initialized} of its {a.nchunks} chunks"
                )
            arrays[name] = np.asarray(a[...])
        attrs = dict(g.attrs)
    except CacheDamaged:
        raise
    except Exception as exc:  # whatever the reader raises on a damaged store is one line
        why = " ".join(str(exc).split())[:200] or type(exc).__name__
        raise CacheDamaged(f"{type(exc).__name__}: {why}") from None
    if attrs.get("sha256") != _digest(arrays):
        raise CacheDamaged(
            "its arrays do not match their SHA-256 digest" if "sha256" in attrs
            else "it has no SHA-256 digest (written before the cache carried one)"
        )  # fmt: skip
    y = arrays["y"]
    if y.shape != (n_runs,) or y.dtype.kind not in "iu":
        raise CacheDamaged(f"y has shape {y.shape}, {y.dtype}; valid: ({n_runs},) integers")
    if y.size and (y.min() < 0 or y.max() >= len(LABELS)):
        raise CacheDamaged(f"labels outside the valid range [0, {len(LABELS) - 1}]")
    out = {}
    for n in names:
        X, mask = arrays[f"X_{n}"], arrays[f"mask_{n}"]
        if X.shape != (n_runs, len(FEATURES)) or X.dtype.kind != "f":
            raise CacheDamaged(
                f"X_{n} has shape {X.shape}, {X.dtype}; valid: ({n_runs}, {len(FEATURES)}) floats"
            )
        if mask.shape != (n_runs,) or mask.dtype != bool:
            raise CacheDamaged(
                f"mask_{n} has shape {mask.shape}, {mask.dtype}; valid: ({n_runs},) bools"
            )
        finite = np.all(np.isfinite(X), axis=1)
        if not np.array_equal(finite, mask):
            bad = int(np.count_nonzero(finite != mask))
            raise CacheDamaged(
                f"X_{n} and mask_{n} disagree on {bad} run(s) (finite rows = kept runs)"
            )
        classes = np.unique(y[mask])
        if classes.size < 2:
            raise CacheDamaged(
                f"set {n!r} keeps {mask.sum()} run(s) of {classes.size} class(es); valid: at "
                "least 2 classes"
            )
        out[n] = (X[mask], y[mask])
    return out, attrs


def train(X, y):
    """A random forest on the simulated features (scikit-learn)."""
    try:
        from sklearn.ensemble import RandomForestClassifier
    except ImportError:
        sys.exit("error: scikit-learn is needed: pip install 'bearingsim[ml]'")
    clf = RandomForestClassifier(
        n_estimators=300, min_samples_leaf=2, random_state=0, class_weight="balanced"
    )
    return clf.fit(X, y)


#: the largest spread of a per-sample speed (a text file's ``rpm`` or ``speed_hz`` column) a
#: record is judged at its median speed with: the 1st-99th percentile span over the median.
#: The features read each line within +/- 1.5 % of its frequency, a 3 % window
SPEED_SPREAD_MAX = 0.03
#: how far outside the trained speeds (``RPMS``) a record's speed may lie before its result
#: carries a warning (a share of the range's ends)
RPM_MARGIN = 0.05


def _record(
    path: Path,
    rpm: float | None = None,
    *,
    channel: str | None = None,
    fs_hz: float | None = None,
    info: dict | None = None,
    bearing=None,
):
    """Signal, fs, shaft speed [r/min], where the speed came from, and bearing of a record
    (``bearingsim.signal.diagnosis.load_signal_and_speed``, the rule of ``bearingsim analyze``).

    * CWRU ``.mat``: the channel of the fault's end in the file name (``FE`` for
      ``Fan_End``, else ``DE``) unless ``channel`` is given; the bearing of that end (the
      6205, or the 6203 on ``FE``). The speed: ``rpm`` if given, else the file's ``X###RPM``,
      else the CWRU nominal speed of the load in the file name (the 0.028 in records store
      none); with none of these it is an error naming --rpm.
    * bearingsim result ``.nc``/``.h5``: the reader's channel (``sensor`` if the result has
      it, else ``y``) unless ``channel`` is given; the bearing stored in the file.
    * ``.csv``/``.txt``: ``channel`` (a column) or the first signal column, ``fs_hz`` where
      there is no time column; the bearing of the end in the name, as for ``.mat``. A
      per-sample speed column (``rpm`` or ``speed_hz``) is judged at its median when its
      1st-99th percentile span is within :data:`SPEED_SPREAD_MAX` of it, else refused.

    ``bearing`` (a Bearing, ``--bearing``) replaces the bearing of any of these. The samples
    pass ``bearing analyze``'s checks (:func:`bearingsim.signal.diagnosis.check_samples`: not
    finite, constant, clipped, or a time or counter column read as the signal).

    ``info`` (a dict) receives the reader's ``fs_source``, the ``channel`` read and where the
    bearing came from (``bearing_source``)."""
    from bearingsim.errors import ConfigError
    from bearingsim.io.cwru import cwru_bearing, cwru_end
    from bearingsim.signal.diagnosis import check_samples, load_signal_and_speed

    end = cwru_end(path)
    suffix = Path(path).suffix.lower()
    ch = channel
    if suffix == ".mat" and ch is None:
        ch = end
    r, source = load_signal_and_speed(path, channel=ch, fs_hz=fs_hz, rpm=rpm)
    # exploratory testing (twenty-fifth session): a time column without a header, read with
    # --fs-hz, was classified ("none", 0.85) where `analyze` refuses it
    check_samples(r)
    info = {} if info is None else info
    info.update(r.info)
    info.setdefault("fs_source", "option" if fs_hz is not None else "file")
    info["channel"] = r.channel
    x = np.asarray(r.x, dtype=float)
    speed = r.rpm
    if speed is None:  # a per-sample speed column: judged at its median if it barely varies
        v = np.asarray(r.speed_hz, dtype=float) * 60.0
        if not (v.size and np.all(np.isfinite(v)) and np.all(v > 0.0)):
            raise ConfigError(
                f"file = {Path(path).name!r}: the speed column holds values that are not "
                "finite and > 0; valid range (0, inf) r/min, or give --rpm R"
            )
        med = float(np.median(v))
        lo, hi = (float(q) for q in np.percentile(v, [1.0, 99.0]))
        spread = (hi - lo) / med
        if spread > SPEED_SPREAD_MAX:
            raise ConfigError(
                f"file = {Path(path).name!r}: the speed column varies by {100 * spread:.1f} % "
                f"({lo:.0f}-{hi:.0f} r/min, 1st-99th percentile); valid range [0, "
                f"{100 * SPEED_SPREAD_MAX:g}] % (the features read each line within +/- 1.5 %), "
                "or give --rpm R to judge it at one speed"
            )
        speed = med
        source = f"median of the speed column ({100 * spread:.1f} % spread)"
    if bearing is not None:
        info["bearing_source"] = "option"
        if r.bearing is not None and r.bearing != bearing:  # as `analyze` notes it
            info["bearing_overrides"] = r.bearing.id
    elif r.bearing is not None:  # a bearingsim result states its bearing
        bearing, info["bearing_source"] = r.bearing, "file"
    elif suffix == ".mat" and r.channel in ("DE", "FE"):
        bearing, info["bearing_source"] = cwru_bearing(r.channel), "CWRU channel"
    else:
        bearing = cwru_bearing(end)
        info["bearing_source"] = "file name (Fan_End)" if end == "FE" else "default (CWRU DE)"
    return x, float(r.fs), float(speed), source, bearing


def segments(x, fs: float) -> list[np.ndarray]:
    """The record cut into consecutive pieces of the simulations' length ``DURATION_S`` (the
    remainder dropped; a shorter record is one piece). Features are levels over the envelope
    spectrum's floor, and the floor of a line spectrum falls with the record's length (a
    10 s record's lines stand ~10 dB higher than a 1 s record's): the classifier must see
    measured features on the same length as the simulated ones it learned."""
    n = int(round(DURATION_S * fs))
    x = np.asarray(x, dtype=float)
    if x.size < 2 * n:
        return [x[:n] if x.size >= n else x]
    return [x[i : i + n] for i in range(0, x.size - n + 1, n)]


def predict(clf, files, rpm: float | None = None, *, channel=None, fs_hz=None, bearing=None):
    """One result per file: ``{"file", "predicted", "probabilities", "rpm", "rpm_source",
    "fs_hz", "fs_source", "channel", "bearing", "bearing_source"}`` (and ``"warning"`` when
    the speed lies outside the trained ones, ...), or ``{"file", "predicted": None,
    "probabilities": None, "error"}``; ``"file"`` is the path as given. ``bearing`` (a
    catalogue id, a Bearing or a bearing TOML path) replaces every file's own."""
    lo, hi = min(RPMS), max(RPMS)
    for f in files:
        p = Path(f)
        try:
            info: dict = {}
            own = _bearing_option(bearing)
            x, fs, rpm_used, source, bearing_used = _record(
                p, rpm, channel=channel, fs_hz=fs_hz, info=info, bearing=own
            )
            _check_length(x, fs, rpm_used, bearing_used)
            warn = (
                _length_warning(x, fs)
                + _speed_warning(
                    x,
                    fs,
                    rpm_used,
                    rpm if rpm is not None else _named(source),
                    info.get("rpm_file"),
                )  # fmt: skip
                + _rate_warning(fs)
                + _bearing_warning(p, info["bearing_source"], bearing_used)
                + _override_warning(info, bearing_used)
            )
            segs = segments(x, fs)
            feats = []
            for k, seg in enumerate(segs):
                try:
                    v = features(seg, fs, rpm_used, bearing_used)
                    if not np.all(np.isfinite(v)):
                        raise ValueError("its features are not finite")
                except Exception as exc:
                    t0 = k * DURATION_S
                    t1 = t0 + seg.size / fs
                    raise ValueError(
                        f"piece {k + 1} of {len(segs)} ({t0:g}-{t1:g} s): {exc}"
                    ) from None
                feats.append(v)
            prob = clf.predict_proba(np.array(feats)).mean(axis=0)
        except Exception as exc:  # one bad file is its own line
            err = " ".join(str(exc).split()) or type(exc).__name__
            yield {"file": str(f), "predicted": None, "probabilities": None, "error": err}
            continue
        probs = dict.fromkeys(LABELS, 0.0)
        probs |= {LABELS[c]: float(v) for c, v in zip(clf.classes_, prob, strict=True)}
        best = max(probs, key=probs.get)
        bid = bearing_used if isinstance(bearing_used, str) else bearing_used.id
        o = {"file": str(f), "predicted": best, "probabilities": probs, "rpm": rpm_used,
             "rpm_source": source, "fs_hz": fs, "fs_source": info["fs_source"],
             "channel": info["channel"], "bearing": bid,
             "bearing_source": info["bearing_source"]}  # fmt: skip
        if not (lo * (1.0 - RPM_MARGIN) <= rpm_used <= hi * (1.0 + RPM_MARGIN)):
            warn.append(
                f"rpm = {rpm_used:g} r/min is outside the trained speeds ({lo:g}-{hi:g} r/min, "
                f"+/- {100 * RPM_MARGIN:g} %); the label is an extrapolation"
            )
        if warn:
            o["warning"] = "; ".join(warn)
        yield o


#: the cage revolutions a record must span: the envelope spectrum's line spacing (1/T) must
#: resolve the cage line (FTF, ~0.4 of the shaft speed) from 0 by three lines, the least the
#: features' windows (+/- 1.5 %, at least 1.5 lines) can tell apart
MIN_CAGE_TURNS = 3.0


def _check_length(x, fs: float, rpm: float, bearing) -> None:
    """Refuse a record too short to resolve the cage line (:data:`MIN_CAGE_TURNS`): its
    features would read every target line in one window of the same few bins (a 0.04 s
    record, 25 Hz lines, was labelled "none" at p = 0.73)."""
    from bearingsim.catalog import as_bearing
    from bearingsim.errors import ConfigError
    from bearingsim.geometry import characteristic_frequencies
    from bearingsim.signal.diagnosis import DiagnosisRule, min_band_width

    # a rate too low for the fault lines (a time column in ms read as s: fs 12 Hz) ended in a
    # kurtogram's error or "signal has 12 samples" (exploratory testing, twenty-fifth
    # session); this is `analyze`'s check and message
    min_band_width(as_bearing(bearing), rpm / 60.0, fs, DiagnosisRule())
    ftf = characteristic_frequencies(as_bearing(bearing), rpm / 60.0).ftf_hz
    t, need = np.asarray(x).size / fs, MIN_CAGE_TURNS / ftf
    if t < need:
        raise ConfigError(
            f"the record is {t:.3g} s long; valid: at least {need:.3g} s ({MIN_CAGE_TURNS:g} "
            f"turns of the cage at {ftf:.4g} Hz, {rpm:g} r/min), so that the envelope spectrum "
            "resolves the cage line"
        )


#: relative difference of a record's sample rate from a training rate that counts as that rate
#: [-] (a time column written to 9 digits gives 12 kHz to 2e-9)
RATE_REL = 1e-6


def _rate_warning(fs: float) -> list[str]:
    """A warning for a sample rate none of the training's rigs has (:data:`PROFILES`): the
    kurtogram's bands and the rig's ringing the classifier learned are those rates'."""
    rates = sorted({float(r) for _, r in PROFILES.values()})
    # a time column's rate is the mean step's: 11999.99998 Hz is 12 kHz (exploratory testing,
    # twenty-fifth session: "fs = 12000 Hz is not a rate ... (12000, 48000 Hz)")
    if any(abs(float(fs) / r - 1.0) <= RATE_REL for r in rates):
        return []
    return [
        f"fs = {fs:g} Hz is not a rate the classifier was trained at ("
        + ", ".join(f"{r:g}" for r in rates)
        + " Hz): its bands and the rigs' ringing differ, the label is less reliable"
    ]


def _length_warning(x, fs: float) -> list[str]:
    """A warning for a record shorter than the simulations (:data:`DURATION_S`): its lines
    stand lower over the envelope spectrum's floor than the training set's (:func:`segments`),
    so a fault reads weaker (CWRU records cut to 0.25 s: 13 of 34 right, against 25 whole)."""
    t = np.asarray(x).size / fs
    if t >= DURATION_S * (1.0 - 1e-9):
        return []
    return [
        f"the record is {t:.3g} s long, shorter than the {DURATION_S:g} s the classifier was "
        "trained on: its fault lines stand lower over the floor, the label is less reliable"
    ]


def _named(source: str) -> float | None:
    """A truthy stand-in for a speed given when ``source`` says the speed is the nominal one
    of the load in the file's name (:func:`_speed_warning` checks those too: a name such as
    ``line4_3_07.csv`` matches the CWRU pattern and gave CWRU record 169, at 1796 r/min,
    1730 r/min and "outer" without a word; exploratory testing, twenty-fifth session)."""
    return 1.0 if source.startswith("name") else None


def _speed_warning(
    x, fs: float, rpm_used: float, rpm_option: float | None, stated: float | None = None
) -> list[str]:
    """A warning when a speed given (``--rpm``, or the nominal speed of a name: ``rpm_option``
    not None) is refuted by the record's own shaft harmonics
    (:func:`bearingsim.signal.contact_angle.refuted_speed`): the features read the fault lines
    at the wrong speed (record 109 at --rpm 1730 instead of its 1796 r/min read "outer")."""
    if rpm_option is None:
        return []
    from bearingsim.signal.contact_angle import check_speed_given, hz_warning

    c, in_hz = check_speed_given(x, fs, rpm_used / 60.0,
                                 stated_hz=None if stated is None else stated / 60.0)  # fmt: skip
    if c is None:  # a speed in Hz typed for --rpm is said too
        return [hz_warning(rpm_used, in_hz)] if in_hz is not None else []
    own = 60.0 * c.shaft_hz
    return [
        f"rpm = {rpm_used:g} r/min: the record's shaft harmonics put its speed at {own:.6g} "
        f"r/min ({100.0 * (own / rpm_used - 1.0):+.2f} %); the fault lines were read at the "
        "wrong speed (check --rpm)"
    ]


def _override_warning(info: dict, bearing) -> list[str]:
    """A warning when ``--bearing`` replaced the bearing a bearingsim result states (``info``'s
    ``bearing_overrides``, :func:`_record`), as ``bearingsim analyze`` notes it."""
    if "bearing_overrides" not in info:
        return []
    return [f"--bearing {bearing.id} overrides the {info['bearing_overrides']} the result was "
            "simulated with"]  # fmt: skip


def _bearing_option(bearing):
    """``--bearing``: None, a Bearing, a catalogue id or a bearing TOML path -> a Bearing."""
    from bearingsim.catalog import resolve_bearing

    if bearing is None or not isinstance(bearing, str | Path):
        return bearing
    if str(bearing).lower().endswith(".toml"):
        return resolve_bearing(bearing_file=bearing)
    return resolve_bearing(str(bearing))


def _bearing_warning(path: Path, source: str, bearing) -> list[str]:
    """A warning when a text record gets a CWRU bearing by default (``bearing_source``
    ``default``/``file name``): its fault lines are read at that bearing's frequencies, and a
    record of another bearing is mislabelled (a 6203 outer-race fault read as the default
    6205: "ball"; exploratory testing, twenty-fifth session)."""
    if Path(path).suffix.lower() not in (".csv", ".txt") or source in ("option", "file"):
        return []
    bid = bearing if isinstance(bearing, str) else bearing.id
    return [
        f"bearing {bid} taken from the {source}: the fault lines are read at its frequencies; "
        "give --bearing ID|FILE.toml for a record of another bearing"
    ]


def _profile(end: str, fs: float) -> str | None:
    """The profile of a record's end and sample rate, or None."""
    for p, (bearing, pfs) in PROFILES.items():
        if _end(bearing) == end and float(pfs) == float(fs):
            return p
    return None


def evaluate(clfs: dict, data: Path, rigs: dict):
    """Label every record of ``data`` with the shipped-rig classifier and with the held-out one
    of its fault size (``clfs`` and ``rigs`` by set name), beside ``bearingsim analyze``; print
    the table and the accuracy per class; return the rows."""
    import subprocess

    from bearingsim.io.cwru import cwru_manifest
    from bearingsim.signal.cwru_benchmark import truth_of

    rows = cwru_manifest(data)
    truth = {f: truth_of(r) for f, r in rows.items()}
    files = [data / f for f in truth]
    shipped = {Path(o["file"]).name: o for o in predict(clfs["shipped"], files)}
    held = {n: {} for n in clfs if n != "shipped"}
    for n in held:
        size = n.removeprefix("without-")
        mine = [
            data / f
            for f, r in rows.items()
            if (r["fault_diameter_in"] == size or not r["fault_diameter_in"])
            and rigs[n].get(_profile(r["end"], float(r["fs_hz"]))) is not None
        ]
        held[n] = {Path(o["file"]).name: o for o in predict(clfs[n], mine)}
    out = []
    for name, r in rows.items():
        a = subprocess.run(
            [sys.executable, "-m", "bearingsim", "analyze", str(data / name), "--json",
             "--channel", r["end"]],
            capture_output=True,
            text=True,
        )  # fmt: skip
        verdict = json.loads(a.stdout).get("diagnosis", "?") if a.returncode == 0 else "error"
        if r["fault_diameter_in"]:
            o = held.get(f"without-{r['fault_diameter_in']}", {}).get(name)
            ho = (o.get("predicted") or "error") if o else "no held-out rig"
        else:  # the healthy record: every held-out classifier (no held-out rig uses it)
            got = [held[n][name].get("predicted") or "error" for n in held if name in held[n]]
            ho = " / ".join(got) if got else "no held-out rig"
        out.append(
            {
                "record": name,
                "truth": truth[name],
                "grade": r.get("smith_randall_grade", ""),
                "sim_to_real": shipped[name].get("predicted") or "error",
                "held_out": ho,
                "analyze": verdict,
            }
        )
    print(
        "| record | truth | S&R grade | sim-to-real, shipped rigs | sim-to-real, held out "
        "| analyze |\n|---|---|---|---|---|---|"
    )
    for o in out:
        print(
            f"| {o['record']} | {o['truth']} | {o['grade'] or '-'} | {o['sim_to_real']} "
            f"| {o['held_out']} | {o['analyze']} |"
        )

    def right(o, who):
        return all(v == o["truth"] for v in o[who].split(" / "))

    for who in ("sim_to_real", "held_out", "analyze"):
        judged = [o for o in out if o[who] != "no held-out rig"]
        print(f"\n{who} ({len(judged)} records judged):")
        for lab in LABELS:
            g = [o for o in judged if o["truth"] == lab]
            if g:
                print(f"  {lab}: {sum(right(o, who) for o in g)} of {len(g)}")
        print(f"  overall: {sum(right(o, who) for o in judged)} of {len(judged)}")
        y = [o for o in judged if o["grade"].startswith("Y") and o["truth"] in ("inner", "outer")]
        print(f"  Smith & Randall Y, inner/outer: {sum(right(o, who) for o in y)} of {len(y)}")
    return out


def _emit(o: dict, as_json: bool) -> None:
    """One result: a JSON line, or a text line (errors and warnings on stderr)."""
    if as_json:
        print(json.dumps(o, allow_nan=False), flush=True)
    elif "error" in o:
        print(f"{o['file']}: error: {o['error']}", file=sys.stderr, flush=True)
    else:
        p = ", ".join(f"{k} {v:.2f}" for k, v in o["probabilities"].items())
        # what the record was judged as (the JSON's keys; the text said none of it before)
        how = (
            f"{o['bearing']} ({o['bearing_source']}), channel {o['channel']}, {o['rpm']:g} r/min "
            f"({o['rpm_source']}), {o['fs_hz']:g} Hz ({o['fs_source']})"
        )
        print(f"{o['file']}: {o['predicted']} ({p}) [{how}]", flush=True)
        if "warning" in o:
            print(f"{o['file']}: warning: {o['warning']}", file=sys.stderr, flush=True)


class _Parser(argparse.ArgumentParser):
    """argparse with a one-line usage error (``sim_to_real.py: error: ...``, exit 2), as
    bearingsim's own commands print; argparse's printed the usage block first (five lines;
    exploratory testing, twenty-fifth session)."""

    def error(self, message: str):
        print(f"{self.prog}: error: {' '.join(message.split())}", file=sys.stderr)
        raise SystemExit(2)


def main() -> int:
    ap = _Parser(description=__doc__.splitlines()[0])
    ap.add_argument("--predict", nargs="+", metavar="FILE")
    ap.add_argument("--evaluate", action="store_true")
    ap.add_argument("--json", action="store_true", help="one JSON object per line")
    ap.add_argument("--data", type=Path, default=DATA)
    ap.add_argument("--cache", type=Path, default=CACHE)
    ap.add_argument("--rpm", type=float, default=None,
                    help="shaft speed [r/min] for --predict (default: the file's, else the "
                    "CWRU nominal speed of the load in its name)")  # fmt: skip
    ap.add_argument("--fs-hz", type=float, default=None,
                    help="sample rate [Hz] of --predict files (CSV/TXT without a time column; "
                    "a CWRU .mat whose name gives no 12k/48k)")  # fmt: skip
    ap.add_argument("--channel", default=None,
                    help="channel of --predict files: DE, FE or BA (.mat; default the fault's "
                    "end in the name), a column (CSV/TXT), x, y or sensor (.nc; default sensor "
                    "if present, else y)")  # fmt: skip
    ap.add_argument("--bearing", default=None, metavar="ID|FILE.toml",
                    help="bearing of every --predict file: a catalogue id or a bearing TOML "
                    "(default: the one a bearingsim result states, else the CWRU bearing of "
                    "the end in the file name: 6203-cwru for Fan_End, else 6205-cwru)")  # fmt: skip
    ap.add_argument("--path-fit", action="store_true",
                    help="an experiment: fit each rig's gains with the DEM's output as the "
                    "known input (bearingsim.side_by_side.model_path_fit) on the CWRU records "
                    "it was identified from (needs --data)")  # fmt: skip
    ap.add_argument("--slip-form", choices=["walk", "jitter"], default=SLIP_FORM,
                    help="an experiment: the slip as the cage-speed random walk (walk) or as "
                    "the balls' jitter in their pockets, the phase locked (jitter)")  # fmt: skip
    ap.add_argument("--defect-profile", choices=["geometric", "pit"], default=DEFECT_PROFILE,
                    help="an experiment: a slot across the track (geometric) or a round pit "
                    "narrower than the contact (pit, CWRU's EDM faults)")  # fmt: skip
    a = ap.parse_args()
    globals()["SLIP_FORM"] = a.slip_form
    globals()["DEFECT_PROFILE"] = a.defect_profile
    if not a.predict and not a.evaluate:
        ap.error("give --predict FILE... or --evaluate")
    if a.rpm is not None and not (math.isfinite(a.rpm) and 0.0 < a.rpm <= 1e6):
        ap.error(f"--rpm = {a.rpm:g} r/min; valid range (0, 1e6] r/min")
    if a.fs_hz is not None and not (math.isfinite(a.fs_hz) and 0.0 < a.fs_hz <= 1e8):
        ap.error(f"--fs-hz = {a.fs_hz:g} Hz; valid range (0, 1e8] Hz")
    if a.bearing is not None:
        from bearingsim.errors import BearingsimError

        try:
            _bearing_option(a.bearing)
        except BearingsimError as exc:  # before minutes of simulation, not after them
            ap.error(f"--bearing: {exc}")
    names = ["shipped", *(f"without-{s}" for s in HELD_OUT)] if a.evaluate else ["shipped"]
    try:
        sets, meta = build_datasets(
            a.cache, names, data=a.data, progress=not a.json, path_fit=a.path_fit
        )
    except (CacheLocationError, ValueError, FileNotFoundError) as exc:
        print(f"error: {' '.join(str(exc).split())}", file=sys.stderr)
        return 2
    clfs = {n: train(*sets[n]) for n in names}
    bad = 0
    if a.predict:
        kw = dict(channel=a.channel, fs_hz=a.fs_hz, bearing=a.bearing)
        for o in predict(clfs["shipped"], a.predict, a.rpm, **kw):
            bad += "error" in o
            _emit(o, a.json)
    if a.evaluate:
        evaluate(clfs, a.data, meta["rigs"])
    return 1 if bad else 0


def _run() -> int:
    """:func:`main`; a reader that closes the pipe (``| head -1``) ends it quietly."""
    try:
        return main()
    except KeyboardInterrupt:  # Ctrl-C: one line and 130, as bearingsim's commands (docs/cli.md)
        print("error: aborted", file=sys.stderr)
        return 130
    except BrokenPipeError:
        # the rest of the output has nowhere to go: point stdout at devnull so that the
        # interpreter's final flush does not raise again (Python docs, "Note on SIGPIPE")
        devnull = os.open(os.devnull, os.O_WRONLY)
        os.dup2(devnull, sys.stdout.fileno())
        return 1


if __name__ == "__main__":
    sys.exit(_run())
