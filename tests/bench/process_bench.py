#!/usr/bin/python3
"""Whole-process figures of the built binaries (`make bench-process`).

    tests/bench/process_bench.py BIN BUILD [--seconds N] [--runs N]
                                 [--siox IMAGE TRIMAP] [--breakdown] [--blocks]

Prints, for issue 15's targets (figures, never a pass/fail: no timed test):
  - the shared libraries each binary in BIN maps (`ldd | wc -l`);
  - depthkeyd on the simulated cameras (BUILD/run.toml as `make run` writes
    it, with a preview port, shared-memory names and snapshot folder of its
    own so that it runs beside a `make run`): milliseconds from exec to
    READY=1 on a NOTIFY_SOCKET of ours, as systemd would see it, then after
    N seconds VmRSS, VmHWM and VmRSS split into anonymous memory (heap,
    frame buffers), file-backed pages (code and libraries) and shared memory
    (the output rings), from /proc/PID/status, and VmRSS read every 10 ms
    over the second half of the N seconds: its median (the reading a
    technician's `ps` gets most often), least and largest. The per-frame
    graph of the band's cut (6-8 MB) comes and goes, so a single reading may
    or may not count it;
  - the same on replayed cameras at 640x480: a sequence of the simulated
    lecture recorded once by depthkey-eval into BUILD/bench-sequence, the
    board a solid colour. Sim minus replay is what the simulator costs;
  - with --breakdown: where the last run's VmRSS is, per mapping of
    /proc/PID/smaps (the heap, other anonymous memory, thread stacks, each
    shared-memory ring, each library), in kB;
  - with --blocks: one more run of each config with tests/bench/rss_blocks.c
    preloaded (built with cc): the resident kB of every live heap block of
    64 KiB or more after N seconds, summed by where it was allocated (the
    first two frames of depthkeyd's own code, addr2line).
  - `depthkey-siox --help`: process start to exit, the median of many runs;
  - with --siox: a whole `depthkey-siox IMAGE TRIMAP OUT` run, the same way.
Medians of --runs runs. Figures are this machine's: under qemu-user they
measure the emulator, not the code.
"""

import argparse
import collections
import os
import re
import socket
import statistics
import subprocess
import sys
import tempfile
import time


def ldd_counts(bin_dir):
    rows = []
    for name in sorted(os.listdir(bin_dir)):
        path = os.path.join(bin_dir, name)
        if not (os.path.isfile(path) and os.access(path, os.X_OK)):
            continue
        out = subprocess.run(["ldd", path], capture_output=True, text=True).stdout
        rows.append((len(out.splitlines()), name))
    return rows


def bench_config(build, bin_dir, work, colour_board=False, replay=None):
    """BUILD/run.toml (as daemon/run-sim.sh makes it) with our own names;
    colour_board: the board a solid colour, composited in the colour
    camera's geometry (640x480) instead of the simulated board's 1920x780;
    replay: a recorded folder both cameras replay instead of the simulator."""
    config = subprocess.run(["sh", "daemon/run-sim.sh", bin_dir, build], check=True, capture_output=True,
                            text=True, env=dict(os.environ, RUN_SIM_PREPARE_ONLY="1")).stdout.strip()
    tag = "bench%d" % os.getpid()
    replace = {
        "composite_name": '"/depthkey-%s.composite"' % tag,
        "lecturer_name": '"/depthkey-%s.lecturer"' % tag,
        "board_lecturer_name": '"/depthkey-%s.lecturer.board"' % tag,
        "listen": '"127.0.0.1:0"',
        "snapshot_dir": '""',
        "record_dir": '""',
    }
    sections = {"board": {"backend": '"colour"', "homography_file": '""'} if colour_board else {}}
    if replay:
        sections["colour"] = sections["depth"] = {"backend": '"replay"'}
        sections["replay"] = {"path": '"%s"' % replay}
    name = "bench-replay.toml" if replay else "bench-colour-board.toml" if colour_board else "bench.toml"
    path = os.path.join(work, name)
    rewrite_config(config, path, sections, replace)
    return path, tag


def rewrite_config(source, path, sections, replace=None):
    """SOURCE with sections[section][key] and replace[key] (any section)
    written over those keys' values, into PATH."""
    lines, section = [], None
    with open(source) as f:
        for line in f:
            if line.startswith("["):
                section = line.strip().strip("[]")
            key = line.split("=", 1)[0].strip()
            if "=" in line and key in sections.get(section, {}):
                line = "%s = %s\n" % (key, sections[section][key])
            elif "=" in line and key in (replace or {}):
                line = "%s = %s\n" % (key, replace[key])
            lines.append(line)
    with open(path, "w") as f:
        f.writelines(lines)


def replay_sequence(build, bin_dir):
    """A 640x480 sequence of the simulated lecture (seed 1, 100 frames),
    recorded once by depthkey-eval into BUILD/bench-sequence."""
    folder = os.path.abspath(os.path.join(build, "bench-sequence"))
    if not os.path.exists(os.path.join(folder, "rgb.txt")):
        config = os.path.join(build, "bench-sequence.toml")
        with open(config, "w") as f:
            f.write('[colour]\nwidth = 640\nheight = 480\n[board]\nbackend = "colour"\n')
        subprocess.run([os.path.join(bin_dir, "depthkey-eval"), "--config", config, "--sim", "1", "--frames", "100",
                        "--save-sequence", folder], check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    return folder


def smaps_breakdown(pid):
    """Resident kB per kind of mapping: the heap, thread stacks (found by
    each thread's stack pointer), other anonymous memory (large malloc
    blocks are mmapped, malloc arenas of other threads), each shared-memory
    file and each library or binary."""
    stack_pointers = []
    for tid in os.listdir("/proc/%d/task" % pid):
        try:
            with open("/proc/%d/task/%s/syscall" % (pid, tid)) as f:
                fields = f.read().split()
            with open("/proc/%d/task/%s/comm" % (pid, tid)) as f:
                comm = f.read().strip()
        except OSError:
            continue
        if len(fields) >= 2 and fields[0] != "running":
            stack_pointers.append((int(fields[-2], 16), comm))
    rows, current = {}, None
    with open("/proc/%d/smaps" % pid) as f:
        for line in f:
            head = line.split()
            if "-" in head[0] and not head[0].endswith(":"):
                lo, hi = (int(x, 16) for x in head[0].split("-"))
                path = head[5] if len(head) > 5 else ""
                if path == "[heap]":
                    current = "[heap] (brk: malloc's main arena)"
                elif path == "[stack]":
                    current = "[stack] (main thread)"
                elif path.startswith("/dev/shm/"):
                    current = "shm " + path[len("/dev/shm/"):]
                elif path.startswith("/"):
                    current = os.path.basename(path)
                elif path:
                    current = path
                else:
                    threads = [c for sp, c in stack_pointers if lo <= sp < hi]
                    current = ("thread stack (%s)" % ", ".join(threads)) if threads else \
                        "anonymous (mmapped malloc blocks, arenas)"
            elif line.startswith("Rss:") and current:
                rows[current] = rows.get(current, 0) + int(head[1])
    return rows


def status_kb(pid):
    fields = {}
    with open("/proc/%d/status" % pid) as f:
        for line in f:
            key, _, value = line.partition(":")
            if value.strip().endswith("kB"):
                fields[key] = int(value.split()[0])
    return fields


def drain_for(sock, seconds):
    """Reads the notify socket for `seconds`, as systemd would: depthkeyd
    sends STATUS= every second, and sd_notify blocks once the socket's queue
    (net.unix.max_dgram_qlen, 10 here) is full, which stalled the daemon
    about 10 s after READY=1."""
    end = time.monotonic() + seconds
    while True:
        left = end - time.monotonic()
        if left <= 0:
            return
        sock.settimeout(left)
        try:
            sock.recv(4096)
        except socket.timeout:
            return


def start_daemon(bin_dir, config, work, extra_env=None):
    """depthkeyd with a notify socket of ours (as systemd's) and its log in
    WORK/daemon.log: (process, socket, log)."""
    sock_path = os.path.join(work, "notify.sock")
    if os.path.exists(sock_path):
        os.unlink(sock_path)
    sock = socket.socket(socket.AF_UNIX, socket.SOCK_DGRAM)
    sock.bind(sock_path)
    env = dict(os.environ, NOTIFY_SOCKET=sock_path, DEPTHKEY_LOG="stderr", **(extra_env or {}))
    env.pop("WATCHDOG_USEC", None)
    log = open(os.path.join(work, "daemon.log"), "w")
    proc = subprocess.Popen([os.path.join(bin_dir, "depthkeyd"), "--config", config], env=env,
                            stdin=subprocess.DEVNULL, stdout=log, stderr=log)
    return proc, sock, log


def stop_daemon(proc, sock, log):
    proc.terminate()
    try:
        proc.wait(timeout=10)
    except subprocess.TimeoutExpired:
        proc.kill()
        proc.wait()
    sock.close()
    log.close()


def run_daemon(bin_dir, config, work, seconds, extra_env=None):
    start = time.monotonic()
    proc, sock, log = start_daemon(bin_dir, config, work, extra_env)
    ready_ms = None
    try:
        sock.settimeout(10.0)
        while ready_ms is None:
            message = sock.recv(4096).decode(errors="replace")
            if "READY=1" in message.split("\n"):
                ready_ms = (time.monotonic() - start) * 1000.0
        drain_for(sock, seconds / 2)
        samples = []
        end = time.monotonic() + seconds / 2
        while time.monotonic() < end:
            drain_for(sock, min(0.01, end - time.monotonic()))
            if proc.poll() is not None:
                break
            samples.append(status_kb(proc.pid).get("VmRSS", 0))
        if proc.poll() is not None or not samples:
            raise RuntimeError("depthkeyd exited early (see %s/daemon.log)" % work)
        status = status_kb(proc.pid)
        samples.append(status.get("VmRSS", 0))
        status["VmRSSLargest"] = max(samples)
        status["VmRSSMedian"] = statistics.median(samples)
        status["VmRSSLeast"] = min(samples)
        breakdown = smaps_breakdown(proc.pid)
    finally:
        stop_daemon(proc, sock, log)
    return ready_ms, status, breakdown


def build_blocks_preload(work):
    here = os.path.dirname(os.path.abspath(__file__))
    out = os.path.join(work, "rss_blocks.so")
    subprocess.run(["cc", "-O1", "-shared", "-fPIC", "-o", out, os.path.join(here, "rss_blocks.c"), "-lpthread"],
                   check=True)
    return out


def heap_blocks(bin_dir, config, work, seconds, preload):
    """Resident and asked kB per allocation site, from one run with
    rss_blocks.so preloaded (see its header)."""
    report = os.path.join(work, "blocks.txt")
    after = max(1, int(seconds))
    run_daemon(bin_dir, config, work, after + 2,
               {"LD_PRELOAD": preload, "RSS_BLOCKS_AFTER": str(after), "RSS_BLOCKS_OUT": report})
    binary = os.path.join(bin_dir, "depthkeyd")
    blocks, current = [], None
    with open(report) as f:
        for line in f:
            if line.startswith("BLOCK "):
                _, size, resident = line.split()
                current = {"asked": int(size), "resident": int(resident), "frames": []}
                blocks.append(current)
            elif current is not None:
                m = re.search(r"depthkeyd\(\+(0x[0-9a-f]+)\)", line)
                if m:
                    current["frames"].append(int(m.group(1), 16) - 1)  # inside the call
    addresses = sorted({a for b in blocks for a in b["frames"]})
    names = {}
    if addresses:
        out = subprocess.run(["addr2line", "-C", "-f", "-e", binary] + [hex(a) for a in addresses],
                             capture_output=True, text=True).stdout.splitlines()
        for i, a in enumerate(addresses):
            function = re.sub(r"\(.*", "", out[2 * i]).replace("depthkey::", "")
            where = os.path.basename(out[2 * i + 1].split(" ")[0])
            names[a] = "%s (%s)" % (function, where)
    plumbing = re.compile(r"^(std::|__gnu_cxx|operator new|void std|\?\?|.*::resize |.*Image<.*>::|.*_M_)")
    sites = collections.defaultdict(lambda: [0, 0, 0])
    for b in blocks:
        own = [names[a] for a in b["frames"] if not plumbing.match(names[a])][:2]
        site = sites[" <- ".join(own) if own else "(libraries)"]
        site[0] += b["resident"]
        site[1] += b["asked"]
        site[2] += 1
    return sites


def wall_ms(argv, runs):
    times = []
    for _ in range(runs):
        start = time.monotonic()
        subprocess.run(argv, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        times.append((time.monotonic() - start) * 1000.0)
    return times


def spread(values, unit, digits=1):
    return "median %.*f %s (min %.*f, max %.*f, %d runs)" % (
        digits, statistics.median(values), unit, digits, min(values), digits, max(values), len(values))


def base_arguments(doc):
    """BIN BUILD [--seconds N] [--runs N], the arguments every process bench takes."""
    parser = argparse.ArgumentParser(description=doc.split("\n")[0])
    parser.add_argument("bin")
    parser.add_argument("build")
    parser.add_argument("--seconds", type=float, default=10.0)
    parser.add_argument("--runs", type=int, default=3)
    return parser


def remove_shm(tag):
    """The shared-memory objects of a config of bench_config's, if left."""
    for name in ("composite", "lecturer", "lecturer.board", "composite.readers", "lecturer.readers",
                 "lecturer.board.readers"):
        try:
            os.unlink("/dev/shm/depthkey-%s.%s" % (tag, name))
        except FileNotFoundError:
            pass


def main():
    parser = base_arguments(__doc__)
    parser.add_argument("--siox", nargs=2, metavar=("IMAGE", "TRIMAP"))
    parser.add_argument("--breakdown", action="store_true", help="VmRSS per mapping (smaps) of each config's last run")
    parser.add_argument("--blocks", action="store_true", help="resident heap blocks >= 64 KiB by allocation site")
    args = parser.parse_args()
    bin_dir = os.path.abspath(args.bin)

    print("shared libraries mapped (ldd lines):")
    for count, name in ldd_counts(bin_dir):
        print("  %4d  %s" % (count, name))

    with tempfile.TemporaryDirectory(prefix="depthkey-bench-") as work:
        sequence = replay_sequence(args.build, bin_dir)
        preload = build_blocks_preload(work) if args.blocks else None
        for colour_board, replay, title in (
                (False, None, "the simulated cameras, make run's config: the simulated board, composite at 1920x780"),
                (True, None, "the simulated cameras, the board a solid colour, composite at the cameras' 640x480"),
                (True, sequence, "replayed cameras (the simulator's lecture recorded), the board a solid colour, "
                 "composite at 640x480")):
            config, tag = bench_config(args.build, bin_dir, work, colour_board, replay)
            ready, rss = [], {}
            for _ in range(args.runs):
                ms, status, breakdown = run_daemon(bin_dir, config, work, args.seconds)
                ready.append(ms)
                for key in ("VmRSS", "VmRSSMedian", "VmRSSLeast", "VmRSSLargest", "VmHWM", "RssAnon", "RssFile",
                            "RssShmem"):
                    rss.setdefault(key, []).append(status.get(key, 0) / 1024.0)
            remove_shm(tag)
            print("depthkeyd on %s:" % title)
            print("  exec to READY=1: %s" % spread(ready, "ms"))
            for key, label in (("VmRSS", "VmRSS after %gs" % args.seconds),
                               ("VmRSSMedian", "VmRSS over %g-%gs, median" % (args.seconds / 2, args.seconds)),
                               ("VmRSSLeast", "VmRSS over %g-%gs, least" % (args.seconds / 2, args.seconds)),
                               ("VmRSSLargest", "largest VmRSS, %g-%gs" % (args.seconds / 2, args.seconds)),
                               ("VmHWM", "VmHWM (peak)"),
                               ("RssAnon", "  of it anonymous (heap, buffers)"),
                               ("RssFile", "  of it file-backed (code, libraries)"),
                               ("RssShmem", "  of it shared memory (output rings)")):
                print("  %-38s %s" % (label + ":", spread(rss[key], "MB")))
            if args.breakdown:
                print("  VmRSS of the last run by mapping (kB, /proc/PID/smaps):")
                for name, kb in sorted(breakdown.items(), key=lambda item: -item[1]):
                    if kb >= 64:
                        print("    %8d  %s" % (kb, name))
                small = [kb for kb in breakdown.values() if kb < 64]
                print("    %8d  %d more mappings under 64 kB each" % (sum(small), len(small)))
            if args.blocks:
                sites = heap_blocks(bin_dir, config, work, args.seconds, preload)
                print("  heap blocks of 64 KiB or more after %ds, by allocation site (one run):" % max(1, int(args.seconds)))
                print("    %8s %8s  %s" % ("resident", "asked", "kB, where (first frames of depthkeyd's own code)"))
                for site, (resident, asked, count) in sorted(sites.items(), key=lambda item: -item[1][0]):
                    print("    %8d %8d  x%-2d %s" % (resident, asked // 1024, count, site[:150]))
                print("    %8d %8d  in all" % (sum(v[0] for v in sites.values()), sum(v[1] for v in sites.values()) // 1024))
            remove_shm(tag)

        siox = os.path.join(bin_dir, "depthkey-siox")
        wall_ms([siox, "--help"], 3)  # warm the page cache
        print("depthkey-siox --help: %s" % spread(wall_ms([siox, "--help"], 31), "ms", 2))
        if args.siox:
            argv = [siox, args.siox[0], args.siox[1], os.path.join(work, "mask.png")]
            wall_ms(argv, 3)
            print("depthkey-siox %s %s OUT: %s" % (args.siox[0], args.siox[1], spread(wall_ms(argv, 31), "ms", 2)))
    return 0


if __name__ == "__main__":
    sys.exit(main())
