#!/bin/sh
# `make frame-instructions`: the instructions one pipeline frame executes,
# the stand-in for `make bench` where time means nothing (under qemu-user,
# docs/arm64.md). Counted with valgrind's callgrind on this machine's build
# (x86-64, the same source and C/SIMD path choice as the box) in
# depthkey-bench's BM_PipelineFrame at 640x480: collection only inside
# Pipeline::process and a dump after each call, so each dump is one whole
# frame (mapping, seeding, learning, SIOX, composite). The bench's first 30
# frames are learning; the figure is the median of the frames after them.
# With a fourth argument, another of the bench's pipeline frames:
# BM_PipelineFrameLecture is the simulated lecture with every artefact.
# usage: frame_instructions.sh BENCH [WIDTH HEIGHT [BENCHMARK]]
set -eu
bench=$1
width=${2:-640}
height=${3:-480}
name=${4:-BM_PipelineFrame}
process='depthkey::Pipeline::process(depthkey::ColourFrame const&, depthkey::DepthFrame const&, depthkey::PipelineOutput&)'
work=$(mktemp -d /tmp/depthkey-callgrind-XXXXXX)
trap 'rm -rf "$work"' EXIT

# One timed iteration is plenty under callgrind (a frame takes ~0.1 s there);
# the 30 warm-up frames come first.
valgrind --tool=callgrind --callgrind-out-file="$work/frame" \
	--toggle-collect="$process" --dump-after="$process" \
	"$bench" --benchmark_filter="^$name/$width/$height\$" --benchmark_min_time=0.01 \
	>"$work/bench.log" 2>"$work/valgrind.log" || {
	cat "$work/valgrind.log" "$work/bench.log" >&2
	exit 1
}
# Each dump's "summary:" line is its instruction count (Ir, the only event).
# Dumps are numbered in call order; frames 31 and on are past learning.
counts=$(for f in "$work"/frame.*; do
	n=${f##*.}
	printf '%s %s\n' "$n" "$(sed -n 's/^summary: *\([0-9]*\).*/\1/p' "$f")"
done | sort -n | awk '$1 > 30 && $2 > 0 { print $2 }' | sort -n)
frames=$(printf '%s\n' "$counts" | grep -c . || true)
if [ "$frames" -eq 0 ]; then
	echo "frame_instructions: no steady frame was dumped (see $work)" >&2
	exit 1
fi
printf '%s\n' "$counts" | awk -v w="$width" -v h="$height" -v n="$frames" -v name="$name" '
	{ v[NR] = $1 }
	END {
		median = (n % 2) ? v[(n + 1) / 2] : int((v[n / 2] + v[n / 2 + 1]) / 2)
		printf "%s %dx%d: %d instructions (median of %d steady frames, min %d, max %d; callgrind, %s)\n",
			name, w, h, median, n, v[1], v[n], "x86-64"
	}'
