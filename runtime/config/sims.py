"""[[sim]]: simulated devices started with the PLC.

    [[sim]]
    type = "ltmr"            # a type a registered device simulates
    name = "motor_sim"       # optional; default from the type and where it sits
    node_id = 40             # the keys of the device's bus (its Attachment)
    registers = { "682" = 2 }   # the device's own keys (its SimOptions)
    faults = [{ at = "20s", fault = "unplug", for = "2s" }]   # config/sim_faults.py

Which keys a table takes depends on its type: the device that simulates
the type says which bus it sits on (the bus's Attachment gives the keys
that place it there and checks them) and which keys of its own it has.
A key of another bus's devices is refused with what this device has.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Annotated, Any

from pydantic import Field, create_model

from ..plugin.registry import PluginError, Registry
from .errors import key_text
from .relations import Relations
from .section import Attachment, Section
from .sim_faults import FaultEvent, Faults, check_faults, fault_events
from .values import Model, choice, identifier, is_ident, optional_field


@dataclass
class SimConfig:
    type: str  # a [[sim]] type of a registered device
    name: str
    key: str  # "sim[0]"
    at: Any  # where it sits: the bus's dataclass (a CAN node, a Modbus unit ...)
    options: Any = None  # the device's own keys, as its SimOptions builds them
    faults: tuple[FaultEvent, ...] = ()  # faults = [...], by time


class SimSection(Section):
    """The [[sim]] section of the devices in a registry."""

    key = "sim"
    many = True
    description = "[[sim]] tables"

    def __init__(self, registry: Registry) -> None:
        self.registry = registry
        self.types = registry.sim_types()  # type -> Device
        self.attachments = {bus.name: bus.attachment for bus in registry.buses if bus.attachment is not None}
        for device in registry.devices:
            if device.sim_types and device.bus not in self.attachments:
                raise PluginError(
                    f"device {device.name}: its simulators sit on bus {device.bus!r}, which is not "
                    "registered or takes no simulated devices"
                )
        self.model = self._model()

    def _model(self) -> type[Model]:
        """Every key a [[sim]] table can have: type, name, each bus's
        placing keys and each device's own (one definition per key)."""
        types = tuple(self.types)
        quoted = [f"'{t}'" for t in types]
        listed = " or ".join([", ".join(quoted[:-1]), quoted[-1]]) if len(quoted) > 1 else "".join(quoted)
        fields: dict[str, Any] = {
            "type": (Annotated[str, choice(types)], Field(description=listed)),
            "name": (
                Annotated[str, identifier("a simulator name")] | None,
                Field(None, description='a simulator name such as "motor_sim"'),
            ),
            "faults": (Faults | None, Field(None, description="faults at times of the run")),
        }
        models = list(self.attachments.values()) + [d.sim_options for d in self.registry.devices if d.sim_options]
        for owner in models:
            model = owner.model if isinstance(owner, Attachment) else owner
            for name, info in model.model_fields.items():
                if name not in fields:
                    fields[name] = optional_field(info)
        return create_model("Sim", __base__=Model, **fields)

    def _device_of(self, sim: dict):
        kind = sim.get("type")
        return self.types.get(kind.lower()) if isinstance(kind, str) else None

    # ---------------------------------------------------------------- pass 2

    def check(self, value: Any, ctx: Relations) -> None:
        if not isinstance(value, list):
            return
        names: dict = {}
        for i, sim in enumerate(value):
            if not isinstance(sim, dict):
                continue
            here = ("sim", i)
            device = self._device_of(sim)
            if device is None:
                continue  # pass 1 reports the type
            attachment = self.attachments[device.bus]
            self._foreign_keys(here, sim, device, ctx)
            attachment.check(here, sim, ctx)
            self._name(here, sim, attachment, names, ctx)
            if device.sim_options is not None:
                ctx.required(here, sim, device.sim_options)
                device.sim_options.check(here, sim, ctx)
            check_faults(here, sim, device, ctx)

    def _foreign_keys(self, here: tuple, sim: dict, device, ctx: Relations) -> None:
        """Keys that place a device on another bus, or that another device has."""
        own = self.attachments[device.bus]
        mine = set(own.keys) | set(device.sim_options.model_fields if device.sim_options else ())
        for bus, attachment in self.attachments.items():
            if attachment is own:
                continue
            types = [t for t, d in self.types.items() if d.bus == bus]
            for key in attachment.keys:
                if key in sim and key not in mine:
                    ctx.error(
                        here + (key,),
                        f"only for a {attachment.kind} device ({', '.join(types)}); "
                        f"a {own.kind} device has {' and '.join(own.keys)}",
                    )
        for other in self.registry.devices:
            if other is device or other.sim_options is None:
                continue
            for key in other.sim_options.model_fields:
                if key in sim and key not in mine and not any(key in a.keys for a in self.attachments.values()):
                    ctx.error(
                        here + (key,), f"only for {', '.join(other.sim_types)}; type {sim['type']!r} does not take it"
                    )

    def _name(self, here: tuple, sim: dict, attachment: Attachment, names: dict, ctx: Relations) -> None:
        if "name" in sim:
            name = sim["name"]
            if not is_ident(name):
                return  # pass 1 reports it
            first = names.setdefault(name.upper(), here)
            if first != here:
                ctx.error(
                    here + ("name",),
                    f"duplicate simulator name '{name}' ({key_text(first)} has it; names are case-insensitive)",
                )
            return
        name = attachment.name(sim["type"].lower(), sim)
        if name is not None:
            first = names.setdefault(name.upper(), here)
            if first != here:
                ctx.error(
                    here,
                    f"duplicate simulator name '{name}', the default {attachment.default_name} "
                    f"({key_text(first)} has it): give one a name",
                )

    # ---------------------------------------------------------------- build

    def build(self, model: Any, ctx: Relations) -> list[SimConfig]:
        out = []
        for i, sim in enumerate(model):
            device = self.types[sim.type]
            attachment = self.attachments[device.bus]
            here = ("sim", i)
            values = {k: getattr(sim, k) for k in attachment.keys}
            at = attachment.build(values, here, ctx)
            options = None
            if device.sim_options is not None:
                own = {k: getattr(sim, k) for k in device.sim_options.model_fields if getattr(sim, k) is not None}
                options = device.sim_options.model_construct(**own).build()  # values validated: the table's
            name = sim.name or attachment.name(sim.type, {k: v for k, v in values.items() if v is not None})
            out.append(
                SimConfig(
                    type=sim.type,
                    name=name,
                    key=key_text(here),
                    at=at,
                    options=options,
                    faults=fault_events(sim.faults),
                )
            )
        return out
