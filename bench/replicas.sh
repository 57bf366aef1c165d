#!/usr/bin/env bash
# Simulations per second of pfem-form (crude Monte Carlo on the model limit state of
# examples/reliability/model_limit_state.json, value-only runs) against 1, 2 and 3 pfem-server
# replicas on 127.0.0.1 (--workers 1 each) behind one ipv4: target, --concurrency = replicas.
# Fresh replicas for every row (no cache hits). Prints a table; asserts nothing.
# The runs are lengthened to t_end = 0.2 s (about 25 ms each) so that the simulations, not the
# calls, dominate.
#   bench/replicas.sh [SAMPLES] [T_END]    (defaults 300, 0.2)
set -euo pipefail
cd "$(dirname "$0")/.."
samples="${1:-300}"
t_end="${2:-0.2}"
bin=build/bin
tmp="$(mktemp -d)"
pids=()
cleanup() {
  for p in "${pids[@]}"; do kill "$p" 2>/dev/null || true; done
  wait 2>/dev/null || true
  rm -rf "$tmp"
}
trap cleanup EXIT

start_replica() {  # prints HOST:PORT
  local dir="$tmp/data-$1-$2"
  mkfifo "$tmp/out-$1-$2"
  "$bin/pfem-server" --listen 127.0.0.1:0 --data-dir "$dir" --workers 1 \
    > "$tmp/out-$1-$2" 2>/dev/null &
  pids+=($!)
  local line
  read -r line < "$tmp/out-$1-$2"
  echo "${line##* }"
}

echo "pfem-form Monte Carlo, $samples samples + FORM, model_limit_state.json to t = $t_end s" \
  "($(nproc) cores, load average $(cut -d' ' -f1 /proc/loadavg) before)"
printf '%-9s %-12s %-10s %-10s %-12s\n' replicas concurrency runs seconds "runs/s"
for n in 1 2 3; do
  addresses=()
  for k in $(seq 1 "$n"); do addresses+=("$(start_replica "$n" "$k")"); done
  target="ipv4:$(IFS=,; echo "${addresses[*]}")"
  "$bin/pfem-form" examples/reliability/model_limit_state.json --out "$tmp/form-$n" \
    --monte-carlo "$samples" --t-end "$t_end" --server "$target" --concurrency "$n" \
    >/dev/null 2>&1
  /usr/bin/python3 - "$tmp/form-$n/result.json" "$n" <<'PY'
import json, sys
r = json.load(open(sys.argv[1]))
s = r["simulations"]
print(f"{sys.argv[2]:<9} {sys.argv[2]:<12} {s['runs']:<10} {r['wall_seconds']:<10.2f} "
      f"{s['runs'] / r['wall_seconds']:<12.1f}")
PY
done
