"""What both sides of the servers' process share (process.py in the PLC's
process, child.py in the servers'): which servers there are and where,
the fields of a snapshot that cross the pipe, how long a call may take,
and the errors both report. Neither side's code: so the child imports
neither process.py nor host.py, and the parent names the child only as
the entry point it spawns."""

from __future__ import annotations

from ..engine.snapshot import Snapshot

#: section key -> module (relative to this package) offering start(surfaces, config)
SERVERS = {"web": ".web", "opcua": ".opcua", "modbus_server": ".modbus_server"}
#: the servers run in the servers' process (the others in the PLC's)
OWN_PROCESS = frozenset(("web", "opcua", "modbus_server"))

CALL_TIMEOUT_S = 30.0
#: the Snapshot fields sent with each capture (the layout goes apart)
FIELDS = tuple(f for f in Snapshot.__dataclass_fields__ if f != "layout")


class PlcBusy(TimeoutError):
    """The PLC did not answer a call of the servers in time (a compile of an
    online change longer than the call's timeout, a host too busy): the web
    page answers 504 with this message, not a 500 of a bare TimeoutError."""


def start_failure(host: str, port: int, exc: OSError) -> str:
    """Why a server did not start, as the PLC reports it after "[key] ". A
    TimeoutError is an OSError too, often without a message (a step of
    asyncua's start on a host too busy for it): no "cannot listen ...: "
    with nothing after it."""
    if isinstance(exc, TimeoutError):
        said = str(exc) or "a step of its start timed out"
        return f"did not start on {host}:{port} in time: {said} (a busy host? start the PLC again)"
    return f"cannot listen on {host}:{port}: {exc.strerror or str(exc) or type(exc).__name__}"
