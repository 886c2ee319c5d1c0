"""Error control of a simulated CANopen slave (CiA 301), the part of
SimulatedCanopenSlave that watches and is watched: the heartbeat producer
(0x1017), heartbeat consumers (0x1016), node guarding replies and life
guarding (0x100C x 0x100D), and what a communication error does (0x1029).

A communication error (a watched heartbeat or the master's guarding
requests stopped) calls the device's on_comm_error() and changes the NMT
state as 0x1029:01 says; its end calls on_comm_restored(). A communication
reset (the master booting the node again) does not end it: the device hears
it is over from the first guarding request, or heartbeat of a watched
producer, after the reset. A reset of the application starts afresh.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

from .cia301 import (
    CONSUMER_HEARTBEAT,
    GUARD_TIME,
    LIFE_TIME_FACTOR,
    PRODUCER_HEARTBEAT,
    STATE_OPERATIONAL,
    STATE_PRE_OPERATIONAL,
    STATE_STOPPED,
    cob_heartbeat,
)

if TYPE_CHECKING:
    from ..ratelog import RateLimitedLog


MS = 1_000_000
_NEVER = 1 << 63  # later than any engine time
GUARDING_TOGGLE = 0x80  # bit 7 of a guarding reply
ERROR_BEHAVIOUR = 0x1029

# 0x1029:01, on a communication error (manual 001 L1017-1030)
ERROR_TO_PRE_OPERATIONAL = 0
ERROR_NO_STATE_CHANGE = 1
ERROR_TO_STOPPED = 2


@dataclass
class _Consumer:
    """One heartbeat consumer entry of 0x1016."""

    producer: int
    timeout_ns: int
    last_ns: int | None = None  # None: not monitoring yet (CiA 301: starts with the first heartbeat)
    lost: bool = False


class ErrorControlMixin:
    """Heartbeat and guarding for SimulatedCanopenSlave (see the module docstring)."""

    od: Any
    name: str
    node_id: int
    _state: int
    lines: RateLimitedLog  # what it logs, rate limited

    # provided by SimulatedCanopenSlave
    def _value(self, index: int, subindex: int) -> int:
        raise NotImplementedError

    def _cached_value(self, index: int, subindex: int) -> int:
        raise NotImplementedError

    def _send(self, can_id: int, data: bytes) -> None:
        raise NotImplementedError

    def _set_state(self, new: int) -> None:
        raise NotImplementedError

    def on_comm_error(self) -> None:
        raise NotImplementedError

    def on_comm_restored(self) -> None:
        raise NotImplementedError

    def _init_error_control(self) -> None:
        self._consumers: list[_Consumer] | None = None
        self._heartbeat_due: int | None = None
        self._guard_toggle = 0  # bit 7 of the next guarding reply
        self._guarded_ns: int | None = None  # the last guarding request (None: not guarded yet)
        self._guarding_lost = False
        self._error_pending = False  # a communication error from before a communication reset
        self._has_guarding = GUARD_TIME in self.od and LIFE_TIME_FACTOR in self.od  # the EDS decides, once
        #: before this time _error_control() has nothing to do (0: look again); see _error_control_due()
        self._error_quiet_until = 0

    def _error_outlives_reset(self, application: bool) -> bool:
        """Before a reset: whether a communication error stays pending after it."""
        if application:
            return False
        return self._error_pending or self._guarding_lost or (self._consumers is not None and self.heartbeat_lost)

    def _restart_error_control(self, now: int, pending: bool) -> None:
        """After a reset of the communication objects: consumers read again,
        guarding from the start, the first heartbeat one period on."""
        self._consumers = None
        self._guard_toggle = 0
        self._guarded_ns = None
        self._guarding_lost = False
        self._error_pending = pending
        period = self._heartbeat_period_ns()
        self._heartbeat_due = now + period if period else None
        self._error_quiet_until = 0

    def _error_control(self, now: int) -> None:
        """At each service step outside boot-up: skipped before the next
        heartbeat to send or deadline to watch (_error_control_due)."""
        if now < self._error_quiet_until:
            return
        self._produce_heartbeat(now)
        self._watch_heartbeats(now)
        self._watch_guarding(now)
        self._error_quiet_until = self._error_control_due()

    def _error_control_due(self) -> int:
        """The first time at which _error_control() would do anything, as
        things stand: the next heartbeat to send, the moment a watched
        producer's heartbeat or the master's guarding is overdue. A received
        heartbeat or guarding request, a reset and a write of the objects
        (_forget_cached) change that, and set _error_quiet_until to 0."""
        due = self._heartbeat_due if self._heartbeat_due is not None else _NEVER
        for consumer in self._heartbeat_consumers():
            if consumer.last_ns is not None and not consumer.lost:
                due = min(due, consumer.last_ns + consumer.timeout_ns + 1)  # lost when more than the timeout
        if self._guarded_ns is not None and not self._guarding_lost:
            life = self._life_time_ns()
            if life:
                due = min(due, self._guarded_ns + life + 1)
        return due

    @property
    def heartbeat_lost(self) -> bool:
        """A watched producer's heartbeat is missing right now."""
        return any(c.lost for c in self._heartbeat_consumers())

    @property
    def guarding_lost(self) -> bool:
        """The master's guarding requests stopped for longer than the life time."""
        return self._guarding_lost

    # ------------------------------------------------------------------ heartbeat (CiA 301)

    def _heartbeat_period_ns(self) -> int:
        return self._cached_value(PRODUCER_HEARTBEAT, 0) * MS if PRODUCER_HEARTBEAT in self.od else 0

    def _produce_heartbeat(self, now: int) -> None:
        if self._heartbeat_due is None or now < self._heartbeat_due:
            return
        self._send(cob_heartbeat(self.node_id), bytes([self._state]))
        period = self._heartbeat_period_ns()
        due = self._heartbeat_due + period
        self._heartbeat_due = due if due > now else now + period  # no burst after a long gap

    def _heartbeat_consumers(self) -> list:
        if self._consumers is None:
            self._consumers = []
            obj = self.od.get(CONSUMER_HEARTBEAT)
            if obj is not None:
                for sub in sorted(obj.subindices):
                    if sub == 0:
                        continue
                    entry = self._value(CONSUMER_HEARTBEAT, sub)
                    producer, time_ms = (entry >> 16) & 0xFF, entry & 0xFFFF
                    if 1 <= producer <= 127 and time_ms:  # 0 = entry not used
                        self._consumers.append(_Consumer(producer, time_ms * MS))
        return self._consumers

    def _on_heartbeat(self, producer: int, now: int) -> None:
        self._error_quiet_until = 0
        was_lost = self.heartbeat_lost
        watched = False
        for consumer in self._heartbeat_consumers():
            if consumer.producer == producer:
                consumer.last_ns = now
                consumer.lost = False
                watched = True
        if (was_lost or (self._error_pending and watched)) and not self.heartbeat_lost:
            self._error_pending = False
            self.on_comm_restored()

    def _watch_heartbeats(self, now: int) -> None:
        for consumer in self._heartbeat_consumers():
            if consumer.last_ns is None or consumer.lost:
                continue
            if now - consumer.last_ns > consumer.timeout_ns:
                consumer.lost = True
                self.lines.info(
                    ("heartbeat lost", consumer.producer), "%s: heartbeat of node %d lost", self.name, consumer.producer
                )
                self._communication_error()

    # ------------------------------------------------------------------ node guarding (CiA 301)

    def _life_time_ns(self) -> int:
        """Guard time x life time factor (0: the node does not watch the master)."""
        if not self._has_guarding:
            return 0
        return self._cached_value(GUARD_TIME, 0) * self._cached_value(LIFE_TIME_FACTOR, 0) * MS

    def _on_guarding_request(self, now: int) -> None:
        """An RTR at 0x700 + node id: answer with the NMT state and the toggle
        bit. A node producing heartbeats does not take part in guarding."""
        if self._heartbeat_period_ns():
            return
        self._error_quiet_until = 0
        self._send(cob_heartbeat(self.node_id), bytes([self._state | self._guard_toggle]))
        self._guard_toggle ^= GUARDING_TOGGLE
        self._guarded_ns = now
        if self._guarding_lost or self._error_pending:
            self._guarding_lost = self._error_pending = False
            self.lines.info(None, "%s: guarding by the master resumed", self.name)
            if not self.heartbeat_lost:
                self.on_comm_restored()

    def _watch_guarding(self, now: int) -> None:
        """Life guarding: from the first request on, a gap longer than the life
        time is a communication error."""
        if self._guarded_ns is None or self._guarding_lost:
            return
        life = self._life_time_ns()
        if not life:
            return
        if now - self._guarded_ns > life:
            self._guarding_lost = True
            self.lines.info(None, "%s: no guarding request for %d ms (life time)", self.name, life // MS)
            self._communication_error()

    def _communication_error(self) -> None:
        self.on_comm_error()
        behaviour = ERROR_TO_PRE_OPERATIONAL
        if ERROR_BEHAVIOUR in self.od:
            behaviour = self._value(ERROR_BEHAVIOUR, 1)
        if behaviour == ERROR_TO_PRE_OPERATIONAL and self._state == STATE_OPERATIONAL:
            self._set_state(STATE_PRE_OPERATIONAL)  # CiA 301: only from Operational
        elif behaviour == ERROR_TO_STOPPED:
            self._set_state(STATE_STOPPED)
