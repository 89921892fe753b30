"""Time-domain bearing models; each file one published model, all integrated by
:mod:`bearingsim.dynamics.integrate`."""
