"""IEC 61131-3 types as OPC UA built-in types, and values both ways.

    BOOL                      Boolean
    SINT INT DINT LINT        SByte Int16 Int32 Int64
    USINT UINT UDINT ULINT    Byte UInt16 UInt32 UInt64
    BYTE WORD DWORD LWORD     Byte UInt16 UInt32 UInt64
    CHAR WCHAR                Byte UInt16 (the character's code)
    REAL LREAL                Float Double
    TIME LTIME                Double, DataType Duration: milliseconds (PLCopen's
                              OPC UA companion specification maps TIME to Duration)
    TOD LTOD                  Double, DataType Duration: milliseconds since midnight
    DATE DT LDATE LDT         DateTime (UTC)
    STRING WSTRING            String
    a subrange                its base type
    an enumeration            Int32, DataType the enumeration's own EnumDataType node

A value from a client is taken when its variant is of the variable's kind
(any integer variant for an integer variable, any number for a REAL, a
number of milliseconds for a TIME ...); the engine's own check
(``engine/values.py``) decides its range. Anything else is ``Refused`` with
the status code a client expects: BadTypeMismatch or BadOutOfRange.
"""

from __future__ import annotations

from dataclasses import dataclass
from datetime import UTC, datetime, timedelta
from typing import Any, cast

from asyncua import ua

from ...engine.values import without_lone_surrogates
from ...st import types as T
from ...st.rtlib.rtlib import iec_literal

VT = ua.VariantType
INTEGER_VARIANTS = frozenset((VT.SByte, VT.Byte, VT.Int16, VT.UInt16, VT.Int32, VT.UInt32, VT.Int64, VT.UInt64))
NUMBER_VARIANTS = INTEGER_VARIANTS | {VT.Float, VT.Double}
EPOCH = datetime(1970, 1, 1, tzinfo=UTC)
DAY_NS = 86_400 * 1_000_000_000

_SIGNED = {8: VT.SByte, 16: VT.Int16, 32: VT.Int32, 64: VT.Int64}
_UNSIGNED = {8: VT.Byte, 16: VT.UInt16, 32: VT.UInt32, 64: VT.UInt64}


def node_id(identifier: int | str, ns: int = 0) -> ua.NodeId:
    """ua.NodeId from a plain int or str (asyncua annotates its fields with NewTypes)."""
    return ua.NodeId(cast(Any, identifier), cast(Any, ns))


class Refused(Exception):
    """A client's value the variable cannot take: status is the OPC UA status code to answer."""

    def __init__(self, status: int, message: str) -> None:
        super().__init__(message)
        self.status = status


@dataclass(frozen=True)
class UaType:
    """How values of one ST type (resolved) appear in OPC UA."""

    st: T.Type
    variant: ua.VariantType
    data_type: ua.NodeId  # a built-in DataType, Duration; an enumeration's is set by the address space

    @property
    def enum(self) -> T.EnumType | None:
        return self.st if isinstance(self.st, T.EnumType) else None

    def default(self) -> Any:
        return self.to_ua(0 if not isinstance(self.st, T.StringType) else "")

    def to_ua(self, raw: Any) -> Any:
        """The value as the engine stores it -> the value of an OPC UA variant."""
        st = self.st
        if isinstance(st, T.ElementaryType):
            if st.is_bool:
                return bool(raw)
            if st.category in (T.DURATION, T.TODCAT):
                return int(raw) * st.unit_ns / 1_000_000
            if st.category in (T.DATECAT, T.DTCAT):
                return EPOCH + timedelta(microseconds=int(raw) * st.unit_ns // 1000)
            if st.is_real:
                return float(raw)
            return int(raw)
        if isinstance(st, T.StringType):  # a lone surrogate no client can decode (engine/values.py)
            return without_lone_surrogates(str(raw))
        return int(raw)

    def from_ua(self, variant: ua.Variant, path: str) -> Any:
        """A client's variant -> a value for Access.submit (engine/values.py from_python)."""
        st, kind, value = self.st, variant.VariantType, variant.Value
        if value is None or isinstance(value, (list, tuple)):
            raise self._mismatch(variant, path)
        if isinstance(st, T.StringType):
            if kind != VT.String:
                raise self._mismatch(variant, path)
            return value
        if isinstance(st, (T.EnumType, T.SubrangeType)):
            if kind not in INTEGER_VARIANTS:
                raise self._mismatch(variant, path)
            return int(value)
        assert isinstance(st, T.ElementaryType)
        if st.is_bool:
            if kind != VT.Boolean:
                raise self._mismatch(variant, path)
            return bool(value)
        if st.category in (T.DURATION, T.TODCAT):
            if kind not in NUMBER_VARIANTS:
                raise self._mismatch(variant, path)
            return self._duration_in(float(value), path)
        if st.category in (T.DATECAT, T.DTCAT):
            if kind != VT.DateTime or not isinstance(value, datetime):
                raise self._mismatch(variant, path)
            return self._date_in(value, path)
        if st.is_real:
            if kind not in NUMBER_VARIANTS:
                raise self._mismatch(variant, path)
            return float(value)
        if kind not in INTEGER_VARIANTS:
            raise self._mismatch(variant, path)
        return int(value)

    def _duration_in(self, ms: float, path: str) -> str:
        st = self.st
        assert isinstance(st, T.ElementaryType)
        if ms != ms or abs(ms) > 1e15:
            raise Refused(ua.StatusCodes.BadOutOfRange, f"{path} is {st.name}: {ms} ms is out of its range")
        raw = round(ms * 1_000_000 / st.unit_ns)
        if st.category == T.TODCAT:
            if not 0 <= raw * st.unit_ns < DAY_NS:
                raise Refused(ua.StatusCodes.BadOutOfRange, f"{path} is {st.name}: write 0 to 86400000 ms")
            return iec_literal(st, raw)
        ns = raw * st.unit_ns
        return f"T#-{-ns}ns" if ns < 0 else f"T#{ns}ns"

    def _date_in(self, when: datetime, path: str) -> str:
        st = self.st
        assert isinstance(st, T.ElementaryType)
        if when.tzinfo is None:
            when = when.replace(tzinfo=UTC)
        delta = when - EPOCH
        ns = (delta.days * 86_400 + delta.seconds) * 1_000_000_000 + delta.microseconds * 1000
        if ns < 0:
            raise Refused(ua.StatusCodes.BadOutOfRange, f"{path} is {st.name}: write a time after 1970-01-01")
        return iec_literal(st, ns // st.unit_ns)

    def _mismatch(self, variant: ua.Variant, path: str) -> Refused:
        return Refused(
            ua.StatusCodes.BadTypeMismatch,
            f"{path} is {self.st.name} ({self.variant.name}): a {variant.VariantType.name} cannot be written to it",
        )


def ua_type(t: T.Type) -> UaType | None:
    """The OPC UA form of a scalar ST type; None for an array, a struct, an
    FB, a reference or anything else with no scalar form."""
    r = T.resolve(t)
    if isinstance(r, T.SubrangeType):
        base = ua_type(r.base)
        return None if base is None else UaType(r, base.variant, base.data_type)
    if isinstance(r, T.EnumType):
        return UaType(r, VT.Int32, node_id(ua.ObjectIds.Int32))
    if isinstance(r, T.StringType):
        return UaType(r, VT.String, node_id(ua.ObjectIds.String))
    if not isinstance(r, T.ElementaryType):
        return None
    if r.is_bool:
        variant = VT.Boolean
    elif r.category in (T.DURATION, T.TODCAT):
        return UaType(r, VT.Double, node_id(ua.ObjectIds.Duration))
    elif r.category in (T.DATECAT, T.DTCAT):
        variant = VT.DateTime
    elif r.is_real:
        variant = VT.Float if r.bits == 32 else VT.Double
    elif r.category == T.SIGNED:
        variant = _SIGNED[r.bits]
    elif r.is_intlike or r.is_char:
        variant = _UNSIGNED[r.bits]
    else:
        return None
    return UaType(r, variant, node_id(int(variant)))
