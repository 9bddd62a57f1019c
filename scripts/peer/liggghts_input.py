#!/usr/bin/env python3
"""LIGGGHTS input for the peer benchmark (issue 28): settle's grains of sample 5 at t = 0.

Reads a settle snapshot CSV (x_m, y_m, diameter_m: positions in the 2D projection of the
cylinder, B = 0.0635 m wide, H = 0.457 m high) and writes into OUT_DIR:
  grains.data  LIGGGHTS data file (atom_style granular: id type diameter density x y z)
  viscous.in   the input script: the grains as Hertz spheres in a thin periodic-z slab of the
               cylinder's projection, walls at x = 0, x = B and y = 0, reduced gravity
               g (1 - rho_f / rho_s) for buoyancy, Stokes drag F = -gamma v with
               gamma = 3 pi mu d per diameter class (fix viscous ... scale, one atom type per
               class), nve/sphere; a short warm-up run, then the timed run of M steps.
  params.txt   the time step and what it is made of (key = value, SI units)

Time step: the explicit drag of the smallest grain is stable only for dt < 2 tau_min with
tau_min = rho_s d_min^2 / (18 mu) (Velocity Verlet on dv/dt = -v / tau); dt = tau_min / 5.
The Young's modulus is softened until 0.2 x the Rayleigh time of the smallest grain
(T_R = pi R sqrt(rho_s / G) / (0.1631 nu + 0.8766)) is no shorter than that dt, so that
contacts do not set the step: the most favourable step for LIGGGHTS that is still stable for
the drag. That E (~1.5e5 Pa) is below LIGGGHTS's floor for SI units (5e6 Pa), hence
`soft_particles yes`; params.txt also gives the step at that floor and at quartz (7e10 Pa),
0.2 T_R each, for the projections (the cost of one step does not depend on E).

Usage: liggghts_input.py SNAPSHOT_CSV OUT_DIR STEPS [CLASSES]
"""
import csv
import math
import os
import sys

WIDTH_M = 0.0635  # B, the cylinder's projection (scenarios/sedimentation_sample5.toml)
HEIGHT_M = 0.457  # H
RHO_S_KG_M3 = 2500.0  # sample.density_kg_m3
RHO_F_KG_M3 = 1000.0  # fluid.density_kg_m3
MU_PA_S = 0.001  # fluid.viscosity_pa_s
G_M_S2 = 9.81
POISSON = 0.3
RESTITUTION = 0.5
FRICTION = 0.5


def main():
    if len(sys.argv) not in (4, 5):
        sys.exit(__doc__)
    snapshot, out_dir, steps = sys.argv[1], sys.argv[2], int(sys.argv[3])
    classes = int(sys.argv[4]) if len(sys.argv) == 5 else 16
    with open(snapshot, newline="") as f:
        rows = [(float(r["x_m"]), float(r["y_m"]), float(r["diameter_m"])) for r in csv.DictReader(f)]
    if not rows:
        sys.exit(f"{snapshot}: no grains")
    d_min = min(r[2] for r in rows)
    d_max = max(r[2] for r in rows)
    # diameter classes, equal in log d; gamma of a class from its geometric mid diameter
    span = math.log(d_max / d_min) or 1.0

    def cls(d):
        return min(classes - 1, int(classes * math.log(d / d_min) / span))

    mids = [d_min * math.exp(span * (k + 0.5) / classes) for k in range(classes)]
    gammas = [3.0 * math.pi * MU_PA_S * d for d in mids]  # Stokes drag, N s/m
    tau_min = RHO_S_KG_M3 * d_min**2 / (18.0 * MU_PA_S)
    dt = tau_min / 5.0
    # softened E: 0.2 T_R(d_min) >= dt
    r_min = d_min / 2.0
    shear = RHO_S_KG_M3 * (math.pi * r_min / (5.0 * dt * (0.1631 * POISSON + 0.8766))) ** 2
    young = 2.0 * (1.0 + POISSON) * shear
    t_rayleigh = math.pi * r_min * math.sqrt(RHO_S_KG_M3 / shear) / (0.1631 * POISSON + 0.8766)

    def dt_at(e):  # 0.2 T_R of the smallest grain at Young's modulus e
        g = e / (2.0 * (1.0 + POISSON))
        return 0.2 * math.pi * r_min * math.sqrt(RHO_S_KG_M3 / g) / (0.1631 * POISSON + 0.8766)

    g_reduced = G_M_S2 * (1.0 - RHO_F_KG_M3 / RHO_S_KG_M3)
    skin = 0.5 * d_max
    cutoff = d_max + skin
    thick = 4.0 * cutoff  # periodic z: no grain meets its own image
    z_mid = 0.5 * thick
    # bins of about the mean spacing of the grains (the default, half the cutoff, would make
    # ~1e8 bins for this dilute box)
    spacing = math.sqrt(WIDTH_M * HEIGHT_M / len(rows))
    binsize = max(cutoff, spacing)

    os.makedirs(out_dir, exist_ok=True)
    with open(os.path.join(out_dir, "grains.data"), "w") as f:
        f.write(f"settle sample 5 grains at t = 0 ({len(rows)})\n\n")
        f.write(f"{len(rows)} atoms\n{classes} atom types\n\n")
        f.write(f"0 {WIDTH_M!r} xlo xhi\n0 {HEIGHT_M!r} ylo yhi\n0 {thick!r} zlo zhi\n\n")
        f.write("Atoms\n\n")
        for i, (x, y, d) in enumerate(rows, 1):
            x = min(max(x, 0.5 * d), WIDTH_M - 0.5 * d)
            y = min(max(y, 0.5 * d), HEIGHT_M - 0.5 * d)
            f.write(f"{i} {cls(d) + 1} {d!r} {RHO_S_KG_M3} {x!r} {y!r} {z_mid!r}\n")

    n = classes
    per_type = lambda v: " ".join([repr(v)] * n)  # noqa: E731
    per_pair = lambda v: " ".join([repr(v)] * (n * n))  # noqa: E731
    scales = "".join(f" scale {k + 1} {g / gammas[0]!r}" for k, g in enumerate(gammas))
    warm = min(100, max(10, steps // 20))
    script = f"""# settle peer benchmark (issue 28): written by scripts/peer/liggghts_input.py
atom_style granular
atom_modify map array
boundary f f p
newton off
soft_particles yes
communicate single vel yes
units si
processors 1 * 1
read_data grains.data
neighbor {skin!r} bin
neigh_modify delay 0 binsize {binsize!r}
fix m1 all property/global youngsModulus peratomtype {per_type(young)}
fix m2 all property/global poissonsRatio peratomtype {per_type(POISSON)}
fix m3 all property/global coefficientRestitution peratomtypepair {n} {per_pair(RESTITUTION)}
fix m4 all property/global coefficientFriction peratomtypepair {n} {per_pair(FRICTION)}
pair_style gran model hertz tangential history
pair_coeff * *
timestep {dt!r}
fix wx0 all wall/gran model hertz tangential history primitive type 1 xplane 0.0
fix wx1 all wall/gran model hertz tangential history primitive type 1 xplane {WIDTH_M!r}
fix wy0 all wall/gran model hertz tangential history primitive type 1 yplane 0.0
fix grav all gravity {g_reduced!r} vector 0.0 -1.0 0.0
fix drag all viscous {gammas[0]!r}{scales}
fix integr all nve/sphere
thermo_style custom step atoms ke
thermo {max(1, steps // 5)}
thermo_modify lost ignore norm no
run {warm}
run {steps}
"""
    with open(os.path.join(out_dir, "viscous.in"), "w") as f:
        f.write(script)
    with open(os.path.join(out_dir, "params.txt"), "w") as f:
        for k, v in [
            ("grains", len(rows)),
            ("steps", steps),
            ("warmup_steps", warm),
            ("diameter_classes", classes),
            ("d_min_m", d_min),
            ("d_max_m", d_max),
            ("tau_stokes_min_s", tau_min),
            ("dt_s", dt),
            ("young_modulus_pa", young),
            ("rayleigh_time_min_s", t_rayleigh),
            ("dt_at_e_5e6_pa_s", dt_at(5e6)),
            ("dt_at_quartz_e_7e10_pa_s", dt_at(7e10)),
            ("g_reduced_m_s2", g_reduced),
            ("skin_m", skin),
            ("binsize_m", binsize),
            ("slab_thickness_m", thick),
        ]:
            f.write(f"{k} = {v}\n")


if __name__ == "__main__":
    main()
