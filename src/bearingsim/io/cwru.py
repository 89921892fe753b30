"""Reader of the CWRU Bearing Data Center ``.mat`` records."""

from __future__ import annotations

import os
import re
import warnings
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ..errors import ConfigError, exception_text
from ._mat5 import mat5_problem

__all__ = [
    "CWRU_NOMINAL_RPM",
    "CWRU_RATES",
    "check_cwru_name_rate",
    "cwru_bearing",
    "cwru_end",
    "cwru_rate_evidence",
    "infer_cwru_fs",
    "cwru_data_dir",
    "cwru_manifest",
    "cwru_nominal_rpm",
    "cwru_record_number",
    "CwruRecord",
    "read_cwru_mat",
    "SHARED_ENV",
]


@dataclass(frozen=True)
class CwruRecord:
    """One CWRU Bearing Data Center record.

    Attributes
    ----------
    path : Path
        Source file.
    number : str
        Record number (e.g. ``"097"``).
    channels : dict[str, ndarray]
        Acceleration per channel (``"DE"``, ``"FE"``, ``"BA"``) [g] as stored by CWRU.
    rpm : float or None
        Shaft speed stored in the file (``X###RPM``) [r/min].
    """

    path: Path
    number: str
    channels: dict[str, np.ndarray]
    rpm: float | None

    def acceleration(self, channel: str = "DE") -> np.ndarray:
        """Acceleration of ``channel`` in [m/s^2] (CWRU stores g; ``scipy.constants.g`` =
        9.80665 m/s^2, the standard acceleration of gravity)."""
        from scipy.constants import g

        ch = channel.upper()
        if ch not in self.channels:
            raise ConfigError(
                f"channel = {channel!r} not in {self.path.name}; valid: {', '.join(self.channels)}"
            )
        return self.channels[ch] * g


_KEY = re.compile(r"^X(\d+)_(DE|FE|BA)_time$")

#: CWRU nominal motor speed [r/min] at each motor load [hp] (CWRU Bearing Data Center,
#: drive-end and fan-end data pages; ../shared/data/cwru/manifest.csv, column nominal_rpm)
CWRU_NOMINAL_RPM = {0: 1797.0, 1: 1772.0, 2: 1750.0, 3: 1730.0}
#: the CWRU file-name convention ``..._<load hp>_<record number>.<ext>`` (``normal_0_97.mat``,
#: ``12k_Drive_End_IR014_2_171.mat``)
_CWRU_NAME = re.compile(r"(?:^|_)([0-3])_\d+$")


def cwru_manifest(data_dir: str | Path) -> dict[str, dict[str, str]]:
    """The rows of a CWRU folder's ``manifest.csv`` by file name, in the file's order.

    Parameters
    ----------
    data_dir : str or Path
        The folder (``../shared/data/cwru``).
    """
    import csv

    with open(Path(data_dir) / "manifest.csv", encoding="utf-8", newline="") as fh:
        return {row["file"]: row for row in csv.DictReader(fh)}


def cwru_record_number(name: str | Path) -> str:
    """The CWRU record number a file name ends in (``12k_Drive_End_IR014_2_171.mat`` → ``"171"``,
    ``132.mat`` → ``"132"``): the stem's last ``_``-separated part.

    Parameters
    ----------
    name : str or Path
        File name or path.
    """
    return Path(name).stem.rsplit("_", 1)[-1]


def cwru_end(name: str | Path) -> str:
    """The end whose bearing a CWRU record's fault is in, from its file name: ``"FE"`` when the
    name says ``Fan_End`` (any case; the fan-end records, whose FE accelerometer faces the
    faulty 6203), else ``"DE"``.

    Parameters
    ----------
    name : str or Path
        File name or path.
    """
    return "FE" if "fan_end" in Path(name).name.lower() else "DE"


def cwru_bearing(end: str) -> str:
    """Catalogue id of the CWRU bearing at ``end`` (``"DE"``: the drive end's 6205, ``"FE"``:
    the fan end's 6203; the CWRU Bearing Data Center's bearing table)."""
    return "6203-cwru" if end == "FE" else "6205-cwru"


def cwru_nominal_rpm(name: str | Path) -> tuple[int, float] | None:
    """``(load [hp], nominal speed [r/min])`` that a CWRU file name (``..._<load>_<number>.mat``,
    load 0-3 hp) gives, or None when the name does not follow that convention.

    Parameters
    ----------
    name : str or Path
        File name or path.
    """
    m = _CWRU_NAME.search(Path(name).stem)
    if m is None:
        return None
    load = int(m.group(1))
    return load, CWRU_NOMINAL_RPM[load]


#: the sample rates of the CWRU records [Hz] (CWRU Bearing Data Center: 12 kHz and 48 kHz)
CWRU_RATES = (12000.0, 48000.0)
#: a line counts in :func:`infer_cwru_fs` when it stands this far over its neighbourhood [dB]
_RATE_SNR_DB = 15.0
#: the positions (in shaft orders, read on the 12 kHz axis) that are shaft harmonics 1-11 when
#: the record was sampled at 48 kHz and none when it was sampled at 12 kHz
_QUARTERS = tuple(j / 4 for j in (1, 2, 3, 5, 6, 7, 9, 10, 11))


def _lines_over_floor(X: np.ndarray, df: float, freqs: list[float]) -> int:
    """How many of ``freqs`` [Hz] carry a line :data:`_RATE_SNR_DB` over the median of the
    amplitude spectrum ``X`` (bin ``df`` [Hz]) within ±5 % around them (window ±0.5 %)."""
    n = 0
    for f0 in freqs:
        tol = max(0.005 * f0, 2.0 * df)
        i0, i1 = int((f0 - tol) / df), int((f0 + tol) / df) + 1
        j0, j1 = max(int((0.95 * f0 - 5 * tol) / df), 1), int((1.05 * f0 + 5 * tol) / df) + 1
        if i1 >= X.size or j1 >= X.size or i0 < 1:
            continue
        floor = np.median(np.concatenate((X[j0:i0], X[i1:j1])))
        if floor > 0 and 20 * np.log10(X[i0:i1].max() / floor) >= _RATE_SNR_DB:
            n += 1
    return n


def cwru_rate_evidence(x: np.ndarray, rpm: float) -> tuple[int, int, str]:
    """How many of the 6 whole shaft orders and of the 9 quarter orders (:data:`_QUARTERS`)
    carry a line when ``x`` is read at 12 kHz with the shaft speed ``rpm`` [r/min], and the
    sentence that says so (:func:`infer_cwru_fs`)."""
    xa = np.asarray(x, dtype=float)
    n = xa.size
    n_fft = 1 << int(np.ceil(np.log2(2 * n)))
    X = np.abs(np.fft.rfft((xa - xa.mean()) * np.hanning(n), n_fft))
    df = CWRU_RATES[0] / n_fft
    fr = rpm / 60.0
    whole = _lines_over_floor(X, df, [k * fr for k in range(1, 7)])
    quarter = _lines_over_floor(X, df, [q * fr for q in _QUARTERS])
    why = (
        f"shaft lines at {whole} of the 6 whole orders and {quarter} of the 9 quarter orders "
        "on the 12 kHz axis"
    )
    return whole, quarter, why


def check_cwru_name_rate(x: np.ndarray, fs: float, rpm: float) -> tuple[float, str | None]:
    """The rate a CWRU file name gives (``fs`` [Hz]), checked against the record's own shaft
    lines (``rpm`` [r/min]): ``(fs, None)`` when they do not contradict it, else the rate the
    lines give and the sentence that says why.

    The name is kept unless the lines leave no doubt, i.e. unless they fall where no record of
    the named rate puts them. On the shared CWRU records (96 signals) the 12 kHz ones show 0-3
    of the nine quarter-order lines and the 48 kHz ones 8-9 (:func:`infer_cwru_fs`); so a name
    that says 12k is overruled by 8 or more (with a shaft to read, >= 3 whole-order lines), and
    one that says 48k by 3 or fewer. A file whose name and samples disagree is a file mislabelled
    somewhere on its way (the CWRU set holds records longer than its own table lists)."""
    whole, quarter, why = cwru_rate_evidence(x, rpm)
    if whole < 3:
        return fs, None
    if fs == CWRU_RATES[0] and quarter >= 8:
        return float(CWRU_RATES[1]), f"{why}; the file name says 12k"
    if fs == CWRU_RATES[1] and quarter <= 3:
        return float(CWRU_RATES[0]), f"{why}; the file name says 48k"
    return fs, None


def infer_cwru_fs(x: np.ndarray, rpm: float) -> tuple[float, str]:
    """The sample rate of a CWRU record whose name does not say it (the CWRU site's own names,
    ``105.mat``), from its shaft lines.

    The rates are 12 or 48 kHz (:data:`CWRU_RATES`), a factor 4 apart. Read on the 12 kHz
    axis, the shaft harmonics of a 12 kHz record lie at whole orders of the stored speed; those
    of a 48 kHz record lie at every quarter order (its harmonic ``j`` at order ``j/4``). So the
    nine positions ``j/4`` (``j`` = 1-11, not a multiple of 4) decide, split at the middle:
    at most 4 carrying a line (another source may put one there) → 12 kHz, 5 or more → 48 kHz;
    and the whole orders 1-6 must show at least 3 lines (a shaft to read), else it is not
    decided. On the shared CWRU records (every channel, 96 signals): the 12 kHz ones show 0-3
    of the nine, the 48 kHz ones 8-9; record 174 (1.3 s, no shaft line) is not decided.

    Parameters
    ----------
    x : ndarray
        The record's samples.
    rpm : float
        Its stored shaft speed [r/min].

    Returns
    -------
    fs : float
        12000 or 48000 [Hz].
    why : str
        The counts that decided, for the output.

    Raises
    ------
    ConfigError
        Not decided (fewer than 3 shaft lines at whole orders): pass ``fs_hz``.
    """
    whole, quarter, why = cwru_rate_evidence(x, rpm)
    if whole >= 3:  # a shaft to read: the quarter orders split the nine at the middle
        return (CWRU_RATES[0] if quarter <= 4 else CWRU_RATES[1]), why
    raise ConfigError(
        f"fs_hz: the sample rate of this CWRU record cannot be told from its shaft lines "
        f"({why}); pass --fs-hz (CWRU: 12000 or 48000)"
    )


def read_cwru_mat(path: str | Path) -> CwruRecord:
    """Read a CWRU ``.mat`` file (keys ``X###_DE_time``, ``X###_FE_time``, ``X###_BA_time``,
    ``X###RPM``).

    A file that is not a readable MATLAB file (empty, truncated, damaged, MATLAB v7.3/HDF5,
    another format), has no CWRU channel, or holds a channel or speed that is not a finite
    number raises a one-line :class:`ConfigError` naming the file and what is wrong.
    """
    from scipy.io import loadmat

    p = Path(path)
    try:
        with open(p, "rb") as fh:
            size = os.fstat(fh.fileno()).st_size
            problem = mat5_problem(fh, size)
    except OSError as exc:
        raise ConfigError(f"file = {str(p)!r} cannot be read ({exc.strerror})") from None
    if size == 0:
        raise ConfigError(f"file = {str(p)!r} is empty (0 bytes); valid: a MATLAB .mat file")
    if problem:  # SciPy's reader would crash on it (io._mat5)
        raise ConfigError(f"file = {str(p)!r} is not a readable MATLAB .mat file ({problem})")
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("error")  # a damaged file's "unreadable variable" warning
            data = loadmat(p)
    except Exception as exc:  # noqa: BLE001 - SciPy's reader raises many types on a damaged
        # file (MatReadError, ValueError, zlib.error, IndexError, NotImplementedError for v7.3)
        raise ConfigError(
            f"file = {str(p)!r} is not a readable MATLAB .mat file ({exception_text(exc)})"
        ) from None
    groups: dict[str, dict[str, str]] = {}  # record number -> channel -> key
    speeds: dict[str, str] = {}  # record number -> key of its X###RPM
    for key in data:
        m = _KEY.match(key)
        if m:
            groups.setdefault(m.group(1), {})[m.group(2)] = key
        elif (r := re.match(r"^X(\d+)RPM$", key)) is not None:
            speeds[r.group(1)] = key
    if not groups:
        raise ConfigError(
            f"file = {str(p)!r} has no CWRU channel (expected keys X###_DE_time / X###_FE_time)"
        )
    number = _record_of(groups, p)
    channels = {ch: _finite(p, key, data[key]) for ch, key in groups[number].items()}
    rpm = None
    key = speeds.get(number) or (next(iter(speeds.values())) if len(speeds) == 1 else None)
    if key is not None:
        v = _finite(p, key, data[key])
        if not v.size:
            raise ConfigError(f"file = {str(p)!r}: {key} is empty; valid: a speed [r/min]")
        rpm = float(v[0])
    return CwruRecord(p, number, channels, rpm)


def _record_of(groups: dict[str, dict[str, str]], p: Path) -> str:
    """The record whose variables a file holding several records' (``X098_DE_time`` beside
    ``X099_DE_time``) is read for: the one its name ends in (``cwru_record_number``, a
    leading ``X`` and zeros ignored), else the one with the most channels, the lowest number
    on a tie. Channels of two records are never mixed."""
    want = cwru_record_number(p.name).lstrip("Xx").lstrip("0")  # "X118.mat" names 118 too
    for number in groups:
        if number.lstrip("0") == want:
            return number
    return sorted(groups, key=lambda n: (-len(groups[n]), n))[0]


def _finite(p: Path, key: str, val: object) -> np.ndarray:
    """``val`` as a flat float array; a non-numeric, complex, non-finite one or one of several
    columns (a CWRU variable is one column or one row) is a one-line error."""
    raw = np.asarray(val)
    if np.iscomplexobj(raw):
        raise ConfigError(
            f"file = {str(p)!r}: {key} is complex; valid: real samples (a CWRU record)"
        )
    if raw.ndim > 2 or (raw.ndim == 2 and min(raw.shape) > 1):
        shape = " x ".join(str(n) for n in raw.shape)
        raise ConfigError(
            f"file = {str(p)!r}: {key} is a {shape} array; valid: one column (or row) of "
            "samples, as in a CWRU record"
        )
    try:
        a = np.asarray(raw, dtype=float).ravel()
    except (TypeError, ValueError):
        raise ConfigError(
            f"file = {str(p)!r}: {key} is not numeric; valid: a CWRU record"
        ) from None
    if not np.all(np.isfinite(a)):
        raise ConfigError(
            f"file = {str(p)!r}: {key} holds {int(np.count_nonzero(~np.isfinite(a)))} values that "
            "are not finite; valid: finite samples"
        )
    return a


#: environment variable naming the ``shared/`` folder that holds ``data/cwru``
SHARED_ENV = "BEARINGSIM_SHARED"


def cwru_data_dir(near: str | Path | None = None) -> Path:
    """The folder of the measured CWRU records, ``<shared>/data/cwru`` (it may not exist).

    ``<shared>`` is ``$BEARINGSIM_SHARED`` when that variable is set (it overrides the search,
    even when it names a missing folder); otherwise the first ``shared`` folder holding
    ``data/cwru`` beside ``near`` (default: this package) or one of its parent folders, as in
    a clone with ``shared/`` beside it. Without either it is ``shared/data/cwru`` in the
    working directory.

    Parameters
    ----------
    near : path, optional
        File or folder to search upwards from.
    """
    env = os.environ.get(SHARED_ENV)
    if env:
        return Path(env) / "data" / "cwru"
    start = Path(near if near is not None else __file__).resolve()
    for parent in start.parents:
        d = parent / "shared" / "data" / "cwru"
        if d.is_dir():
            return d
    return Path("shared") / "data" / "cwru"
