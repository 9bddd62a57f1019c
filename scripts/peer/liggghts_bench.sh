#!/usr/bin/env bash
# settle side by side with a peer DEM code, LIGGGHTS 3.8 (issue 28; page:
# docs/validation/peer.md). A benchmark, not a test: never run by the test suite.
#
# For each N: the grains of sample 5 at t ~ 0 are taken from settle itself (a snapshot of
# scenarios/sedimentation_sample5.toml at 1 ms, x_m, y_m, diameter_m), written as a LIGGGHTS
# input by liggghts_input.py (Hertz spheres in a thin periodic-z slab of the cylinder's
# projection, walls, reduced gravity, Stokes drag by `fix viscous`), and LIGGGHTS runs M steps
# with `mpirun -np NP`; its particle-steps/s = N x M / loop time ("Loop time of X on P procs
# for M steps with N atoms": setup excluded, after a short warm-up run). Back to back, settle's
# own benchmark runs at the same N (`settle bench --quick --sedimentation-only --grains N`: the
# full 1440 min of sample 5, full physics without contacts, and ideal Stokes). Each round runs
# every N; the load average is recorded before every run. Results in OUT:
#   runs.csv     one row per run (tool, N, round, ranks, steps, wall, rate, load)
#   summary.md   medians and best per N, the ratios, the projected 1440 min wall times
#   logs/        LIGGGHTS's log of every run, settle's bench.csv, params.txt of each N
#
# Usage: scripts/peer/liggghts_bench.sh [OUT] (default out/peer)
# Environment: SETTLE (settle binary; default target/release/settle, else `settle` on PATH),
#   NS (grain counts, default "10000 100000"), ROUNDS (default 3), NP (MPI ranks, default "2";
#   several allowed, e.g. "2 1"), STEPS_BUDGET (LIGGGHTS steps = max(100, STEPS_BUDGET / N),
#   default 1e8), CLASSES (diameter classes = atom types for the drag, default 16),
#   LIGGGHTS (binary, default liggghts), MPIRUN (default mpirun), MPIRUN_ARGS (extra mpirun
#   options; default "--mca mpi_yield_when_idle 1": a rank waiting for the other yields its core,
#   which on a loaded machine doubled LIGGGHTS's rate at np 2 (not measured on an
#   idle one); MPIRUN_ARGS= for Open MPI's busy polling).
# Needs: LIGGGHTS and Open MPI (Debian: apt-get install liggghts openmpi-bin), python3.
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../.." && pwd)
out=${1:-out/peer}
ns=${NS:-10000 100000}
rounds=${ROUNDS:-3}
nps=${NP:-2}
budget=${STEPS_BUDGET:-100000000}
classes=${CLASSES:-16}
liggghts=${LIGGGHTS:-liggghts}
mpirun=${MPIRUN:-mpirun}
mpirun_args=${MPIRUN_ARGS-"--mca mpi_yield_when_idle 1"}
if [[ -z "${SETTLE:-}" ]]; then
  if [[ -x "$root/target/release/settle" ]]; then SETTLE="$root/target/release/settle"
  else SETTLE=settle; fi
fi
missing=()
command -v "$liggghts" > /dev/null || missing+=("LIGGGHTS ('$liggghts' not found; Debian: apt-get install liggghts)")
command -v "$mpirun" > /dev/null || missing+=("mpirun ('$mpirun' not found; Debian: apt-get install openmpi-bin)")
command -v "$SETTLE" > /dev/null || missing+=("settle ('$SETTLE' not found: cargo build --release, or SETTLE=path)")
command -v python3 > /dev/null || missing+=("python3")
if ((${#missing[@]})); then
  printf 'liggghts_bench.sh: missing: %s\n' "${missing[@]}" >&2
  exit 2
fi
if [[ $(id -u) == 0 ]]; then  # Open MPI refuses root without these
  export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
fi
mkdir -p "$out/logs"
out=$(cd "$out" && pwd)
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
load1() { cut -d' ' -f1 /proc/loadavg; }

{
  echo "date_utc = $(date -u +%FT%TZ)"
  echo "settle = $("$SETTLE" --version)"
  echo "liggghts = $(dpkg-query -W -f '${Version}' liggghts 2> /dev/null || echo unknown)"
  echo "mpirun = $("$mpirun" --version 2>&1 | head -1)"
  echo "nproc = $(nproc)"
  echo "cpu = $(lscpu | sed -n 's/^Model name: *//p' | head -1)"
  echo "ns = $ns; rounds = $rounds; np = $nps; mpirun_args = $mpirun_args; steps_budget = $budget; classes = $classes"
  echo "load_average_at_start = $(cut -d' ' -f1-3 /proc/loadavg)"
} > "$out/machine.txt"
cat "$out/machine.txt"

echo "tool,grains,round,ranks,steps,wall_s,grain_steps_per_s,run_grain_steps_per_s,n_times_steps_per_s,wall_1440min_s,load1_before,load1_after" > "$out/runs.csv"
for n in $ns; do
  # the grains at t ~ 0, from settle
  "$SETTLE" run "$root/scenarios/sedimentation_sample5.toml" --out "$tmp/snap_$n" -q \
    --set "sample.particles=$n" --set time.end_s=0.002 --set time.dt_s=0.001 \
    --set sample.max_step_s=0.001 --set 'sample.snapshot_times_s=[0.001]'
  snap=$(ls "$tmp/snap_$n"/sedimentation_sample5/snapshots/*.csv | head -1)
  m=$((budget / n)); ((m < 100)) && m=100
  python3 "$here/liggghts_input.py" "$snap" "$tmp/lg_$n" "$m" "$classes"
  grains=$(sed -n 's/^grains = //p' "$tmp/lg_$n/params.txt")  # N rounded by settle's classes
  cp "$tmp/lg_$n/params.txt" "$out/logs/params_$grains.txt"
  rm -rf "$tmp/snap_$n"
done

for r in $(seq 1 "$rounds"); do
  for n in $ns; do
    for np in $nps; do
      l0=$(load1)
      log="$out/logs/liggghts_${n}_np${np}_r$r.log"
      (cd "$tmp/lg_$n" && "$mpirun" $mpirun_args -np "$np" "$liggghts" -in viscous.in -log none > "$log" 2>&1) || {
        echo "LIGGGHTS failed at N = $n (log: $log)" >&2
        exit 1
      }
      l1=$(load1)
      # the last loop is the timed run (the first is the warm-up)
      read -r wall procs steps atoms < <(sed -n 's/^Loop time of \([^ ]*\) on \([0-9]*\) procs for \([0-9]*\) steps with \([0-9]*\) atoms.*/\1 \2 \3 \4/p' "$log" | tail -1)
      rate=$(python3 -c "print($atoms * $steps / $wall)")
      echo "liggghts,$atoms,$r,$procs,$steps,$wall,$rate,$rate,$rate,,$l0,$l1" >> "$out/runs.csv"
      printf 'round %s N %s: LIGGGHTS np %s, %s steps in %s s: %.3g particle-steps/s (load %s)\n' \
        "$r" "$atoms" "$procs" "$steps" "$wall" "$rate" "$l0"
    done
    l0=$(load1)
    rm -rf "$tmp/bench"
    "$SETTLE" bench --quick --sedimentation-only --grains "$n" --out "$tmp/bench" > "$out/logs/settle_${n}_r$r.log" 2>&1
    l1=$(load1)
    cp "$tmp/bench/bench/bench.csv" "$out/logs/settle_bench_${n}_r$r.csv"
    python3 - "$tmp/bench/bench/bench.csv" "$r" "$l0" "$l1" >> "$out/runs.csv" <<'PY'
import csv, sys
v = {}
for row in csv.DictReader(open(sys.argv[1])):
    v[(row["benchmark"], row["quantity"])] = row["value"]
for physics in ("full-nocontacts", "ideal-stokes"):
    b = f"sedimentation_sample5_{physics}"
    q = lambda k: v[(b, k)]  # noqa: E731
    print(f"settle-{physics},{q('grains')},{sys.argv[2]},,{q('steps')},{q('wall_time_1440min_s')},"
          f"{q('free_update_grain_steps_per_s')},{q('run_grain_steps_per_s')},"
          f"{q('all_grains_times_steps_per_s')},{q('wall_time_1440min_s')},{sys.argv[3]},{sys.argv[4]}")
PY
    tail -2 "$out/runs.csv" | awk -F, -v r="$r" '{printf "round %s N %s: %s, free update %.3g suspended grain-steps/s, run %.3g, 1440 min in %s s\n", r, $2, $1, $7, $8, $10}'
  done
done

python3 "$here/liggghts_summary.py" "$out" | tee "$out/summary.md"
