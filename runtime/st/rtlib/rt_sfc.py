"""What generated code calls to run an SFC network (IEC 61131-3 ed.3 6.7,
ed.2 2.6): the step flags, one evolution per cycle and the action control.

A POU with an SFC body keeps, besides its variables,

* one ``Step`` per step, a variable of the POU of the type ``STEP_TYPE``:
  ``s.X`` (active) and ``s.T`` (TIME since the step was last activated, on
  the task clock like TON; it keeps its value when the step is cleared, ed.3
  6.7.2). They are ordinary members of the instance, so ``--watch``,
  traces and the testing API see them like any struct.
* one ``ActionFlags`` per ACTION, a variable of the POU named like it, of
  the type ``ACTION_TYPE``: ``a.Q`` (the action control's output Q) and
  ``a.A`` (whether the action runs this cycle: Q, or its final scan as Q
  falls), as IEC 61131-3 ed.3 6.7.4 exposes an action's Q and A and
  CODESYS/TwinCAT their ``_a.x``. Seen like the steps.
* one ``SfcState``: an ``ActionControl`` per action.

Per cycle the generated code (codegen_sfc.py) calls ``elapse``, evaluates
the conditions of the enabled transitions (all with the state the cycle
started with), calls ``evolve`` (every transition that fires clears its
steps and activates its successors at once: one evolution per cycle, ed.3
6.7.5), then ``control`` (the action control of ed.3 6.7.4 and
ed.2 2.6.4) and runs each action whose activation is
TRUE.
"""

from __future__ import annotations

from .. import types as T

# The step flags as a STRUCT type for the checker and the value walkers
# (its class is Step, bound as _SfcStep in the generated module).
STEP_TYPE = T.StructType(
    "SFC_STEP",
    {
        "X": T.StructField("X", T.BOOL, pyname="v_x"),
        "T": T.StructField("T", T.TIME, pyname="v_t"),
    },
    pyclass="_SfcStep",
)

# An action's flags, as STEP_TYPE (its class is ActionFlags, bound as
# _SfcAction in the generated module).
ACTION_TYPE = T.StructType(
    "SFC_ACTION",
    {
        "Q": T.StructField("Q", T.BOOL, pyname="v_q"),
        "A": T.StructField("A", T.BOOL, pyname="v_a"),
    },
    pyclass="_SfcAction",
)

# Qualifiers (ed.3 6.7.4, ed.2 2.6.4) and those that take a duration.
QUALIFIERS = ("N", "R", "S", "P", "P1", "P0", "L", "D", "SD", "DS", "SL")
TIMED = frozenset(("L", "D", "SD", "DS", "SL"))

_TIME_SPAN = 1 << 32
_TIME_HALF = 1 << 31


def _elapsed(now: int, start: int) -> int:
    """now - start as a TIME (32-bit ms; right across the clock wrapping)."""
    return (now - start + _TIME_HALF) % _TIME_SPAN - _TIME_HALF


class Step:
    """An SFC step's flags: X (active) and T (elapsed TIME, ms); start is
    the task clock when it became active (None: at the first cycle)."""

    __slots__ = ("v_x", "v_t", "start")
    _VARS_ = (("X", "v_x", T.BOOL, "FIELD"), ("T", "v_t", T.TIME, "FIELD"))

    def __init__(self) -> None:
        self.v_x = False
        self.v_t = 0
        self.start: int | None = None

    def _assign(self, o: Step) -> None:
        self.v_x, self.v_t, self.start = o.v_x, o.v_t, o.start

    def _copy(self) -> Step:
        n = Step.__new__(Step)
        n._assign(self)
        return n


class ActionFlags:
    """An SFC ACTION's flags: Q (its control output) and A (it runs this
    cycle: while Q, and once more with Q FALSE as Q falls)."""

    __slots__ = ("v_q", "v_a")
    _VARS_ = (("Q", "v_q", T.BOOL, "FIELD"), ("A", "v_a", T.BOOL, "FIELD"))

    def __init__(self) -> None:
        self.v_q = False
        self.v_a = False

    def _assign(self, o: ActionFlags) -> None:
        self.v_q, self.v_a = o.v_q, o.v_a

    def _copy(self) -> ActionFlags:
        n = ActionFlags.__new__(ActionFlags)
        n._assign(self)
        return n


class ActionControl:
    """One action's control block (ed.3 6.7.4, ed.2 2.6.4):
    the stored flip-flops (reset dominant), the timers on the task clock
    and the edges; q is the control output Q of the last cycle."""

    __slots__ = ("q", "s", "sd", "ds", "sl", "p", "p1", "p0", "sd_t", "sl_t", "l_at", "d_at", "sd_at", "ds_at", "sl_at")

    def __init__(self) -> None:
        self.q = self.s = self.sd = self.ds = self.sl = False
        self.p = self.p1 = self.p0 = False  # the P, P1, P0 inputs last cycle (edges)
        self.sd_t = self.sl_t = 0  # the durations of the stored SD and SL
        # when each timer's input rose (None: the input is FALSE)
        self.l_at: int | None = None
        self.d_at: int | None = None
        self.sd_at: int | None = None
        self.ds_at: int | None = None
        self.sl_at: int | None = None

    def _copy(self) -> ActionControl:
        n = ActionControl.__new__(ActionControl)
        for name in ActionControl.__slots__:
            setattr(n, name, getattr(self, name))
        return n

    def update(self, inputs: dict, now: int) -> bool:
        """Q from this cycle's inputs: qualifier -> duration (ms; 0 for the
        untimed ones) for each qualifier an active step associates with
        the action (the OR of the associations, ed.3 6.7.4)."""
        r = "R" in inputs
        # P and P1 pulse when their step becomes active, P0 when it is cleared
        p, p1, p0 = "P" in inputs, "P1" in inputs, "P0" in inputs
        pulse = (p and not self.p) or (p1 and not self.p1) or (self.p0 and not p0)
        self.p, self.p1, self.p0 = p, p1, p0
        # S: stored until R
        self.s = not r and ("S" in inputs or self.s)
        # L: TRUE for its duration once the association is active
        self.l_at = _timer(self.l_at, "L" in inputs, now)
        limited = self.l_at is not None and _elapsed(now, self.l_at) < inputs["L"]
        # D: TRUE once the association has been active for its duration
        self.d_at = _timer(self.d_at, "D" in inputs, now)
        delayed = self.d_at is not None and _elapsed(now, self.d_at) >= inputs["D"]
        # SD: stored at once, TRUE after the delay, until R
        if "SD" in inputs:
            self.sd_t = inputs["SD"]
        self.sd = not r and ("SD" in inputs or self.sd)
        self.sd_at = _timer(self.sd_at, self.sd, now)
        sd_out = self.sd_at is not None and _elapsed(now, self.sd_at) >= self.sd_t
        # DS: delayed while the association is active, then stored until R
        self.ds_at = _timer(self.ds_at, "DS" in inputs, now)
        due = self.ds_at is not None and _elapsed(now, self.ds_at) >= inputs["DS"]
        self.ds = not r and (due or self.ds)
        # SL: stored at once, TRUE for its duration, until R
        if "SL" in inputs:
            self.sl_t = inputs["SL"]
        self.sl = not r and ("SL" in inputs or self.sl)
        self.sl_at = _timer(self.sl_at, self.sl, now)
        sl_out = self.sl_at is not None and _elapsed(now, self.sl_at) < self.sl_t
        self.q = "N" in inputs or pulse or limited or delayed or self.s or sd_out or self.ds or sl_out
        return self.q


def _timer(at: int | None, on: bool, now: int) -> int | None:
    """A TON's memory: when its input rose (now if it rises now), None while FALSE."""
    if not on:
        return None
    return now if at is None else at


class Network:
    """The shape of one POU's SFC network, made once by the code generator:
    transitions (sources, targets) as step indices, in priority order;
    for each step its associations (action index, qualifier, duration slot
    or -1); the number of actions."""

    __slots__ = ("transitions", "assocs", "n_actions")

    def __init__(self, transitions: tuple, assocs: tuple, n_actions: int) -> None:
        self.transitions = transitions
        self.assocs = assocs
        self.n_actions = n_actions


class SfcState:
    """One instance's action control blocks (the steps are its variables)."""

    __slots__ = ("net", "controls")

    def __init__(self, net: Network) -> None:
        self.net = net
        self.controls = [ActionControl() for _ in range(net.n_actions)]

    def _assign(self, o: SfcState) -> None:
        self.controls = [c._copy() for c in o.controls]

    def _copy(self) -> SfcState:
        n = SfcState.__new__(SfcState)
        n.net = self.net
        n.controls = [c._copy() for c in self.controls]
        return n

    @staticmethod
    def elapse(steps: tuple, now: int) -> None:
        """T of every active step, as the cycle starts."""
        for s in steps:
            if s.v_x:
                if s.start is None:  # the initial step, at the first cycle
                    s.start = now
                s.v_t = _elapsed(now, s.start)

    def evolve(self, steps: tuple, fire: tuple, now: int) -> None:
        """Clear and activate at once (ed.3 6.7.5, ed.2 2.6.5): fire[k] is
        whether transition k (in priority order) is enabled and its condition
        TRUE. Of the transitions that share a step (a selection divergence)
        only the first in priority order fires; a step both cleared and
        activated stays active and starts again at T#0s."""
        taken: set = set()
        cleared: list = []
        activated: list = []
        for k, (sources, targets) in enumerate(self.net.transitions):
            if fire[k] and taken.isdisjoint(sources):
                taken.update(sources)
                cleared += sources
                activated += targets
        for i in cleared:
            steps[i].v_x = False
        for i in activated:
            s = steps[i]
            s.v_x = True
            s.v_t = 0
            s.start = now

    def control(self, steps: tuple, times: tuple, now: int, flags: tuple = ()) -> list:
        """(Q, A) of every action after the evolution: Q its control output,
        A whether it runs this cycle (while Q, and once more when Q falls:
        ed.3 6.7.4, ed.2 2.6.4; CODESYS and TwinCAT alike). flags: the
        ActionFlags of each ACTION (None for a BOOL variable as action),
        set before any action runs, so that its final scan sees Q FALSE."""
        inputs: list = [{} for _ in range(self.net.n_actions)]
        for i, s in enumerate(steps):
            if s.v_x:
                for action, qualifier, slot in self.net.assocs[i]:
                    got = inputs[action]
                    if qualifier not in got:
                        got[qualifier] = times[slot] if slot >= 0 else 0
        out = []
        for c, got in zip(self.controls, inputs, strict=True):
            was = c.q
            q = c.update(got, now)
            out.append((q, q or was))
        for f, (q, a) in zip(flags, out, strict=False):
            if f is not None:
                f.v_q, f.v_a = q, a
        return out
