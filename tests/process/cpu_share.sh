#!/bin/sh
# A share of one CPU core for a process: a Pi-class box on a fast machine
# (issue 29). Makes a cgroup with a CPU quota (cgroup v1 cpu.cfs_quota_us,
# else cgroup v2 cpu.max) and moves processes into it.
#
#   sh cpu_share.sh create NAME PERCENT   prints the cgroup's folder
#   sh cpu_share.sh add DIR PID           moves PID (all its threads) in
#   sh cpu_share.sh release DIR PID PREFIX...  moves PID's threads named
#                                         PREFIX* out, to DIR's parent; prints
#                                         "TID NAME" for each thread it moved
#   sh cpu_share.sh remove DIR            moves what is left out, removes it
#   sh cpu_share.sh run PERCENT COMMAND...  runs COMMAND in a fresh share
#
# Exit status 77 with the reason on stderr when neither hierarchy is
# writable here (a test reports itself skipped with that reason).
set -eu

period=100000 # us: the kernel's default CFS period

fail() {
	echo "cpu_share.sh: $*" >&2
	exit 1
}

unavailable() {
	echo "cpu_share.sh: $*" >&2
	exit 77
}

create() {
	name=$1
	percent=$2
	case $percent in '' | *[!0-9]*) fail "PERCENT must be a whole number, not '$percent'" ;; esac
	[ "$percent" -ge 1 ] || fail "PERCENT must be at least 1"
	quota=$((period * percent / 100))
	v1=/sys/fs/cgroup/cpu
	if [ -w "$v1/cpu.cfs_quota_us" ] || [ -w "$v1" ]; then
		dir=$v1/$name
		mkdir -p "$dir" 2>/dev/null || unavailable "cannot make $dir (cgroup v1 cpu not writable)"
		echo "$period" > "$dir/cpu.cfs_period_us" || unavailable "cannot write $dir/cpu.cfs_period_us"
		echo "$quota" > "$dir/cpu.cfs_quota_us" || unavailable "cannot write $dir/cpu.cfs_quota_us"
		echo "$dir"
		return
	fi
	v2=/sys/fs/cgroup
	if [ -f "$v2/cgroup.controllers" ] && grep -qw cpu "$v2/cgroup.controllers"; then
		echo +cpu > "$v2/cgroup.subtree_control" 2>/dev/null || true
		dir=$v2/$name
		mkdir -p "$dir" 2>/dev/null || unavailable "cannot make $dir (cgroup v2 not writable)"
		echo "$quota $period" > "$dir/cpu.max" 2>/dev/null || unavailable "cannot write $dir/cpu.max"
		echo "$dir"
		return
	fi
	unavailable "neither cgroup v1 $v1/cpu.cfs_quota_us nor cgroup v2 cpu.max is writable here"
}

add() {
	echo "$2" > "$1/cgroup.procs" || fail "cannot move process $2 into $1"
}

# Some threads' work is not the box's: a camera on the box delivers raw
# frames by DMA, while here a stand-in decodes a recording (dk-replay) or
# renders the simulated board (dk-sim*). Those threads leave the share
# (issue 29 §2). cgroup v1 moves one thread by writing its TID to another
# cgroup's tasks. cgroup v2 moves a thread apart from its process only
# inside a threaded subtree (cgroup.type "threaded", the cpu controller
# enabled in it, TIDs written to cgroup.threads); a share made by create
# is a domain cgroup, so there the whole process stays in: exit 77 says so.
release() {
	dir=$1 pid=$2
	shift 2
	if [ ! -f "$dir/tasks" ]; then
		unavailable "cgroup v2 without threaded mode: a thread cannot leave its process's cgroup $dir; the whole process stays in the share"
	fi
	parent=$(dirname "$dir")
	for task in /proc/"$pid"/task/*; do
		tid=${task##*/}
		name=$(cat "$task/comm" 2>/dev/null) || continue # the thread has ended
		for prefix in "$@"; do
			case $name in "$prefix"*) ;; *) continue ;; esac
			grep -qx "$tid" "$dir/tasks" || break # moved already
			if echo "$tid" > "$parent/tasks" 2>/dev/null; then
				echo "$tid $name"
			elif [ -d "$task" ]; then
				fail "cannot move thread $tid ($name) of $pid to $parent"
			fi
			break
		done
	done
}

remove() {
	dir=$1
	[ -d "$dir" ] || return 0
	parent=$(dirname "$dir")
	# Whatever is still inside goes back to the parent, so the folder can go.
	if [ -r "$dir/cgroup.procs" ]; then
		while read -r pid; do
			echo "$pid" > "$parent/cgroup.procs" 2>/dev/null || true
		done < "$dir/cgroup.procs"
	fi
	rmdir "$dir" || fail "cannot remove $dir"
}

[ $# -ge 1 ] || fail "usage: cpu_share.sh create NAME PERCENT | add DIR PID | release DIR PID PREFIX... | remove DIR | run PERCENT COMMAND..."
command=$1
shift
case $command in
create) [ $# = 2 ] || fail "usage: cpu_share.sh create NAME PERCENT"; create "$1" "$2" ;;
add) [ $# = 2 ] || fail "usage: cpu_share.sh add DIR PID"; add "$1" "$2" ;;
release) [ $# -ge 3 ] || fail "usage: cpu_share.sh release DIR PID PREFIX..."; release "$@" ;;
remove) [ $# = 1 ] || fail "usage: cpu_share.sh remove DIR"; remove "$1" ;;
run)
	[ $# -ge 2 ] || fail "usage: cpu_share.sh run PERCENT COMMAND..."
	percent=$1
	shift
	dir=$(create "depthkey-share-$$" "$percent")
	status=0
	# The child moves itself in before it becomes COMMAND: none of COMMAND's
	# work runs outside the share.
	sh -c 'echo $$ > "$1/cgroup.procs" && shift && exec "$@"' sh "$dir" "$@" || status=$?
	remove "$dir"
	exit "$status"
	;;
*) fail "unknown command '$command'" ;;
esac
