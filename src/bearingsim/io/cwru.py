"""Reader of the CWRU Bearing Data Center ``.mat`` records."""

from __future__ import annotations

import os
import re
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ..errors import ConfigError

__all__ = [
    "cwru_data_dir",
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


def read_cwru_mat(path: str | Path) -> CwruRecord:
    """Read a CWRU ``.mat`` file (keys ``X###_DE_time``, ``X###_FE_time``, ``X###_BA_time``,
    ``X###RPM``)."""
    from scipy.io import loadmat

    p = Path(path)
    try:
        data = loadmat(p)
    except (OSError, ValueError, TypeError) as exc:
        raise ConfigError(f"file = {str(p)!r} is not a readable MATLAB .mat file ({exc})") from None
    channels: dict[str, np.ndarray] = {}
    numbers = set()
    for key, val in data.items():
        m = _KEY.match(key)
        if m:
            numbers.add(m.group(1))
            channels[m.group(2)] = np.asarray(val, dtype=float).ravel()
    if not channels:
        raise ConfigError(
            f"file = {str(p)!r} has no CWRU channel (expected keys X###_DE_time / X###_FE_time)"
        )
    number = sorted(numbers)[0]
    rpm = None
    for key, val in data.items():
        if re.match(r"^X\d+RPM$", key):
            rpm = float(np.asarray(val).ravel()[0])
    return CwruRecord(p, number, channels, rpm)


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
