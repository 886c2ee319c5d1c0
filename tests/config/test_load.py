"""Reading a configuration (runtime/config/load.py): the examples and the
default load, a file that cannot be read or is not TOML names itself, a
file's errors are all reported at once, in file order."""

from __future__ import annotations

import subprocess
import sys

import pytest

from softplc.runtime.config import (
    ConfigError,
    ProgramInstance,
    RetainConfig,
    SafeOutput,
    TaskConfig,
    config_from_dict,
    default_config_path,
    load_config,
)

from .support import EXAMPLES, MS, PROG, ST, addr, write

# ====================================================================== examples


def test_example_tasks():
    cfg = load_config(EXAMPLES / "tasks.toml")
    assert cfg.path == EXAMPLES / "tasks.toml"
    assert cfg.base_dir == EXAMPLES
    assert cfg.profile == "codesys" and cfg.on_fault == "task" and cfg.start == "warm"
    assert cfg.programs == [ST / "blink.st", ST / "conveyor.st", ST / "counter_retain.st"]
    assert cfg.tasks == [
        TaskConfig(
            "Fast",
            10 * MS,
            1 * MS,
            0,
            50 * MS,
            2,
            [ProgramInstance("Blink", "Blink", "task[0].programs[0]")],
            "task[0]",
        ),
        TaskConfig(
            "Slow",
            100 * MS,
            1 * MS,
            5,
            1000 * MS,
            1,
            [
                ProgramInstance("Conveyor", "Conveyor", "task[1].programs[0]"),
                ProgramInstance("Line2", "Conveyor", "task[1].programs[1]"),
            ],
            "task[1]",
        ),
        TaskConfig(
            "Background",
            None,
            5 * MS,
            20,
            1000 * MS,
            1,
            [ProgramInstance("Counter", "Counter", "task[2].programs[0]")],
            "task[2]",
        ),
    ]
    assert cfg.retain is None and cfg.safe_outputs == [] and cfg.loopback == []
    assert cfg.raw["task"][0]["name"] == "Fast"


def test_example_retain():
    cfg = load_config(EXAMPLES / "retain.toml")
    assert cfg.programs == [ST / "counter_retain.st"]
    assert cfg.retain == RetainConfig(EXAMPLES / "counter.retain", 500 * MS)
    assert cfg.start == "warm"
    assert cfg.tasks == []


def test_example_faults():
    cfg = load_config(EXAMPLES / "faults.toml")
    assert cfg.on_fault == "plc"
    assert cfg.programs == [ST / "heater.st", ST / "blink.st"]
    assert [(t.name, t.interval_ns, t.priority, t.watchdog_ns) for t in cfg.tasks] == [
        ("Control", 100 * MS, 1, 1000 * MS),
        ("Lamp", 10 * MS, 2, 100 * MS),
    ]
    assert cfg.safe_outputs == [
        SafeOutput(addr("%QX0.0"), False, 'outputs.safe."%QX0.0"'),
        SafeOutput(addr("%QX0.1"), False, 'outputs.safe."%QX0.1"'),
        SafeOutput(addr("%QX0.2"), True, 'outputs.safe."%QX0.2"'),
        SafeOutput(addr("%QW2"), 0, 'outputs.safe."%QW2"'),
        SafeOutput(addr("%QD4"), 100.0, 'outputs.safe."%QD4"'),
    ]
    assert type(cfg.safe_outputs[0].value) is bool and type(cfg.safe_outputs[4].value) is float


@pytest.mark.parametrize("name", sorted(p.name for p in EXAMPLES.glob("*.toml")))
def test_every_example_loads_and_its_programs_compile(name):
    """The ST files compile without a warning and declare every PROGRAM the
    tasks name."""
    from softplc.runtime.program import check_files, compile_files

    cfg = load_config(EXAMPLES / name)
    diags, _ = check_files([str(p) for p in cfg.programs], profile=cfg.profile)
    assert [d.format() for d in diags] == []
    program = compile_files([str(p) for p in cfg.programs], profile=cfg.profile)
    declared = {n.upper() for n, kind in program.pous.items() if kind == "PROGRAM"}
    named = {inst.program.upper() for t in cfg.tasks for inst in t.programs}
    assert named <= declared


def test_examples_cover_every_section():
    assert sorted(p.name for p in EXAMPLES.glob("*.toml")) == [
        "canopen.toml",
        "faults.toml",
        "fc280_dsp402.toml",
        "fc280_fc.toml",
        "genset.toml",
        "genset_dead_bus.toml",
        "loopback.toml",
        "modbus_rtu.toml",
        "modbus_tcp.toml",
        "motors_oop.toml",
        "retain.toml",
        "sfc.toml",
        "tasks.toml",
    ]


def test_default_config_path():
    """io_config/default.toml: in the source tree (editable install) or in
    site-packages (.ci/run installs the project)."""
    path = default_config_path()
    assert (path.parent.name, path.name) == ("io_config", "default.toml")
    assert (path.parent / "examples" / "tasks.toml").is_file()
    assert (path.parent.parent / "st_programs" / "blink.st").is_file()


def test_default_config_loads():
    cfg = load_config(default_config_path())
    assert cfg.tasks and all(p.exists() for p in cfg.programs)


# ====================================================================== the file itself


def test_missing_file(tmp_path):
    path = tmp_path / "nope.toml"
    with pytest.raises(ConfigError) as info:
        load_config(path)
    assert str(info.value) == f"{path}: no such configuration file"


def test_directory_instead_of_file(tmp_path):
    with pytest.raises(ConfigError) as info:
        load_config(tmp_path)
    assert str(info.value) == f"{tmp_path}: is a directory, not a configuration file"


def test_not_utf8(tmp_path):
    path = tmp_path / "latin1.toml"
    path.write_bytes(b"# caf\xe9\n[plc]\n")
    with pytest.raises(ConfigError) as info:
        load_config(path)
    assert str(info.value) == f"{path}: not UTF-8 text (byte 5); a TOML file is UTF-8"


def test_message_names_the_path_as_given(tmp_path, monkeypatch):
    write(tmp_path, "[[task]]\n", name="plant.toml")
    monkeypatch.chdir(tmp_path)
    with pytest.raises(ConfigError) as info:
        load_config("plant.toml")
    assert str(info.value).splitlines()[0].startswith("plant.toml: ")


def test_toml_syntax_error_has_line_and_column(tmp_path):
    path = write(tmp_path, '[plc]\nprograms = ["main.st"]\nstart = \n')
    with pytest.raises(ConfigError) as info:
        load_config(path)
    assert str(info.value) == f"{path}:3:9: invalid TOML: Invalid value"
    assert info.value.position == (3, 9)
    assert info.value.errors == [("", "invalid TOML: Invalid value")]


def test_toml_syntax_error_at_end_of_file(tmp_path):
    path = write(tmp_path, '[plc]\nprograms = ["main.st"\n')
    with pytest.raises(ConfigError) as info:
        load_config(path)
    assert str(info.value) == f"{path}:3:1: invalid TOML: Unclosed array at the end of the file"


def test_toml_duplicate_key(tmp_path):
    path = write(tmp_path, '[plc]\nprograms = ["main.st"]\nprograms = ["main.st"]\n')
    with pytest.raises(ConfigError) as info:
        load_config(path)
    assert str(info.value) == f"{path}:3:23: invalid TOML: Cannot overwrite a value"


# ====================================================================== hostile documents
# Each of these ended in a RecursionError or a ValueError of Python's (exit 4).


@pytest.mark.parametrize(
    ("body", "column"),
    [
        ("x = " + "[" * 5000 + "]" * 5000, 4 + 33),  # arrays: the TOML reader recurses into them
        ("x = " + "{a = " * 2000 + "1" + "}" * 2000, 4 + 32 * 5 + 1),  # inline tables: likewise
    ],
    ids=["arrays", "inline tables"],
)
def test_values_nested_too_deep_for_the_reader_are_an_error_at_the_33rd_level(tmp_path, body, column):
    path = write(tmp_path, '[plc]\nprograms = ["main.st"]\n' + body + "\n")
    with pytest.raises(ConfigError) as info:
        load_config(path)
    message = "tables, arrays or dotted keys nested more than 32 deep: no key takes that"
    assert str(info.value) == f"{path}:3:{column}: {message}"


def test_a_deep_document_is_refused_before_the_reader_recurses(tmp_path):
    """The reader's recursion 5000 levels deep made any collector callback
    that ran there fail too: "Exception ignored in sys.unraisablehook:
    RecursionError" at the head of the error (softplc's own callback times
    the collector). A collection at every allocation makes it certain."""
    path = write(tmp_path, '[plc]\nprograms = ["main.st"]\nx = ' + "[" * 5000 + "]" * 5000 + "\n")
    script = (
        "import gc, sys\n"
        "from softplc.runtime.config import ConfigError, load_config\n"
        "import softplc.runtime.engine.cputime  # its callback times every collection\n"
        "gc.set_threshold(1)\n"
        "try:\n"
        "    load_config(sys.argv[1])\n"
        "except ConfigError as exc:\n"
        "    print(exc)\n"
    )
    proc = subprocess.run([sys.executable, "-c", script, str(path)], capture_output=True, text=True, check=True)
    assert proc.stderr == ""
    assert proc.stdout == f"{path}:3:37: tables, arrays or dotted keys nested more than 32 deep: no key takes that\n"


def test_brackets_in_strings_and_comments_are_no_nesting(tmp_path):
    deep = "[" * 40 + "{" * 40
    body = f'# {deep}\n[[task]]\nname = \'{deep}\'\nprograms = ["""Main{deep}\\""""""]\n'
    path = write(tmp_path, '[plc]\nprograms = ["main.st"]\n' + body)
    with pytest.raises(ConfigError) as info:  # the task's name and its program are wrong: no more
        load_config(path)
    assert "nested" not in str(info.value)
    assert [loc for loc, _ in info.value.errors][:1] == ["task[0].name"]


def test_dotted_keys_nested_too_deep_are_an_error_at_their_key(tmp_path):
    """5000 dotted keys: the reader takes them, the checks after it recursed."""
    path = write(tmp_path, '[plc]\nprograms = ["main.st"]\n[outputs]\n' + ".".join(["a"] * 5000) + " = 1\n")
    with pytest.raises(ConfigError) as info:
        load_config(path)
    assert info.value.errors == [
        (
            "outputs." + ".".join(["a"] * 31),
            "tables, arrays or dotted keys nested more than 32 deep: no key takes that",
        ),
        ("outputs.a", "unknown key (expected one of safe)"),
    ]


def test_what_is_nested_deep_enough_still_reads():
    """The shipped examples nest 8 deep; 32 levels are checked, no more."""
    data = {"plc": {"programs": []}, "outputs": {"safe": {}}}
    node = data["outputs"]["safe"]
    for _ in range(29):  # outputs.safe and 29 more tables: 31 levels, a value at the 32nd
        node["a"] = {}
        node = node["a"]
    with pytest.raises(ConfigError) as info:
        config_from_dict(data)
    assert "nested" not in str(info.value)


def test_an_integer_of_5000_digits_names_its_line_and_column(tmp_path):
    path = write(tmp_path, '[plc]\nprograms = ["main.st"]\n[retain]\nfile = "r"\nperiod = ' + "9" * 5000 + "\n")
    with pytest.raises(ConfigError) as info:
        load_config(path)
    assert str(info.value) == f"{path}:5:10: an integer of 5000 digits: no key takes a number that large"


def test_an_integer_beyond_64_bits_is_refused_at_its_key(tmp_path):
    """A hexadecimal integer has no digit limit in the reader; its decimal
    text (for the message) had: 4800 digits are more than Python writes."""
    path = write(
        tmp_path,
        '[plc]\nprograms = ["main.st"]\n[[task]]\nname = "T"\ninterval = "10ms"\n'
        'programs = ["Main"]\npriority = 0x' + "f" * 4000 + "\n",
    )
    with pytest.raises(ConfigError) as info:
        load_config(path)
    assert info.value.errors == [
        ("task[0].priority", "expected an integer from 0 to 31 (got an integer of about 4817 digits)")
    ]


def test_a_file_of_many_errors_shows_50_and_counts_the_rest(tmp_path):
    """10,000 tasks gave 2.1 MB of errors."""
    tasks = "".join(f'[[task]]\nname = "T{i}"\ninterval = "1x"\nprograms = ["Main"]\n' for i in range(1000))
    path = write(tmp_path, '[plc]\nprograms = ["main.st"]\n' + tasks)
    with pytest.raises(ConfigError) as info:
        load_config(path)
    lines = str(info.value).splitlines()
    assert len(info.value.errors) == 1000 + 999  # each interval, and each instance Main after the first
    assert len(lines) == 51 and lines[-1] == f"{path}: ... 1949 more errors"
    assert lines[0] == f"{path}: task[0].interval: expected a duration such as 10ms, 1s, T#250ms (got '1x')"


# ====================================================================== all at once


def test_several_errors_reported_together(tmp_path):
    path = write(
        tmp_path,
        """\
        [plc]
        profile = "siemens"
        programs = ["main.st", "gone.st"]

        [[task]]
        name = "Fast"
        interval = "10 parsecs"
        priority = 99
        programs = ["Main"]

        [[task]]
        name = "fast"
        freewheeling = true
        programs = ["Main"]

        [outputs]
        safe = { "%IX0.0" = false, "%QW2" = true }

        [canopen]
        bus = "can0"
        """,
    )
    with pytest.raises(ConfigError) as info:
        load_config(path)
    assert str(info.value).splitlines() == [
        f"{path}: plc.profile: expected one of 'iec', 'matiec', 'codesys', 'twincat', 'schneider' (got 'siemens')",
        f"{path}: plc.programs[1]: no such file: {tmp_path / 'gone.st'} (relative paths start at the "
        "config file's directory)",
        f"{path}: task[0].interval: expected a duration such as 10ms, 1s, T#250ms (got '10 parsecs')",
        f"{path}: task[0].priority: expected an integer from 0 to 31 (got 99)",
        f"{path}: task[1].name: duplicate task name 'fast' (task[0] has it; names are case-insensitive)",
        f"{path}: task[1].programs[0]: duplicate program instance 'Main' (also at task[0].programs[0]; "
        "instance names are unique across tasks, case-insensitive); give one its own instance name: "
        '{ instance = "Main2", program = "Main" }',
        f"{path}: outputs.safe.\"%IX0.0\": expected a %Q output address (got '%IX0.0', an input)",
        f'{path}: outputs.safe."%QW2": expected an integer for a word address (got true)',
        f"{path}: canopen: the CANopen master needs a [[can]] bus (the file has none): add a [[can]] "
        "table with interface and channel",
    ]


# ====================================================================== config_from_dict, ConfigError


def test_config_from_dict(tmp_path):
    (tmp_path / "main.st").write_text(PROG)
    data = {"plc": {"programs": ["main.st"]}, "task": [{"name": "T", "interval": "5ms", "programs": ["Main"]}]}
    cfg = config_from_dict(data, tmp_path / "virtual.toml")
    assert cfg.path == tmp_path / "virtual.toml" and cfg.base_dir == tmp_path
    assert cfg.tasks[0].interval_ns == 5 * MS and cfg.raw is data
    cfg = config_from_dict(data, base_dir=tmp_path)
    assert cfg.path is None and cfg.programs == [tmp_path / "main.st"]
    with pytest.raises(ConfigError) as info:
        config_from_dict({"plc": {}})
    assert str(info.value).startswith("<configuration>: plc.programs: required key missing")


def test_config_error_format():
    err = ConfigError("a.toml", [("task[0].name", "bad"), ("", "whole file")])
    assert str(err) == "a.toml: task[0].name: bad\na.toml: whole file"
    assert err.file == "a.toml" and err.errors == [("task[0].name", "bad"), ("", "whole file")]
    assert err.position is None
    err = ConfigError("a.toml", [("", "invalid TOML: Invalid value")], position=(3, 9))
    assert str(err) == "a.toml:3:9: invalid TOML: Invalid value"
