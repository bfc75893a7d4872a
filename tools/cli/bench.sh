#!/bin/sh
# The CLI's parallel speed-up: ratios to `--threads 1` of the same release binary in
# the same run, wall time and CPU time (user + system) side by side, runs interleaved
# (1, 2, 1, 2, ...) so that a load change on a shared machine hits both alike.
#
#   tools/cli/bench.sh                 # RUNS=3 WORST=2048x2048 LAB=4096x4096
#
# - docs/cli_worst_case.toml (256 spheres enclosing the eye: tracing-bound), shrunk to
#   WORST with --size (the per-pixel cost is the full-size file's);
# - scenes/lab.toml at LAB (encoding-bound: the serial PNG encoder is most of the CPU);
#   its serial fraction is measured from the single-thread run's own split (the
#   summary's render and PNG times) and the Amdahl bound printed beside the ratio; the
#   PNG's size is printed (the compression is the same for every thread count).
set -eu
cd "$(dirname "$0")/../.."
RUNS=${RUNS:-3}
WORST=${WORST:-2048x2048}
LAB=${LAB:-4096x4096}
THREADS=${THREADS:-2}
cargo build --release -q -p embedded-raytracer-cli
bin=target/release/ertrace
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT

# One run: prints "wall cpu" (seconds) and keeps the summary in $out/summary.
one() { # scene size threads
    /usr/bin/time -f "%e %U %S" -o "$out/time" "$bin" "$1" --size "$2" --threads "$3" \
        --quiet --output "$out/bench.png" >"$out/summary"
    awk '{ printf "%s %.2f\n", $1, $2 + $3 }' "$out/time"
}

bench() { # name scene size
    echo "== $1: $2 at $3, $RUNS runs, threads 1 and $THREADS ($(nproc) cores)"
    i=0
    while [ "$i" -lt "$RUNS" ]; do
        set -- "$1" "$2" "$3" $(one "$2" "$3" 1)
        serial_line=$(cat "$out/summary")
        size1=$(stat -c %s "$out/bench.png")
        set -- "$1" "$2" "$3" "$4" "$5" $(one "$2" "$3" "$THREADS")
        sizeN=$(stat -c %s "$out/bench.png")
        # The single-thread summary's render and PNG times: the encoder's share of the
        # work is the serial fraction s; the bound is 1 / max(s, 1/threads)... with the
        # tracing overlapping the encoder, at most 1 / max(s, (1 - s) / threads + 0).
        split=$(echo "$serial_line" | sed -E 's/.*, ([0-9.]+) ms \([0-9.]+ ns\/pixel\), PNG ([0-9.]+) ms.*/\1 \2/')
        echo "$4 $5 $6 $7 $split $size1 $sizeN" | awk -v t="$THREADS" '{
            s = $6 / ($5 + $6); p = (1 - s) / t; bound = 1 / (s > p ? s : p);
            printf "wall %6.2f s -> %6.2f s: %.2fx   cpu %6.2f s -> %6.2f s (%.2fx the CPU)   encoder share %.0f %%, bound %.2fx   PNG %d -> %d bytes\n",
                $1, $3, $1 / $3, $2, $4, $4 / $2, 100 * s, bound, $7, $8 }'
        i=$((i + 1))
    done
}

bench worst docs/cli_worst_case.toml "$WORST"
bench lab scenes/lab.toml "$LAB"
