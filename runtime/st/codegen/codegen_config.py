"""Code generation of VAR_CONFIG: what each program instance's settings do.

For every configured program instance with settings, a function the
engine calls on the new instance (``_VAR_CONFIG[NAME](instance)``,
program/loaded.py): it stores the instance-specific initial values and
returns what the task calls each cycle. A variable given an address
(declared ``AT %QX*``) is ordinary storage of its instance; the returned
call reads it from the process image before the instance runs and, for
%Q and %M, writes it back after: the image holds it as if it were
located there (inputs are read once per cycle anyway, outputs reach the
bus after the tasks).
"""

from __future__ import annotations

from .. import types as T
from .codegen_base import CodeGenBase, FnState


class ConfigGen(CodeGenBase):
    """VAR_CONFIG."""

    def _var_config(self) -> None:
        self.fn = FnState(None, "o")
        table: list = []  # (instance name, upper case; function name)
        for config in self.prog.configurations:
            by_instance: dict = {}
            for s in config.settings:
                by_instance.setdefault(s.instance.upper(), []).append(s)
            for key, settings in by_instance.items():
                fn = f"_VC{len(table)}"
                table.append((key, fn))
                self._configure_function(fn, settings)
        self.pos = None
        self.emit("")
        self.emit(f"_VAR_CONFIG = {{{''.join(f'{key!r}: {fn}, ' for key, fn in table)}}}")

    def _configure_function(self, fn: str, settings: list) -> None:
        self.pos = settings[0].pos
        self.emit("")
        self.emit(f"def {fn}(o):")
        self.indent += 1
        holders: dict = {}  # the attribute path of an FB instance -> a local bound to it
        mapped = []
        for s in settings:
            self.pos = s.pos
            owner = self._holder(s.path[:-1], holders)
            target = f"{owner}.{s.path[-1].pyname}"
            ty = s.path[-1].type
            if s.init_value is not None and T.resolve(ty).is_aggregate:  # into the object references may hold
                self.emit(f"_assign_into({target}, {self._aggregate_expr(ty, s.init_value)})")
            elif s.init_value is not None:
                self._emit_init(target, ty, s.init_value)
            if s.location is not None:
                idx = self.accessor(s.location, T.base_elementary(s.path[-1].type))
                mapped.append((target, idx, s.location.area != "I"))
                if s.location.area != "I":
                    self.emit(f"_A{idx}s({target})")  # the initial value reaches the image at once
        if not mapped:
            self.emit("return o")
        else:
            self.emit("def call():")
            self.indent += 1
            for target, idx, _out in mapped:
                self.emit(f"{target} = _A{idx}g()")
            self.emit("o()")
            for target, idx, out in mapped:
                if out:
                    self.emit(f"_A{idx}s({target})")
            self.indent -= 1
            self.emit("return call")
        self.indent -= 1

    def _holder(self, path: list, holders: dict) -> str:
        """A local of the configure function bound to the FB instance at
        path inside the program instance o (instances never move)."""
        code = "o"
        for i, sym in enumerate(path):
            key = tuple(id(s) for s in path[: i + 1])
            if key not in holders:
                local = f"_i{len(holders)}"
                self.emit(f"{local} = {code}.{sym.pyname}")
                holders[key] = local
            code = holders[key]
        return code
