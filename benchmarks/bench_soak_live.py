"""Live soak (issue 31): the default plant on the REAL clock, at normal
priority, with its web page, OPC UA server and Modbus TCP server on
127.0.0.1, under random server clients, bus faults, online changes and
kill -9, for --minutes of wall time. bench_soak.py is the same plant in
virtual time (faults) and a bare retain example killed; this is the live PLC.

The PLC: io_config/default.toml (CANopen LTMR and FC 280 on python-can's
virtual bus, the DA1 on Modbus RTU over a pseudo-terminal, tasks of 10, 20
and 100 ms) plus soak.st, written here: PROGRAM Soak in the 100 ms task, its
VAR RETAIN `kept` and the VAR_GLOBAL PERSISTENT `gSoakTotal` counting its
scans, a CONSTANT `version` (copied to `running`) that each online change
edits, and `setpoint`, `note`, `flag`, `count` for the clients to write;
[retain] period 200 ms; [web], [opcua], [modbus_server] on free ports.
It runs as `softplc run` does (launch.run_plc) in soak_live_plc.py, which
also cuts the buses at random moments from inside the PLC's process (one
fault at a time, 20-60 s apart, 3-15 s long) and writes the engine's counters
and a histogram of how late each tick began every second.

Beside it:
* the clients (soak_live_clients.py), one process for the whole soak: web,
  OPC UA and Modbus TCP requests, well-formed and hostile-but-legal;
* online changes every --change-every seconds (and one in each life's
  warm-up, whose first change keeps the replaced program in memory once),
  alternately through the web page's POST /api/online-change and by the
  file watcher alone; each must show its new `version` in the PLC within 10 s;
* --kills SIGKILLs at random moments; after each the retain file must read
  back (retain_file.read_file, as a start reads it) with kept = gSoakTotal,
  holding at least the newest value seen 0.7 s (a retain period and a save)
  before the kill; the next life must start warm with it restored (the first
  value seen not below it). The last life stops with SIGTERM and exit 0.

A monitor (an event stream of the web page, in this process) watches the
counter. RSS of the PLC's process (and of its servers' process) is taken
after each life's warm-up and at its end. The report: wall time, scans,
overruns per task (the engine's counters), tick lateness p50/p99/max, RSS
per life, client requests by kind, faults injected/seen/recovered, online
changes, kills and retained values, log lines with a traceback (must be 0).
Exit 1 when anything failed.

    python benchmarks/bench_soak_live.py --minutes 60          # the hour (3 kills)
    python benchmarks/bench_soak_live.py --minutes 3 --kills 1
    python benchmarks/bench_soak_live.py --minutes 20 --without clients   # whose memory?
"""

from __future__ import annotations

import argparse
import multiprocessing
import os
import random
import shutil
import signal
import socket
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from soak_live_host import HostLoad
from soak_live_report import Life, Monitor, children, percentiles, report, rss_kb, web_post

from softplc.runtime.engine.retain_file import RetainFileError, read_file

ROOT = Path(__file__).resolve().parents[1]
HERE = Path(__file__).resolve().parent
RETAIN_PERIOD_S = 0.2
SAVE_MARGIN_S = 0.5  # a save's own time (fsync) and a snapshot's age
SEEN_WITHIN_S = 10.0

SOAK_ST = """\
VAR_GLOBAL PERSISTENT
    gSoakTotal : UDINT;
END_VAR

PROGRAM Soak
VAR CONSTANT
    version : INT := {version};
END_VAR
VAR
    running : INT;
    setpoint : REAL := 1.0;
    note : STRING[20];
    flag : BOOL;
    count : DINT;
END_VAR
VAR RETAIN
    kept : UDINT;
END_VAR
kept := kept + 1;
gSoakTotal := gSoakTotal + 1;
running := version;
count := count + 1;
END_PROGRAM
"""


def free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def make_config(tmp: Path, ports: dict) -> Path:
    """default.toml with absolute paths, soak.st in the 100 ms task, retain and the three servers."""
    text = (ROOT / "io_config" / "default.toml").read_text()
    text = text.replace('"../st_programs/', f'"{ROOT}/st_programs/')
    text = text.replace('fc280_pump.st"]', f'fc280_pump.st", "{tmp}/soak.st"]')
    text = text.replace('programs = ["Panel"]', 'programs = ["Panel", "Soak"]')
    text = text.replace('channel = "softplc-default"', f'channel = "soak-live-{ports["web"]}"')
    (tmp / "soak.st").write_text(SOAK_ST.format(version=0))
    text += f"""
[retain]
file = "{tmp}/soak.retain"
period = "{RETAIN_PERIOD_S * 1000:g}ms"

[web]
port = {ports["web"]}
writable = ["Soak.*"]

[opcua]
port = {ports["opcua"]}
writable = ["Soak.setpoint", "Soak.note"]

[modbus_server]
port = {ports["modbus"]}
writable = ["%MW*", "%QX100.*"]
"""
    path = tmp / "soak.toml"
    path.write_text(text)
    for key in ("programs", "[web]", "[opcua]", "[modbus_server]"):
        assert key in text
    assert f"{tmp}/soak.st" in text and '"Panel", "Soak"' in text
    return path


def retained(path: Path) -> tuple:
    """(Soak.kept, gSoakTotal) as a start reads the retain file."""
    data = read_file(path)
    if data is None:
        raise RetainFileError("no retain file")
    found = {name.upper(): v["value"] for name, v in data.vars.items()}
    return found["SOAK.KEPT"], found["GSOAKTOTAL"]


def schedule_kills(rng: random.Random, kills: int, total_s: float) -> list:
    lo, hi = 90.0, total_s - 60.0
    if kills <= 0 or hi <= lo:
        return []
    for _ in range(1000):
        times = sorted(rng.uniform(lo, hi) for _ in range(kills))
        if all(b - a >= 60 for a, b in zip(times, times[1:], strict=False)):
            return times
    return sorted(rng.uniform(lo, hi) for _ in range(kills))


class Soak:
    def __init__(self, args, tmp: Path) -> None:
        self.args = args
        self.tmp = tmp
        self.ports = {"web": free_port(), "opcua": free_port(), "modbus": free_port()}
        self.config = make_config(tmp, self.ports)
        self.retain = tmp / "soak.retain"
        self.version = 0
        self.lives: list[Life] = []
        self.changes: list = []  # (method, applied, seen)
        self.kills: list = []  # dicts: the kill's retained-data checks
        self.problems: list = []
        self.events: list = []  # (wall, "change" | "kill") for the attribution of late ticks and errors
        self.monitor = Monitor(self.ports["web"])
        self.host = HostLoad()  # what processes outside the soak's tree used

    # ------------------------------------------------------------ a life

    def start_life(self) -> Life:
        n = len(self.lives) + 1
        life = Life(n, self.tmp / f"stats-{n}.json", self.tmp / f"plc-{n}.log")
        stderr = open(life.log, "w")
        life.proc = subprocess.Popen(
            [
                sys.executable,
                str(HERE / "soak_live_plc.py"),
                str(self.config),
                str(life.stats),
                str(life.log) + ".file",
                str(self.args.seed * 100 + n),
                "no-faults" if "faults" in self.args.without else "faults",
            ],
            stdin=subprocess.DEVNULL,
            stdout=subprocess.DEVNULL,
            stderr=stderr,
            cwd=self.tmp,
            env={**os.environ, "SOFTPLC_SOAK_TRACE_MEMORY": str(self.tmp / f"memory-{n}.txt")}
            if self.args.trace_memory
            else None,
        )
        stderr.close()
        life.started = time.time()
        self.lives.append(life)
        self.monitor.reset()
        deadline = time.monotonic() + 120
        while self.monitor.first() is None:
            if life.proc.poll() is not None or time.monotonic() > deadline:
                self.problems.append(f"life {n} did not start (exit {life.proc.poll()}); see {life.log}")
                raise SystemExit(self.finish_report())
            time.sleep(0.2)
        life.first_seen = self.monitor.first()
        life.warm = self.restored(life)
        return life

    @staticmethod
    def restored(life: Life, wait_s: float = 10.0) -> bool:
        """Whether the life's log says its retained data was restored; the
        line may reach the file after the first value reached the monitor
        (a life was once taken for a cold start that way)."""
        deadline = time.monotonic() + wait_s
        while True:
            if "retained variable(s) restored" in life.log.read_text(errors="replace"):
                return True
            if time.monotonic() > deadline:
                return False
            time.sleep(0.2)

    def end_life(self, life: Life, kill: bool) -> None:
        life.rss_end = rss_kb(life.proc.pid)
        life.servers_end = sum(rss_kb(c) for c in children(life.proc.pid))
        self.monitor.pause()
        if kill:
            t_kill = time.time()
            self.events.append((t_kill, "kill"))
            life.proc.send_signal(signal.SIGKILL)
            life.proc.wait(30)
            self.check_kill(life, t_kill)
        else:
            life.proc.send_signal(signal.SIGTERM)
            life.code = life.proc.wait(60)
            if life.code != 0:
                self.problems.append(f"life {life.n}: the stop by SIGTERM exited {life.code}")
            self.check_stop()
        life.ended = time.time()
        life.read_stats()

    def check_kill(self, life: Life, t_kill: float) -> None:
        seen = self.monitor.values_before(t_kill - RETAIN_PERIOD_S - SAVE_MARGIN_S)
        newest = self.monitor.values_before(t_kill)
        entry = {"life": life.n, "at_s": round(t_kill - self.t0, 1), "must_hold": seen, "newest_seen": newest}
        try:
            kept, total = retained(self.retain)
            entry.update(file=kept, ok=kept == total and (seen is None or kept >= seen))
            if kept != total:
                self.problems.append(f"kill {len(self.kills) + 1}: kept {kept} != gSoakTotal {total} in the file")
            elif seen is not None and kept < seen:
                self.problems.append(f"kill {len(self.kills) + 1}: the file holds {kept}, below {seen} seen before")
        except (RetainFileError, KeyError, OSError) as exc:
            entry.update(file=None, ok=False)
            self.problems.append(f"kill {len(self.kills) + 1}: the retain file does not read back: {exc}")
        self.kills.append(entry)

    def check_stop(self) -> None:
        newest = self.monitor.values_before(time.time())
        try:
            kept, total = retained(self.retain)
        except (RetainFileError, KeyError, OSError) as exc:
            self.problems.append(f"the stop: the retain file does not read back: {exc}")
            return
        if kept != total or (newest is not None and kept < newest):
            self.problems.append(f"the stop: file kept {kept}, gSoakTotal {total}, last seen {newest}")

    def after_restart(self, life: Life) -> None:
        """The life after a kill: warm, and its first value not below the file's."""
        kill = self.kills[-1]
        kill["restored_first_seen"] = life.first_seen
        kill["warm"] = life.warm
        if not life.warm:
            self.problems.append(f"life {life.n}: not a warm start with the retained data restored")
        if kill.get("file") is not None and life.first_seen < kill["file"]:
            self.problems.append(f"life {life.n}: first value {life.first_seen} below the file's {kill['file']}")

    # ------------------------------------------------------------ online change

    def online_change(self) -> None:
        self.version += 1
        method = "web" if self.version % 2 else "file"
        self.events.append((time.time(), "change"))
        (self.tmp / "soak.st").write_text(SOAK_ST.format(version=self.version))
        applied = None
        if method == "web":
            status, body = web_post(self.ports["web"], "/api/online-change", {}, timeout=60)
            applied = status == 200 and bool(body.get("applied"))
            if status == 409:  # the file watcher took it first: its report is in the log
                applied = None
        deadline = time.monotonic() + SEEN_WITHIN_S
        seen = False
        while time.monotonic() < deadline:
            if self.monitor.running == self.version:
                seen = True
                break
            time.sleep(0.1)
        self.changes.append((method, applied, seen))
        if not seen:
            self.problems.append(f"online change {self.version} ({method}) not seen within {SEEN_WITHIN_S:g} s")

    # ------------------------------------------------------------ the run

    def run(self) -> int:
        args = self.args
        total = args.minutes * 60
        rng = random.Random(args.seed)
        kill_at = [] if "kills" in args.without else schedule_kills(rng, args.kills, total)
        ctx = multiprocessing.get_context("spawn")
        up, stop = ctx.Event(), ctx.Event()
        import soak_live_clients

        self.client_stats = self.tmp / "clients.json"
        clients = ctx.Process(
            target=soak_live_clients.run,
            args=(self.ports, args.seed, str(self.client_stats), up, stop),
            name="soak-clients",
        )
        self.t0 = time.time()
        self.monitor.start()
        self.host.start()
        life = self.start_life()
        up.set()
        if "clients" not in args.without:
            clients.start()
        changes = "changes" not in args.without
        next_change = time.time() + (args.change_every if changes else 10 * total)
        next_progress = time.time() + args.progress
        life_change_done = False
        cut: list = []  # SIGINT (Ctrl-C) or SIGTERM: end here, with the report of what ran

        def cut_short(signum, _frame) -> None:
            cut.append(signal.Signals(signum).name)

        for signum in (signal.SIGINT, signal.SIGTERM):
            signal.signal(signum, cut_short)
        while time.time() - self.t0 < total and not cut:
            now = time.time()
            if life.proc.poll() is not None:  # not a kill of ours: the soak has failed
                self.problems.append(f"life {life.n} ended by itself (exit {life.proc.returncode}); see its log")
                break
            if not life_change_done and changes and now - life.started >= min(20.0, args.warm_up / 2):
                life_change_done = True
                self.online_change()
            if life.rss_warm is None and now - life.started >= args.warm_up:
                life.rss_warm = rss_kb(life.proc.pid)
                life.servers_warm = sum(rss_kb(c) for c in children(life.proc.pid))
            if now >= next_change:
                next_change = now + args.change_every
                self.online_change()
            if kill_at and now - self.t0 >= kill_at[0]:
                kill_at.pop(0)
                up.clear()
                self.end_life(life, kill=True)
                life = self.start_life()
                up.set()
                self.after_restart(life)
                life_change_done = False
            if now >= next_progress:
                next_progress = now + args.progress
                self.progress(life)
            time.sleep(0.5)
        if cut:
            minutes = (time.time() - self.t0) / 60
            self.problems.append(f"cut short by {cut[0]} after {minutes:.1f} of {args.minutes:g} min")
        if life.rss_warm is None:
            life.rss_warm = rss_kb(life.proc.pid)
        stop.set()
        if clients.is_alive():
            clients.join(30)
        up.clear()
        if life.proc.poll() is None:
            self.end_life(life, kill=False)
        else:  # gone: no RSS at its end (the report shows none grown)
            life.ended, life.rss_end = time.time(), life.rss_warm or 0
            life.read_stats()
        self.monitor.stop()
        self.host.stop()
        self.wall = time.time() - self.t0
        return self.finish_report()

    def progress(self, life: Life) -> None:
        life.read_stats()
        scans = sum(lf.cycles() for lf in self.lives)
        overruns = sum(lf.overruns_total() for lf in self.lives)
        p50, p99, worst = percentiles(self.lives)
        print(
            f"[{(time.time() - self.t0) / 60:5.1f} min] life {life.n}: scans {scans}, overruns {overruns}, "
            f"late p50 {p50:.2f} p99 {p99:.2f} max {worst:.1f} ms, RSS {rss_kb(life.proc.pid) / 1024:.1f} MB, "
            f"changes {len(self.changes)}, kills {len(self.kills)}, kept {self.monitor.kept}",
            flush=True,
        )

    def finish_report(self) -> int:
        if not hasattr(self, "wall"):
            self.wall = time.time() - getattr(self, "t0", time.time())
        return report(self)


#: what --without can leave out (--baseline: all of them)
PARTS = ("clients", "faults", "changes", "kills")


def main(argv: list | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--minutes", type=float, default=60, help="wall minutes of the soak (default 60)")
    parser.add_argument("--seed", type=int, default=1, help="the seed of the kills, faults and clients")
    parser.add_argument("--kills", type=int, default=3, help="SIGKILLs at random moments (default 3)")
    parser.add_argument("--change-every", type=float, default=180, help="seconds between online changes (default 180)")
    parser.add_argument(
        "--warm-up", type=float, default=60, help="seconds of a life before its RSS is taken (default 60)"
    )
    parser.add_argument("--progress", type=float, default=120, help="seconds between progress lines (default 120)")
    parser.add_argument(
        "--baseline",
        action="store_true",
        help="the same PLC and servers with no client, fault, online change or kill: the host's own overruns",
    )
    parser.add_argument(
        "--without",
        action="append",
        default=[],
        choices=PARTS,
        help="leave one part out (again for another): to find which one memory or overruns come from",
    )
    parser.add_argument(
        "--trace-memory",
        action="store_true",
        help="the PLC traces its allocations (tracemalloc: slower) and writes their growth to memory-N.txt",
    )
    parser.add_argument("--keep-logs", metavar="DIR", help="copy the PLC's logs (one per life) into DIR at the end")
    args = parser.parse_args(argv)
    if args.baseline:
        args.without = list(PARTS)
    with tempfile.TemporaryDirectory(prefix="softplc-soak-live-") as tmp:
        what = (
            "baseline: no client, fault, change or kill"
            if args.baseline
            else f"seed {args.seed}, {args.kills} kills" + "".join(f", without {p}" for p in args.without)
        )
        print(f"== live soak: default plant + web, OPC UA, Modbus TCP; {args.minutes:g} min, {what}", flush=True)
        try:
            return Soak(args, Path(tmp)).run()
        finally:
            if args.keep_logs:
                Path(args.keep_logs).mkdir(parents=True, exist_ok=True)
                for log in [
                    *Path(tmp).glob("plc-*.log"),
                    *Path(tmp).glob("clients.json"),
                    *Path(tmp).glob("memory-*.txt"),
                    *Path(tmp).glob("stats-*.json"),
                ]:
                    shutil.copy(log, args.keep_logs)


if __name__ == "__main__":
    sys.exit(main())
