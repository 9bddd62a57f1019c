#!/usr/bin/env bash
# Counting noise of the virtual instruments against N (issue 17): sample K of seed 000 under
# ideal Stokes settling, where an instrument's reading differs from the same instrument on the
# exact ideal suspension (granulometry.csv `ideal_percent_finer`) only by the noise of N
# representative grains. Prints, per N and instrument, the RMS of that difference over the
# readings and seeds, and its ratio to the RMS at the first N: 1/sqrt(N) scaling means the RMS
# falls by sqrt(10) = 3.16 per decade. Also the RMS of z = difference / sd_percent (the run's own
# counting sigma of each reading, which scales exactly as 1/sqrt(N)): it stays near 1 at every N
# if the noise is the counting noise and nothing else. The RMS of the differences is dominated by
# the 0.5 min readings of the sphere and the pipette (the fewest grains per reading), so with a
# few seeds it is itself uncertain by tens of %; rms_z is the figure to read. Usage:
# SEEDS="1 2 3 4 5" scripts/noise_vs_n.sh [K] [N...] (default seeds 1-5, K = 2,
# N = 10000 30000 100000 300000); rms_sd_percent is the RMS of the runs' own sd_percent, the
# value rms_noise_percent should scatter about; needs `cargo build --release`.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
cd "$root"
k=${1:-2}
shift || true
ns=("${@:-10000 30000 100000 300000}")
read -r -a ns <<< "${ns[*]}"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
for n in "${ns[@]}"; do
  for seed in ${SEEDS:-1 2 3 4 5}; do
    target/release/settle run "scenarios/sedimentation_sample$k.toml" --set physics=ideal-stokes \
      --set "sample.particles=$n" --set "sample.seed=$seed" --out "$tmp/${n}_$seed" -q
  done
done
SEEDS="${SEEDS:-1 2 3 4 5}" python3 - "$tmp" "$k" "${ns[@]}" <<'PY'
import csv, math, os, sys
tmp, k, ns = sys.argv[1], sys.argv[2], sys.argv[3:]
seeds = os.environ["SEEDS"].split()
rms, zs, sds = {}, {}, {}
for n in ns:
    for seed in seeds:
        path = f"{tmp}/{n}_{seed}/sedimentation_sample{k}/granulometry.csv"
        for r in csv.DictReader(open(path)):
            if r["instrument"] == "input":
                continue
            d = float(r["percent_finer"]) - float(r["ideal_percent_finer"])
            rms.setdefault((n, r["instrument"]), []).append(d * d)
            sd = float(r["sd_percent"] or 0)
            sds.setdefault((n, r["instrument"]), []).append(sd * sd)
            if sd > 0:
                zs.setdefault((n, r["instrument"]), []).append((d / sd) ** 2)
print("N,instrument,rms_noise_percent,rms_sd_percent,ratio_to_first_N,sqrt_N_ratio,rms_z,readings")
for (n, inst), v in sorted(rms.items(), key=lambda x: (x[0][1], int(x[0][0]))):
    r = math.sqrt(sum(v) / len(v))
    r0 = math.sqrt(sum(rms[(ns[0], inst)]) / len(rms[(ns[0], inst)]))
    z = zs.get((n, inst), [])
    rz = math.sqrt(sum(z) / len(z)) if z else float("nan")
    sd = math.sqrt(sum(sds[(n, inst)]) / len(sds[(n, inst)]))
    print(f"{n},{inst},{r:.4f},{sd:.4f},{r / r0:.4f},{math.sqrt(int(ns[0]) / int(n)):.4f},{rz:.3f},{len(z)}")
PY
