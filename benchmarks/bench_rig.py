"""Benchmark of the measurement chain (issue 16, item 3).

Prints the wall time of a VSM simulation of 1 s at 12 kHz (outer-race fault, 1.5 % random
slip), of passing it through a rig (three modes, a background table, three shaft-order tones,
sensor noise), and of both together (warm, one core), with the boxcar sampling and with the
anti-aliasing filter a rig turns on; the same as a scenario's ``rig`` key runs it (with the
realistic defaults a rig brings: slip, geometric drop, rough contacts); then the same
(anti-aliased) through the rig with every machine fact the sim-to-real example draws (DEM,
10 um preload, 2 um ball spread, 20 N unbalance), and those with rough contacts (0.1 um, the
rough load law) and then a 250 N axial load (docs/models.md "Axial load"); and the rotor model
(outer-race fault, 1.5 % slip, 9 disks, anti-aliased) through the rig, with its balls as masses
(the seed's) and quasi-static (`ball_inertia = false`). Issue 16's target: a
1 s simulation at 12 kHz with slip and rig <= 0.2 s warm on one core.

Run:  PYTHONPATH=src python benchmarks/bench_rig.py [--repeats 5]

Prints plain text; writes nothing.
"""

from __future__ import annotations

import argparse
import os

os.environ.setdefault("NUMBA_NUM_THREADS", "1")
os.environ.setdefault("OMP_NUM_THREADS", "1")
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

from _timing import best  # noqa: E402

from bearingsim import simulate  # noqa: E402
from bearingsim.rig import Background, Mode, Rig, Tone, apply_rig  # noqa: E402

#: a chain with the parts a profile has (values for timing only, not identified from data)
RIG = Rig(
    name="bench",
    description="timing only",
    provenance="benchmarks/bench_rig.py: timing values, not a machine",
    modes=(
        Mode(3350.0, 0.05, 4.0, "timing"),
        Mode(1200.0, 0.08, 1.5, "timing"),
        Mode(5200.0, 0.04, 2.0, "timing"),
    ),
    background=Background((20.0, 500.0, 6000.0), (1e-4, 1e-5, 1e-6), "timing"),
    tones=tuple(Tone(0.05 / k, "timing", order=float(k)) for k in (1, 2, 3)),
    noise_rms_m_per_s2=0.01,
    noise_provenance="timing",
)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeats", type=int, default=5)
    a = ap.parse_args()
    sc = dict(model="vsm", duration_s=1.0, fs_hz=12000.0, fault="outer", slip_percent=1.5)
    res = simulate(sc)
    t_sim = best(lambda: simulate(sc), a.repeats)
    t_rig = best(lambda: apply_rig(res, RIG), a.repeats)
    t_all = best(lambda: apply_rig(simulate(sc), RIG), a.repeats)
    # a scenario with a rig samples through the anti-aliasing filter by default (4x internal
    # rate, dynamics.sampling); the seed comparisons' boxcar sampling above is the plain default
    sc["antialias"] = True
    simulate(sc)
    t_aa = best(lambda: apply_rig(simulate(sc), RIG), a.repeats)
    print(f"bench_rig: best of {a.repeats}, one core, load average {os.getloadavg()[0]:.2f}")
    print(f"   VSM outer, 1.5 % slip, 1 s at 12 kHz  {t_sim:.4f} s")
    print(f"   rig (3 modes, background, 3 tones, noise) {t_rig:.4f} s")
    print(f"   both                            {t_all:.4f} s  (target <= 0.2 s)")
    print(f"   both, anti-aliased (the default with a rig) {t_aa:.4f} s  (target <= 0.2 s)")
    # what `simulate --rig cwru-de-12k` runs: the rig key's defaults (anti-aliased, 1.5 % slip,
    # geometric drop, 0.1 um rough contacts; bearingsim.config.REALISM) and the shipped profile
    keyed = dict(model="vsm", duration_s=1.0, fs_hz=12000.0, fault="outer", rig="cwru-de-12k")
    simulate(keyed)
    t_key = best(lambda: simulate(keyed), a.repeats)
    print(f"   VSM, rig = cwru-de-12k (its realistic defaults) {t_key:.4f} s  (target <= 0.2 s)")
    pit = dict(keyed, defect_profile="pit")  # CWRU's round pit instead of the slot
    simulate(pit)
    t_pit = best(lambda: simulate(pit), a.repeats)
    print(f"   the same with a round pit (defect_profile = pit) {t_pit:.4f} s  (target <= 0.2 s)")
    facts = dict(sc, model="dem", clearance_m=-10e-6, ball_diameter_spread_m=2e-6)
    facts["unbalance_n"] = 20.0
    simulate(facts)
    t_facts = best(lambda: apply_rig(simulate(facts), RIG), a.repeats)
    print(f"   DEM, preload, ball spread, unbalance, slip + rig {t_facts:.4f} s  (target <= 0.2 s)")
    facts["contact_roughness_m"] = 1e-7
    simulate(facts)
    t_rough = best(lambda: apply_rig(simulate(facts), RIG), a.repeats)
    print(f"   the same with rough contacts (0.1 um) {t_rough:.4f} s  (target <= 0.2 s)")
    facts["axial_load_n"] = 250.0  # the sim-to-real's heaviest spring preload on the 6205
    simulate(facts)
    t_axial = best(lambda: apply_rig(simulate(facts), RIG), a.repeats)
    print(f"   the same with a 250 N axial load      {t_axial:.4f} s  (target <= 0.2 s)")
    rot = dict(model="rotor", duration_s=1.0, fs_hz=12000.0, de_fault="outer", slip_percent=1.5)
    simulate(rot)
    t_rot = best(lambda: apply_rig(simulate(rot), RIG), a.repeats)
    print(f"   rotor (9 disks) outer, 1.5 % slip + rig {t_rot:.4f} s  (target <= 0.2 s)")
    rot["ball_inertia"] = False
    simulate(rot)
    t_qs = best(lambda: apply_rig(simulate(rot), RIG), a.repeats)
    print(f"   the same with quasi-static balls  {t_qs:.4f} s  (target <= 0.2 s)")


if __name__ == "__main__":
    main()
