"""What a bus or a device plugs into softplc: the shapes of the seams.

A bus (a driver package, runtime/io/<bus>/) declares a ``Bus``:

    sections      its configuration sections (config.Section subclasses:
                  a pydantic model for pass 1, relations for pass 2, and the
                  dataclasses the driver reads)
    attachment    how a simulated device sits on it: the [[sim]] keys that
                  place a device there (a CAN node id, a Modbus unit ...)
    natives       ST functions its services execute (st/native.py)
    libraries     ST files with its blocks and diagnostic structs, compiled
                  into a program that names something they declare
    read_log      `softplc log`: a bus log it wrote, decoded (frame_text: a
                  protocol's words for the frames of another bus's log)
    build         the drivers and simulators for a configuration
                  (Contribution): drivers exchange with the process image at
                  the cycle boundary, offer their services, publish their
                  diagnostics, and stop in the order they are listed

A device (runtime/devices/<device>/) declares a ``Device``: the [[sim]] types
it simulates and their own keys, the simulator factory its bus calls, its ST
libraries and native functions, the files it ships (an EDS by name) and the
files generated from its manual tables. Its codec (registers, words, codes)
is the package's own modules; nothing else needs to know them.

Both are found through the registry (registry.py): Python entry points in
the groups ``softplc.buses`` and ``softplc.devices``, so an installed package
adds one with no change to softplc.
"""

from __future__ import annotations

from collections.abc import Callable, Iterable, Mapping
from dataclasses import dataclass, field
from importlib import resources
from pathlib import Path
from typing import Any

from ..st.native import NativeFunction


@dataclass(frozen=True)
class StLibrary:
    """An ST file installed as package data: ``StLibrary("softplc.fblocks.comm",
    "sdo.st")``. Diagnostics name it <lib>/<last package part>/<file>."""

    package: str
    file: str

    @property
    def name(self) -> str:
        return f"<lib>/{self.package.rsplit('.', 1)[-1]}/{self.file}"

    def read_text(self) -> str:
        return resources.files(self.package).joinpath(self.file).read_text("utf-8")


@dataclass(frozen=True)
class PackageFile:
    """A file installed with a package, such as a shipped EDS."""

    package: str
    file: str

    @property
    def path(self) -> Path:
        return Path(str(resources.files(self.package).joinpath(self.file)))


@dataclass(frozen=True)
class GeneratedFile:
    """A shipped file written from a device's tables: ``render()`` gives its
    text. A test compares every one with its generator, and
    ``python -m softplc.runtime.devices`` rewrites them."""

    target: PackageFile
    render: Callable[[], str]
    encoding: str = "utf-8"


@dataclass
class BuildContext:
    """What a bus's build gets besides the configuration: the engine's clock
    (virtual or real), the profile's addressing model, the configuration
    file for messages, and a dict the buses of one engine share (a
    virtual-time pump every CAN endpoint uses ...). A bus hands every
    simulator it makes for a [[sim]] table to simulated(): the engine finds
    them there by name (scheduled faults, tests). bus_log: the file
    `softplc run --bus-log` names (None: nothing recorded); each bus
    records its wire there or beside it, in engine time, and closes it with
    its drivers (the docs/guide/simulation.md "Bus log" says which file has what)."""

    clock: Any
    addressing: str
    where: str = "<config>"
    shared: dict = field(default_factory=dict)
    simulators: dict = field(default_factory=dict)  # [[sim]] name -> the simulator object
    bus_log: Path | None = None

    @property
    def virtual(self) -> bool:
        return bool(self.clock.virtual)

    def simulated(self, sim: Any, simulator: Any) -> Any:
        """Record the simulator built for the [[sim]] table sim (a SimConfig); returns it."""
        self.simulators[sim.name] = simulator
        return simulator


@dataclass(frozen=True)
class SimFault:
    """A fault a device's simulator takes, from [[sim]] faults = [...] at a
    time of the run or from a test: simulator.inject(name, value, True), and
    inject(name, value, False) to undo a lasting one."""

    name: str  # lower case, as the configuration writes it: "over_current"
    description: str
    value: str = ""  # what its value is ("an alarm bit of 16-90"), "" when it takes none
    lasting: bool = False  # it lasts until undone: the configuration may give `for`


@dataclass
class Contribution:
    """A bus's part of an engine. simulators: simulated devices (started
    first, advanced first at each tick, stopped last); drivers: the bus
    drivers, in the order they meet the scan (and stop in reverse)."""

    simulators: list = field(default_factory=list)
    drivers: list = field(default_factory=list)


@dataclass(frozen=True)
class Bus:
    name: str
    #: where it comes among the buses (lower first; equal: by name): the order
    #: of configuration checks and of drivers in the scan
    order: int = 100
    sections: tuple = ()  # config.Section instances
    attachment: Any = None  # config.Attachment, or None: no simulated devices
    natives: tuple[NativeFunction, ...] = ()
    libraries: tuple[StLibrary, ...] = ()
    build: Callable[[Any, BuildContext], Contribution] | None = None  # (PlcConfig, context)
    #: `softplc log FILE`: the lines of a bus log this bus wrote (BuildContext.bus_log),
    #: decoded with the configuration's words (PlcConfig), or None when FILE is not its
    read_log: Callable[[Path, Any], Iterable[str] | None] | None = None
    #: a protocol on another bus's wire (CANopen, a plain-CAN device on a [[can]] bus):
    #: (PlcConfig) -> (bus name, frame) -> its words for the frame, or None when not its
    frame_text: Callable[[Any], Callable[[str, Any], str | None]] | None = None


class ParameterValueError(ValueError):
    """Device.parameter_object: the parameter is known, its value cannot be
    written (out of range, not a number it holds); the configuration error
    then names the write's value, not its parameter."""


@dataclass(frozen=True)
class Device:
    name: str
    #: where it comes among the devices (lower first; equal: by name): the
    #: order of [[sim]] types in messages
    order: int = 100
    bus: str = ""  # the bus its simulators attach to
    sim_types: tuple[str, ...] = ()  # [[sim]] type values it simulates
    sim_options: Any = None  # config.SimOptions subclass: its own [[sim]] keys
    simulator: Callable[..., Any] | None = None  # (SimConfig, the bus's context) -> a simulator
    natives: tuple[NativeFunction, ...] = ()
    libraries: tuple[StLibrary, ...] = ()
    files: Mapping[str, Mapping[str, PackageFile]] = field(default_factory=dict)  # kind -> name -> file
    generated: tuple[GeneratedFile, ...] = ()
    #: a parameter named as the device's manual writes it ("8-03") and a value
    #: in its unit -> (object index, sub-index, size in bytes, raw value), for
    #: configured writes to a node with one of the device's files (its EDS);
    #: ValueError with a message for an unknown name, ParameterValueError for
    #: a value it cannot write
    parameter_object: Callable[[str, Any], tuple[int, int, int, int]] | None = None
    #: the faults its simulators take (config/sim_faults.py)
    sim_faults: tuple[SimFault, ...] = ()
    #: how a real device of this kind is driven, declared for the bus that
    #: hosts such devices (a plain-CAN protocol: io/plaincan's PlainCanKind)
    node_kind: Any = None
    #: an EMCY of a node with one of the device's files, in words for the log:
    #: (error code, error register, manufacturer bytes) -> text
    emcy_text: Callable[[int, int, bytes], str] | None = None
    #: a value of one of its objects in the manual's words, for `softplc log`:
    #: (object index, sub-index, raw value) -> text, or None for an object it has no words for
    object_text: Callable[[int, int, int], str | None] | None = None
    #: the device's safe state, for a node with one of its files: (object
    #: index, sub-index) -> the raw value an RPDO carries there while the PLC
    #: holds its outputs safe (a task fault, the stop), where [outputs] safe
    #: sets none of the bits of the %Q address mapped to the object
    safe_objects: Mapping[tuple[int, int], int] = field(default_factory=dict)
