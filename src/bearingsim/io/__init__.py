"""Input and output: atomic writers, JSON conversion, signal-file readers.

- :mod:`.atomic` — atomic writers (an output file is complete or absent, created with the
  umask's mode; stale temporaries of killed writers removed) and :func:`check_output`, the
  check that an output location can be written, made before any work.
- :mod:`.jsonable` — JSON conversion of NumPy values.
- :mod:`.cwru` — CWRU Bearing Data Center ``.mat`` records.
- :mod:`.text` — numeric text tables (CSV and the like).
- :mod:`.signal` — :func:`read_signal`, the one reader of signal files (CWRU ``.mat``,
  bearingsim results, text tables).

Imports only :mod:`bearingsim.errors` (and NumPy/SciPy) at import time, so every layer may import
it; :func:`read_signal` imports :mod:`bearingsim.geometry`, :mod:`bearingsim.materials` and
:mod:`bearingsim.results` when it reads a result file.
"""

from .atomic import atomic_open, atomic_path, check_output, clean_stale_temporaries, write_json
from .cwru import CwruRecord, cwru_data_dir, read_cwru_mat
from .jsonable import dumps_jsonable, to_jsonable
from .signal import CWRU_DEFAULT_FS, SignalRecord, read_signal
from .text import TextTable, read_table

__all__ = [
    "CWRU_DEFAULT_FS",
    "CwruRecord",
    "SignalRecord",
    "TextTable",
    "atomic_open",
    "atomic_path",
    "check_output",
    "clean_stale_temporaries",
    "cwru_data_dir",
    "dumps_jsonable",
    "read_cwru_mat",
    "read_signal",
    "read_table",
    "to_jsonable",
    "write_json",
]
