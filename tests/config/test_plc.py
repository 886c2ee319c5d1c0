"""The core sections (runtime/config/plc.py): [plc], [[task]], [retain] and
[outputs]; every malformed value names the key and what was expected."""

from __future__ import annotations

import pytest

from softplc.runtime.config import (
    DEFAULT_SPIN_NS,
    PlcConfig,
    RetainConfig,
    load_config,
)

from .support import MS, PLC, PROG, error, errors, load

# ====================================================================== [plc]


def test_minimal_file_and_defaults(tmp_path):
    cfg = load(tmp_path, PLC)
    assert cfg == PlcConfig(
        path=tmp_path / "plant.toml",
        base_dir=tmp_path,
        profile="codesys",
        programs=[tmp_path / "main.st"],
        on_fault="task",
        start="warm",
        tasks=[],
        retain=None,
        safe_outputs=[],
        sections={
            "web": None,
            "opcua": None,
            "modbus_server": None,
            "loopback": [],
            "can": [],
            "canopen": None,
            "plaincan": [],
            "modbus": [],
        },
        raw={"plc": {"programs": ["main.st"]}},
    )


def test_relative_paths_start_at_the_config_directory(tmp_path, monkeypatch):
    (tmp_path / "st").mkdir()
    (tmp_path / "st" / "a.st").write_text(PROG)
    (tmp_path / "cfg").mkdir()
    (tmp_path / "cfg" / "p.toml").write_text('[plc]\nprograms = ["../st/a.st"]\n[retain]\nfile = "p.retain"\n')
    monkeypatch.chdir(tmp_path / "st")
    cfg = load_config("../cfg/p.toml")
    assert cfg.programs == [tmp_path / "st" / "a.st"]  # normalised, absolute
    assert cfg.retain == RetainConfig(tmp_path / "cfg" / "p.retain", 1000 * MS)
    assert cfg.base_dir == tmp_path / "cfg"


def test_absolute_program_path(tmp_path):
    cfg = load(tmp_path, f'[plc]\nprograms = ["{tmp_path / "main.st"}"]\n')
    assert cfg.programs == [tmp_path / "main.st"]


def test_missing_program_file(tmp_path):
    assert error(tmp_path, '[plc]\nprograms = ["main.st", "../nope.st"]\n') == (
        "plc.programs[1]",
        f"no such file: {tmp_path.parent / 'nope.st'} (relative paths start at the config file's directory)",
    )


def test_program_path_is_a_directory(tmp_path):
    (tmp_path / "dir.st").mkdir()
    assert error(tmp_path, '[plc]\nprograms = ["dir.st"]\n') == (
        "plc.programs[0]",
        f"not a file: {tmp_path / 'dir.st'}",
    )


def test_programs_wrong_types(tmp_path):
    assert errors(tmp_path, '[plc]\nprograms = "main.st"\n') == [
        ("plc.programs", "expected an array of ST files such as [\"../st_programs/conveyor.st\"] (got 'main.st')")
    ]
    assert errors(tmp_path, "[plc]\nprograms = []\n") == [
        ("plc.programs", 'expected an array of ST files such as ["../st_programs/conveyor.st"] (got an empty array)')
    ]
    assert errors(tmp_path, '[plc]\nprograms = [1, ""]\n') == [
        ("plc.programs[0]", 'expected the path of an ST file such as "../st_programs/conveyor.st" (got 1)'),
        ("plc.programs[1]", "expected the path of an ST file such as \"../st_programs/conveyor.st\" (got '')"),
    ]


def test_missing_plc_section(tmp_path):
    assert error(tmp_path, "") == (
        "plc",
        'required key missing (expected a [plc] table with at least programs = ["file.st"])',
    )


def test_missing_programs(tmp_path):
    assert error(tmp_path, '[plc]\nprofile = "iec"\n') == (
        "plc.programs",
        'required key missing (expected an array of ST files such as ["../st_programs/conveyor.st"])',
    )


def test_plc_not_a_table(tmp_path):
    assert error(tmp_path, 'plc = "main.st"\n') == (
        "plc",
        "expected a [plc] table with at least programs = [\"file.st\"] (got 'main.st')",
    )


@pytest.mark.parametrize(
    "written, profile",
    [("iec", "iec"), ("MatIEC", "matiec"), ("CODESYS", "codesys"), ("twincat", "twincat"), ("Schneider", "schneider")],
)
def test_profiles(tmp_path, written, profile):
    assert load(tmp_path, PLC + f'profile = "{written}"\n').profile == profile


def test_unknown_profile_lists_the_valid_ones(tmp_path):
    assert error(tmp_path, PLC + 'profile = "siemens"\n') == (
        "plc.profile",
        "expected one of 'iec', 'matiec', 'codesys', 'twincat', 'schneider' (got 'siemens')",
    )
    assert error(tmp_path, PLC + 'profile = "codesis"\n') == (
        "plc.profile",
        "expected one of 'iec', 'matiec', 'codesys', 'twincat', 'schneider' (got 'codesis'; did you mean 'codesys'?)",
    )
    assert error(tmp_path, PLC + "profile = 3\n") == (
        "plc.profile",
        "expected one of 'iec', 'matiec', 'codesys', 'twincat', 'schneider' (got 3)",
    )


def test_on_fault_and_start(tmp_path):
    cfg = load(tmp_path, PLC + 'on_fault = "plc"\nstart = "cold"\n')
    assert (cfg.on_fault, cfg.start) == ("plc", "cold")
    assert errors(tmp_path, PLC + 'on_fault = "all"\nstart = "cld"\n') == [
        ("plc.on_fault", "expected one of 'task', 'plc' (got 'all')"),
        ("plc.start", "expected one of 'warm', 'cold' (got 'cld'; did you mean 'cold'?)"),
    ]


def test_spin_of_the_real_clock(tmp_path):
    assert load(tmp_path, PLC).spin_ns == DEFAULT_SPIN_NS
    for written, ns in (('"0.5ms"', 500_000), ('"200us"', 200_000), ("0", 0), ('"T#1ms"', MS), ('"0.1ms"', 100_000)):
        assert load(tmp_path, PLC + f"spin = {written}\n").spin_ns == ns


@pytest.mark.parametrize("written", ['"20ms"', "-1", '"-0.1ms"', '"fast"', "true", "[]"])
def test_spin_out_of_range_names_the_file_and_key(tmp_path, written):
    key, message = error(tmp_path, PLC + f"spin = {written}\n")
    assert key == "plc.spin"
    assert message.startswith("expected a duration from 0 to 10ms such as 200us, 0.5ms or 0 (got ")


def test_unknown_key_with_suggestion(tmp_path):
    assert error(tmp_path, PLC + 'on_falut = "plc"\n') == ("plc.on_falut", "unknown key (did you mean 'on_fault'?)")


def test_unknown_key_without_suggestion(tmp_path):
    assert error(tmp_path, PLC + 'colour = "blue"\n') == (
        "plc.colour",
        "unknown key (expected one of profile, programs, libraries, on_fault, start, spin, realtime_priority)",
    )


def test_later_sections_are_unknown_for_now(tmp_path):
    assert error(tmp_path, PLC + "[mpu2s]\nx = 1\n") == (
        "mpu2s",
        "unknown key (expected one of plc, retain, task, outputs, init, schedule, web, opcua, modbus_server, sim, "
        "loopback, can, canopen, plaincan, modbus)",
    )


def test_unknown_section_suggestion(tmp_path):
    assert error(tmp_path, PLC + "[[tasks]]\nname = 'A'\n") == ("tasks", "unknown key (did you mean 'task'?)")


# ====================================================================== [retain]


def test_retain_defaults(tmp_path):
    cfg = load(tmp_path, PLC + '[retain]\nfile = "plant.retain"\n')
    assert cfg.retain == RetainConfig(tmp_path / "plant.retain", 1000 * MS)


def test_retain_errors(tmp_path):
    assert errors(tmp_path, PLC + '[retain]\nperiod = "0s"\n') == [
        ("retain.file", 'required key missing (expected a file name such as "plant.retain")'),
        ("retain.period", "expected a duration > 0 such as 10ms, 1s, T#250ms (got '0s')"),
    ]
    assert error(tmp_path, PLC + '[retain]\nfile = "."\n') == (
        "retain.file",
        f"{tmp_path} is a directory; expected a file name",
    )
    assert error(tmp_path, PLC + "[retain]\nfile = 1\n") == (
        "retain.file",
        'expected a file name such as "plant.retain" (got 1)',
    )
    # found by the fuzz harness (tests/fuzz): loaded, then the start crashed reading it (ValueError)
    assert error(tmp_path, PLC + '[retain]\nfile = "a\\u0000b"\n') == (
        "retain.file",
        "expected a file name such as \"plant.retain\" (got 'a\\x00b')",
    )


# ====================================================================== [outputs]


def test_safe_outputs(tmp_path):
    cfg = load(
        tmp_path,
        PLC + '[outputs]\nsafe = { "%QX0.0" = true, "%qx0.1" = 1, "%QX0.2" = 0, '
        '"%QB1" = 255, "%QW2" = -32768, "%QD4" = 1.5, "%QD5" = 7, "%QL1" = 2.5e300 }\n',
    )
    assert [(s.address.text, s.value, type(s.value)) for s in cfg.safe_outputs] == [
        ("%QX0.0", True, bool),
        ("%QX0.1", True, bool),
        ("%QX0.2", False, bool),
        ("%QB1", 255, int),
        ("%QW2", -32768, int),
        ("%QD4", 1.5, float),
        ("%QD5", 7, int),
        ("%QL1", 2.5e300, float),
    ]
    assert cfg.safe_outputs[1].key == 'outputs.safe."%qx0.1"'


def test_safe_output_on_an_input(tmp_path):
    assert error(tmp_path, PLC + '[outputs]\nsafe = { "%IX0.0" = false }\n') == (
        'outputs.safe."%IX0.0"',
        "expected a %Q output address (got '%IX0.0', an input)",
    )
    assert error(tmp_path, PLC + '[outputs]\nsafe = { "%MW0" = 0 }\n') == (
        'outputs.safe."%MW0"',
        "expected a %Q output address (got '%MW0', a memory address)",
    )


@pytest.mark.parametrize("text", ["QX0.0", "%QZ0", "%QX", "%Q*", "%QW0.1", "%QX0.8", "%QX0.1.2", ""])
def test_safe_output_bad_address(tmp_path, text):
    key, message = error(tmp_path, PLC + f'[outputs]\nsafe = {{ "{text}" = 0 }}\n')
    assert key == f'outputs.safe."{text}"'
    assert message  # the address module's words; the common case:
    if text in ("QX0.0", "%QZ0", "%QX", ""):
        assert message == f"expected a direct address such as %QX0.0, %QW2 (got '{text}')"


def test_safe_output_address_messages(tmp_path):
    assert error(tmp_path, PLC + '[outputs]\nsafe = { "%QX0.8" = 0 }\n') == (
        'outputs.safe."%QX0.8"',
        "bit number 8 is not 0..7",
    )


@pytest.mark.parametrize(
    ("text", "message"),
    [
        ("%QL65535", "%QL65535 (bytes 524280..524287) is outside the 65536-byte %Q area"),
        ("%QW65535", "%QW65535 (bytes 131070..131071) is outside the 65536-byte %Q area"),
        ("%QX65536.0", "'%QX65536.0' is outside the 65536-byte %Q area"),
    ],
)
def test_a_safe_value_past_the_image_is_an_error(tmp_path, text, message):
    """%QL65535 passed the configuration and crashed the start (exit 4)."""
    assert error(tmp_path, PLC + f'[outputs]\nsafe = {{ "{text}" = 1 }}\n') == (f'outputs.safe."{text}"', message)


@pytest.mark.parametrize(
    "text, value, message",
    [
        ("%QW2", "true", "expected an integer for a word address (got true)"),
        ("%QB0", "false", "expected an integer for a byte address (got false)"),
        ("%QD4", "true", "expected an integer or a float for a dword address (got true)"),
        (
            "%QW2",
            "1.5",
            "expected an integer for a word address (got 1.5; a REAL needs a %QD address, an LREAL a %QL address)",
        ),
        ("%QW2", "70000", "expected an integer from -32768 to 65535 for a word address (got 70000)"),
        ("%QB0", "256", "expected an integer from -128 to 255 for a byte address (got 256)"),
        ("%QD0", "1e39", "expected a REAL (at most 3.4e38) for a dword address (got 1e+39)"),
        ("%QW2", '"0"', "expected an integer for a word address (got '0')"),
        ("%QX0.0", "2", "expected true or false (or 0 / 1) for a bit address (got 2)"),
        ("%QX0.0", '"true"', "expected true or false (or 0 / 1) for a bit address (got 'true')"),
    ],
)
def test_safe_output_values(tmp_path, text, value, message):
    assert error(tmp_path, PLC + f'[outputs]\nsafe = {{ "{text}" = {value} }}\n') == (f'outputs.safe."{text}"', message)


def test_safe_output_same_address_twice(tmp_path):
    assert error(tmp_path, PLC + '[outputs]\nsafe = { "%QX0.0" = true, " %qx0.0" = false }\n') == (
        'outputs.safe." %qx0.0"',
        'the same address as outputs.safe."%QX0.0"',
    )


def test_safe_outputs_schneider_addressing(tmp_path):
    cfg = load(tmp_path, PLC + 'profile = "schneider"\n[outputs]\nsafe = { "%QW3:X2" = true }\n')
    assert cfg.safe_outputs[0].address.bit == 2 and cfg.safe_outputs[0].value is True
    key, message = error(tmp_path, PLC + '[outputs]\nsafe = { "%QW3:X2" = true }\n')
    assert key == 'outputs.safe."%QW3:X2"' and "schneider" in message
    assert error(tmp_path, PLC + 'profile = "schneider"\n[outputs]\nsafe = { "%QW3:4" = 0 }\n') == (
        'outputs.safe."%QW3:4"',
        "expected a single bit, byte, word, dword or lword (got a word table); list the words one by one",
    )


def test_outputs_unknown_key_and_type(tmp_path):
    assert errors(tmp_path, PLC + "[outputs]\nsaf = {}\n") == [("outputs.saf", "unknown key (did you mean 'safe'?)")]
    assert errors(tmp_path, PLC + '[outputs]\nsafe = ["%QX0.0"]\n') == [
        ("outputs.safe", 'expected a table of %Q address = value, such as { "%QX0.0" = false } (got an array)')
    ]


# ====================================================================== servers


def test_a_server_section_defaults_to_loopback_and_warns_when_it_listens_beyond(tmp_path):
    cfg = load(tmp_path, PLC + "[web]\n[opcua]\nhost = '0.0.0.0'\nwritable = ['Main.Setpoint']\n")
    web, opcua = cfg.sections["web"], cfg.sections["opcua"]
    assert (web.host, web.port, web.writable, web.public) == ("127.0.0.1", 8080, ("*",), False)
    assert (opcua.host, opcua.port, opcua.writable, opcua.public) == ("0.0.0.0", 4840, ("Main.Setpoint",), True)
    assert cfg.sections["modbus_server"] is None
    assert [w.split(": ", 1)[1] for w in cfg.warnings] == [
        "opcua.host: listens on 0.0.0.0: the PLC is reachable from the network (127.0.0.1 keeps it local)"
    ]


def test_a_bad_server_key_names_the_key(tmp_path):
    assert error(tmp_path, PLC + "[modbus_server]\nport = 70000\n") == (
        "modbus_server.port",
        "expected an integer from 0 to 65535 (got 70000)",
    )


@pytest.mark.parametrize("written", ["100", "-1"])
def test_realtime_priority_out_of_range(tmp_path, written):
    assert error(tmp_path, PLC + f"realtime_priority = {written}\n") == (
        "plc.realtime_priority",
        f"expected an integer from 0 to 99 (got {written})",
    )


def test_realtime_priority_reaches_the_real_clock(tmp_path):
    from softplc.runtime.engine.build import build_engine

    cfg = load(tmp_path, PLC + 'realtime_priority = 40\n[[task]]\nname = "T"\ninterval = "10ms"\nprograms = ["Main"]\n')
    assert cfg.realtime_priority == 40
    assert build_engine(cfg, virtual_time=False).clock.realtime_priority == 40
