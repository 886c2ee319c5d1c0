"""One slave as the CANopen manager sees it: its boot-up, its heartbeat, its
emergencies. A small state machine driven by frames and by time, with no
bus access of its own: it returns what to do, the master does it.

    INIT ──reset communication──> BOOTING ──boot-up──> CONFIGURING ──SDO writes ok──> OPERATIONAL
      ^                             │ no boot-up           │ SDO error                   │ heartbeat lost
      └──── retry time later ─── MISSING / CONFIG_ERROR <──┘                            v
      └──── a heartbeat or boot-up again, or retry time later ──────────────────────── LOST

A node in OPERATIONAL whose heartbeat reports another NMT state (it fell to
pre-operational after it lost the master, it was reset) is booted again.

Node guarding (CiA 301) instead of a heartbeat: in OPERATIONAL and LOST the
master asks every guard time (an RTR at 0x700 + id, guard_due) and the node
answers with its state and a toggle bit (guard_reply). No good answer for
guard time x life time factor is a lost node; a reply whose toggle did not
alternate is no good answer (a reply went missing). A lost node that
answers again is booted afresh, as one whose heartbeat comes back. A
guarded node sends nothing unasked, so the master keeps asking while it
waits for it (MISSING, and BOOTING: a reset sent while the cable was cut
never reached it) and boots it as soon as it answers: a node booted a
guard time ago that answers without having sent its boot-up missed the
reset, and is reset again. Without that a drive whose cable came back
waited the boot timeout and the retry time (2.2 s), though it was heard.

Boots are rate-limited: a node is booted (reset communication, or
configured after a boot-up it sent unasked) at most BOOT_BURST times in any
BOOT_WINDOW_NS. A flood of NMT reset-node commands or of bogus heartbeat
states (anyone on the bus can send them) made the master boot a node 100
times a second; beyond the limit the node is held LOST until its next boot
is due, and what it sends meanwhile starts nothing.
"""

from __future__ import annotations

from collections import deque
from dataclasses import dataclass
from enum import IntEnum

from .cia301 import STATE_BOOTUP, STATE_NAMES, STATE_OPERATIONAL

#: the emergencies a node keeps for the monitors (Driver.details), newest last
EMCY_HISTORY = 10
#: at most BOOT_BURST boots of a node in any BOOT_WINDOW_NS (a flood of resets or bogus heartbeats)
BOOT_BURST = 3
BOOT_WINDOW_NS = 10_000_000_000


class NodeState(IntEnum):
    """As CANOPEN_NODE[n].State shows it to the program (fblocks/comm/canopen_diag.st)."""

    UNKNOWN = 0
    BOOTING = 1  # reset communication sent, waiting for the boot-up
    CONFIGURING = 2  # boot-up seen, SDO configuration running
    OPERATIONAL = 3  # started, heartbeat (if any) arriving
    MISSING = 4  # no boot-up within the boot timeout
    LOST = 5  # heartbeat stopped, or the node left OPERATIONAL
    CONFIG_ERROR = 6  # an SDO write of the configuration failed


@dataclass
class Emergency:
    code: int  # the EMCY error code (0 = error reset / no error)
    register: int  # error register (0x1001)
    data: bytes  # manufacturer-specific bytes
    time_ns: int


#: where a guarded node is asked (guard_due): running, and while the master waits to hear it
_GUARDED_STATES = frozenset((NodeState.OPERATIONAL, NodeState.LOST, NodeState.MISSING, NodeState.BOOTING))


class NodeSupervisor:
    def __init__(
        self,
        name: str,
        node_id: int,
        *,
        mandatory: bool,
        heartbeat_timeout_ns: int,
        boot_timeout_ns: int,
        retry_ns: int,
        guard_ns: int = 0,
        life_time_factor: int = 0,
    ) -> None:
        self.name = name
        self.node_id = node_id
        self.mandatory = mandatory
        self.heartbeat_timeout_ns = heartbeat_timeout_ns
        self.boot_timeout_ns = boot_timeout_ns
        self.retry_ns = retry_ns
        self.guard_ns = guard_ns  # 0: the node is not guarded
        self.life_ns = guard_ns * life_time_factor
        self.next_guard_ns = 0
        self.expected_toggle = 0  # bit 7 of the next guarding reply
        self.toggle_errors = 0
        self.state = NodeState.UNKNOWN
        self.nmt_state: int | None = None  # last state byte of its heartbeat
        self.deadline_ns: int | None = None  # boot-up wait, heartbeat watch or retry
        self.boots = 0  # boot-ups seen
        self._booted: deque[int] = deque(maxlen=BOOT_BURST)  # when the latest boots started
        self.boot_sent_ns = 0  # when the master last sent a reset communication (BOOTING since)
        self.held_until_ns: int | None = None  # boots held off until then (BOOT_BURST reached)
        self.held_off = 0  # boots the limit held off
        self.emergencies = 0
        self.malformed = 0  # its frames dropped as malformed (an EMCY or heartbeat of the wrong length ...)
        self.last_emcy: Emergency | None = None
        self.emcy_history: deque[Emergency] = deque(maxlen=EMCY_HISTORY)
        self.message = ""
        self.version = 0  # bumped on every change the program can see

    def _enter(self, state: NodeState, deadline_ns: int | None, message: str = "") -> None:
        self.state = state
        self.deadline_ns = deadline_ns
        self.message = message
        self.version += 1

    # ------------------------------------------------------------ events -> actions
    # Each returns the action the master must take: None, "reset", "configure", "start",
    # "hold" (a boot held off: the master logs it).

    def tick(self, now_ns: int) -> str | None:
        if self.state == NodeState.UNKNOWN:
            return self._boot(now_ns, timed=True)
        if self.deadline_ns is None or now_ns < self.deadline_ns:
            return None
        if self.state == NodeState.BOOTING:
            self._enter(
                NodeState.MISSING, now_ns + self.retry_ns, f"no boot-up within {self.boot_timeout_ns // 1_000_000} ms"
            )
        elif self.state == NodeState.OPERATIONAL:
            lost = (
                f"node guarding lost (no good reply for {self.life_ns // 1_000_000} ms)"
                if self.guard_ns
                else f"heartbeat lost (none for {self.heartbeat_timeout_ns // 1_000_000} ms)"
            )
            self._enter(NodeState.LOST, now_ns + self.retry_ns, lost)
        elif self.state in (NodeState.MISSING, NodeState.LOST, NodeState.CONFIG_ERROR):
            return self._boot(now_ns, timed=True)
        return None

    def _may_boot(self, now_ns: int) -> bool:
        """Fewer than BOOT_BURST boots in the last BOOT_WINDOW_NS: counts
        this one; else the node is held off (held_until_ns)."""
        if len(self._booted) == BOOT_BURST and now_ns < self._booted[0] + BOOT_WINDOW_NS:
            self.held_off += 1
            return False
        self._booted.append(now_ns)
        self.held_until_ns = None
        return True

    def _hold(self, now_ns: int, why: str) -> str | None:
        """Held off: LOST until the next boot is due ("hold" the first time,
        for the master's log; nothing for what comes meanwhile)."""
        until = self._booted[0] + BOOT_WINDOW_NS
        if self.held_until_ns == until and self.state == NodeState.LOST:
            return None
        self.held_until_ns = until
        self._enter(
            NodeState.LOST,
            until,
            f"{why}; booted {BOOT_BURST} times in {BOOT_WINDOW_NS // 1_000_000_000} s (a flood of resets or bogus "
            f"heartbeats?): the next boot in {(until - now_ns) // 1_000_000} ms",
        )
        return "hold"

    def _boot(self, now_ns: int, message: str = "", *, timed: bool = False) -> str | None:
        """Reset communication (the master sends it), or held off. A timed
        boot (the first, a retry after the retry time) is paced by its
        deadline; one a frame asks for counts against BOOT_BURST."""
        if timed:
            self.held_until_ns = None
        elif not self._may_boot(now_ns):
            return self._hold(now_ns, message or "node heard again")
        self._enter(NodeState.BOOTING, now_ns + self.boot_timeout_ns, message)
        self.boot_sent_ns = now_ns
        return "reset"

    def _seen(self, state_byte: int) -> None:
        if state_byte != self.nmt_state:
            self.nmt_state = state_byte
            self.version += 1

    def _restart_unless_operational(self, state_byte: int, now_ns: int) -> str | None:
        """An OPERATIONAL node that reports another state is booted again."""
        if state_byte == STATE_OPERATIONAL:
            return None
        reported = STATE_NAMES.get(state_byte, hex(state_byte))
        return self._boot(now_ns, f"node reported {reported}")

    def heartbeat(self, state_byte: int, now_ns: int) -> str | None:
        state_byte &= 0x7F
        self._seen(state_byte)
        if state_byte == STATE_BOOTUP:
            self.boots += 1
            self.version += 1
            if self.state == NodeState.CONFIGURING:
                return None  # a second boot-up while configuring: the running writes decide
            # the answer to our reset communication, or a boot it started by itself (counted)
            if self.state != NodeState.BOOTING and not self._may_boot(now_ns):
                return self._hold(now_ns, "node sent a boot-up")
            self._enter(NodeState.CONFIGURING, None)
            return "configure"
        if self.state == NodeState.OPERATIONAL:
            if state_byte != STATE_OPERATIONAL:
                return self._restart_unless_operational(state_byte, now_ns)
            if self.heartbeat_timeout_ns:
                self.deadline_ns = now_ns + self.heartbeat_timeout_ns
        elif self.state in (NodeState.LOST, NodeState.MISSING):
            # It is back (it never booted again: a cable was cut): boot it afresh.
            return self._boot(now_ns)
        return None

    def configured(self, ok: bool, message: str, now_ns: int) -> str | None:
        if self.state != NodeState.CONFIGURING:
            return None
        if not ok:
            self._enter(NodeState.CONFIG_ERROR, now_ns + self.retry_ns, message)
            return None
        if self.guard_ns:  # the node's first reply after its boot-up has toggle 0
            self.expected_toggle = 0
            self.next_guard_ns = now_ns
            self._enter(NodeState.OPERATIONAL, now_ns + self.life_ns)
        else:
            watch = now_ns + self.heartbeat_timeout_ns if self.heartbeat_timeout_ns else None
            self._enter(NodeState.OPERATIONAL, watch)
        return "start"

    # ------------------------------------------------------------ node guarding

    def guard_due(self, now_ns: int) -> bool:
        """Time to send a guarding request (the master sends the RTR)."""
        if not self.guard_ns or self.state not in _GUARDED_STATES:
            return False
        if self.state == NodeState.BOOTING and now_ns < self.boot_sent_ns + self.guard_ns:
            return False  # its boot-up is due first: a request now would start its life guarding early
        if now_ns < self.next_guard_ns:
            return False
        self.next_guard_ns = now_ns + self.guard_ns
        return True

    def guard_reply(self, state_byte: int, now_ns: int) -> str | None:
        """A guarding reply: the NMT state in bits 0-6, the toggle in bit 7."""
        toggle, state_byte = state_byte & 0x80, state_byte & 0x7F
        self._seen(state_byte)
        if self.state in (NodeState.LOST, NodeState.MISSING):
            return self._boot(now_ns)  # it is back: boot it afresh
        if self.state == NodeState.BOOTING and now_ns >= self.boot_sent_ns + self.guard_ns:
            # alive a guard time after the reset, and no boot-up: the reset never reached it
            return self._boot(now_ns, "node answered guarding but sent no boot-up")
        if self.state != NodeState.OPERATIONAL:
            return None
        if state_byte != STATE_OPERATIONAL:
            return self._restart_unless_operational(state_byte, now_ns)
        good = toggle == self.expected_toggle
        self.expected_toggle = toggle ^ 0x80  # follow the node either way
        if good:
            self.deadline_ns = now_ns + self.life_ns
        else:
            self.toggle_errors += 1
            self.version += 1
        return None

    def emergency(self, emcy: Emergency) -> None:
        self.emergencies += 1
        self.last_emcy = emcy
        self.emcy_history.append(emcy)
        self.version += 1

    def malformed_frame(self) -> None:
        self.malformed += 1
        self.version += 1
