"""Helpers of bench_soak_live.py: a life of the PLC process and its figures,
the monitor (one event stream of the web page watching the counter), RSS,
and the report."""

from __future__ import annotations

import http.client
import json
import re
import threading
import time
from collections import Counter
from dataclasses import dataclass, field
from pathlib import Path

BUCKET_MS = 0.01  # soak_live_plc.BUCKET_NS
RSS_FLAT = 0.10


def rss_kb(pid: int) -> int:
    try:
        with open(f"/proc/{pid}/status") as f:
            for line in f:
                if line.startswith("VmRSS:"):
                    return int(line.split()[1])
    except OSError:
        pass
    return 0


def children(pid: int) -> list:
    out = []
    try:
        for task in Path(f"/proc/{pid}/task").iterdir():
            out += [int(c) for c in (task / "children").read_text().split()]
    except OSError:
        pass
    return out


def web_post(port: int, path: str, body: dict, timeout: float = 10) -> tuple:
    conn = http.client.HTTPConnection("127.0.0.1", port, timeout=timeout)
    try:
        conn.request("POST", path, json.dumps(body), {"Content-Type": "application/json"})
        response = conn.getresponse()
        text = response.read()
        try:
            return response.status, json.loads(text)
        except ValueError:
            return response.status, {}
    except (OSError, http.client.HTTPException) as exc:
        return 0, {"error": str(exc)}
    finally:
        conn.close()


@dataclass
class Life:
    n: int
    stats: Path
    log: Path
    proc: object = None
    started: float = 0.0
    ended: float = 0.0
    first_seen: int = 0
    warm: bool = False
    rss_warm: int | None = None  # kB
    rss_end: int = 0
    servers_warm: int = 0
    servers_end: int = 0
    code: int | None = None
    data: dict = field(default_factory=dict)

    def read_stats(self) -> None:
        try:
            self.data = json.loads(self.stats.read_text())
        except (OSError, ValueError):
            pass

    def cycles(self) -> int:
        return self.data.get("cycle", 0)

    def overruns(self) -> dict:
        return {t["name"]: t["overruns"] for t in self.data.get("tasks", ())}

    def overruns_total(self) -> int:
        return sum(self.overruns().values())


def percentiles(lives: list) -> tuple:
    """Tick lateness p50, p99 (bucket upper edges) and the max over every life, in ms."""
    merged: Counter = Counter()
    worst = 0
    for life in lives:
        for k, c in life.data.get("late", {}).items():
            merged[int(k)] += c
        worst = max(worst, life.data.get("late_max_ns", 0))
    n = sum(merged.values())
    if not n:
        return 0.0, 0.0, 0.0
    out = []
    for q in (0.50, 0.99):
        seen = 0
        for k in sorted(merged):
            seen += merged[k]
            if seen >= q * n:
                out.append((k + 1) * BUCKET_MS)
                break
    return out[0], out[1], worst / 1e6


class Monitor:
    """One page of the web monitor watching Soak.kept and Soak.running: the
    values seen, with the wall time they arrived, for the retain checks."""

    def __init__(self, port: int) -> None:
        self.port = port
        self.history: list = []  # (wall, kept) of this life, the newest 600
        self.kept = None
        self.running = None
        self.paused = threading.Event()
        self.stopped = threading.Event()
        self.lock = threading.Lock()

    def start(self) -> None:
        threading.Thread(target=self._run, name="soak-monitor", daemon=True).start()

    def stop(self) -> None:
        self.stopped.set()

    def pause(self) -> None:
        self.paused.set()

    def reset(self) -> None:
        with self.lock:
            self.history = []
            self.kept = self.running = None
        self.paused.clear()

    def first(self):
        with self.lock:
            return self.history[0][1] if self.history else None

    def values_before(self, wall: float):
        with self.lock:
            before = [v for t, v in self.history if t <= wall]
        return before[-1] if before else None

    def _run(self) -> None:
        while not self.stopped.is_set():
            if self.paused.is_set():
                time.sleep(0.1)
                continue
            try:
                self._stream()
            except (OSError, http.client.HTTPException, ValueError):
                pass
            time.sleep(0.3)

    def _stream(self) -> None:
        status, _ = web_post(self.port, "/api/watch", {"client": "soakmonitor", "paths": ["Soak.kept", "Soak.running"]})
        if status != 200:
            return
        conn = http.client.HTTPConnection("127.0.0.1", self.port, timeout=5)
        try:
            conn.request("GET", "/api/events?client=soakmonitor")
            response = conn.getresponse()
            if response.status != 200:
                return
            while not self.stopped.is_set() and not self.paused.is_set():
                line = response.fp.readline()
                if not line:
                    return
                if not line.startswith(b"data:"):
                    continue
                values = json.loads(line[5:]).get("values", {})
                if "Soak.kept" not in values:
                    continue
                with self.lock:
                    if self.paused.is_set():
                        return
                    self.kept = values["Soak.kept"]
                    self.running = values.get("Soak.running")
                    self.history.append((time.time(), self.kept))
                    del self.history[1:-600]  # the first of the life, and the newest
        finally:
            conn.close()


def attribute(wall: float, soak, window_s: float = 3.0) -> str:
    """What was going on at wall: other processes on the host busy, the
    hypervisor running other guests, a life's start-up, an online change, a
    kill, a bus fault's cut or mend."""
    host = getattr(soak, "host", None)
    if host is not None and host.busy(wall):
        return "a second when other processes used 0.2 cores or more"
    if host is not None and host.stole(wall) > 0:
        return "a second when the hypervisor took CPU time (steal)"
    for when, kind in soak.events:
        if 0 <= wall - when <= window_s:
            return f"{window_s:g} s after an online change" if kind == "change" else f"{window_s:g} s after a kill"
    for life in soak.lives:
        if life.started <= wall < life.started + 30:
            return "a life's first 30 s"
    for life in soak.lives:
        for f in life.data.get("faults", ()):
            if any(abs(wall - t) <= 2 for t in (f["on"], f.get("off", f["on"]))):
                return "2 s around a bus cut or mend"
    return "none of these"


def late_ticks(soak) -> Counter:
    """The ticks late by a period of the fastest task (10 ms) or more, by what was going on."""
    out: Counter = Counter()
    for life in soak.lives:
        for wall, ms, *_ in life.data.get("late_ticks", ()):
            if ms >= 10:
                out[attribute(wall, soak)] += 1
    return out


_TIME = re.compile(r"^\S+ \S+ (t=\S+ )?")


def log_lines(lives: list) -> tuple:
    """(lines with a traceback, warnings/errors by their start, the tracebacks' first lines)."""
    tracebacks = 0
    kinds: Counter = Counter()
    first: list = []
    for life in lives:
        try:
            lines = life.log.read_text(errors="replace").splitlines()
        except OSError:
            continue
        for i, line in enumerate(lines):
            if "Traceback" in line:
                tracebacks += 1
                if len(first) < 5:
                    first.append(
                        f"life {life.n}: " + " | ".join(lines[max(i - 1, 0) : i + 1] + lines[i + 1 : i + 8][-3:])
                    )
            if " WARNING: " in line or " ERROR: " in line:
                kinds[_TIME.sub("", line)[:70]] += 1
    return tracebacks, kinds, first


def report(soak) -> int:
    lives = soak.lives
    for life in lives:
        life.read_stats()
    print(f"== report: wall {soak.wall / 60:.1f} min, {len(lives)} lives, ports {soak.ports}")
    scans = sum(lf.cycles() for lf in lives)
    by_task: Counter = Counter()
    for life in lives:
        by_task.update(life.overruns())
    total_over = sum(by_task.values())
    print(f"scans {scans}; overruns {total_over}: " + ", ".join(f"{k} {v}" for k, v in by_task.items()))
    p50, p99, worst = percentiles(lives)
    n = sum(lf.data.get("late_n", 0) for lf in lives)
    print(f"tick lateness over {n} ticks: p50 {p50:.2f} ms, p99 {p99:.2f} ms, max {worst:.2f} ms")
    if getattr(soak, "host", None) is not None:
        print(soak.host.summary())
    causes = late_ticks(soak)
    if causes:
        print("ticks late by 10 ms or more: " + ", ".join(f"{v} in {k}" for k, v in causes.most_common()))
    rss_ok = True
    for life in lives:
        warm, end = life.rss_warm or 0, life.rss_end
        growth = (end - warm) / warm if warm else 0.0
        flat = abs(growth) <= RSS_FLAT
        rss_ok = rss_ok and flat
        print(
            f"life {life.n}: {life.ended - life.started:6.0f} s, scans {life.cycles()}, "
            f"overruns {life.overruns_total()}, RSS after warm-up {warm / 1024:.1f} MB, "
            f"at the end {end / 1024:.1f} MB ({growth:+.1%}{'' if flat else ' NOT FLAT'}; "
            f"servers' process {life.servers_warm / 1024:.1f} -> {life.servers_end / 1024:.1f} MB), "
            f"runtime faults {life.data.get('runtime_faults', '?')}, {'warm' if life.warm else 'cold'} start, "
            f"first kept {life.first_seen}"
        )
    if not rss_ok:
        soak.problems.append(f"RSS not flat within {RSS_FLAT:.0%} in some life")
    faults = [f for life in lives for f in life.data.get("faults", ())]
    kinds = Counter(f["kind"] for f in faults)
    recovered = [f for f in faults if f.get("recovered_s") is not None]
    cut_short = [f for f in faults if "recovered_s" not in f]
    lost = [f for f in faults if "recovered_s" in f and f["recovered_s"] is None]
    times = sorted(f["recovered_s"] for f in recovered)
    print(
        f"bus faults injected {len(faults)} ({', '.join(f'{k} {v}' for k, v in sorted(kinds.items()))}); "
        f"seen {sum(f['seen'] for f in faults)}, recovered {len(recovered)}"
        + (f" (median {times[len(times) // 2]:.1f} s, worst {times[-1]:.1f} s)" if times else "")
        + f", not recovered in 60 s {len(lost)}, ended by a kill {len(cut_short)}"
    )
    if lost:
        soak.problems.append(f"{len(lost)} bus fault(s) not recovered within 60 s")
    applied = Counter((m, a, s) for m, a, s in soak.changes)
    print(
        f"online changes {len(soak.changes)}: seen in the PLC {sum(s for _m, _a, s in soak.changes)}; "
        + ", ".join(f"{m} applied={a} seen={s}: {c}" for (m, a, s), c in sorted(applied.items(), key=str))
    )
    print(f"kills {len(soak.kills)}:")
    for k in soak.kills:
        print(
            f"  life {k['life']} killed at {k['at_s']} s: seen before {k['must_hold']} (newest {k['newest_seen']}), "
            f"file {k.get('file')}, next life first {k.get('restored_first_seen')} "
            f"({'warm' if k.get('warm') else 'cold'}): {'ok' if k.get('ok') else 'NOT OK'}"
        )
    try:
        clients = json.loads(soak.client_stats.read_text())
    except (AttributeError, OSError, ValueError):
        clients = {"counts": {}, "samples": {}}
    counts = clients["counts"]
    print(f"client requests {sum(counts.values())}:")
    for key, count in sorted(counts.items()):
        print(f"  {count:7} {key}")
    unexpected = {k: v for k, v in counts.items() if "unexpected" in k or (" ok" not in k and "(PLC down)" not in k)}
    for key in unexpected:
        print(f"    sample of {key}: {clients['samples'].get(key, '')}")
        times = clients.get("times", {}).get(key, ())
        when = Counter(attribute(t, soak, 10.0) for t in times)
        print("      when (the first 50): " + ", ".join(f"{v} in {k}" for k, v in when.most_common()))
        t0 = getattr(soak, "t0", 0.0)
        events = [*soak.events, *((lf.started, f"life {lf.n} start") for lf in soak.lives)]
        events += [
            (f[k], f"bus {k}") for lf in soak.lives for f in lf.data.get("faults", ()) for k in ("on", "off") if k in f
        ]
        for t in times[:5]:  # each, with every event near it: a busy host does not hide a kill
            near = sorted({f"{kind} {t - at:+.1f} s" for at, kind in events if abs(t - at) <= 30})
            print(f"      at {t - t0:.1f} s" + (f" ({', '.join(near)})" if near else ""))
    tracebacks, kinds, first = log_lines(lives)
    print(f"log: {tracebacks} traceback(s); warnings and errors by kind ({sum(kinds.values())}):")
    for text, count in kinds.most_common(12):
        print(f"  {count:6} {text}")
    for line in first:
        print(f"  traceback: {line[:400]}")
    if tracebacks:
        soak.problems.append(f"{tracebacks} traceback(s) in the PLC's log")
    if total_over:
        soak.problems.append(f"{total_over} overrun(s)")
    print("problems: " + ("none" if not soak.problems else ""))
    for p in soak.problems:
        print(f"  {p}")
    return 1 if soak.problems else 0
