#!/usr/bin/python3
"""The daemon's keying cost live (issue 28), part of `make bench-process`.

    tests/bench/keying_share.py BIN BUILD [--seconds N] [--runs N]

For each case (640x480 at 25 fps, 1280x720 at 30 fps; the simulated cameras,
calibrated for that size by `depthkey-calibrate --sim --sim-colour-size`, the
board a solid colour so the composite is in the camera's geometry), depthkeyd
runs N seconds after a 3 s start, and this prints, as figures (medians of the
runs, never a verdict):
  - the CPU share of one core of each of its threads, from
    /proc/PID/task/TID/stat over the measured seconds: dk-keying (the
    pipeline, daemon/keying_worker.hpp) apart from the event loop, which
    pairs and publishes; and apart from both, the dk-sim* threads, where the
    simulated cameras render (hal/sim/sim_render_thread.hpp): the
    simulator's own cost, a camera's DMA on the box, not the daemon's
    (issue 29 §2), so the box's share is the total without them;
  - the status line's keying time (median and p99 of a frame's work) and the
    frames shed (a waiting frame dropped because the worker was busy), read
    from the last STATUS= the daemon sent to our notify socket;
  - the output rate.
Issue 28's targets: <= 10% of one core and 0 shed at 640x480 25 fps, <= 40%
at 1280x720 30 fps.
"""

import os
import re
import socket
import statistics
import subprocess
import sys
import tempfile
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import process_bench  # noqa: E402  (make run's config with names of our own, start and stop)

CASES = ((640, 480, 25), (1280, 720, 30))
WARMUP_S = 3.0


def thread_ticks(pid):
    """{thread name: utime + stime in clock ticks}, threads of one name summed."""
    ticks = {}
    for tid in os.listdir("/proc/%d/task" % pid):
        try:
            with open("/proc/%d/task/%s/stat" % (pid, tid)) as f:
                stat = f.read()
        except FileNotFoundError:
            continue  # the thread ended meanwhile
        name = stat[stat.index("(") + 1:stat.rindex(")")]
        fields = stat[stat.rindex(")") + 2:].split()
        ticks[name] = ticks.get(name, 0) + int(fields[11]) + int(fields[12])
    return ticks


def case_config(bin_dir, build, work, width, height, fps):
    config, tag = process_bench.bench_config(build, bin_dir, work, colour_board=True)
    calibration = os.path.join(work, "cal-%dx%d.toml" % (width, height))
    if not os.path.exists(calibration):
        subprocess.run([os.path.join(bin_dir, "depthkey-calibrate"), "--sim", "--sim-colour-size",
                        "%dx%d" % (width, height), "--output", calibration], check=True,
                       stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    values = {"colour": {"width": str(width), "height": str(height), "fps": str(fps)},
              "mapping": {"calibration_file": '"%s"' % calibration}}
    path = os.path.join(work, "keying-%dx%d.toml" % (width, height))
    process_bench.rewrite_config(config, path, values)
    return path, tag


def run_case(bin_dir, config, work, seconds):
    proc, sock, log = process_bench.start_daemon(bin_dir, config, work)
    status, shed_at_start, before = "", None, None
    start = time.monotonic()
    try:
        while True:
            now = time.monotonic() - start
            if before is None and now >= WARMUP_S:
                before, t0, shed_at_start = thread_ticks(proc.pid), time.monotonic(), shed_of(status)
            if now >= WARMUP_S + seconds:
                break
            if proc.poll() is not None:
                raise RuntimeError("depthkeyd exited early (see %s/daemon.log)" % work)
            sock.settimeout(0.05)
            try:
                for line in sock.recv(4096).decode(errors="replace").split("\n"):
                    if line.startswith("STATUS="):
                        status = line[len("STATUS="):]
            except socket.timeout:
                pass
        after, t1 = thread_ticks(proc.pid), time.monotonic()
    finally:
        process_bench.stop_daemon(proc, sock, log)
    hz = os.sysconf("SC_CLK_TCK")
    shares = {name: 100.0 * (after[name] - before.get(name, 0)) / hz / (t1 - t0) for name in after}
    keying = re.search(r"keying ([0-9.]+) ms \(p99 ([0-9.]+)\)", status)
    output = re.search(r"output ([0-9.]+) fps", status)
    shed = shed_of(status)
    return {
        "shares": shares,
        "keying_ms": float(keying.group(1)) if keying else float("nan"),
        "keying_p99_ms": float(keying.group(2)) if keying else float("nan"),
        "output_fps": float(output.group(1)) if output else float("nan"),
        "shed": (shed - (shed_at_start or 0)) if shed is not None else -1,
    }


def is_simulator(name):
    """A thread of the simulated cameras' rendering (dk-sim-colour, -depth,
    -board): the stand-in's cost, not the box's."""
    return name.startswith("dk-sim")


def thread_label(name):
    if is_simulator(name):
        return "the simulator's rendering (a camera's DMA on the box: not the daemon's)"
    return {"dk-keying": "the keying worker", "depthkeyd": "the event loop (pairing, publishing)"}.get(name, "")


def shed_of(status):
    m = re.search(r"([0-9]+) shed", status)
    return int(m.group(1)) if m else None


def main():
    parser = process_bench.base_arguments(__doc__)
    args = parser.parse_args()
    bin_dir = os.path.abspath(args.bin)
    print("keying live, the simulated cameras, the board a solid colour (%d runs of %gs after %gs):" %
          (args.runs, args.seconds, WARMUP_S))
    with tempfile.TemporaryDirectory(prefix="depthkey-keying-") as work:
        for width, height, fps in CASES:
            config, tag = case_config(bin_dir, args.build, work, width, height, fps)
            runs = [run_case(bin_dir, config, work, args.seconds) for _ in range(args.runs)]
            process_bench.remove_shm(tag)
            med = lambda values: statistics.median(values)
            names = sorted({n for r in runs for n in r["shares"]}, key=lambda n: -med([r["shares"].get(n, 0) for r in runs]))
            print("  %dx%d at %d fps:" % (width, height, fps))
            print("    keying %.1f ms a frame (p99 %.1f), %s shed in %gs, output %.1f fps" % (
                med([r["keying_ms"] for r in runs]), med([r["keying_p99_ms"] for r in runs]),
                "/".join(str(r["shed"]) for r in runs), args.seconds, med([r["output_fps"] for r in runs])))
            for name in names:
                print("    %-13s %5.1f%% of one core  %s" % (name, med([r["shares"].get(name, 0) for r in runs]),
                                                         thread_label(name)))
            box = [sum(v for n, v in r["shares"].items() if not is_simulator(n)) for r in runs]
            sim = [sum(v for n, v in r["shares"].items() if is_simulator(n)) for r in runs]
            print("    the box's threads %5.1f%% of one core; the simulator's rendering %.1f%% apart" % (
                med(box), med(sim)))


if __name__ == "__main__":
    main()
