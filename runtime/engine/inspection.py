"""What the engine lets a test, a surface or a simulator reach between
two scans: a variable or an address read (get) and written (set), found
(variable), forced and released (force, unforce), and every variable
dumped (dump) as `softplc exec` prints it. Part of Engine (engine/scan.py).
"""

from __future__ import annotations

from collections.abc import Callable
from typing import TYPE_CHECKING, Any

from ..program import Program, locate
from ..st.valuejson import encode_instance

if TYPE_CHECKING:
    from ..image.memory import ProcessImage


class Inspection:
    """Engine's accessors (a mixin: Engine sets these attributes)."""

    program: Program
    image: ProcessImage
    ns: dict
    instances: dict
    forces: dict[str, Callable[[], None]]
    forced_values: dict

    def load(self) -> Any: ...

    def force(self, key: str, apply: Callable[[], None]) -> None:
        """Hold a value against the program, as a PLC's force does: apply()
        stores it, now and in every scan after the drivers read the inputs
        and again after the tasks ran, so neither a bus nor the program
        changes what the next scan and the drivers see. key names the forced
        variable or address; a new force of the same key replaces the old."""
        self.forces[key] = apply
        apply()

    def unforce(self, key: str) -> bool:
        """Release a force; the variable keeps its value until someone writes it. False if key was not forced."""
        self.forced_values.pop(key, None)
        return self.forces.pop(key, None) is not None

    def variable(self, path: str):
        """(holder, attribute, Type) of 'Instance.var.field' or 'GlobalVar.field'.
        Works before start(): the program is loaded first."""
        self.load()
        first, _, rest = path.partition(".")
        entry = self.instances.get(first.upper())
        if entry is not None and rest:
            return locate(rest, (entry[2],))
        return self.program.locate(path, (self.ns["_G"],))  # GVL.x too

    def get(self, path: str):
        """The value of a variable ('Main.count', 'G_total') or of a direct address ('%QW0')."""
        if path.startswith("%"):
            return self.image.read(path)
        holder, attr, _ty = self.variable(path)
        return getattr(holder, attr)

    def set(self, path: str, value) -> None:
        """Force a variable (tests and simulators; no type conversion)."""
        if path.startswith("%"):
            self.image.write(path, value)
            return
        holder, attr, _ty = self.variable(path)
        setattr(holder, attr, value)

    def dump(self) -> dict:
        """Every program instance's variables and the globals, as `softplc exec` prints them."""
        self.load()
        out = {name: encode_instance(obj) for name, _info, obj in self.instances.values()}
        globals_ = encode_instance(self.ns["_G"], skip=self.program.library_globals)
        if globals_:
            out["VAR_GLOBAL"] = globals_
        return out
