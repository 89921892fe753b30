"""Input and output: atomic writers, JSON conversion, signal-file readers.

Imports only :mod:`bearingsim.errors` (and NumPy/SciPy); every layer may import it.
"""

from .atomic import atomic_open, atomic_path, write_json
from .cwru import CwruRecord, cwru_data_dir, read_cwru_mat
from .jsonable import dumps_jsonable, to_jsonable

__all__ = [
    "CwruRecord",
    "atomic_open",
    "atomic_path",
    "cwru_data_dir",
    "dumps_jsonable",
    "read_cwru_mat",
    "to_jsonable",
    "write_json",
]
