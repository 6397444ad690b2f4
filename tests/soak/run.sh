#!/bin/sh
# `make soak`: a million frames through the real depthkeyd, as fast as it
# takes them, with its memory, file descriptors and per-frame time sampled.
#
#   tests/soak/run.sh BIN BUILD     (SOAK_FRAMES, SOAK_INTERVAL, SOAK_PORT)
#
# The frames are a recorded sequence of the simulated lecture (250 frames at
# 160x120 colour, 160x124 depth; PNG stored without compression so that the
# replay's inflate does not dominate), replayed with realtime = false and
# loop = true: the daemon keys the next frame as soon as it has published
# the last. A reader (depthkey-shmcat) copies every composite meanwhile.
# Every SOAK_INTERVAL seconds one line (and a row of BUILD/soak/curve.csv):
# frames published, frames per second, the mean keying time of the interval
# (from /metrics' depthkey_keying_seconds_sum and _count), VmRSS, VmHWM and
# open fds. At the end the keying quantiles since the start (median, p99,
# p99.9, max) and the verdict:
# - the daemon never died and published SOAK_FRAMES frames;
# - open fds the same at the end as at the first sample;
# - VmRSS at the end within 1 MiB of the sample at 10 % of the frames
#   (the start-up allocations done).
set -eu
bin=$1
build=$2
frames=${SOAK_FRAMES:-1000000}
interval=${SOAK_INTERVAL:-10}
port=${SOAK_PORT:-18089}
dir=$(mkdir -p "$build/soak" && cd "$build/soak" && pwd)
name=/depthkey-soak-$$
curve=$dir/curve.csv
log=$dir/depthkeyd.log

fail() {
	echo "soak: FAIL $*" >&2
	exit 1
}

# The sequence, made once (depthkey-eval renders and records the simulator).
if [ ! -s "$dir/sequence/rgb.txt" ]; then
	cat >"$dir/sequence.toml" <<-TOML
	[daemon]
	record_compression = 0
	[colour]
	width = 160
	height = 120
	[board]
	backend = "colour"
	TOML
	rm -rf "$dir/sequence"
	"$bin/depthkey-eval" --config "$dir/sequence.toml" --sim 1 --frames 250 --save-sequence "$dir/sequence" \
		>"$dir/sequence.log" 2>&1 || { cat "$dir/sequence.log"; fail "could not record the sequence"; }
fi

cat >"$dir/depthkeyd.toml" <<TOML
[colour]
backend = "replay"
width = 160
height = 120
[depth]
backend = "replay"
[board]
backend = "colour"
[output]
composite_name = "$name.composite"
lecturer_name = "$name.lecturer"
board_lecturer_name = "$name.lecturer.board"
[preview]
listen = "127.0.0.1:$port"
[replay]
path = "$dir/sequence"
realtime = false
loop = true
TOML

"$bin/depthkeyd" --config "$dir/depthkeyd.toml" >"$log" 2>&1 &
daemon=$!
reader=
cleanup() {
	[ -n "$reader" ] && kill "$reader" 2>/dev/null
	kill "$daemon" 2>/dev/null && wait "$daemon" 2>/dev/null
	rm -f "/dev/shm$name.composite" "/dev/shm$name.lecturer" "/dev/shm$name.lecturer.board"
}
trap cleanup EXIT INT TERM

metric() { # NAME: its value in the last /metrics read
	sed -n "s/^$1 //p" "$dir/metrics" | head -n 1
}
status() { # FIELD: kB or count from /proc/PID/status
	sed -n "s/^$1:[[:space:]]*\([0-9]*\).*/\1/p" "/proc/$daemon/status"
}
sample() {
	kill -0 "$daemon" 2>/dev/null || { tail -n 20 "$log"; fail "depthkeyd died"; }
	# fds before asking /metrics: its connection's socket may outlive curl a moment.
	fds=$(ls "/proc/$daemon/fd" | wc -l)
	rss=$(status VmRSS)
	hwm=$(status VmHWM)
	curl -s --max-time 5 "http://127.0.0.1:$port/metrics" >"$dir/metrics" || fail "no /metrics on 127.0.0.1:$port"
	published=$(metric depthkey_output_frames_total)
	sum=$(metric depthkey_keying_seconds_sum)
	count=$(metric depthkey_keying_seconds_count)
}

# Wait for the first frames, then start the reader.
i=0
until curl -s --max-time 1 "http://127.0.0.1:$port/metrics" >"$dir/metrics" 2>/dev/null &&
	[ "$(metric depthkey_output_frames_total)" != "0" ]; do
	i=$((i + 1))
	[ $i -lt 100 ] || { tail -n 20 "$log"; fail "no frames after 10 s"; }
	kill -0 "$daemon" 2>/dev/null || { tail -n 20 "$log"; fail "depthkeyd died at start"; }
	sleep 0.1
done
"$bin/depthkey-shmcat" --name "$name.composite" --timeout 30 >/dev/null 2>"$dir/reader.log" &
reader=$!

echo "seconds,frames,fps,keying_ms,vmrss_kb,vmhwm_kb,fds" >"$curve"
start=$(date +%s)
sample
first_fds=$fds last_published=$published last_sum=$sum last_count=$count last_t=$start
warm_rss=
echo "soak: $frames frames through depthkeyd (pid $daemon), a sample every $interval s; curve in $curve"
while [ "$published" -lt "$frames" ]; do
	sleep "$interval"
	sample
	now=$(date +%s)
	line=$(awk -v t="$((now - start))" -v dt="$((now - last_t))" -v f="$published" -v lf="$last_published" \
		-v s="$sum" -v ls="$last_sum" -v c="$count" -v lc="$last_count" -v rss="$rss" -v hwm="$hwm" -v fds="$fds" \
		'BEGIN { n = c - lc; printf "%d,%d,%.0f,%.3f,%d,%d,%d", t, f, (dt > 0 ? (f - lf) / dt : 0), (n > 0 ? (s - ls) * 1000 / n : 0), rss, hwm, fds }')
	echo "$line" >>"$curve"
	echo "soak: $line"
	[ -z "$warm_rss" ] && [ "$published" -ge $((frames / 10)) ] && warm_rss=$rss
	kill -0 "$reader" 2>/dev/null || fail "the reader stopped: $(cat "$dir/reader.log")"
	last_published=$published last_sum=$sum last_count=$count last_t=$now
done

q() { sed -n "s/^depthkey_keying_seconds{quantile=\"$1\"} //p" "$dir/metrics" | awk '{ printf "%.2f", $1 * 1000 }'; }
max=$(metric depthkey_keying_max_seconds | awk '{ printf "%.2f", $1 * 1000 }')
echo "soak: $published frames in $(($(date +%s) - start)) s; keying median $(q 0.5) ms, p99 $(q 0.99) ms, p99.9 $(q 0.999) ms, max $max ms"
echo "soak: fds $first_fds -> $fds; VmRSS ${warm_rss:-$rss} kB at 10 % -> $rss kB at the end (VmHWM $hwm kB)"
[ "$fds" -eq "$first_fds" ] || fail "open fds grew from $first_fds to $fds"
[ "$rss" -le $((${warm_rss:-$rss} + 1024)) ] || fail "VmRSS grew by $((rss - warm_rss)) kB after 10 % of the frames"
echo "soak: PASS"
