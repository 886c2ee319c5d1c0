"""MODBUS_SAFE_WRITE's table (runtime/io/modbus/safe.py): what a block may
declare, the writes it gives while outputs are held safe, and the safe
values in place of what the program's requests would write. End to end,
with the Eaton drive: tests/devices/eaton/test_safe_state.py."""

from __future__ import annotations

import pytest

from softplc.runtime.io.modbus.link import Transaction
from softplc.runtime.io.modbus.safe import RETRY_NS, SafeWrites


def table() -> SafeWrites:
    return SafeWrites(lambda name: name == "drives")


@pytest.mark.parametrize(
    ("connection", "unit", "offset", "count", "values"),
    [
        ("pumps", 1, 0, 2, [0, 0]),  # no such connection
        ("drives", 0, 0, 2, [0, 0]),  # broadcast: nobody answers
        ("drives", 248, 0, 2, [0, 0]),
        ("drives", 1, 0, 0, [0, 0]),
        ("drives", 1, 0, 3, [0, 0]),  # more than the table holds
        ("drives", 1, 0, 124, [0] * 124),  # more than function 16 carries
        ("drives", 1, 65535, 2, [0, 0]),  # past the last register
        ("drives", 1, -1, 1, [0]),
    ],
)
def test_what_a_block_cannot_declare(connection, unit, offset, count, values):
    safe = table()
    assert safe.request("MODBUS_SAFE_WRITE", connection, unit, offset, count, values, False) is False
    assert safe.values == {}


def test_the_writes_while_held_and_their_retry():
    safe = table()
    assert safe.request("MODBUS_SAFE_WRITE", "drives", 1, 0, 2, [0, 0], False)
    assert safe.request("MODBUS_SAFE_WRITE", "drives", 1, 3, 1, [300], False)  # ID 4 too
    assert safe.request("MODBUS_SAFE_WRITE", "drives", 2, 0, 2, [-1, 5], True)  # signed table: raw words
    safe.hold()
    due = safe.due(0)
    assert [(c, tx) for c, tx, _key in due] == [
        ("drives", Transaction(1, 16, 0, 0, (0, 0))),
        ("drives", Transaction(1, 16, 3, 0, (300,))),
        ("drives", Transaction(2, 16, 0, 0, (0xFFFF, 5))),
    ]
    safe.done(due[0][2], True)  # unit 1 answered; unit 2 did not
    assert safe.due(RETRY_NS - 1) == []
    assert [tx.unit for _c, tx, _k in safe.due(RETRY_NS)] == [2]


def test_a_block_declaring_again_while_held_is_written_once_more_only_if_it_changed():
    safe = table()
    safe.request("MODBUS_SAFE_WRITE", "drives", 1, 0, 2, [0, 0], False)
    safe.hold()
    [(_c, _tx, key)] = safe.due(0)
    safe.done(key, True)
    safe.request("MODBUS_SAFE_WRITE", "drives", 1, 0, 2, [0, 0], False)  # the block identified again
    assert safe.due(10) == []
    safe.request("MODBUS_SAFE_WRITE", "drives", 1, 0, 2, [8, 0], False)  # now coast
    assert [tx.values for _c, tx, _k in safe.due(10)] == [(8, 0)]


@pytest.mark.parametrize(
    ("tx", "written"),
    [
        (Transaction(1, 6, 0, 0, (1,)), (0,)),  # ID 1 alone
        (Transaction(1, 6, 2, 0, (7,)), (7,)),  # a register without a safe value
        (Transaction(1, 16, 0, 0, (1, 400, 9)), (0, 0, 9)),  # IDs 1-3: ID 3 is the program's
        (Transaction(1, 23, 5, 6, (1, 400), 0), (0, 0)),  # DA1_DRIVE's exchange: the read stays
        (Transaction(2, 16, 0, 0, (1, 400)), (1, 400)),  # another unit
        (Transaction(1, 5, 0, 0, (True,)), (True,)),  # a coil is no register
    ],
)
def test_the_safe_values_in_place_of_the_programs(tx, written):
    safe = table()
    safe.request("MODBUS_SAFE_WRITE", "drives", 1, 0, 2, [0, 0], False)
    out = safe.substitute("drives", tx)
    assert out.values == written
    assert (out.unit, out.function, out.offset, out.count, out.write_offset) == (
        tx.unit,
        tx.function,
        tx.offset,
        tx.count,
        tx.write_offset,
    )
