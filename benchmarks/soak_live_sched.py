"""What the scan thread waited for at each late tick of a live soak: the
kernel's scheduler events (perf) read at the late ticks' times.

    perf record -e sched:sched_switch -e sched:sched_waking -a -k CLOCK_MONOTONIC \\
        -o soak.perf &                                         # beside the soak
    SOFTPLC_SOAK_NAME_THREADS=1 python benchmarks/bench_soak_live.py --minutes 30 --keep-logs DIR
    python benchmarks/soak_live_sched.py soak.perf DIR/stats-*.json [--late-ms 7]
    python benchmarks/soak_live_sched.py soak.perf DIR/stats-*.json --long   # the long ticks

A tick was due at R (its release) and began at T = R + late (soak_live_plc.py
keeps each tick late by 5 ms or more with its CLOCK_MONOTONIC time). Between
R and T the scan thread ("plc-main": the soak names the threads for the
kernel) was, by the scheduler's events:

* "lock": asleep and woken by a thread of its own process: that thread held
  the interpreter lock (it wakes the waiter when it drops it), named;
* "runnable": preempted, or woken and kept waiting in the run queue: the
  CPUs were busy, and the tasks that ran on them are named;
* "running": the scan thread itself was busy (its own work between ticks,
  a collection, a page fault);
* "timer": asleep until a wake-up from no thread of its process came late.

Each late tick gets a line with the split of its R..T window, and a summary
counts the windows by their greatest part (and those that a garbage
collection of the PLC's process overlaps: the stats' "collections") and names the lock holders and
the CPU's other tasks, by time.
"""

from __future__ import annotations

import argparse
import bisect
import json
import re
import subprocess
import sys
from collections import Counter
from pathlib import Path

SCAN = "plc-main"
_LINE = re.compile(r"^\s*(.+?)\s+(\d+)\s+\[(\d+)\]\s+([\d.]+):\s+(\S+):\s+(.*)$")
_SWITCH = re.compile(
    r"prev_comm=(.*?) prev_pid=(\d+) prev_prio=\d+ prev_state=(\S+) ==> next_comm=(.*?) next_pid=(\d+)"
)
_WAKING = re.compile(r"comm=(.*?) pid=(\d+) prio=\d+ target_cpu=(\d+)")
MARGIN_S = 0.002


def late_ticks(paths: list, late_ms: float, key: str = "late_ticks") -> list:
    """(release, start, late ms) of every kept tick late by late_ms or more,
    in time order; key "long_ticks": (begin, end, ms) of the ticks that took
    that long (the scan thread's time inside a tick: a swap, a lock)."""
    ticks = []
    for path in paths:
        for entry in json.loads(Path(path).read_text()).get(key, ()):
            if len(entry) >= 3 and entry[1] >= late_ms:
                start = entry[2]
                ticks.append((start - entry[1] / 1e3, start, entry[1]))
    return sorted(ticks)


def collections(paths: list) -> list:
    """(start, end, generation, thread) of the soak's kept garbage collections, in time order."""
    found = []
    for path in paths:
        for start, ms, generation, _collected, thread in json.loads(Path(path).read_text()).get("collections", ()):
            found.append((start, start + ms / 1e3, generation, thread))
    return sorted(found)


def events(perf_data: str, windows: list):
    """The scheduler events inside any window (lo, hi), in time order."""
    los = [lo for lo, _ in windows]
    his = [hi for _, hi in windows]
    cmd = ["perf", "script", "-i", perf_data, "-F", "comm,tid,cpu,time,event,trace"]
    cmd += ["--time", f"{min(los):.6f},{max(his):.6f}"]  # perf skips what lies outside every window
    with subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.DEVNULL, text=True) as proc:
        assert proc.stdout is not None
        for line in proc.stdout:
            m = _LINE.match(line)
            if not m:
                continue
            t = float(m.group(4))
            i = bisect.bisect_right(los, t) - 1
            if i < 0 or t > his[i]:
                continue
            yield t, m.group(1), int(m.group(2)), int(m.group(3)), m.group(5), m.group(6)


class Window:
    def __init__(self, release: float, start: float, late_ms: float):
        self.release, self.start, self.late_ms = release, start, late_ms
        self.events: list = []

    def explain(self, scan_tids: set, own: dict) -> tuple:
        """({part: seconds}, {lock holder: s}, {task on the CPUs: s}, timeline) of R..T."""
        lo, hi = self.release, self.start
        state, since = None, lo  # None: not known before the scan thread's first event
        parts: Counter = Counter()
        holders: Counter = Counter()
        others: Counter = Counter()
        running: dict = {}  # cpu -> (comm, tid, since)
        timeline: list = []

        def close(t: float, new_state: str, guess: str, waker: str | None = None) -> None:
            nonlocal state, since
            span = max(0.0, min(t, hi) - max(since, lo))
            part = state or guess
            if part == "asleep" and waker is not None:
                part = "lock" if waker in own.values() else "timer"
                if part == "lock":
                    holders[waker] += span
            if span:
                parts[part] += span
            state, since = new_state, t

        for t, comm, _tid, cpu, event, trace in self.events:
            if event == "sched:sched_switch":
                m = _SWITCH.search(trace)
                if not m:
                    continue
                prev_pid, prev_state, next_comm, next_pid = int(m.group(2)), m.group(3), m.group(4), int(m.group(5))
                if cpu in running:
                    c, p, s0 = running[cpu]
                    if p not in scan_tids and p != 0:
                        others[c] += max(0.0, min(t, hi) - max(s0, lo))
                running[cpu] = (next_comm, next_pid, t)
                if prev_pid in scan_tids:
                    close(t, "runnable" if prev_state.startswith("R") else "asleep", "running")
                    if lo <= t <= hi:
                        timeline.append(f"{(t - lo) * 1e3:+.1f} out({prev_state})")
                if next_pid in scan_tids:
                    close(t, "running", "runnable")
                    if lo <= t <= hi:
                        timeline.append(f"{(t - lo) * 1e3:+.1f} in")
            elif event == "sched:sched_waking":
                m = _WAKING.search(trace)
                if m and int(m.group(2)) in scan_tids:
                    close(t, "runnable", "asleep", comm)
                    if lo <= t <= hi:
                        timeline.append(f"{(t - lo) * 1e3:+.1f} woken by {comm}")
        close(hi, state or "running", "running")
        for c, p, s0 in running.values():
            if p not in scan_tids and p != 0:
                others[c] += max(0.0, hi - max(s0, lo))
        return parts, holders, others, timeline


def main(argv: list | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("perf_data")
    parser.add_argument("stats", nargs="+", help="the soak's stats-N.json (bench_soak_live.py --keep-logs)")
    parser.add_argument("--late-ms", type=float, default=7.0, help="the ticks at least this late (default 7)")
    parser.add_argument("--long", action="store_true", help="the ticks that took --late-ms or more instead")
    args = parser.parse_args(argv)
    ticks = late_ticks(args.stats, args.late_ms, "long_ticks" if args.long else "late_ticks")
    if not ticks:
        print(f"no tick late by {args.late_ms:g} ms or more in {', '.join(args.stats)}")
        return 0
    windows = [Window(r, s, ms) for r, s, ms in ticks]
    spans = [(w.release - MARGIN_S, w.start + MARGIN_S) for w in windows]
    scan_tids: set = set()
    process_tids: dict = {}
    for t, comm, tid, cpu, event, trace in events(args.perf_data, spans):
        i = bisect.bisect_right([lo for lo, _ in spans], t) - 1
        windows[i].events.append((t, comm, tid, cpu, event, trace))
        if comm == SCAN:
            scan_tids.add(tid)
    # the threads of the scan's process: those whose wake-up of it is a lock's hand-over
    for w in windows:
        for _, comm, tid, _, _, _ in w.events:
            process_tids.setdefault(tid, comm)
    gcs = collections(args.stats)
    gc_starts = [c[0] for c in gcs]
    mains: Counter = Counter()
    holders_all: Counter = Counter()
    others_all: Counter = Counter()
    for w in windows:
        parts, holders, others, timeline = w.explain(scan_tids, _same_process(process_tids))
        mains[parts.most_common(1)[0][0] if parts else "unknown"] += 1
        holders_all.update(holders)
        others_all.update(others)
        split = ", ".join(f"{k} {v * 1e3:.1f}" for k, v in parts.most_common())
        who = ", ".join(f"{k} {v * 1e3:.1f}" for k, v in holders.most_common(3))
        ran = ", ".join(f"{k} {v * 1e3:.1f}" for k, v in others.most_common(3))
        print(f"{w.start:.4f} late {w.late_ms:5.1f} ms: {split} | lock: {who or '-'} | CPUs: {ran or '-'}")
        lo = bisect.bisect_left(gc_starts, w.release - 0.1)
        overlap = [c for c in gcs[lo : lo + 50] if c[0] < w.start and c[1] > w.release]
        for start, end, generation, thread in overlap:
            timeline.insert(0, f"[gen{generation} collection in {thread}: {(end - start) * 1e3:.1f} ms]")
        if overlap:
            mains["(a collection overlaps)"] += 1
        print(f"        {' '.join(timeline[:12])}")
    print(f"\n{len(windows)} ticks late by {args.late_ms:g} ms or more; by their greatest part: {dict(mains)}")
    print("lock holders (ms):", ", ".join(f"{k} {v * 1e3:.0f}" for k, v in holders_all.most_common(10)))
    print("other tasks on the CPUs (ms):", ", ".join(f"{k} {v * 1e3:.0f}" for k, v in others_all.most_common(10)))
    return 0


def _same_process(tids: dict) -> dict:
    """The thread ids of the PLC's process: its threads carry the soak's names
    (the kernel knows no process of a tid from these events; a Python thread
    of another process is named "python")."""
    return {tid: comm for tid, comm in tids.items() if comm not in ("python", "python3", "perf") and "/" not in comm}


if __name__ == "__main__":
    sys.exit(main())
