#!/usr/bin/env bash
# Counting noise of the virtual instruments against N (issue 17): sample K of seed 000 under
# ideal Stokes settling, where an instrument's reading differs from the same instrument on the
# exact ideal suspension (granulometry.csv `ideal_percent_finer`) only by the noise of N
# representative grains. Prints, per N and instrument, the RMS of that difference over the
# readings and seeds, and its ratio to the RMS at the first N: 1/sqrt(N) scaling means the RMS
# falls by sqrt(10) = 3.16 per decade. Usage: scripts/noise_vs_n.sh [K] [N...] (default 2,
# 10000 30000 100000 300000); needs `cargo build --release`.
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
  for seed in 1 2 3; do
    target/release/settle run "scenarios/sedimentation_sample$k.toml" --set physics=ideal-stokes \
      --set "sample.particles=$n" --set "sample.seed=$seed" --out "$tmp/${n}_$seed" -q
  done
done
python3 - "$tmp" "$k" "${ns[@]}" <<'PY'
import csv, math, sys
tmp, k, ns = sys.argv[1], sys.argv[2], sys.argv[3:]
rms = {}
for n in ns:
    for seed in (1, 2, 3):
        path = f"{tmp}/{n}_{seed}/sedimentation_sample{k}/granulometry.csv"
        for r in csv.DictReader(open(path)):
            if r["instrument"] == "input":
                continue
            d = float(r["percent_finer"]) - float(r["ideal_percent_finer"])
            rms.setdefault((n, r["instrument"]), []).append(d * d)
print("N,instrument,rms_noise_percent,ratio_to_first_N,sqrt_N_ratio")
for (n, inst), v in sorted(rms.items(), key=lambda x: (x[0][1], int(x[0][0]))):
    r = math.sqrt(sum(v) / len(v))
    r0 = math.sqrt(sum(rms[(ns[0], inst)]) / len(rms[(ns[0], inst)]))
    print(f"{n},{inst},{r:.4f},{r / r0:.4f},{math.sqrt(int(ns[0]) / int(n)):.4f}")
PY
