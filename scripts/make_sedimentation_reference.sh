#!/usr/bin/env bash
# Regression data of the full-physics cylinder (issue 17): samples 2 and 4 of seed 000, full
# physics, N = 10 000 representative grains, contacts on (lubrication follows) and off; each
# instrument's largest and mean error against the input curve (instrument_errors.csv). Writes data/sedimentation_reference_metrics.toml, which
# tests/validation/sedimentation_reference.rs checks. Run from the repository root after
# `cargo build --release`; rerun only with a physics change you explain in the commit message.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
cd "$root"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
n=10000
for k in 2 4; do
  for c in on off; do
    extra=(--set sample.contacts=false)
    if [ "$c" = on ]; then extra=(--set sample.contacts=true); fi
    target/release/settle run "scenarios/sedimentation_sample$k.toml" --set "sample.particles=$n" \
      "${extra[@]}" --out "$tmp/${k}_$c" -q
  done
done
python3 - "$tmp" "$n" "$(git rev-parse --short HEAD)" > data/sedimentation_reference_metrics.toml <<'PY'
import csv, sys
tmp, n, commit = sys.argv[1], sys.argv[2], sys.argv[3]
print(f"""# Reference figures of the full-physics cylinder (issue 17), written by
# scripts/make_sedimentation_reference.sh at commit {commit}:
# `settle run scenarios/sedimentation_sample{{2,4}}.toml --set sample.particles={n}`, with
# `--set sample.contacts=true` (lubrication follows) or `=false`. Per instrument, from instrument_errors.csv: the largest and mean
# |percent finer - input curve| over its readings (points) and the mean counting noise (1 sigma)
# of its readings at this N. tests/validation/sedimentation_reference.rs fails when a change
# moves a figure (or the contacts' effect, on - off) by more than 3 sigma: update these only with a
# physics change that you explain in the commit message and in docs/validation/sedimentation.md.
""")
for k in (2, 4):
    for c in ("on", "off"):
        path = f"{tmp}/{k}_{c}/sedimentation_sample{k}/instrument_errors.csv"
        for r in csv.DictReader(open(path)):
            print(f"[sample{k}.contacts_{c}.{r['instrument']}]")
            print(f"particles = {r['particles']}")
            for key in ("max_abs_error_percent", "mean_abs_error_percent", "mean_sd_percent"):
                print(f"{key} = {float(r[key]):.6f}")
            print()
PY
