#!/usr/bin/env bash
# Compares two builds of bench_step on one benchmark, run after run.
#
#   scripts/bench_ab.sh OLD_BENCH NEW_BENCH FILTER [THREADS] [REPS]
#
# e.g. scripts/bench_ab.sh /tmp/old/bench_step build/bench/bench_step \
#        'Bed3DPaperSize/0/100' 2 6
#
# The guests we measure on change speed by up to 25% within minutes
# (docs/benchmarks.md), so timing one build and then the other compares the
# guest's states, not the builds. This runs the two alternately REPS times
# (default 5) with OMP_NUM_THREADS=THREADS (default 2) and prints, per build,
# the lowest and the median (the lower middle one for an even count) of the
# benchmark's ns_per_row_sweep counter and every run's figure, sorted.
# FILTER must select one benchmark.
set -euo pipefail

if [[ $# -lt 3 ]]; then
  sed -n '2,15p' "$0" >&2
  exit 2
fi
old=$1
new=$2
filter=$3
threads=${4:-2}
reps=${5:-5}
for bin in "$old" "$new"; do
  if [[ ! -x $bin ]]; then
    echo "bench_ab.sh: $bin is not an executable bench_step" >&2
    exit 2
  fi
done
if ! [[ $threads =~ ^[1-9][0-9]*$ && $reps =~ ^[1-9][0-9]*$ ]]; then
  echo "bench_ab.sh: THREADS and REPS must be positive integers (got '$threads', '$reps')" >&2
  exit 2
fi

# One run's ns_per_row_sweep (Google Benchmark prints 1.2k for 1200).
figure() {
  local out value
  out=$(OMP_NUM_THREADS=$threads "$1" --benchmark_filter="$filter" 2>&1)
  value=$(grep -o 'ns_per_row_sweep=[0-9.]*k\?' <<<"$out" | cut -d= -f2 || true)
  if [[ -z $value ]]; then
    echo "bench_ab.sh: no ns_per_row_sweep from $1 for '$filter'" >&2
    exit 1
  fi
  if [[ $value == *$'\n'* ]]; then
    echo "bench_ab.sh: '$filter' selects more than one benchmark of $1" >&2
    exit 1
  fi
  if [[ $value == *k ]]; then
    awk -v v="${value%k}" 'BEGIN { printf "%.1f\n", v * 1000 }'
  else
    printf '%s\n' "$value"
  fi
}

declare -a a b
for ((i = 0; i < reps; ++i)); do
  a+=("$(figure "$old")")
  b+=("$(figure "$new")")
done

summary() {
  local name=$1
  shift
  printf '%s\n' "$@" | sort -g | awk -v name="$name" '
    { v[NR] = $1; all = all " " $1 }
    END { printf "%s: lowest %.1f, median %.1f ns per row and sweep (runs:%s)\n",
                 name, v[1], v[int((NR + 1) / 2)], all }'
}
echo "$filter, $threads thread(s), $reps alternating runs each"
summary old "${a[@]}"
summary new "${b[@]}"
