"""What else the host was doing during a live soak: every second, the CPU
that processes outside the soak's own tree (this script, the PLC, its
servers' and compile processes, the clients) used, in cores, and the CPU
time the hypervisor gave to other guests while this one's were ready
(steal, /proc/stat). A soak at normal priority shares the machine; a tick
late because another process held the core, or because the virtual CPU
did not run at all, is the host's, not the PLC's, and the report says
which is which (soak_live_report.attribute)."""

from __future__ import annotations

import os
import threading
import time

_TICK = os.sysconf("SC_CLK_TCK")


def _processes() -> dict:
    """pid -> (ppid, utime + stime in clock ticks) of every process now."""
    out: dict = {}
    for name in os.listdir("/proc"):
        if not name.isdigit():
            continue
        try:
            with open(f"/proc/{name}/stat", "rb") as f:
                text = f.read().decode("ascii", "replace")
        except OSError:
            continue
        fields = text[text.rfind(")") + 2 :].split()  # after "pid (comm) "
        out[int(name)] = (int(fields[1]), int(fields[11]) + int(fields[12]))
    return out


def _steal() -> int:
    """Clock ticks of steal time of all the CPUs since boot (0 where not counted)."""
    try:
        with open("/proc/stat", "rb") as f:
            fields = f.readline().split()  # cpu user nice system idle iowait irq softirq steal ...
        return int(fields[8]) if len(fields) > 8 else 0
    except (OSError, ValueError):
        return 0


def _tree(procs: dict, root: int) -> set:
    children: dict = {}
    for pid, (ppid, _t) in procs.items():
        children.setdefault(ppid, []).append(pid)
    out, pending = set(), [root]
    while pending:
        pid = pending.pop()
        out.add(pid)
        pending += children.get(pid, ())
    return out


def _around(samples: dict, wall: float) -> float:
    """The greater of the samples taken in the second of wall and in the
    next (a sample, keyed by the second it was taken in, covers the second
    before it)."""
    second = int(wall)
    return max(samples.get(second, 0.0), samples.get(second + 1, 0.0))


class HostLoad:
    """others[int(wall second)] = cores used by processes outside the tree
    of root; stolen[int(wall second)] = cores the hypervisor took."""

    def __init__(self, root: int | None = None, period_s: float = 1.0) -> None:
        self.root = root or os.getpid()
        self.period_s = period_s
        self.others: dict[int, float] = {}
        self.stolen: dict[int, float] = {}
        self._stop = threading.Event()
        self._thread = threading.Thread(target=self._run, name="host-load", daemon=True)

    def start(self) -> None:
        self._thread.start()

    def stop(self) -> None:
        self._stop.set()
        self._thread.join(5)

    def _run(self) -> None:
        before, steal = _processes(), _steal()
        t0 = time.time()
        while not self._stop.wait(self.period_s):
            now_procs, now_steal, t1 = _processes(), _steal(), time.time()
            ours = _tree(now_procs, self.root)
            used = sum(
                ticks - before.get(pid, (0, ticks))[1]
                for pid, (ppid, ticks) in now_procs.items()
                if pid not in ours and ppid != 2 and pid != 2  # not a kernel thread
            )
            self.others[int(t1)] = used / _TICK / (t1 - t0)
            self.stolen[int(t1)] = (now_steal - steal) / _TICK / (t1 - t0)
            before, steal, t0 = now_procs, now_steal, t1

    def busy(self, wall: float, cores: float = 0.2) -> bool:
        """Whether others used at least cores around wall (_around)."""
        return _around(self.others, wall) >= cores

    def stole(self, wall: float) -> float:
        """The cores the hypervisor took around wall (_around)."""
        return _around(self.stolen, wall)

    def summary(self) -> str:
        if not self.others:
            return "host: not sampled"
        values = sorted(self.others.values())
        busy = sum(1 for v in values if v >= 0.2)
        stolen = [v for v in self.stolen.values() if v > 0]
        return (
            f"host: other processes used {sum(values) / len(values):.2f} cores on average, "
            f"max {values[-1]:.2f}; {busy} of {len(values)} s with 0.2 cores or more; "
            f"the hypervisor took CPU time (steal) in {len(stolen)} s, "
            f"{sum(stolen):.2f} core-seconds in all, max {max(stolen, default=0.0):.2f} cores in a second"
        )
