#!/usr/bin/env bash
# Service load benchmark: Evaluate throughput and p50/p99 latency over gRPC on 127.0.0.1
# (cached and uncached), against an in-process pfem-server. Prints one table; never fails on
# time. Extra arguments go to the benchmark, e.g.
#   bench/service_load.sh --clients 64 --calls 5000 --model examples/dam-break.json --functional front_x:max
#   bench/service_load.sh --server 10.0.0.5:50051      # an external server
set -euo pipefail
cd "$(dirname "$0")/.."
if [ ! -f build/CMakeCache.txt ]; then
  cmake -S . -B build -DCMAKE_BUILD_TYPE=Release >/dev/null
fi
cmake --build build --target pfem-bench-service -j"$(nproc)" >/dev/null
exec ./build/bin/pfem-bench-service "$@"
