"""A client's write to a PLC variable: checked, then made through the
engine's one write API (``Access.submit(..., surface="opcua")``), so the
PLC variable changes at the start of the next scan, not only the node.

asyncua's attribute service stores a written value in the node; this one
(put in its place on the internal server) does that for nodes that are not
PLC variables, and for PLC variables answers

    BadNotWritable        the variable is not in [opcua] writable
    BadUserAccessDenied   users are configured and the client is anonymous,
                          or the engine's permission check refused it
    BadTypeMismatch       a value of another kind (a string for an INT ...)
    BadOutOfRange         a value the ST type cannot hold (300 for a SINT)
    BadTimeout            no scan took the write within WRITE_TIMEOUT_S
    BadNodeIdUnknown      the variable is gone (an online change)

Each refusal is logged with the variable and the reason (the value in it
cut; the lines rate limited, child.py). A REAL takes no NaN or infinity
(BadOutOfRange), a string no lone surrogate: the one write API's rules
(engine/values.py). The server's own updates of the nodes go around this
service (``write_attribute_value``).
"""

from __future__ import annotations

import asyncio
import logging

from asyncua import ua
from asyncua.crypto.permission_rules import User, UserRole
from asyncua.server.address_space import AttributeService

from ...config.values import cut
from ...engine.access import Access, AccessDenied
from ...engine.places import PathError
from .space import flatten, nest
from .tree import Variable
from .typemap import Refused

log = logging.getLogger("softplc.surfaces.opcua")

ADMIN = User(role=UserRole.Admin)  # the server's own writes, as asyncua's default
#: how long a write waits for the scan that makes it
WRITE_TIMEOUT_S = 5.0


class PlcAttributeService(AttributeService):
    def __init__(self, aspace, access: Access, variables: dict, login_to_write: bool, on_written) -> None:
        super().__init__(aspace)
        self.access = access
        self.variables = variables  # NodeId -> Variable
        self.login_to_write = login_to_write
        self.on_written = on_written  # (variable, the client's DataValue) -> None

    async def write(self, params: ua.WriteParameters, user: User = ADMIN) -> list[ua.StatusCode]:
        results: list[ua.StatusCode] = []
        for item in params.NodesToWrite:
            var = self.variables.get(item.NodeId)
            if var is None or item.AttributeId != ua.AttributeIds.Value:
                one = ua.WriteParameters(NodesToWrite=[item])
                results.extend(await super().write(one, user))
                continue
            try:
                await self._write(var, item.Value, user)
            except Refused as exc:  # rate limited with every line of this process (child.py)
                log.info("opcua: write to %s refused: %s", var.path, cut(str(exc)))
                results.append(ua.StatusCode(ua.UInt32(exc.status)))
                continue
            self.on_written(var, item.Value)
            results.append(ua.StatusCode())
        return results

    async def _write(self, var: Variable, value: ua.DataValue, user: User) -> None:
        if not var.writable:
            raise Refused(ua.StatusCodes.BadNotWritable, "read-only (list it in [opcua] writable to allow writes)")
        if self.login_to_write and user.role != UserRole.Admin and user.name is None:
            raise Refused(ua.StatusCodes.BadUserAccessDenied, "anonymous clients may not write: log in as a user")
        if value.Value is None:
            raise Refused(ua.StatusCodes.BadTypeMismatch, "no value")
        plc_value = _plc_value(var, value.Value)
        try:
            future = self.access.submit("write", var.path, plc_value, surface="opcua")
        except AccessDenied as exc:
            raise Refused(ua.StatusCodes.BadUserAccessDenied, str(exc)) from None
        except PathError as exc:
            raise Refused(ua.StatusCodes.BadNodeIdUnknown, str(exc)) from None
        except ValueError as exc:
            raise Refused(ua.StatusCodes.BadOutOfRange, str(exc)) from None
        try:
            await asyncio.wait_for(asyncio.wrap_future(future), WRITE_TIMEOUT_S)
        except TimeoutError:
            raise Refused(ua.StatusCodes.BadTimeout, f"no scan took it within {WRITE_TIMEOUT_S} s") from None
        except Exception as exc:  # the scan refused it (a fault storing it): the client hears why
            raise Refused(ua.StatusCodes.BadInternalError, str(exc)) from None


def _plc_value(var: Variable, variant: ua.Variant):
    """The client's variant as a value Access takes: a scalar, or nested lists for an array."""
    if not var.dims:
        return var.ua.from_ua(variant, var.path)
    if not isinstance(variant.Value, (list, tuple)):
        raise Refused(ua.StatusCodes.BadTypeMismatch, f"{var.path} is an array: write an array")
    flat = flatten(variant.Value)
    if len(flat) != len(var.elements):
        raise Refused(ua.StatusCodes.BadTypeMismatch, f"{var.path} has {len(var.elements)} elements, not {len(flat)}")
    out = [var.ua.from_ua(ua.Variant(v, variant.VariantType), f"{var.path} element {i}") for i, v in enumerate(flat)]
    return nest(out, var.dims)
