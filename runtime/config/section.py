"""The configuration seams: what a bus's section of the file, a bus's way of
placing a simulated device, and a device's own simulator keys provide.

    class CanopenSection(Section):      # [canopen] (runtime/io/canopen/config.py)
        key = "canopen"
        model = _Canopen                # pass 1: a pydantic model of one table
        description = "a [canopen] table"
        def check(self, value, ctx): ...  # pass 2: relations on the raw TOML value
        def build(self, model, ctx): ...  # the dataclasses the driver reads

A configuration (config/load.py) is the core sections (plc.py, sims.py)
and the sections of every registered bus, in registry order; each
section's check runs whatever pass 1 found (value may be missing or of
the wrong type: pass 1 reports that), and build runs only for a file
without errors.
"""

from __future__ import annotations

from typing import Any, ClassVar

from .relations import Relations
from .values import Model


class Section:
    #: the TOML key: [key] or [[key]]
    key: ClassVar[str]
    #: [[key]]: an array of tables (build gets a list); [key]: one table or none
    many: ClassVar[bool] = False
    #: one table, for pass 1 (a class attribute, or set in __init__ where it
    #: depends on the registry: the [[sim]] section)
    model: type[Model]
    #: what the key holds, for messages: "[[can]] tables", "a [canopen] table"
    description: ClassVar[str]

    @property
    def default(self) -> Any:
        """The section's value in a file that has none."""
        return [] if self.many else None

    def bind(self, registry: Any) -> None:
        """Before the document is built, for each state of the registry: a
        section whose keys depend on the registered devices (their own keys
        in its tables) sets its model here."""

    def check(self, value: Any, ctx: Relations) -> None:
        """Pass 2: relations between values of the raw TOML value (None when
        the file has no such key), reported with ctx.error(loc, message);
        results the build needs go into ctx.state[self.key]."""

    def build(self, model: Any, ctx: Relations) -> Any:
        """The section's configuration from the validated model (a list of
        them for a [[key]] section): what its driver reads."""
        raise NotImplementedError


class Attachment:
    """How a simulated device sits on a bus: the [[sim]] keys that place it
    (a [[can]] bus and node id, a [[modbus]] connection and unit).

    kind: the bus in messages ("only for a CAN device"); model: the keys,
    for pass 1; default_name: the shape of a simulator's default name in
    messages ("<type><node_id>")."""

    kind: ClassVar[str]
    model: ClassVar[type[Model]]
    default_name: ClassVar[str]

    @property
    def keys(self) -> tuple:
        return tuple(self.model.model_fields)

    def check(self, here: tuple, sim: dict, ctx: Relations) -> None:
        """Pass 2 of one [[sim]] table of a device on this bus (here: its loc)."""

    def name(self, sim_type: str, sim: dict) -> str | None:
        """The simulator's default name from the raw table, or None when the
        keys it is made of are not valid (pass 1 reports them)."""
        raise NotImplementedError

    def build(self, values: dict, here: tuple, ctx: Relations) -> Any:
        """Where the device is (a dataclass the bus's build reads), from the
        validated keys."""
        raise NotImplementedError


class SimOptions(Model):
    """A device's own [[sim]] keys (initial register values ...): a model
    for pass 1, with a check for pass 2 and the options the simulator gets."""

    @classmethod
    def check(cls, here: tuple, sim: dict, ctx: Relations) -> None:
        """Pass 2 of the device's keys in one [[sim]] table."""

    def build(self) -> Any:
        return self
