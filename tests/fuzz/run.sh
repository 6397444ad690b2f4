#!/bin/sh
# Runs each libFuzzer harness for SECONDS on its seed corpus (tests/fuzz/corpus/NAME)
# plus what earlier runs found (FUZZ_DIR/corpus/NAME), and prints one line a
# harness: "fuzz: NAME: EXECS execs in S s, CRASHES crashes". A crash leaves its
# input in FUZZ_DIR/crashes/ and fails the run.
#   tests/fuzz/run.sh FUZZ_DIR SECONDS NAME...    (`make fuzz` calls it)
# With FUZZ_RUNS=N set, each harness runs N executions instead, however long
# that takes (`make fuzz FUZZ_RUNS=10000000`: the long run issue 14 asks for).
set -u
dir=$1 seconds=$2
shift 2
limit="-max_total_time=$seconds" what="in $seconds s"
if [ -n "${FUZZ_RUNS:-}" ]; then
	limit="-runs=$FUZZ_RUNS" what="(FUZZ_RUNS=$FUZZ_RUNS)"
fi
# FUZZ_JOBS harnesses at a time (default: the cores; each is one thread):
# CI's 30 s smoke run of the eight takes 2 minutes instead of 4 on 2 cores.
jobs=${FUZZ_JOBS:-$(nproc)}
results=$(mktemp -d)
trap 'rm -rf "$results"' EXIT
fuzz_one() {
	name=$1
	bin=$dir/bin/${name}_fuzz
	corpus=$dir/corpus/$name
	mkdir -p "$corpus" "$dir/crashes" "$dir/logs"
	log=$dir/logs/$name.log
	# The preview server's own threads allocate and free while an input runs,
	# so libFuzzer's per-input leak check (on any malloc/free mismatch) ran
	# after nearly every input and took a third of the time. Leaks are still
	# reported at exit (ASan's detect_leaks).
	extra=
	[ "$name" = preview_request ] && extra=-detect_leaks=0
	# -rss_limit_mb: the box has 1-2 GB; an input that needs more is a bug too.
	# malloc_context_size=5: recording 30 frames of every allocation's stack
	# was a third of the config harness's time; replay a crash's input
	# without it for the whole stacks.
	ASAN_OPTIONS=detect_leaks=1:abort_on_error=1:malloc_context_size=5 UBSAN_OPTIONS=print_stacktrace=1 \
		"$bin" "$limit" $extra -print_final_stats=1 -rss_limit_mb=1024 -timeout=10 \
		-artifact_prefix="$dir/crashes/$name-" "$corpus" "tests/fuzz/corpus/$name" >"$log" 2>&1
	rc=$?
	took=$(sed -n 's/^Done [0-9]* runs in \([0-9]*\) second.*/\1/p' "$log" | tail -n 1)
	execs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -n 1)
	crashes=$(ls "$dir/crashes" 2>/dev/null | grep -c "^$name-")
	{
		echo "fuzz: $name: ${execs:-0} execs $what${took:+, $took s}, $crashes crashes (exit $rc, log $log)"
		if [ "$rc" -ne 0 ] || [ "$crashes" -ne 0 ]; then
			grep -m 5 -E 'ERROR|runtime error|SUMMARY' "$log" | sed "s/^/fuzz: $name: /"
			: >"$results/$name.failed"
		fi
	} >"$results/$name.out"
}
running=0
for name in "$@"; do
	fuzz_one "$name" &
	running=$((running + 1))
	if [ "$running" -ge "$jobs" ]; then
		wait
		running=0
	fi
done
wait
# One line a harness, in the order asked for.
failed=0
for name in "$@"; do
	cat "$results/$name.out"
	[ -e "$results/$name.failed" ] && failed=1
done
exit "$failed"
