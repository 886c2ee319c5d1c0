"""What the parts of the checker share: state, scope and helpers.

The Checker (checker.py) is one class composed of a part per concern, each
in its own module: checker_types (declared types), checker_decls
(variables and initial values), checker_storage (types that contain
themselves, the size limits of limits.py), checker_exprs (names, members, indices,
literals, addresses), checker_operators, checker_stmts (statements and
assignment targets), checker_calls (every kind of call),
checker_actions (ACTIONs of POUs), checker_jumps (JMP and labels) and
checker_config (the CONFIGURATION). The implicit-conversion rule they apply is
conversions.py. A part calls the others through ``self``; what it may call
is declared at the end of CheckerBase, for the type checker.
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import TYPE_CHECKING, Any, Protocol

from .. import ast as A
from .. import types as T
from ..diagnostics import DiagnosticBag
from ..hints import NameIndex
from ..profile import Profile, names_where
from .conversions import check_implicit
from .symbols import CallInfo, POUInfo, VarSymbol

# Called like functions without a declaration (checker_calls._builtin_call).
BUILTINS = ("TIME", "LTIME", "REF", "ADR", "SIZEOF", "__ISVALIDREF", "LOWER_BOUND", "UPPER_BOUND")


class AddressSpace(Protocol):
    """Where direct addresses are checked: a process image laid out for the
    profile's addressing model (runtime/image/memory.ProcessImage). Both
    calls raise ValueError for an address outside it."""

    size: int

    def table(self, addr: A.LocatedAddress) -> Any: ...

    def accessor(self, addr: A.LocatedAddress, ty: T.ElementaryType) -> Any: ...


class Scope:
    """Where an expression is checked: the POU (or None for global
    initialisers) and the loop nesting for EXIT/CONTINUE."""

    def __init__(self, pou: POUInfo | None) -> None:
        self.pou = pou
        self.loops = 0
        self.for_vars: list = []  # VarSymbols of enclosing FOR loops
        self.names: dict = {}  # UPPER -> VarSymbol of this part only (an SFC transition's name)
        self.sfc_part: str | None = None  # 'an ACTION' or 'a TRANSITION' of an SFC body


class CheckerBase:
    """The checker's state; the parts add the checks (see the module docstring)."""

    def __init__(
        self,
        profile: Profile,
        diags: DiagnosticBag,
        std_functions: dict,
        natives: Mapping | None = None,
        image: AddressSpace | None = None,
        elsewhere: Mapping | None = None,
    ) -> None:
        self.profile = profile
        self.d = diags
        self.std = std_functions
        self.natives: Mapping = natives or {}  # UPPER -> native.NativeFunction
        #: UPPER name -> where it is declared when not in the program: a library
        #: softplc knows ("Tc2_System; add it to libraries = [...]"), looked up
        #: only for a name that is unknown (so it may be built lazily)
        self.elsewhere: Mapping = elsewhere or {}
        self.type_decls: dict = {}  # UPPER -> TypeDecl
        self.types: dict = {}  # UPPER -> Type (resolved)
        self._resolving: dict = {}  # UPPER -> name as declared, of the types being resolved, in order
        self._depth: dict = {}  # id of a StructType -> how deep it nests (limits.MAX_TYPE_NESTING)
        self._too_deep: set = set()  # UPPER names of the types past the limit (reported at the first)
        self.pous: dict = {}  # UPPER -> POUInfo
        self.action_names: set = set()  # UPPER names of all ACTIONs (checker_actions.py)
        self.globals: dict = {}  # UPPER -> VarSymbol
        self.enumerators: dict = {}  # UPPER -> [(EnumType, value)]
        self.structs: list = []
        self.configs: list = []
        self.library_files: set = set()
        self.lowered_lines: dict = {}
        #: the user's libraries: UPPER namespace -> (spelling, UPPER names) (namespaces.py)
        self.user_namespaces: dict = {}
        self._inited: set = set()  # ids of VarSymbols whose initial value is checked
        self._chain_checked: set = set()  # ids of a long chain's operations checked ahead (checker_exprs.py)
        self._image_probe = image  # to validate direct addresses (None: not checked)
        self._setter_only: list = []  # uses of a PROPERTY without GET (checker_oop.py)
        self._assigned: set = set()  # ids of the assignment targets among them
        #: id -> (Member, VarSymbol, FBType): an FB's internal variable read
        #: from outside where the profile allows it (W113; E013 when written)
        self._internal_reads: dict = {}
        #: the global variable list whose variable's initial value is being
        #: checked: its qualified_only names may go bare there (namespaces.py)
        self.initialising_list: str | None = None
        #: the name lists hints were looked up in -> their index (hints.py)
        self._hint_indexes: dict[tuple, NameIndex] = {}

    def _is_bool(self, ty: T.Type) -> bool:
        e = T.base_elementary(ty)
        return e is not None and e.is_bool and not isinstance(T.resolve(ty), T.EnumType)

    def check_convertible(self, src: T.Type, dst: T.Type, e: A.Expr, what: str) -> bool:
        """Report unless a value of type src may be stored into dst
        implicitly (the rule: conversions.check_implicit)."""
        return check_implicit(src, dst, e, what, self.profile, self.d)

    def trailing_comma(self, pos: A.Pos | None) -> None:
        """A comma that ends an argument list, F(a := 1,): accepted where
        the profile says so (TwinCAT), E044 elsewhere."""
        if pos is not None and not self.profile.trailing_comma_in_calls:
            self.d.error(
                "E044",
                "a comma ends the argument list",
                pos,
                f"remove it (the {names_where(lambda p: p.trailing_comma_in_calls)} profiles accept it)",
            )

    def _elsewhere(self, name: str) -> str:
        """' (Tc2_System; add it to libraries = [...])' for an unknown name a
        library softplc knows declares, else ''."""
        where = self.elsewhere.get(name.upper()) if self.elsewhere else None
        return f" ({where})" if where else ""

    def _suggest(self, key: str, names: list) -> str | None:
        """ "did you mean 'Name'?" for the UPPER key, or None: the closest
        of names (hints.py), each list indexed once per check."""
        listed = tuple(names)
        index = self._hint_indexes.get(listed)
        if index is None:
            index = self._hint_indexes[listed] = NameIndex(listed)
        close = index.closest(key, 0.75)
        return f"did you mean '{close}'?" if close is not None else None

    if TYPE_CHECKING:
        # namespaces.py: UPPER global variable list -> its UPPER variable names
        _lists: dict

        # Implemented by the parts: what one part calls of another.
        # checker_types
        def type_of(self, spec: A.TypeSpec, scope: Scope | None = None) -> T.Type | None: ...

        # checker_decls
        def init_value(self, ty: T.Type, init: Any, scope: Scope, what: str, ref_ok: bool = False) -> Any: ...

        def _const_int(self, e: A.Expr, scope: Scope, what: str) -> int | None: ...

        # checker_exprs
        def expr(self, e: A.Expr, scope: Scope, expected: T.Type | None = None) -> T.Type | None: ...

        def internal_written(self, e: A.Member) -> bool: ...

        def report_internal_reads(self) -> None: ...

        def _address_fits(self, addr: A.LocatedAddress, ty: T.ElementaryType | None, pos: A.Pos) -> bool: ...

        # namespaces
        def _check_qualified_only(self, e: A.Name) -> None: ...

        # checker_varconfig
        def _check_placeholder(self, sym: VarSymbol) -> None: ...

        def _var_config(self, blocks: list, config: Any) -> None: ...

        # checker_operators
        def _unary(self, e: A.Unary, scope: Scope, expected: T.Type | None) -> T.Type | None: ...

        def _binary(self, e: A.Binary, scope: Scope, expected: T.Type | None) -> T.Type | None: ...

        def _takes_context(self, e: A.Expr, scope: Scope) -> bool: ...

        def _common(
            self, le: T.ElementaryType, re_: T.ElementaryType, e: A.Expr, report: bool = True
        ) -> T.ElementaryType | None: ...

        # checker_stmts
        def _stmts(self, body: list, scope: Scope) -> None: ...

        def lvalue(self, e: A.Expr, scope: Scope) -> T.Type | None: ...

        def assign_expr(self, e: A.AssignExpr, scope: Scope) -> T.Type | None: ...

        def _is_lvalue_expr(self, e: A.Expr) -> bool: ...

        def _check_writable(self, e: A.Expr, scope: Scope) -> None: ...

        def operator_call(self, e: A.Call, func: Any, scope: Scope) -> T.Type | None: ...

        # checker_jumps
        def _check_jumps(self, body: list) -> None: ...

        # checker_actions
        def own_action_call(self, e: A.Call, scope: Scope, as_statement: bool) -> bool: ...

        def member_action_call(self, e: A.Call, scope: Scope, as_statement: bool) -> bool: ...

        # checker_sfc
        def is_sfc_action(self, pou: POUInfo, key: str) -> bool: ...

        # checker_pointers
        def pointer_index(self, e: A.Index, ptr: T.Type, scope: Scope) -> T.Type | None: ...

        # checker_oop
        @staticmethod
        def owner_fb(scope: Scope) -> POUInfo | None: ...

        # checker_calls
        def call(
            self, e: A.Call, scope: Scope, as_statement: bool, expected: T.Type | None = None
        ) -> T.Type | None: ...

        def is_context_trunc(self, e: A.Expr) -> bool: ...

        def _std_args(self, e: A.Call, func: Any, scope: Scope) -> list | None: ...

        def _check_args_loosely(self, e: A.Call, scope: Scope) -> None: ...

        def _bind_args(self, e: A.Call, pou: POUInfo, info: CallInfo, scope: Scope, is_fb: bool) -> None: ...

        def _mark_boxed(self, e: A.Expr, scope: Scope) -> None: ...

        # checker_refs
        def _not_a_reference(self, ty: T.Type, what: str, pos: A.Pos) -> bool: ...

        def implicit_deref(self, e: A.Expr, ty: T.Type | None) -> T.Type | None: ...

        def ref_bind(self, s: A.Assign, scope: Scope) -> None: ...

        def isvalidref(self, e: A.Call, scope: Scope) -> T.Type | None: ...

        def sizeof_call(self, e: A.Call, a: A.Expr, scope: Scope) -> T.Type | None: ...

        # checker_pointers
        def string_index(self, e: A.Index, b: T.StringType) -> T.Type | None: ...

        # checker_pointers
        def pointer_binary(self, e: A.Binary, lt: T.Type, rt: T.Type) -> T.Type | None: ...

        def reference_init(self, ty: T.Type, init: A.Expr, scope: Scope, what: str, ref_ok: bool) -> Any: ...

        def bind_argument(self, param: VarSymbol, value: A.Expr, scope: Scope) -> bool: ...

        def _fixed_place(self, e: A.Expr) -> bool: ...

        def _fb_call(
            self, e: A.Call, inst: A.Expr, scope: Scope, as_statement: bool, typed: bool = False
        ) -> T.Type | None: ...

        # checker_exprs
        def _member_of(self, e: A.Member, bty: T.Type, scope: Scope) -> T.Type | None: ...

        # checker_types
        def _clash(self, key: str, name: str, pos: A.Pos) -> bool: ...

        # checker_decls
        def _declare_pou_vars(self, pou: POUInfo) -> None: ...

        def _make_var(self, decl: A.VarDecl, block: A.VarBlock, owner: POUInfo | None) -> VarSymbol | None: ...

        def _check_var_init(self, sym: VarSymbol, scope: Scope) -> None: ...

        # checker_stmts
        def _stmts(self, body: list, scope: Scope) -> None: ...

        # checker_oop
        def _collect_interface(self, decl: A.Interface, library: bool) -> None: ...

        def _oop_name(self, e: A.Name, key: str, scope: Scope) -> tuple | None: ...

        def _this_deref(self, e: A.Deref, scope: Scope) -> T.Type | None: ...

        def _oop_member(self, e: A.Member, b: T.Type, scope: Scope) -> tuple | None: ...

        def _program_property(self, e: A.Member, scope: Scope) -> tuple | None: ...

        # checker_fbinit
        def fb_init_spec(self, spec: A.TypeSpec) -> tuple: ...

        def _check_fb_init_var(self, sym: VarSymbol, scope: Scope) -> None: ...

        def _fb_init_required(self, pou: POUInfo | None, what: str, pos: A.Pos) -> None: ...

        def inside_fb(self, scope: Scope, fb: POUInfo) -> bool: ...

        def _oop_call(self, e: A.Call, scope: Scope, as_statement: bool) -> tuple | None: ...

        def _query_interface(self, e: A.Call, scope: Scope) -> T.Type | None: ...

        def _assignment_attempt(self, s: A.Assign, scope: Scope) -> None: ...

        # checker_arrays
        def bound_call(self, e: A.Call, key: str, scope: Scope) -> T.Type | None: ...

        # checker_generics
        def generic_input_type(self, spec: A.TypeSpec, section: str, owner_kind: str | None) -> tuple | None: ...

        def generic_argument(self, param: VarSymbol, ty: T.Type, value: A.Expr) -> None: ...

        # checker_eno
        def check_declared_eno(self, pou: POUInfo) -> None: ...

        def implicit_eno(self, pou: POUInfo | None) -> VarSymbol | None: ...

        def en_argument(self, a: A.Arg, info: CallInfo, scope: Scope) -> None: ...

        def split_en_eno(self, e: A.Call, scope: Scope) -> Any: ...

        def attach_gate(self, e: A.Call, gate: Any) -> None: ...
