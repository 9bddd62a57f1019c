#!/usr/bin/env bash
# Screenshots of two report pages as a user sees them, for docs/:
#   docs/report_valentik_combined.png  OUT/combined/report.html of the six Valentik suspensions
#   docs/report_cylinder.png           OUT/<cylinder>/report.html of a sedimentation cylinder
# Usage: scripts/screenshot_reports.sh OUT DOCS   (e.g. scripts/screenshot_reports.sh /tmp/reports docs)
# Needs headless Chromium (Debian: apt-get install -y chromium); no network is used: the pages
# are self-contained. Runs settle from this checkout (cargo build --release first if needed).
set -euo pipefail
if [ $# -ne 2 ]; then
  echo "usage: $0 OUT DOCS" >&2
  exit 2
fi
out=$1
docs=$2
root=$(cd "$(dirname "$0")/.." && pwd)
cd "$root"
cargo build --release --quiet
settle=$root/target/release/settle
browser=$(command -v chromium || command -v chromium-browser || command -v google-chrome || true)
if [ -z "$browser" ]; then
  echo "no headless Chromium found: apt-get install -y chromium" >&2
  exit 2
fi
mkdir -p "$out" "$docs"
out=$(cd "$out" && pwd)
docs=$(cd "$docs" && pwd)

"$settle" run scenarios/valentik_susp{1..6}.toml --out "$out" --quiet > "$out/valentik.log"
"$settle" run scenarios/sedimentation_sample2.toml --set sample.particles=20000 --out "$out" \
  --quiet > "$out/cylinder.log"

shot() { # PAGE PNG
  "$browser" --headless --no-sandbox --disable-gpu --hide-scrollbars --no-first-run \
    --screenshot="$2" --window-size=1280,2400 "file://$1" 2> /dev/null
  echo "$1 -> $2"
}
shot "$out/combined/report.html" "$docs/report_valentik_combined.png"
shot "$out/sedimentation_sample2/report.html" "$docs/report_cylinder.png"
