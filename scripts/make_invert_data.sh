#!/usr/bin/env bash
# Reference data for `settle invert`'s full-physics round trip (issue 14): samples 2 and 4 run
# with full physics (Dallavalle drag, hindered settling), N = 100 000 representative grains,
#   - contacts off:  data/invert/sample{2,4}_full/           (~75 s each on 2 cores)
#   - contacts on:   data/invert/sample{2,4}_full_contacts/  (the scenario default, 3–6 min each)
# Each folder gets the run's four readings files (readings.csv, readings_d7928.csv,
# readings_pipette.csv, readings_sphere.csv), its granulometry.csv and a README.md naming the
# command, the settle commit and N.
# Usage: scripts/make_invert_data.sh [off|on|all]   (default all; `on` runs under nice -n 10)
set -euo pipefail
which=${1:-all}
root=$(cd "$(dirname "$0")/.." && pwd)
cd "$root"
cargo build --release --quiet
commit=$(git rev-parse HEAD)
n=100000
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
# A copy, so that a rebuild during the long runs does not replace the binary under them.
settle=$tmp/settle
cp "$root/target/release/settle" "$settle"

run() { # sample, suffix, extra --set arguments...
  local sample=$1 suffix=$2
  shift 2
  local dest=data/invert/sample${sample}_full${suffix}
  local nice=()
  if [ -z "$suffix" ]; then :; else nice=(nice -n 10); fi
  local args=(run "scenarios/sedimentation_sample${sample}.toml" --set "sample.particles=$n" "$@"
    --quiet --out "$tmp/$sample$suffix")
  local t0=$SECONDS
  "${nice[@]}" "$settle" "${args[@]}"
  local wall=$((SECONDS - t0))
  mkdir -p "$dest"
  local run_dir="$tmp/$sample$suffix/sedimentation_sample${sample}"
  for f in readings.csv readings_d7928.csv readings_pipette.csv readings_sphere.csv \
    granulometry.csv; do
    cp "$run_dir/$f" "$dest/$f"
  done
  cat >"$dest/README.md" <<MD
# Sample ${sample}, full physics$( [ -n "$suffix" ] && echo ", contacts on" || echo ", contacts off")

Reference data for \`settle invert\`'s full-physics round trip (issue 14), written by
\`scripts/make_invert_data.sh\`:

\`\`\`text
settle ${args[*]/#$tmp*/OUT}
\`\`\`

- settle commit: \`${commit}\`
- N = ${n} representative grains; wall time ${wall} s on this machine
- files: the run's four readings files (\`readings.csv\` D422, \`readings_d7928.csv\`,
  \`readings_pipette.csv\`, \`readings_sphere.csv\`, in the format \`settle reduce\` reads) and
  its \`granulometry.csv\` (each instrument's percent finer and the input curve)
MD
  echo "$dest: ${wall} s"
}

if [ "$which" = off ] || [ "$which" = all ]; then
  run 2 "" --set sample.contacts=false --set sample.lubrication=false
  run 4 "" --set sample.contacts=false --set sample.lubrication=false
fi
if [ "$which" = on ] || [ "$which" = all ]; then
  run 2 _contacts
  run 4 _contacts
fi
