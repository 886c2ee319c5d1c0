"""Value semantics of aggregates at run time: ST assigns arrays, structs and
function block instances by value. Generated code assigns into the existing
object (so references to it stay valid) and copies where a new value is
needed (a FUNCTION input, a returned structure)."""

from __future__ import annotations


def copy_value(v):
    """A deep copy of an ST value (scalars are immutable and returned as is)."""
    if isinstance(v, list):
        if v and isinstance(v[0], list) or (v and hasattr(v[0], "_copy")):
            return [copy_value(x) for x in v]
        return v[:]
    copier = getattr(v, "_copy", None)
    if copier is not None:
        return copier()
    if hasattr(v, "__len__") and hasattr(v, "__getitem__") and not isinstance(v, str):
        return [v[i] for i in range(len(v))]  # a process-image word table
    return v


def assign_into(dst, src) -> None:
    """dst := src for an aggregate, in place."""
    if isinstance(dst, list):
        if dst and (isinstance(dst[0], list) or hasattr(dst[0], "_assign")):
            for d, s in zip(dst, src):
                assign_into(d, s)
        else:
            dst[:] = list(src)
        return
    assigner = getattr(dst, "_assign", None)
    if assigner is not None:
        assigner(src)
        return
    for i in range(len(dst)):  # a process-image word table
        dst[i] = src[i]


# A FUNCTION_BLOCK's or PROGRAM's class takes these as its _assign and _copy,
# driven by its _COPY_ plan ((slot, aggregate?) for every stored variable,
# inherited ones included): instances are seldom copied (fb1 := fb2), and
# unrolled methods would be a third of the generated lines for every block
# (codegen_pous.py). A STRUCT keeps unrolled ones: structs are copied often.


def slot_assign(self, o) -> None:
    """self := o for an FB instance, in place (aggregates into their objects)."""
    for name, aggregate in self._COPY_:
        if aggregate:
            assign_into(getattr(self, name), getattr(o, name))
        else:
            setattr(self, name, getattr(o, name))


def slot_copy(self):
    """A copy of an FB instance: a new object of its class, aggregates deep."""
    cls = type(self)
    n = cls.__new__(cls)
    for name, aggregate in self._COPY_:
        value = getattr(self, name)
        setattr(n, name, copy_value(value) if aggregate else value)
    return n
