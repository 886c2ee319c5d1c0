"""The checker: resolves every name and type, applies the IEC implicit
conversion rules, folds constants and reports coded diagnostics.

It annotates the AST in place (``Expr.ty``, ``Expr.const``, ``Name.sym``,
``Call.target``) and returns a ``CheckedProgram`` the code generator reads.
All errors of all files are collected; the checker never raises on bad input.

The Checker is composed of one part per concern (checker_base.py lists
them); this module runs the passes in order.
"""

from __future__ import annotations

from dataclasses import dataclass, field

from .. import ast as A
from .. import types as T
from .checker_actions import ActionChecks
from .checker_arrays import ArrayChecks
from .checker_base import AddressSpace, Scope
from .checker_calls import CallChecks
from .checker_config import ConfigChecks, ConfigInfo
from .checker_decls import DeclChecks
from .checker_eno import EnEnoChecks
from .checker_exprs import ExprChecks
from .checker_fbinit import FbInitChecks
from .checker_generics import GenericChecks
from .checker_jumps import JumpChecks
from .checker_oop import OopChecks
from .checker_operators import OperatorChecks
from .checker_pointers import PointerChecks
from .checker_refs import RefChecks
from .checker_sfc import SfcChecks
from .checker_stmts import StmtChecks
from .checker_storage import StorageChecks
from .checker_types import TypeChecks
from .checker_varconfig import VarConfigChecks
from .conversions import const_as
from .namespaces import NamespaceChecks

__all__ = ["AddressSpace", "CheckedProgram", "Checker", "ConfigInfo", "const_as"]


@dataclass
class CheckedProgram:
    pous: list  # POUInfo, user and library
    globals: list  # VarSymbol
    structs: list  # StructType in declaration order
    configurations: list  # ConfigInfo
    types: dict  # UPPER -> Type
    # the global variable lists (namespaces.py): UPPER list name -> its UPPER variable names
    global_lists: dict = field(default_factory=dict)
    # the paths of the library files (their globals are not the user's state)
    library_files: frozenset = frozenset()


class Checker(
    TypeChecks,
    DeclChecks,
    StorageChecks,
    ExprChecks,
    OperatorChecks,
    StmtChecks,
    CallChecks,
    RefChecks,
    PointerChecks,
    EnEnoChecks,
    ArrayChecks,
    GenericChecks,
    ConfigChecks,
    VarConfigChecks,
    ActionChecks,
    JumpChecks,
    SfcChecks,
    NamespaceChecks,
    OopChecks,
    FbInitChecks,
):
    """Checker(profile, diags, std_functions, natives=None, image=None).run(files)
    -> CheckedProgram. std_functions: UPPER name -> standard function
    (fblocks/iec/functions.py); natives: UPPER name -> NativeFunction
    (st/native.py); image: where direct addresses are checked (None: not)."""

    def run(self, files: list, library_files: tuple = (), namespaces: dict | None = None) -> CheckedProgram:
        """namespaces: the user's libraries, UPPER namespace -> (its spelling,
        the UPPER names it declares), for OSCAT.DEC_2 (namespaces.py)."""
        self.library_files = set(library_files)
        self.lowered_lines: dict = {}  # file -> (first, last) lines of ST written from another language
        for sf in files:
            if sf.lowered:
                self.lowered_lines.setdefault(sf.path, []).extend(sf.lowered)
        self.user_namespaces: dict = namespaces or {}
        for sf in files:
            self._collect(sf)
        self._collect_actions(files)
        self._resolve_namespaces(files)
        self._declare_early_constants(files)
        for key in self.type_order():
            self._resolve_named_type(key, self.type_decls[key].pos)
        global_blocks: list[tuple[A.VarBlock, A.Configuration | None]] = [
            (b, None) for sf in files for b in sf.decls if isinstance(b, A.VarBlock)
        ]
        for sf in files:
            for decl in sf.decls:
                if isinstance(decl, A.Configuration):
                    # VAR_CONFIG is checked with the CONFIGURATION (checker_varconfig.py)
                    global_blocks += [(b, decl) for b in decl.var_blocks if b.kind != "VAR_CONFIG"]
                    for res in decl.resources:
                        global_blocks += [(b, decl) for b in res.var_blocks if b.kind != "VAR_CONFIG"]
        for block, _ in global_blocks:
            self._declare_globals(block)
        for pou in self.pous.values():
            self._declare_pou_vars(pou)
            self._declare_sfc(pou)
        self._mark_hidden()
        self._oop_declare()
        self._check_instances()
        self._check_containment()
        self._check_sizes()
        for st in self.structs:
            for f in st.fields.values():
                if f.init is not None:
                    f.init_value = self.init_value(f.type, f.init, Scope(None), f"{st.name}.{f.name}")
                else:
                    f.init_value = T.declared_default(f.type)
        for sym in self.globals.values():
            self._check_var_init(sym, Scope(None))
        for pou in self.pous.values():
            scope = Scope(pou)
            for sym in pou.vars.values():
                self._check_var_init(sym, scope)
            self._stmts(pou.node.body, scope)
            self._check_jumps(pou.node.body)
            self._check_actions(pou)
            self._check_sfc(pou)
        self._oop_bodies()
        self.report_internal_reads()
        for sf in files:
            for decl in sf.decls:
                if isinstance(decl, A.Configuration):
                    self._configuration(decl)
        self._check_placeholders()
        return CheckedProgram(
            list(self.pous.values()),
            list(self.globals.values()),
            self.structs,
            self.configs,
            self.types,
            self._lists,
            frozenset(self.library_files),
        )
