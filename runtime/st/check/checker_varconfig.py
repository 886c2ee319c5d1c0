"""The checker's VAR_CONFIG: instance-specific addresses and initial values.

    VAR_CONFIG
      Cpu.line1.valve.open AT %QX0.1 : BOOL;   (* resource.instance.fb...var *)
      line1.speed : INT := 50;                  (* the resource may be left out *)
    END_VAR

A path starts with a RESOURCE of the CONFIGURATION (or directly with a
program instance), names a program instance, then FB instances down to a
variable (IEC 61131-3: instance-specific initialisation). The variable
may take an initial value for this instance; an address only if it is
declared with an incomplete one (``open AT %QX* : BOOL;``), which every
instance then needs (E083). The code generator turns each instance's
settings into a function the engine calls on the new instance
(codegen_config.py): an addressed variable is read from the image before
the instance runs and, for %Q and %M, written back after it.

Errors: E094 a path that names nothing (or a STRUCT member, an array
element: VAR_CONFIG reaches FB instances only), E020 a type other than
the variable's, E083 an incomplete address left without one.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from .. import ast as A
from .. import types as T
from .checker_base import CheckerBase, Scope
from .conversions import same_type
from .symbols import POUInfo, VarSymbol

# Where an FB instance or a variable VAR_CONFIG can name may be declared.
_REACHABLE = ("VAR", "VAR_INPUT", "VAR_OUTPUT", "VAR_STAT")
# Where a variable with an incomplete address may be declared.
_PLACEHOLDER_SECTIONS = ("VAR", "VAR_INPUT", "VAR_OUTPUT")


@dataclass
class ConfigSetting:
    """One VAR_CONFIG line, checked: the program instance, the variables
    from it down to the one set, the address and the initial value plan."""

    instance: str  # the program instance's name, as declared
    path: list  # VarSymbols: FB instances, then the variable
    location: A.LocatedAddress | None
    init_value: Any  # a plan (checker_decls.init_value), or None
    pos: A.Pos
    text: str  # the path as written, for messages


def _example(placeholder: A.LocatedAddress, ty: T.Type) -> str:
    """A full address that completes the placeholder, for hints."""
    size = placeholder.size
    if not size:
        be = T.base_elementary(ty)
        size = {1: "X", 8: "B", 16: "W", 32: "D", 64: "L"}.get(be.bits if be is not None else 1, "X")
    return f"%{placeholder.area}{size}0" + (".0" if size == "X" else "")


class VarConfigChecks(CheckerBase):
    """VAR_CONFIG and the variables with incomplete addresses."""

    def _check_placeholder(self, sym: VarSymbol) -> None:
        """A variable declared AT %IX* (an incomplete address): an
        elementary value of the address's size, in a PROGRAM or FB."""
        addr = sym.location
        sym.placeholder = addr
        if sym.owner is None:
            self.d.error(
                "E083",
                f"{addr.text} is an incomplete address; a global variable needs a full one",
                sym.pos,
                "give the full address (e.g. %IX0.0), or declare it in a PROGRAM or FUNCTION_BLOCK "
                "and give each instance its address in VAR_CONFIG",
            )
            return
        be = T.base_elementary(sym.type)
        want = {"X": 1, "B": 8, "W": 16, "D": 32, "L": 64}.get(addr.size)
        if be is None or (want is not None and be.bits != want):
            self.d.error(
                "E081",
                f"{addr.text} takes {'an elementary value' if want is None else f'a {want}-bit value'}; "
                f"'{sym.name}' is {sym.type}",
                sym.pos,
            )

    def _var_config(self, blocks: list, config: Any) -> None:
        """Check the VAR_CONFIG lines of a CONFIGURATION into config.settings."""
        resources = {r.name.upper(): r for r in config.node.resources}
        instances = {p["name"].upper(): p for p in config.programs}
        done: dict = {}
        for block in blocks:
            for decl in block.decls:
                setting = self._setting(decl, resources, instances)
                if setting is None:
                    continue
                key = (setting.instance.upper(), *(s.name.upper() for s in setting.path))
                if key in done:
                    self.d.error(
                        "E094", f"'{decl.name}' is configured twice", decl.pos, f"the first time at {done[key]}"
                    )
                    continue
                done[key] = decl.pos
                config.settings.append(setting)

    def _setting(self, decl: A.VarDecl, resources: dict, instances: dict) -> ConfigSetting | None:
        parts = decl.name.split(".")
        first = parts[0].upper()
        if first in resources and first not in instances:
            res = resources[first]
            mine = [p["name"] for p in instances.values() if p["resource"].upper() == first]
            inst = instances.get(parts[1].upper()) if len(parts) > 1 else None
            if inst is None or inst["resource"].upper() != first:
                return self._unreachable(
                    decl,
                    f"RESOURCE {res.name} has no program instance '{parts[1] if len(parts) > 1 else ''}'",
                    self._suggest(parts[1].upper(), mine) if len(parts) > 1 else None,
                )
            rest = parts[2:]
        elif first in instances:
            inst, rest = instances[first], parts[1:]
        else:
            names = [r.name for r in resources.values()] + [p["name"] for p in instances.values()]
            return self._unreachable(
                decl,
                f"'{parts[0]}' is neither a RESOURCE nor a program instance of this CONFIGURATION",
                self._suggest(first, names),
            )
        if not rest:
            return self._unreachable(
                decl,
                f"'{inst['name']}' is a program instance; name a variable in it",
                "write Resource.Instance.Variable, or Resource.Instance.FBInstance.Variable",
            )
        path = self._walk_path(decl, inst["type"], rest)
        if path is None:
            return None
        target = path[-1]
        ty = self.type_of(decl.type)
        if ty is None:
            return None
        if not same_type(ty, target.type):
            self.d.error(
                "E020",
                f"'{decl.name}' is {target.type}, not {ty}",
                decl.pos,
                f"declare it as in {target.owner.name}: {target.type}",
            )
            return None
        if decl.location is not None and not self._config_address(decl, decl.location, target):
            return None
        plan = None
        if decl.init is not None:
            plan = self.init_value(target.type, decl.init, Scope(None), decl.name)
        return ConfigSetting(inst["name"], path, decl.location, plan, decl.pos, decl.name)

    def _walk_path(self, decl: A.VarDecl, pou: POUInfo, names: list) -> list | None:
        """The VarSymbols from the program instance down to the variable."""
        path: list = []
        for i, name in enumerate(names):
            sym = pou.vars.get(name.upper())
            if sym is None or sym.section not in _REACHABLE:
                hint = self._suggest(name.upper(), [v.name for v in pou.vars.values() if v.section in _REACHABLE])
                what = "has no variable" if sym is None else f"has '{name}' in {sym.section}, not"
                return self._unreachable(decl, f"{pou.kind} {pou.name} {what} '{name}' to configure", hint)
            path.append(sym)
            if i == len(names) - 1:
                return path
            fb = T.resolve(sym.type)
            if not isinstance(fb, T.FBType):
                return self._unreachable(
                    decl,
                    f"'{name}' in {pou.name} is {sym.type}, not a function block instance",
                    "a VAR_CONFIG path goes through FB instances only (no STRUCT members or array elements)",
                )
            pou = fb.pou
        return path

    def _config_address(self, decl: A.VarDecl, addr: A.LocatedAddress, target: VarSymbol) -> bool:
        placeholder, owner = target.placeholder, target.owner.name if target.owner is not None else ""
        if placeholder is None:
            self.d.error(
                "E094",
                f"'{decl.name}' has no incomplete address to complete",
                decl.pos,
                f"declare it AT %{addr.area}{addr.size}* in {owner} "
                "to give it an address here, or leave AT out to set only its initial value",
            )
            return False
        if not addr.indices or addr.area != placeholder.area or (placeholder.size and addr.size != placeholder.size):
            self.d.error(
                "E083",
                f"{addr.text} does not complete {placeholder.text}",
                decl.pos,
                f"give a full address of the same area and size, e.g. {_example(placeholder, target.type)}",
            )
            return False
        be = T.base_elementary(target.type)
        want = 1 if (addr.size in ("", "X") or addr.bit is not None) else {"B": 8, "W": 16, "D": 32, "L": 64}[addr.size]
        if addr.table is not None or be is None or be.bits != want:
            self.d.error("E081", f"{addr.text} is a {want}-bit address; '{decl.name}' is {target.type}", decl.pos)
            return False
        return self._address_fits(addr, be, decl.pos)

    def _unreachable(self, decl: A.VarDecl, message: str, hint: str | None = None) -> Any:
        """Report a path that names nothing (E094); None, for the caller to return."""
        self.d.error("E094", f"VAR_CONFIG '{decl.name}': {message}", decl.pos, hint)
        return None

    # ------------------------------------------------------------ incomplete addresses

    def _check_placeholders(self) -> None:
        """E083 for every incomplete address no VAR_CONFIG completes: in
        each configured program instance, or in an instance VAR_CONFIG
        cannot name (in an array, a STRUCT, a global, a FUNCTION). Then
        such variables are plain storage for the code generator: the
        engine copies them from and to the image (codegen_config.py)."""
        holders = self._placeholder_holders()
        if not holders:
            return
        self._misplaced_instances(holders)
        configured = {id(c) for c in self.configs}
        for config in self.configs:
            given = {
                (s.instance.upper(), *(v.name.upper() for v in s.path))
                for s in config.settings
                if s.location is not None
            }
            for p in config.programs:
                for path in self._placeholder_paths(p["type"], holders):
                    key = (p["name"].upper(), *(v.name.upper() for v in path))
                    if key not in given:
                        shown = ".".join([p["name"]] + [v.name for v in path])
                        self._missing(path[-1], f"instance {shown} has no address", shown)
        if not configured:
            for pou in self.pous.values():
                if pou.kind == "PROGRAM" and id(pou) in holders:
                    for path in self._placeholder_paths(pou, holders):
                        shown = ".".join([pou.name] + [v.name for v in path])
                        self._missing(path[-1], f"{shown} has no address: there is no CONFIGURATION", shown)
        for pou in self.pous.values():
            for sym in pou.vars.values():
                if sym.placeholder is not None:
                    sym.location = None  # storage; the engine copies it (see above)

    def _missing(self, sym: VarSymbol, message: str, shown: str) -> None:
        self.d.error(
            "E083",
            f"{sym.placeholder.text} of {message}",
            sym.pos,
            f"give it one in the CONFIGURATION: VAR_CONFIG {shown} AT "
            f"{_example(sym.placeholder, sym.type)} : {sym.type}; END_VAR",
        )

    def _placeholder_holders(self) -> set:
        """ids of the PROGRAMs and FBs that hold a variable with an
        incomplete address, themselves or in an FB instance."""
        holders: set = set()
        grew = True
        while grew:
            grew = False
            for pou in self.pous.values():
                if id(pou) in holders or pou.kind == "FUNCTION":
                    continue
                for sym in pou.vars.values():
                    fb = T.resolve(sym.type)
                    if sym.placeholder is not None or (
                        isinstance(fb, T.FBType) and id(fb.pou) in holders and sym.section in _REACHABLE
                    ):
                        holders.add(id(pou))
                        grew = True
                        break
        return holders

    def _placeholder_paths(self, pou: POUInfo, holders: set, seen: tuple = ()) -> list:
        """The paths (lists of VarSymbols) from an instance of pou to each
        variable with an incomplete address inside it."""
        out = []
        for sym in pou.vars.values():
            if sym.section not in _REACHABLE:
                continue
            if sym.placeholder is not None:
                out.append([sym])
                continue
            fb = T.resolve(sym.type)
            if isinstance(fb, T.FBType) and id(fb.pou) in holders and id(fb.pou) not in seen:
                out += [[sym, *rest] for rest in self._placeholder_paths(fb.pou, holders, (*seen, id(pou)))]
        return out

    def _misplaced_instances(self, holders: set) -> None:
        """E083 where an FB with incomplete addresses is instantiated where
        VAR_CONFIG cannot name the instance."""

        def inside(ty: T.Type) -> str | None:
            """The name of such an FB that a value of type ty holds, if any
            (STRUCT cycles are cut already: E014)."""
            t = T.resolve(ty)
            while isinstance(t, T.ArrayType):
                t = T.resolve(t.elem)
            if isinstance(t, T.FBType):
                return t.name if id(t.pou) in holders else None
            if isinstance(t, T.StructType):
                for f in t.fields.values():
                    found = inside(f.type) if f.type is not None else None
                    if found is not None:
                        return found
            return None

        syms = [(s, "a global variable") for s in self.globals.values()]
        for pou in self.pous.values():
            for s in pou.vars.values():
                direct = isinstance(T.resolve(s.type), T.FBType)
                if pou.kind == "FUNCTION":
                    syms.append((s, "a FUNCTION's variable"))
                elif not direct or s.section not in _REACHABLE:
                    syms.append((s, "an ARRAY or STRUCT" if not direct else f"{s.section}"))
        for sym, where in syms:
            name = inside(sym.type)
            if name is not None and sym.section not in ("VAR_IN_OUT", "VAR_EXTERNAL"):
                self.d.error(
                    "E083",
                    f"'{sym.name}' holds {name}, whose incomplete addresses VAR_CONFIG cannot reach in {where}",
                    sym.pos,
                    f"declare each {name} as a variable of a PROGRAM or FUNCTION_BLOCK, or give {name} full addresses",
                )
