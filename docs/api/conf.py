"""Sphinx configuration of the bearingsim API reference (built from the docstrings).

Build: ``python -m sphinx -W --keep-going -b html docs/api docs/api/_build`` (warnings are
errors; ``tests/test_docs.py`` runs this build).
"""

from __future__ import annotations

import os
import sys

_SRC = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", "..", "src"))
if os.path.isdir(_SRC):  # a build from the repository; else bearingsim from PYTHONPATH/site
    sys.path.insert(0, _SRC)

import bearingsim  # noqa: E402

project = "bearingsim"
author = "the bearingsim developers"
copyright = "2026, the bearingsim developers"  # noqa: A001
release = bearingsim.__version__
version = release

extensions = [
    "sphinx.ext.autodoc",
    "sphinx.ext.autosummary",
    "sphinx.ext.mathjax",
    "numpydoc",
]
autosummary_generate = True
autosummary_imported_members = False
autodoc_default_options = {"members": True, "show-inheritance": True, "ignore-module-all": True}
autodoc_typehints = "none"  # numpydoc sections carry the types and units
numpydoc_show_class_members = False
numpydoc_class_members_toctree = False
numpydoc_xref_param_type = False
numpydoc_validation_checks: set[str] = set()
default_role = "py:obj"
nitpicky = False
exclude_patterns = ["_build"]
templates_path = ["_templates"]
html_theme = "alabaster"
html_title = f"bearingsim {release} API"
suppress_warnings: list[str] = []
