"""Time-domain models and their shared integrators.

- :mod:`.integrate` — compiled fixed-step RK4 and adaptive Dormand–Prince 5(4) kernels, shared by
  every model (no Python call per step).
- :mod:`.ring` — single-bearing ring models of a local defect: VSM (seed VSM), DEM, TVSM.
- :mod:`.rotor` — the bearing–rotor–housing system of the CWRU rig (seed ROTOR).
- :mod:`.ias` — the 3-DOF instantaneous-angular-speed model of a roller bearing (seed IAS).

Model families never import each other; they may import errors, geometry, materials, catalog,
contact, load_distribution, io, signal and results. Importing this package loads no model (the
families compile their kernels on first import).
"""

__all__ = ["ias", "integrate", "ring", "rotor"]
