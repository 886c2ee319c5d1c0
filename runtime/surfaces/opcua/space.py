"""The tree (tree.py) as nodes of an asyncua server's address space.

Objects and variables are added in one AddNodes call (thousands of
variables in a fraction of a second); each enumeration becomes a DataType
under Enumeration with its EnumValues property and its EnumDefinition, so
a client shows the names (UaExpert, asyncua's ``load_enums``).
"""

from __future__ import annotations

from dataclasses import replace
from typing import Any, cast

from asyncua import Server, ua

from ...st import types as T
from .tree import Object, Tree, Variable
from .typemap import node_id

_OBJECTS = node_id(ua.ObjectIds.ObjectsFolder)
_ORGANIZES = node_id(ua.ObjectIds.Organizes)
_HAS_COMPONENT = node_id(ua.ObjectIds.HasComponent)
_BASE_OBJECT = node_id(ua.ObjectIds.BaseObjectType)
_FOLDER = node_id(ua.ObjectIds.FolderType)
_BASE_VARIABLE = node_id(ua.ObjectIds.BaseDataVariableType)
READ = ua.AccessLevel.CurrentRead.mask
READ_WRITE = READ | ua.AccessLevel.CurrentWrite.mask


async def add_enums(server: Server, idx: int, enums: dict) -> dict:
    """A DataType node per enumeration: ST name -> its NodeId."""
    out: dict = {}
    for name, enum in enums.items():
        nid = node_id(f"#type.{name}", idx)
        dtype = await server.nodes.enum_data_type.add_data_type(nid, ua.QualifiedName(name, idx))
        values = [(enum.spelled[key], int(v)) for key, v in enum.values.items()]
        await dtype.add_property(
            node_id(f"#type.{name}.EnumValues", idx),
            ua.QualifiedName("EnumValues", 0),  # the standard property's name, in namespace 0
            [
                ua.EnumValueType(Value=v, DisplayName=ua.LocalizedText(n), Description=ua.LocalizedText(n))
                for n, v in values
            ],
            varianttype=ua.VariantType.ExtensionObject,
            datatype=node_id(ua.ObjectIds.EnumValueType),
        )
        definition = ua.EnumDefinition(
            Fields=[ua.EnumField(Name=n, Value=v, DisplayName=ua.LocalizedText(n)) for n, v in values]
        )
        await dtype.write_data_type_definition(definition)
        out[name] = nid
    return out


def tree_items(idx: int, tree: Tree, enums: dict, values: dict) -> list:
    """Every object and variable of tree under Objects as AddNodesItems, each
    after its parent; values: a snapshot's (path -> value as stored), a
    variable without one starts at its type's default."""
    items: list = []
    for root in tree.roots:
        _object_items(root, _OBJECTS, _ORGANIZES, idx, enums, values, items)
    return items


async def add_tree(server: Server, items: list, known: dict | None = None) -> dict:
    """The nodes of items (tree_items) in the server's address space, and the
    signature of each (NodeId -> what the node is, its value aside).

    known: what the last call returned, for a tree already in the space (an
    online change): a node the same as before, under a parent the same as
    before, stays as it is, so a client's subscription of it goes on; a node
    that changed or went is deleted with everything under it, and what is
    new or changed is added. Kept variables' values are the caller's to
    update (they still hold the last published ones)."""
    known = known or {}
    signatures = {item.RequestedNewNodeId: _signature(item) for item in items}
    kept: set = set()
    for item in items:  # parents first: a node is kept only under a kept parent
        nid = item.RequestedNewNodeId
        if known.get(nid) == signatures[nid] and (item.ParentNodeId == _OBJECTS or item.ParentNodeId in kept):
            kept.add(nid)
    gone = [nid for nid, sig in known.items() if nid not in kept and (sig[0] == _OBJECTS or sig[0] in kept)]
    if gone:  # the topmost of what goes: deleting them takes what is under them too
        await server.delete_nodes([server.get_node(nid) for nid in gone], True)
    added = [item for item in items if item.RequestedNewNodeId not in kept]
    results = await server.iserver.isession.add_nodes(added)
    for item, result in zip(added, results):
        if not result.StatusCode.is_good():
            raise RuntimeError(f"opcua: cannot add {item.RequestedNewNodeId.Identifier}: {result.StatusCode}")
    return signatures


def _signature(item: ua.AddNodesItem) -> tuple:
    """What a node is, its value aside: parent first (add_tree reads it)."""
    attrs = item.NodeAttributes
    if isinstance(attrs, ua.VariableAttributes):
        attrs = replace(attrs, Value=ua.Variant())
    return (item.ParentNodeId, item.ReferenceTypeId, item.BrowseName, item.NodeClass, item.TypeDefinition, attrs)


def _object_items(
    obj: Object, parent: ua.NodeId, ref: ua.NodeId, idx: int, enums: dict, values: dict, items: list
) -> None:
    nid = node_id(obj.node_id, idx)
    attrs = ua.ObjectAttributes(
        DisplayName=ua.LocalizedText(obj.name), Description=ua.LocalizedText(obj.type_name), EventNotifier=0
    )
    items.append(
        ua.AddNodesItem(
            ParentNodeId=parent,
            ReferenceTypeId=ref,
            RequestedNewNodeId=nid,
            BrowseName=ua.QualifiedName(obj.name, idx),
            NodeClass=ua.NodeClass.Object,
            NodeAttributes=attrs,
            TypeDefinition=_FOLDER if obj.folder else _BASE_OBJECT,
        )
    )
    child_ref = _ORGANIZES if obj.folder else _HAS_COMPONENT
    for child in obj.children:
        if isinstance(child, Object):
            _object_items(child, nid, child_ref, idx, enums, values, items)
        else:
            items.append(_variable_item(child, nid, child_ref, idx, enums, values))


def _variable_item(
    var: Variable, parent: ua.NodeId, ref: ua.NodeId, idx: int, enums: dict, values: dict
) -> ua.AddNodesItem:
    enum = var.ua.enum
    data_type = enums[enum.name] if enum is not None else var.ua.data_type
    access = READ_WRITE if var.writable else READ
    attrs = ua.VariableAttributes(
        DisplayName=ua.LocalizedText(var.name),
        Description=ua.LocalizedText(_describe(var)),
        Value=variant(var, values),
        DataType=data_type,
        ValueRank=len(var.dims) if var.dims else ua.ValueRank.Scalar,
        ArrayDimensions=cast(Any, list(var.dims) if var.dims else None),
        AccessLevel=access,
        UserAccessLevel=access,
        WriteMask=0,
        UserWriteMask=0,
        Historizing=False,
    )
    return ua.AddNodesItem(
        ParentNodeId=parent,
        ReferenceTypeId=ref,
        RequestedNewNodeId=node_id(var.path, idx),
        BrowseName=ua.QualifiedName(var.name, idx),
        NodeClass=ua.NodeClass.Variable,
        NodeAttributes=attrs,
        TypeDefinition=_BASE_VARIABLE,
    )


def _describe(var: Variable) -> str:
    text = var.ua.st.name
    if var.dims:
        text = f"ARRAY[{', '.join(f'{d}' for d in var.dims)} elements] OF {text}"
    if isinstance(var.ua.st, T.ElementaryType) and var.ua.st.category in (T.DURATION, T.TODCAT):
        text += " (ms)"
    return text


def variant(var: Variable, values: dict) -> ua.Variant:
    """The variable's value in values (path -> as stored) as a Variant; the
    type's default where a value is missing."""
    t = var.ua
    if not var.dims:
        raw = values.get(var.path)
        return ua.Variant(t.default() if raw is None else t.to_ua(raw), t.variant)
    flat = [t.default() if (raw := values.get(p)) is None else t.to_ua(raw) for p in var.elements]
    return ua.Variant(nest(flat, var.dims), t.variant, Dimensions=list(var.dims) if len(var.dims) > 1 else None)


def nest(flat: list, dims: tuple) -> list:
    """A flat list, row by row, as nested lists of dims."""
    if len(dims) <= 1:
        return flat
    step = len(flat) // dims[0]
    return [nest(flat[i * step : (i + 1) * step], dims[1:]) for i in range(dims[0])]


def flatten(value: Any) -> list:
    if isinstance(value, (list, tuple)):
        return [x for item in value for x in flatten(item)]
    return [value]
