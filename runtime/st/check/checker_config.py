"""The checker's CONFIGURATION: tasks and program instances for the engine.

Tasks with INTERVAL, PRIORITY and SINGLE; program instances with their
task and parameters; the VAR_CONFIG lines (checker_varconfig.py).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

from .. import ast as A
from .. import types as T
from .checker_base import CheckerBase, Scope
from .symbols import CallInfo


@dataclass
class ConfigInfo:
    """A checked CONFIGURATION: tasks and program instances for the engine."""

    name: str
    tasks: list = field(default_factory=list)  # dicts: name, interval_ms, priority, single, pos
    programs: list = field(default_factory=list)  # dicts: name, type (POUInfo), task, resource, binding, pos
    node: Any = None
    settings: list = field(default_factory=list)  # checker_varconfig.ConfigSetting, one per VAR_CONFIG line


class ConfigChecks(CheckerBase):
    """The CONFIGURATION."""

    def _configuration(self, c: A.Configuration) -> None:
        info = ConfigInfo(c.name, node=c)
        task_names: dict = {}
        for res in c.resources:
            for t in res.tasks:
                key = t.name.upper()
                if key in task_names:
                    self.d.error("E090", f"task '{t.name}' is declared twice", t.pos)
                    continue
                task = {
                    "name": t.name,
                    "interval_ms": None,
                    "priority": 0,
                    "single": None,
                    "pos": t.pos,
                    "resource": res.name,
                }
                for pname, pexpr in t.params.items():
                    p = pname.upper()
                    if p == "INTERVAL":
                        ty = self.expr(pexpr, Scope(None), expected=T.TIME)
                        be = T.base_elementary(ty) if ty is not None else None
                        if be is not None and be.category == T.DURATION and pexpr.const is not None:
                            task["interval_ms"] = pexpr.const * be.unit_ns / 1e6
                            if task["interval_ms"] <= 0:
                                self.d.error("E091", "a task INTERVAL must be positive", pexpr.pos)
                        else:
                            self.d.error("E091", "INTERVAL must be a constant TIME such as T#10ms", pexpr.pos)
                    elif p == "PRIORITY":
                        v = self._const_int(pexpr, Scope(None), "PRIORITY")
                        if v is not None:
                            if not 0 <= v <= 255:
                                self.d.error("E091", "PRIORITY must be within 0..255", pexpr.pos)
                            task["priority"] = v
                    elif p == "SINGLE":
                        ty = self.expr(pexpr, Scope(None))
                        if ty is not None and not self._is_bool(ty):
                            self.d.error("E091", "SINGLE must be a BOOL variable", pexpr.pos)
                        task["single"] = pexpr
                    else:
                        self.d.error(
                            "E091",
                            f"unknown task parameter '{pname}'",
                            pexpr.pos,
                            "TASK parameters are INTERVAL, PRIORITY and SINGLE",
                        )
                task_names[key] = task
                info.tasks.append(task)
        inst_names: set = set()
        for res in c.resources:
            for p in res.programs:
                key = p.name.upper()
                if key in inst_names:
                    self.d.error("E090", f"program instance '{p.name}' is declared twice", p.pos)
                    continue
                inst_names.add(key)
                pou = self.pous.get(p.type_name.upper())
                if pou is None or pou.kind != "PROGRAM":
                    self.d.error(
                        "E092",
                        f"'{p.type_name}' is not a PROGRAM",
                        p.pos,
                        self._suggest(p.type_name.upper(), [k for k, v in self.pous.items() if v.kind == "PROGRAM"]),
                    )
                    continue
                if p.task is not None and p.task.upper() not in task_names:
                    self.d.error(
                        "E093", f"unknown task '{p.task}'", p.pos, self._suggest(p.task.upper(), list(task_names))
                    )
                    continue
                self.trailing_comma(p.trailing_comma)
                fake = A.Call(A.Name(p.type_name, pos=p.pos), p.args, pos=p.pos)
                binding = CallInfo("fb", pou=pou)
                self._bind_args(fake, pou, binding, Scope(None), is_fb=True)
                info.programs.append(
                    {
                        "name": p.name,
                        "type": pou,
                        "task": p.task,
                        "resource": res.name,
                        "pos": p.pos,
                        "binding": binding,
                    }
                )
        blocks = [b for b in c.var_blocks if b.kind == "VAR_CONFIG"]
        blocks += [b for res in c.resources for b in res.var_blocks if b.kind == "VAR_CONFIG"]
        self._var_config(blocks, info)
        self.configs.append(info)
