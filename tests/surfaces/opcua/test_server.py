"""The OPC UA server seen by a real asyncua client on 127.0.0.1: the tree a
client browses, values that follow the program, subscriptions, writes that
change the PLC variable (and only where allowed), a clean stop."""

from __future__ import annotations

import asyncio
import socket
import threading
from datetime import UTC, datetime

import pytest
from asyncua import Client, ua

from softplc.runtime.surfaces.host import SurfaceError, Surfaces

from ...engine.conftest import make_engine, task
from .conftest import TIMEOUT_S, client, greater, opcua_config, run, until, value

SRC = """
TYPE E_Mode : (Idle := 0, Run := 5, Fault := 6); END_TYPE
TYPE S_Pair : STRUCT a : INT; b : BOOL; END_STRUCT END_TYPE
VAR_GLOBAL total : DINT; END_VAR
FUNCTION_BLOCK FB_Motor
VAR_INPUT start : BOOL; END_VAR
VAR_OUTPUT running : BOOL; END_VAR
running := start;
END_FUNCTION_BLOCK
PROGRAM Main
VAR
    n : INT;
    setpoint : REAL := 12.5;
    doubled : REAL;
    small : SINT;
    mode : E_Mode := Run;
    pair : S_Pair;
    levels : ARRAY[1..4] OF LREAL;
    pairs : ARRAY[0..1] OF S_Pair;
    grid : ARRAY[1..2, 1..3] OF INT;
    t : TON;
    motor : FB_Motor;
    name : STRING[10] := 'abc';
    dwell : TIME := T#1500ms;
    day : DATE := D#2024-01-02;
END_VAR
n := n + 1;
total := total + 1;
doubled := setpoint * 2.0;
pair.a := n;
pairs[1].b := TRUE;
grid[2, 3] := 7;
t(IN := TRUE, PT := T#1S);
motor(start := mode = Run);
END_PROGRAM
"""
TASKS = [task("Main", 10, "Main")]
WRITABLE = ["Main.setpoint", "Main.small", "Main.mode", "Main.levels", "Main.dwell", "Main.day"]


async def names(node) -> list:
    return [(await child.read_browse_name()).Name for child in await node.get_children()]


async def refused(client: Client, path: str, variant: ua.Variant) -> int:
    """The status code of a refused write (fails when the write is taken)."""
    try:
        await client.get_node(f"ns=2;s={path}").write_value(ua.DataValue(variant))
    except ua.UaStatusCodeError as exc:
        return exc.code
    raise AssertionError(f"the write of {variant} to {path} was taken")


def test_a_client_browses_programs_fb_instances_structs_arrays_globals_and_enums(running):
    plc = running(SRC, TASKS)

    async def check() -> None:
        async with client(plc.url) as c:
            assert await c.get_namespace_index("urn:softplc") == 2
            top = await names(c.nodes.objects)
            assert "Main" in top and "Globals" in top
            main = c.get_node("ns=2;s=Main")
            assert await names(main) == [
                "n", "setpoint", "doubled", "small", "mode", "pair", "levels", "pairs",
                "grid", "t", "motor", "name", "dwell", "day",
            ]  # fmt: skip
            assert {"IN", "PT", "Q", "ET"} <= set(await names(c.get_node("ns=2;s=Main.t")))
            assert await names(c.get_node("ns=2;s=Main.motor")) == ["start", "running"]
            assert await names(c.get_node("ns=2;s=Main.pair")) == ["a", "b"]
            assert await names(c.get_node("ns=2;s=Main.pairs")) == ["[0]", "[1]"]
            assert await names(c.get_node("ns=2;s=Main.pairs[1]")) == ["a", "b"]
            assert await names(c.get_node("ns=2;s=#Globals")) == ["total"]  # not the libraries' (PLC_DIAG)

            kinds = {
                "Main.n": ua.ObjectIds.Int16,
                "Main.small": ua.ObjectIds.SByte,
                "Main.setpoint": ua.ObjectIds.Float,
                "Main.levels": ua.ObjectIds.Double,
                "Main.t.Q": ua.ObjectIds.Boolean,
                "Main.dwell": ua.ObjectIds.Duration,
                "Main.day": ua.ObjectIds.DateTime,
                "Main.name": ua.ObjectIds.String,
                "total": ua.ObjectIds.Int32,
            }
            for path, kind in kinds.items():
                assert await c.get_node(f"ns=2;s={path}").read_data_type() == ua.NodeId(kind), path
            levels = c.get_node("ns=2;s=Main.levels")
            assert await levels.read_value_rank() == 1 and await levels.read_array_dimensions() == [4]
            grid = c.get_node("ns=2;s=Main.grid")
            assert await grid.read_value_rank() == 2 and await grid.read_array_dimensions() == [2, 3]

            mode = c.get_node("ns=2;s=Main.mode")
            enum = c.get_node(await mode.read_data_type())
            assert (await enum.read_browse_name()).Name == "E_Mode"
            assert ua.NodeId(ua.ObjectIds.Enumeration) == (await enum.get_parent()).nodeid
            enum_values = await (await enum.get_child("0:EnumValues")).read_value()
            assert [(v.DisplayName.Text, v.Value) for v in enum_values] == [("Idle", 0), ("Run", 5), ("Fault", 6)]
            assert await mode.read_value() == 5

    run(check())


def test_values_follow_the_program(running):
    plc = running(SRC, TASKS)

    async def check() -> None:
        async with client(plc.url) as c:
            n = await until(lambda: value(c, "Main.n"), "Main.n to count")
            await until(lambda: greater(value(c, "Main.n"), n + 3), "Main.n to count on")
            assert await value(c, "total") > 0
            assert await until(lambda: value(c, "Main.t.Q"), "the TON's Q after 1 s of PLC time") is True
            assert await value(c, "Main.t.ET") == 1000.0  # TIME in milliseconds, held at PT
            assert await value(c, "Main.pairs[1].b") is True and await value(c, "Main.motor.running") is True
            assert await value(c, "Main.grid") == [[0, 0, 0], [0, 0, 7]]
            assert await value(c, "Main.doubled") == 25.0 and await value(c, "Main.name") == "abc"
            assert await value(c, "Main.dwell") == 1500.0
            day = await value(c, "Main.day")
            assert day.replace(tzinfo=UTC) == datetime(2024, 1, 2, tzinfo=UTC)

    run(check())


def test_a_subscription_receives_data_changes(running):
    plc = running(SRC, TASKS)
    seen: list = []

    class Handler:
        def datachange_notification(self, node, val, data) -> None:
            seen.append(val)

    async def check() -> None:
        async with client(plc.url) as c:
            sub = await c.create_subscription(20, Handler())
            await sub.subscribe_data_change(c.get_node("ns=2;s=Main.n"))

            async def three_changes():
                return len(set(seen)) >= 4

            await until(three_changes, "data changes of Main.n")
            assert seen == sorted(seen)  # the counter as it counted, never back
            await sub.delete()

    run(check())


def test_a_write_changes_the_plc_variable_and_the_program_reacts(running):
    plc = running(SRC, TASKS, writable=WRITABLE)

    async def check() -> None:
        async with client(plc.url) as c:
            setpoint = c.get_node("ns=2;s=Main.setpoint")
            await setpoint.write_value(ua.DataValue(ua.Variant(20.0, ua.VariantType.Float)))
            assert plc.surfaces.access.place("Main.setpoint").read() == 20.0  # the PLC's, not only the node's
            await until(lambda: _eq(value(c, "Main.doubled"), 40.0), "the program to double the new setpoint")
            await until(lambda: _eq(value(c, "Main.setpoint"), 20.0), "the node to show the PLC's value")

            await c.get_node("ns=2;s=Main.mode").write_value(ua.DataValue(ua.Variant(6, ua.VariantType.Int32)))
            await until(lambda: _eq(value(c, "Main.motor.running"), False), "the motor to stop in mode Fault")

            levels = [1.0, 2.0, 3.0, 4.0]
            await c.get_node("ns=2;s=Main.levels").write_value(ua.DataValue(ua.Variant(levels, ua.VariantType.Double)))
            assert plc.surfaces.access.place("Main.levels[3]").read() == 3.0
            await c.get_node("ns=2;s=Main.dwell").write_value(ua.DataValue(ua.Variant(2500.0, ua.VariantType.Double)))
            assert plc.surfaces.access.place("Main.dwell").read().total_seconds() == 2.5
            when = datetime(2025, 6, 1, tzinfo=UTC)
            await c.get_node("ns=2;s=Main.day").write_value(ua.DataValue(ua.Variant(when, ua.VariantType.DateTime)))
            assert plc.surfaces.access.place("Main.day").read() == "D#2025-06-01"

    run(check())


async def _eq(read, expected):
    return (await read) == expected


def test_writes_are_refused_where_not_allowed_or_of_the_wrong_type(running):
    plc = running(SRC, TASKS, writable=WRITABLE)
    V = ua.VariantType

    async def check() -> None:
        async with client(plc.url) as c:
            assert await refused(c, "Main.n", ua.Variant(5, V.Int16)) == ua.StatusCodes.BadNotWritable
            assert await refused(c, "total", ua.Variant(5, V.Int32)) == ua.StatusCodes.BadNotWritable
            assert await refused(c, "Main.setpoint", ua.Variant("fast", V.String)) == ua.StatusCodes.BadTypeMismatch
            assert await refused(c, "Main.small", ua.Variant(True, V.Boolean)) == ua.StatusCodes.BadTypeMismatch
            assert await refused(c, "Main.small", ua.Variant(300, V.Int16)) == ua.StatusCodes.BadOutOfRange
            assert await refused(c, "Main.mode", ua.Variant(3, V.Int32)) == ua.StatusCodes.BadOutOfRange
            assert await refused(c, "Main.levels", ua.Variant([1.0], V.Double)) == ua.StatusCodes.BadTypeMismatch
            n = plc.surfaces.access.place("Main.n")
            assert plc.surfaces.access.place("Main.small").read() == 0 and n.read() > 0
            await c.get_node("ns=2;s=Main.small").write_value(ua.DataValue(ua.Variant(-100, V.Int64)))
            assert plc.surfaces.access.place("Main.small").read() == -100  # any integer variant that fits

    run(check())


def test_with_users_only_a_logged_in_client_writes(running, tmp_path):
    from softplc.runtime.surfaces.opcua.users import hash_password

    users_file = tmp_path / "users.toml"
    users_file.write_text(f'[users]\noperator = "{hash_password("s3cret", iterations=1000)}"\n')
    plc = running(SRC, TASKS, writable=WRITABLE, users_file=users_file, users={"viewer": "plain"})
    setpoint = ua.Variant(30.0, ua.VariantType.Float)

    async def check() -> None:
        async with client(plc.url) as anonymous:
            assert await value(anonymous, "Main.setpoint") == 12.5  # reading stays open
            assert await refused(anonymous, "Main.setpoint", setpoint) == ua.StatusCodes.BadUserAccessDenied
        wrong = client(plc.url)
        wrong.set_user("operator")
        wrong.set_password("guess")
        with pytest.raises(ua.uaerrors.BadUserAccessDenied):
            await wrong.connect()
        operator = client(plc.url)
        operator.set_user("operator")
        operator.set_password("s3cret")
        async with operator:
            await operator.get_node("ns=2;s=Main.setpoint").write_value(ua.DataValue(setpoint))
        assert plc.surfaces.access.place("Main.setpoint").read() == 30.0

    run(check())


def test_stop_ends_the_thread_and_closes_the_port(running):
    plc = running(SRC, TASKS)
    port = int(plc.url.rsplit(":", 1)[1].split("/")[0])
    plc.stop()
    assert not [t for t in threading.enumerate() if t.name == "opcua"]
    with pytest.raises(ConnectionRefusedError), socket.create_connection(("127.0.0.1", port), timeout=TIMEOUT_S):
        pass


def test_a_taken_port_is_an_error_naming_it():
    with socket.socket() as taken:
        taken.bind(("127.0.0.1", 0))
        taken.listen()
        port = taken.getsockname()[1]
        engine = make_engine(SRC, TASKS)
        config = opcua_config()
        config = type(config)(**{**config.__dict__, "port": port})
        surfaces = Surfaces(engine, {"opcua": config})
        try:
            with pytest.raises(SurfaceError, match=f"opcua.*127.0.0.1:{port}"):
                surfaces.start()
        finally:
            engine.stop()
    assert not [t for t in threading.enumerate() if t.name == "opcua"]


def many(n: int) -> str:
    decl = "\n".join(f"v{i} : DINT;" for i in range(n))
    body = "\n".join(f"v{i} := v{i} + {i};" for i in range(n))
    return f"PROGRAM Main\nVAR\n{decl}\nEND_VAR\n{body}\nEND_PROGRAM\n"


def test_a_thousand_variables_are_published_to_a_subscription(running):
    plc = running(many(1000), TASKS, period_ms=50)
    seen: dict = {}

    class Handler:
        def datachange_notification(self, node, val, data) -> None:
            seen[node.nodeid.Identifier] = val

    async def check() -> None:
        async with client(plc.url) as c:
            main = c.get_node("ns=2;s=Main")
            assert len(await main.get_children()) == 1000
            sub = await c.create_subscription(50, Handler())
            await sub.subscribe_data_change([c.get_node(f"ns=2;s=Main.v{i}") for i in range(1000)])
            first = await until(lambda: greater(value(c, "Main.v999"), 0), "Main.v999 to move")

            async def all_moved():
                return len(seen) == 1000 and seen["Main.v999"] > first and seen["Main.v1"] > 0

            await until(all_moved, "data changes of all 1,000 variables")
            await sub.delete()

    run(check())


def test_beyond_max_variables_the_rest_is_left_out_with_a_warning(running, caplog):
    plc = running(many(50), TASKS, max_variables=20)

    async def check() -> None:
        async with client(plc.url) as c:
            assert await names(c.get_node("ns=2;s=Main")) == [f"v{i}" for i in range(20)]

    run(check())
    assert "30 variable(s) not published: more than 20 values ([opcua] max_variables)" in caplog.text


def test_an_online_change_rebuilds_the_tree(running):
    from types import SimpleNamespace

    from softplc.runtime.engine.online_change import OnlineChange

    from ...engine.conftest import compile_st

    plc = running(SRC, TASKS)
    after = SRC.replace("    small : SINT;\n", "    added : INT := 42;\n")
    config = SimpleNamespace(tasks=TASKS, path=None, programs=[], libraries=[])

    async def check() -> None:
        async with client(plc.url) as c:
            main = c.get_node("ns=2;s=Main")
            assert "small" in await names(main)
            report = await asyncio.to_thread(
                OnlineChange(plc.engine, config, compile=lambda: compile_st(after)).request, "test", TIMEOUT_S
            )
            assert report.applied, report.errors

            async def rebuilt():
                try:
                    return "added" in await names(main)
                except ua.UaStatusCodeError:  # between the old nodes' deletion and the new ones
                    return False

            await until(rebuilt, "the new variable in the tree")
            assert "small" not in await names(main)
            assert await value(c, "Main.added") == 42
            n = await value(c, "Main.n")
            await until(lambda: greater(value(c, "Main.n"), n), "Main.n to count on after the change")

    run(check())


def test_a_subscription_goes_on_through_an_online_change(running):
    """An HMI subscribed to a variable the change keeps sees it go on counting,
    with no bad status and no drop: only what changed is deleted and added
    (the soak found every client's subscription broken at every change); a
    variable whose type changed is a new node of the new type."""
    from types import SimpleNamespace

    from softplc.runtime.engine.online_change import OnlineChange

    from ...engine.conftest import compile_st

    plc = running(SRC, TASKS)
    after = SRC.replace("    small : SINT;\n", "    added : INT := 42;\n").replace(
        "doubled : REAL;", "doubled : LREAL;"
    )
    config = SimpleNamespace(tasks=TASKS, path=None, programs=[], libraries=[])
    seen: list = []
    statuses: list = []

    class Handler:
        def datachange_notification(self, node, val, data) -> None:
            seen.append(val)
            statuses.append(data.monitored_item.Value.StatusCode)

        def status_change_notification(self, status) -> None:
            statuses.append(status)

    async def check() -> None:
        async with client(plc.url) as c:
            sub = await c.create_subscription(20, Handler())
            await sub.subscribe_data_change(c.get_node("ns=2;s=Main.n"))
            await until(lambda: asyncio.sleep(0, bool(seen)), "a first value of Main.n")
            report = await asyncio.to_thread(
                OnlineChange(plc.engine, config, compile=lambda: compile_st(after)).request, "test", TIMEOUT_S
            )
            assert report.applied, report.errors
            main = c.get_node("ns=2;s=Main")
            await until(lambda: _has(main, "added"), "the new variable in the tree")
            at_change = len(seen)
            await until(lambda: asyncio.sleep(0, len(seen) >= at_change + 3), "Main.n to go on after the change")
            assert seen == sorted(seen)  # one counter, never back to a default
            assert all(s.is_good() for s in statuses if isinstance(s, ua.StatusCode))
            assert "small" not in await names(main)
            assert await value(c, "Main.added") == 42
            # a variable whose type changed is a new node of its new type
            doubled = c.get_node("ns=2;s=Main.doubled")
            assert await doubled.read_data_type() == ua.NodeId(ua.ObjectIds.Double)
            assert await doubled.read_value() == 25.0
            await sub.delete()

    run(check())


async def _has(node, name: str) -> bool:
    try:
        return name in await names(node)
    except ua.UaStatusCodeError:  # between the old nodes' deletion and the new ones
        return False
