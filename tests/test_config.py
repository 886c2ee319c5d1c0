"""The TOML configuration (runtime/config.py): the examples load into the
expected dataclasses, and every malformed file names the file, the key and
what was expected -- all of a file's errors at once."""
from __future__ import annotations

import os
import textwrap
from importlib import resources
from pathlib import Path

import pytest

from softplc.runtime.config import (
    CanBusConfig, CanopenConfig, CanopenNodeConfig, ConfigError, LoopbackLink, PdoConfig, PdoEntryConfig,
    PlcConfig, ProgramInstance, RetainConfig, SafeOutput, SdoWriteConfig, SimConfig, TaskConfig,
    config_from_dict, default_config_path, load_config)
from softplc.runtime.st.ast import LocatedAddress

REPO = Path(__file__).resolve().parents[1]
EXAMPLES = REPO / "io_config" / "examples"
# where eds = "ltmr" resolves: the installed package (the source tree in a development install)
EDS = Path(os.fspath(resources.files("softplc.io_config").joinpath("eds")))
ST = REPO / "st_programs"

MS = 1_000_000
PROG = "PROGRAM Main\nVAR x : INT; END_VAR\nx := x + 1;\nEND_PROGRAM\n"
PLC = '[plc]\nprograms = ["main.st"]\n'
DURATION = "a duration such as 10ms, 1s, T#250ms"


def write(tmp_path: Path, text: str, name: str = "plant.toml") -> Path:
    (tmp_path / "main.st").write_text(PROG)
    path = tmp_path / name
    path.write_text(textwrap.dedent(text))
    return path


def load(tmp_path: Path, text: str) -> PlcConfig:
    return load_config(write(tmp_path, text))


def errors(tmp_path: Path, text: str) -> list:
    """The (key, message) pairs of the ConfigError the file raises, after
    checking that every line of the message names the file."""
    path = write(tmp_path, text)
    with pytest.raises(ConfigError) as info:
        load_config(path)
    err = info.value
    assert err.file == str(path)
    lines = str(err).splitlines()
    assert len(lines) == len(err.errors)
    for line, (key, message) in zip(lines, err.errors):
        assert line == (f"{path}: {key}: {message}" if key else f"{path}: {message}")
    return err.errors


def error(tmp_path: Path, text: str) -> tuple:
    found = errors(tmp_path, text)
    assert len(found) == 1, found
    return found[0]


def addr(text: str) -> LocatedAddress:
    from softplc.runtime.image.address import parse_address
    return parse_address(text)


# ====================================================================== examples


def test_example_tasks():
    cfg = load_config(EXAMPLES / "tasks.toml")
    assert cfg.path == EXAMPLES / "tasks.toml"
    assert cfg.base_dir == EXAMPLES
    assert cfg.profile == "codesys" and cfg.on_fault == "task" and cfg.start == "warm"
    assert cfg.programs == [ST / "blink.st", ST / "conveyor.st", ST / "counter_retain.st"]
    assert cfg.tasks == [
        TaskConfig("Fast", 10 * MS, 1 * MS, 0, 50 * MS, 2,
                   [ProgramInstance("Blink", "Blink", "task[0].programs[0]")], "task[0]"),
        TaskConfig("Slow", 100 * MS, 1 * MS, 5, 1000 * MS, 1,
                   [ProgramInstance("Conveyor", "Conveyor", "task[1].programs[0]"),
                    ProgramInstance("Line2", "Conveyor", "task[1].programs[1]")], "task[1]"),
        TaskConfig("Background", None, 5 * MS, 20, 1000 * MS, 1,
                   [ProgramInstance("Counter", "Counter", "task[2].programs[0]")], "task[2]"),
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
    assert [(t.name, t.interval_ns, t.priority, t.watchdog_ns) for t in cfg.tasks] == \
        [("Control", 100 * MS, 1, 1000 * MS), ("Lamp", 10 * MS, 2, 100 * MS)]
    assert cfg.safe_outputs == [
        SafeOutput(addr("%QX0.0"), False, 'outputs.safe."%QX0.0"'),
        SafeOutput(addr("%QX0.1"), False, 'outputs.safe."%QX0.1"'),
        SafeOutput(addr("%QX0.2"), True, 'outputs.safe."%QX0.2"'),
        SafeOutput(addr("%QW2"), 0, 'outputs.safe."%QW2"'),
        SafeOutput(addr("%QD4"), 100.0, 'outputs.safe."%QD4"'),
    ]
    assert type(cfg.safe_outputs[0].value) is bool and type(cfg.safe_outputs[4].value) is float


def test_example_loopback():
    cfg = load_config(EXAMPLES / "loopback.toml")
    assert cfg.loopback == [LoopbackLink(addr("%QB0"), addr("%IB0"), 2, "loopback[0]"),
                            LoopbackLink(addr("%QD1"), addr("%ID2"), 4, "loopback[1]")]
    assert [(t.name, t.programs[0].program) for t in cfg.tasks] == [("Main", "Echo")]


def test_example_canopen():
    cfg = load_config(EXAMPLES / "canopen.toml")
    assert cfg.programs == [ST / "ltmr_motor.st"]
    assert cfg.can == [CanBusConfig("can0", "virtual", "softplc-example-canopen", 250_000, {}, "can[0]")]
    key = "canopen.node[0]"

    def entries(pdo: str, *pairs) -> list:
        return [PdoEntryConfig(index, sub, addr(text), f"{key}.{pdo}.map[{k}]")
                for k, (index, sub, text) in enumerate(pairs)]
    assert cfg.canopen == CanopenConfig(
        bus="can0", node_id=127, heartbeat_ms=100, sync_us=50_000, sdo_timeout_ms=500, boot_timeout_ms=2000,
        retry_ms=1000, key="canopen", nodes=[CanopenNodeConfig(
            name="motor", node_id=40, eds=EDS / "ltmr.eds", mandatory=True, heartbeat_ms=100,
            heartbeat_timeout_ms=300, master_timeout_ms=500, key=key,
            sdo=[SdoWriteConfig(0x2007, 0x21, 2, None, f"{key}.sdo[0]"),
                 SdoWriteConfig(0x1029, 0x01, 0, 1, f"{key}.sdo[1]")],
            tpdo=[PdoConfig(1, 255, 0, 0, False, entries("tpdo[0]", (0x2004, 0x06, "%IW100"),
                                                         (0x2004, 0x07, "%IW101"), (0x2004, 0x08, "%IW102"),
                                                         (0x2004, 0x0A, "%IW103")), f"{key}.tpdo[0]"),
                  PdoConfig(2, 255, 10_000, 1000, True, entries("tpdo[1]", (0x2004, 0x02, "%IW104"),
                                                                (0x2004, 0x0B, "%IW105")), f"{key}.tpdo[1]"),
                  PdoConfig(3, 1, 0, 0, True, entries("tpdo[2]", (0x2004, 0x10, "%IW106"),
                                                      (0x2004, 0x11, "%IW107")), f"{key}.tpdo[2]")],
            rpdo=[PdoConfig(1, 255, 0, 0, False, entries("rpdo[0]", (0x2008, 0x05, "%QW100"),
                                                         (0x2008, 0x04, "%QW101"), (0x2008, 0x01, "%QW102")),
                            f"{key}.rpdo[0]")])])
    assert cfg.sims == [SimConfig("ltmr", "ltmr40", "can0", 40, {682: 0}, "sim[0]")]
    assert cfg.safe_outputs == [SafeOutput(addr("%QW100"), 0, 'outputs.safe."%QW100"')]


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
    assert sorted(p.name for p in EXAMPLES.glob("*.toml")) == \
        ["canopen.toml", "faults.toml", "loopback.toml", "modbus_rtu.toml", "modbus_tcp.toml", "retain.toml",
         "tasks.toml"]


def test_default_config_path():
    """io_config/default.toml: in the source tree (editable install) or in
    site-packages (.ci/run installs the project)."""
    path = default_config_path()
    assert (path.parent.name, path.name) == ("io_config", "default.toml")
    assert (path.parent / "examples" / "tasks.toml").is_file()
    assert (path.parent.parent / "st_programs" / "blink.st").is_file()


@pytest.mark.skipif(not (REPO / "io_config" / "default.toml").exists(), reason="no default.toml yet")
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
    path.write_bytes(b'# caf\xe9\n[plc]\n')
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


# ====================================================================== [plc]


def test_minimal_file_and_defaults(tmp_path):
    cfg = load(tmp_path, PLC)
    assert cfg == PlcConfig(path=tmp_path / "plant.toml", base_dir=tmp_path, profile="codesys",
                            programs=[tmp_path / "main.st"], on_fault="task", start="warm", tasks=[],
                            retain=None, safe_outputs=[], loopback=[],
                            raw={"plc": {"programs": ["main.st"]}})


def test_relative_paths_start_at_the_config_directory(tmp_path, monkeypatch):
    (tmp_path / "st").mkdir()
    (tmp_path / "st" / "a.st").write_text(PROG)
    (tmp_path / "cfg").mkdir()
    (tmp_path / "cfg" / "p.toml").write_text('[plc]\nprograms = ["../st/a.st"]\n'
                                             '[retain]\nfile = "p.retain"\n')
    monkeypatch.chdir(tmp_path / "st")
    cfg = load_config("../cfg/p.toml")
    assert cfg.programs == [tmp_path / "st" / "a.st"]       # normalised, absolute
    assert cfg.retain == RetainConfig(tmp_path / "cfg" / "p.retain", 1000 * MS)
    assert cfg.base_dir == tmp_path / "cfg"


def test_absolute_program_path(tmp_path):
    cfg = load(tmp_path, f'[plc]\nprograms = ["{tmp_path / "main.st"}"]\n')
    assert cfg.programs == [tmp_path / "main.st"]


def test_missing_program_file(tmp_path):
    assert error(tmp_path, '[plc]\nprograms = ["main.st", "../nope.st"]\n') == \
        ("plc.programs[1]", f"no such file: {tmp_path.parent / 'nope.st'} (relative paths start at "
                            "the config file's directory)")


def test_program_path_is_a_directory(tmp_path):
    (tmp_path / "dir.st").mkdir()
    assert error(tmp_path, '[plc]\nprograms = ["dir.st"]\n') == \
        ("plc.programs[0]", f"not a file: {tmp_path / 'dir.st'}")


def test_programs_wrong_types(tmp_path):
    assert errors(tmp_path, '[plc]\nprograms = "main.st"\n') == [
        ("plc.programs", 'expected an array of ST files such as ["../st_programs/conveyor.st"] '
                         "(got 'main.st')")]
    assert errors(tmp_path, '[plc]\nprograms = []\n') == [
        ("plc.programs", 'expected an array of ST files such as ["../st_programs/conveyor.st"] '
                         "(got an empty array)")]
    assert errors(tmp_path, '[plc]\nprograms = [1, ""]\n') == [
        ("plc.programs[0]", 'expected the path of an ST file such as "../st_programs/conveyor.st" (got 1)'),
        ("plc.programs[1]", 'expected the path of an ST file such as "../st_programs/conveyor.st" (got \'\')')]


def test_missing_plc_section(tmp_path):
    assert error(tmp_path, "") == \
        ("plc", 'required key missing (expected a [plc] table with at least programs = ["file.st"])')


def test_missing_programs(tmp_path):
    assert error(tmp_path, '[plc]\nprofile = "iec"\n') == \
        ("plc.programs", 'required key missing (expected an array of ST files such as '
                         '["../st_programs/conveyor.st"])')


def test_plc_not_a_table(tmp_path):
    assert error(tmp_path, 'plc = "main.st"\n') == \
        ("plc", "expected a [plc] table with at least programs = [\"file.st\"] (got 'main.st')")


@pytest.mark.parametrize("written, profile", [("iec", "iec"), ("CODESYS", "codesys"),
                                              ("twincat", "twincat"), ("Schneider", "schneider")])
def test_profiles(tmp_path, written, profile):
    assert load(tmp_path, PLC + f'profile = "{written}"\n').profile == profile


def test_unknown_profile_lists_the_valid_ones(tmp_path):
    assert error(tmp_path, PLC + 'profile = "siemens"\n') == \
        ("plc.profile", "expected one of 'iec', 'codesys', 'twincat', 'schneider' (got 'siemens')")
    assert error(tmp_path, PLC + 'profile = "codesis"\n') == \
        ("plc.profile", "expected one of 'iec', 'codesys', 'twincat', 'schneider' "
                        "(got 'codesis'; did you mean 'codesys'?)")
    assert error(tmp_path, PLC + 'profile = 3\n') == \
        ("plc.profile", "expected one of 'iec', 'codesys', 'twincat', 'schneider' (got 3)")


def test_on_fault_and_start(tmp_path):
    cfg = load(tmp_path, PLC + 'on_fault = "plc"\nstart = "cold"\n')
    assert (cfg.on_fault, cfg.start) == ("plc", "cold")
    assert errors(tmp_path, PLC + 'on_fault = "all"\nstart = "cld"\n') == [
        ("plc.on_fault", "expected one of 'task', 'plc' (got 'all')"),
        ("plc.start", "expected one of 'warm', 'cold' (got 'cld'; did you mean 'cold'?)")]


def test_unknown_key_with_suggestion(tmp_path):
    assert error(tmp_path, PLC + 'on_falut = "plc"\n') == \
        ("plc.on_falut", "unknown key (did you mean 'on_fault'?)")


def test_unknown_key_without_suggestion(tmp_path):
    assert error(tmp_path, PLC + 'colour = "blue"\n') == \
        ("plc.colour", "unknown key (expected one of profile, programs, on_fault, start)")


def test_later_sections_are_unknown_for_now(tmp_path):
    assert error(tmp_path, PLC + "[mpu2s]\nx = 1\n") == \
        ("mpu2s", "unknown key (expected one of plc, retain, task, outputs, loopback, can, canopen, sim, modbus)")


def test_unknown_section_suggestion(tmp_path):
    assert error(tmp_path, PLC + "[[tasks]]\nname = 'A'\n") == ("tasks", "unknown key (did you mean 'task'?)")


# ====================================================================== [[task]]


def task(body: str) -> str:
    return PLC + "[[task]]\n" + textwrap.dedent(body)


@pytest.mark.parametrize("written, ns", [
    ('"10ms"', 10 * MS), ("10", 10 * MS), ("2.5", 2_500_000), ('"1s500ms"', 1_500_000_000),
    ('"T#250ms"', 250 * MS), ('"TIME#1s"', 1_000_000_000), ('"100us"', 100_000), ('"1.5us"', 1_500),
    ('"1m"', 60_000 * MS)])
def test_interval_spellings(tmp_path, written, ns):
    cfg = load(tmp_path, task(f'name = "T"\ninterval = {written}\nprograms = ["Main"]\n'))
    assert cfg.tasks[0].interval_ns == ns


def test_task_defaults(tmp_path):
    cfg = load(tmp_path, task('name = "T"\ninterval = "10ms"\nprograms = ["Main"]\n'))
    assert cfg.tasks == [TaskConfig(name="T", interval_ns=10 * MS, pause_ns=1 * MS, priority=1,
                                    watchdog_ns=100 * MS, sensitivity=1,
                                    programs=[ProgramInstance("Main", "Main", "task[0].programs[0]")],
                                    key="task[0]")]


@pytest.mark.parametrize("timing, watchdog_ns", [
    ('interval = "1ms"', 100 * MS),            # at least 100 ms
    ('interval = "50ms"', 500 * MS),           # 10 x interval
    ("freewheeling = true", 1000 * MS),        # freewheeling: 1 s
    ('interval = "10ms"\nwatchdog = "20ms"', 20 * MS),
    ('interval = "10ms"\nwatchdog = 15', 15 * MS),
    ("interval = 10\nwatchdog = false", None),
    ("freewheeling = true\nwatchdog = false", None),
])
def test_watchdog(tmp_path, timing, watchdog_ns):
    cfg = load(tmp_path, task(f'name = "T"\n{timing}\nprograms = ["Main"]\n'))
    assert cfg.tasks[0].watchdog_ns == watchdog_ns


def test_freewheeling_task(tmp_path):
    t = load(tmp_path, task('name = "T"\nfreewheeling = true\npause = "250us"\npriority = 31\n'
                            'sensitivity = 3\nprograms = ["Main"]\n')).tasks[0]
    assert (t.interval_ns, t.pause_ns, t.priority, t.sensitivity) == (None, 250_000, 31, 3)
    t = load(tmp_path, task('name = "T"\nfreewheeling = true\nprograms = ["Main"]\n')).tasks[0]
    assert t.pause_ns == 1 * MS


def test_interval_and_freewheeling(tmp_path):
    assert error(tmp_path, task('name = "T"\ninterval = "10ms"\nfreewheeling = true\nprograms = ["Main"]\n')) \
        == ("task[0].freewheeling", "a task has either an interval or freewheeling = true, not both")


def test_interval_with_freewheeling_false_is_cyclic(tmp_path):
    t = load(tmp_path, task('name = "T"\ninterval = "10ms"\nfreewheeling = false\nprograms = ["Main"]\n'))
    assert t.tasks[0].interval_ns == 10 * MS


@pytest.mark.parametrize("timing", ["", "freewheeling = false\n"])
def test_neither_interval_nor_freewheeling(tmp_path, timing):
    assert error(tmp_path, task(f'name = "T"\n{timing}programs = ["Main"]\n')) == \
        ("task[0]", 'expected interval = "10ms" (a cyclic task) or freewheeling = true (got neither)')


def test_pause_with_interval(tmp_path):
    assert error(tmp_path, task('name = "T"\ninterval = "10ms"\npause = "1ms"\nprograms = ["Main"]\n')) == \
        ("task[0].pause", "only for a freewheeling task (this one has an interval)")


def test_sensitivity_without_watchdog(tmp_path):
    assert error(tmp_path, task('name = "T"\ninterval = 10\nwatchdog = false\nsensitivity = 2\n'
                                'programs = ["Main"]\n')) == \
        ("task[0].sensitivity", "only meaningful with a watchdog (this task has watchdog = false)")


def test_bad_duration_text(tmp_path):
    path = write(tmp_path, task('name = "T"\ninterval = "10 parsecs"\nprograms = ["Main"]\n'))
    with pytest.raises(ConfigError) as info:
        load_config(path)
    assert str(info.value) == f"{path}: task[0].interval: expected {DURATION} (got '10 parsecs')"


@pytest.mark.parametrize("key, written", [
    ("interval", "0"), ("interval", '"0ms"'), ("interval", "-5"), ("interval", '"-5ms"'),
    ("interval", '"T#-5ms"'), ("interval", "-0.5"), ("interval", '"0.1ns"')])
def test_zero_and_negative_durations(tmp_path, key, written):
    assert error(tmp_path, task(f'name = "T"\n{key} = {written}\nprograms = ["Main"]\n')) == \
        (f"task[0].{key}", f"expected a duration > 0 such as 10ms, 1s, T#250ms (got {_got(written)})")


def _got(toml_value: str) -> str:
    """How the messages quote a TOML value: strings in single quotes."""
    return f"'{toml_value[1:-1]}'" if toml_value.startswith('"') else toml_value


@pytest.mark.parametrize("written", ["true", '"fast"', "[10]", "inf", "nan", "1979-05-27"])
def test_durations_of_the_wrong_type(tmp_path, written):
    key, message = error(tmp_path, task(f'name = "T"\ninterval = {written}\nprograms = ["Main"]\n'))
    assert key == "task[0].interval"
    assert message.startswith(f"expected {DURATION} (got ")


def test_zero_pause_and_watchdog(tmp_path):
    assert errors(tmp_path, task('name = "T"\nfreewheeling = true\npause = 0\nwatchdog = "0s"\n'
                                 'programs = ["Main"]\n')) == [
        ("task[0].pause", "expected a duration > 0 such as 10ms, 1s, T#250ms (got 0)"),
        ("task[0].watchdog", "expected a duration > 0 such as 10ms, 1s, T#250ms, or false for no "
                             "watchdog (got '0s')")]


def test_watchdog_true_is_refused(tmp_path):
    assert error(tmp_path, task('name = "T"\ninterval = 10\nwatchdog = true\nprograms = ["Main"]\n')) == \
        ("task[0].watchdog", "expected a duration > 0 such as 10ms, 1s, T#250ms, or false for no "
                             "watchdog (got true)")


@pytest.mark.parametrize("written", ["32", "-1", "100"])
def test_priority_out_of_range(tmp_path, written):
    assert error(tmp_path, task(f'name = "T"\ninterval = 10\npriority = {written}\nprograms = ["Main"]\n')) == \
        ("task[0].priority", f"expected an integer from 0 to 31 (got {written})")


@pytest.mark.parametrize("written, got", [('"10"', "'10'"), ("1.0", "1.0"), ("true", "true")])
def test_priority_wrong_type(tmp_path, written, got):
    assert error(tmp_path, task(f'name = "T"\ninterval = 10\npriority = {written}\nprograms = ["Main"]\n')) == \
        ("task[0].priority", f"expected an integer from 0 to 31 (got {got})")


def test_priority_bounds_accepted(tmp_path):
    cfg = load(tmp_path, task('name = "A"\ninterval = 10\npriority = 0\nprograms = ["Main"]\n'
                              '[[task]]\nname = "B"\ninterval = 10\npriority = 31\nprograms = ["M2"]\n'))
    assert [t.priority for t in cfg.tasks] == [0, 31]


def test_sensitivity_range(tmp_path):
    assert error(tmp_path, task('name = "T"\ninterval = 10\nsensitivity = 0\nprograms = ["Main"]\n')) == \
        ("task[0].sensitivity", "expected an integer >= 1 (got 0)")


def test_freewheeling_wrong_type(tmp_path):
    assert error(tmp_path, task('name = "T"\nfreewheeling = "yes"\nprograms = ["Main"]\n')) == \
        ("task[0].freewheeling", "expected true or false (got 'yes')")


def test_task_unknown_key(tmp_path):
    assert errors(tmp_path, task('name = "T"\nintervall = "10ms"\nprograms = ["Main"]\n')) == [
        ("task[0].intervall", "unknown key (did you mean 'interval'?)"),
        ("task[0]", 'expected interval = "10ms" (a cyclic task) or freewheeling = true (got neither)')]


def test_task_missing_keys(tmp_path):
    assert errors(tmp_path, task('interval = "10ms"\n')) == [
        ("task[0].name", 'required key missing (expected a task name such as "Fast")'),
        ("task[0].programs", 'required key missing (expected an array of PROGRAM names or '
                             '{ instance = "...", program = "..." } tables, such as ["Conveyor"])')]


def test_task_as_a_table_instead_of_an_array(tmp_path):
    assert error(tmp_path, PLC + '[task]\nname = "T"\n') == ("task", "expected [[task]] tables (got a table)")


def test_task_name_must_be_an_identifier(tmp_path):
    assert error(tmp_path, task('name = "1st task"\ninterval = 10\nprograms = ["Main"]\n')) == \
        ("task[0].name", "expected a task name: an IEC identifier (letters, digits, _; not starting "
                         "with a digit) (got '1st task')")


def test_duplicate_task_names(tmp_path):
    assert error(tmp_path, task('name = "Fast"\ninterval = 10\nprograms = ["Main"]\n'
                                '[[task]]\nname = "FAST"\ninterval = 20\nprograms = ["Other"]\n')) == \
        ("task[1].name", "duplicate task name 'FAST' (task[0] has it; names are case-insensitive)")


def test_program_instances(tmp_path):
    cfg = load(tmp_path, task('name = "T"\ninterval = 10\nprograms = ["Main", '
                              '{ instance = "Main2", program = "Main" }]\n'))
    assert cfg.tasks[0].programs == [ProgramInstance("Main", "Main", "task[0].programs[0]"),
                                     ProgramInstance("Main2", "Main", "task[0].programs[1]")]


def test_duplicate_instance_names_across_tasks(tmp_path):
    assert error(tmp_path, task('name = "A"\ninterval = 10\nprograms = ["Main"]\n'
                                '[[task]]\nname = "B"\ninterval = 20\nprograms = ["main"]\n')) == \
        ("task[1].programs[0]", "duplicate program instance 'main' (also at task[0].programs[0]; instance "
                                "names are unique across tasks, case-insensitive); give one its own "
                                'instance name: { instance = "main2", program = "main" }')


def test_duplicate_instance_names_in_tables(tmp_path):
    assert error(tmp_path, task('name = "A"\ninterval = 10\nprograms = ["Main", '
                                '{ instance = "Main", program = "Other" }]\n')) == \
        ("task[0].programs[1].instance", "duplicate program instance 'Main' (also at task[0].programs[0]; "
                                         "instance names are unique across tasks, case-insensitive)")


def test_bad_program_entries(tmp_path):
    assert errors(tmp_path, task('name = "A"\ninterval = 10\nprograms = [5, "no good", '
                                 '{ instance = "X" }, { instance = "Y", program = "P", prio = 1 }]\n')) == [
        ("task[0].programs[0]", 'expected a PROGRAM name such as "Conveyor" or a table '
                                '{ instance = "Line2", program = "Conveyor" } (got 5)'),
        ("task[0].programs[1]", "expected a PROGRAM name (an IEC identifier) (got 'no good')"),
        ("task[0].programs[2].program", 'required key missing (expected a PROGRAM name such as "Conveyor")'),
        ("task[0].programs[3].prio", "unknown key (expected one of instance, program)")]


def test_empty_program_list(tmp_path):
    assert error(tmp_path, task('name = "A"\ninterval = 10\nprograms = []\n')) == \
        ("task[0].programs", 'expected an array of PROGRAM names or { instance = "...", program = "..." } '
                             'tables, such as ["Conveyor"] (got an empty array)')


# ====================================================================== [retain]


def test_retain_defaults(tmp_path):
    cfg = load(tmp_path, PLC + '[retain]\nfile = "plant.retain"\n')
    assert cfg.retain == RetainConfig(tmp_path / "plant.retain", 1000 * MS)


def test_retain_errors(tmp_path):
    assert errors(tmp_path, PLC + '[retain]\nperiod = "0s"\n') == [
        ("retain.file", 'required key missing (expected a file name such as "plant.retain")'),
        ("retain.period", "expected a duration > 0 such as 10ms, 1s, T#250ms (got '0s')")]
    assert error(tmp_path, PLC + '[retain]\nfile = "."\n') == \
        ("retain.file", f"{tmp_path} is a directory; expected a file name")
    assert error(tmp_path, PLC + '[retain]\nfile = 1\n') == \
        ("retain.file", 'expected a file name such as "plant.retain" (got 1)')


# ====================================================================== [outputs]


def test_safe_outputs(tmp_path):
    cfg = load(tmp_path, PLC + '[outputs]\nsafe = { "%QX0.0" = true, "%qx0.1" = 1, "%QX0.2" = 0, '
                               '"%QB1" = 255, "%QW2" = -32768, "%QD4" = 1.5, "%QD5" = 7, "%QL1" = 2.5e300 }\n')
    assert [(s.address.text, s.value, type(s.value)) for s in cfg.safe_outputs] == [
        ("%QX0.0", True, bool), ("%QX0.1", True, bool), ("%QX0.2", False, bool),
        ("%QB1", 255, int), ("%QW2", -32768, int), ("%QD4", 1.5, float), ("%QD5", 7, int),
        ("%QL1", 2.5e300, float)]
    assert cfg.safe_outputs[1].key == 'outputs.safe."%qx0.1"'


def test_safe_output_on_an_input(tmp_path):
    assert error(tmp_path, PLC + '[outputs]\nsafe = { "%IX0.0" = false }\n') == \
        ('outputs.safe."%IX0.0"', "expected a %Q output address (got '%IX0.0', an input)")
    assert error(tmp_path, PLC + '[outputs]\nsafe = { "%MW0" = 0 }\n') == \
        ('outputs.safe."%MW0"', "expected a %Q output address (got '%MW0', a memory address)")


@pytest.mark.parametrize("text", ["QX0.0", "%QZ0", "%QX", "%Q*", "%QW0.1", "%QX0.8", "%QX0.1.2", ""])
def test_safe_output_bad_address(tmp_path, text):
    key, message = error(tmp_path, PLC + f'[outputs]\nsafe = {{ "{text}" = 0 }}\n')
    assert key == f'outputs.safe."{text}"'
    assert message  # the address module's words; the common case:
    if text in ("QX0.0", "%QZ0", "%QX", ""):
        assert message == f"expected a direct address such as %QX0.0, %QW2 (got '{text}')"


def test_safe_output_address_messages(tmp_path):
    assert error(tmp_path, PLC + '[outputs]\nsafe = { "%QX0.8" = 0 }\n') == \
        ('outputs.safe."%QX0.8"', "bit number 8 is not 0..7")


@pytest.mark.parametrize("text, value, message", [
    ("%QW2", "true", "expected an integer for a word address (got true)"),
    ("%QB0", "false", "expected an integer for a byte address (got false)"),
    ("%QD4", "true", "expected an integer or a float for a dword address (got true)"),
    ("%QW2", "1.5", "expected an integer for a word address (got 1.5; a REAL needs a %QD address, "
                    "an LREAL a %QL address)"),
    ("%QW2", "70000", "expected an integer from -32768 to 65535 for a word address (got 70000)"),
    ("%QB0", "256", "expected an integer from -128 to 255 for a byte address (got 256)"),
    ("%QD0", "1e39", "expected a REAL (at most 3.4e38) for a dword address (got 1e+39)"),
    ("%QW2", '"0"', "expected an integer for a word address (got '0')"),
    ("%QX0.0", "2", "expected true or false (or 0 / 1) for a bit address (got 2)"),
    ("%QX0.0", '"true"', "expected true or false (or 0 / 1) for a bit address (got 'true')"),
])
def test_safe_output_values(tmp_path, text, value, message):
    assert error(tmp_path, PLC + f'[outputs]\nsafe = {{ "{text}" = {value} }}\n') == \
        (f'outputs.safe."{text}"', message)


def test_safe_output_same_address_twice(tmp_path):
    assert error(tmp_path, PLC + '[outputs]\nsafe = { "%QX0.0" = true, " %qx0.0" = false }\n') == \
        ('outputs.safe." %qx0.0"', 'the same address as outputs.safe."%QX0.0"')


def test_safe_outputs_schneider_addressing(tmp_path):
    cfg = load(tmp_path, PLC + 'profile = "schneider"\n[outputs]\nsafe = { "%QW3:X2" = true }\n')
    assert cfg.safe_outputs[0].address.bit == 2 and cfg.safe_outputs[0].value is True
    key, message = error(tmp_path, PLC + '[outputs]\nsafe = { "%QW3:X2" = true }\n')
    assert key == 'outputs.safe."%QW3:X2"' and "schneider" in message
    assert error(tmp_path, PLC + 'profile = "schneider"\n[outputs]\nsafe = { "%QW3:4" = 0 }\n') == \
        ('outputs.safe."%QW3:4"', "expected a single bit, byte, word, dword or lword (got a word table); "
                                  "list the words one by one")


def test_outputs_unknown_key_and_type(tmp_path):
    assert errors(tmp_path, PLC + '[outputs]\nsaf = {}\n') == [
        ("outputs.saf", "unknown key (did you mean 'safe'?)")]
    assert errors(tmp_path, PLC + '[outputs]\nsafe = ["%QX0.0"]\n') == [
        ("outputs.safe", 'expected a table of %Q address = value, such as { "%QX0.0" = false } (got an array)')]


# ====================================================================== [[loopback]]


def test_loopback_errors(tmp_path):
    assert errors(tmp_path, PLC + '[[loopback]]\nfrom = "%IB0"\nto = "%QB0"\nbytes = 0\n'
                                  '[[loopback]]\nfrom = "%QX0.0"\nto = "%IX0.0"\nbytes = 1\n'
                                  '[[loopback]]\nfrom = "%QB0"\nbytes = true\n'
                                  '[[loopback]]\nfrom = 3\nto = "%IZ0"\nbytes = 1\nsize = 2\n') == [
        ("loopback[0].bytes", "expected an integer >= 1 (got 0)"),
        ("loopback[0].from", "expected a %Q output address (got '%IB0', an input)"),
        ("loopback[0].to", "expected a %I input address (got '%QB0', an output)"),
        ("loopback[1].from", "expected a %Q output byte, word, dword or lword address such as %QB0 "
                             "(got '%QX0.0'); the link copies whole bytes"),
        ("loopback[1].to", "expected a %I input byte, word, dword or lword address such as %IB0 "
                           "(got '%IX0.0'); the link copies whole bytes"),
        ("loopback[2].to", 'required key missing (expected a %I byte/word/dword/lword address such as "%IB0")'),
        ("loopback[2].bytes", "expected an integer >= 1 (got true)"),
        ("loopback[3].size", "unknown key (expected one of from, to, bytes)"),
        ("loopback[3].from", "expected a direct address such as %QB0, %QW2 (got 3)"),
        ("loopback[3].to", "expected a direct address such as %IB0, %IW2 (got '%IZ0')"),
    ]


# ====================================================================== [[can]], [canopen], [[sim]]
#
# Numbers from the LTMR CANopen manual (001, English) where it sets them:
# node ids 1..127 (L163), the bitrates (L183-205, 250 kBaud the factory
# setting, L206), 0x1016:01 and 0x1017 in 16 bits of ms (L957, L964), the
# TPDO inhibit time in 16 bits of 100 us (L1365), 8 bytes per PDO (L117).

CAN = '[[can]]\ninterface = "virtual"\nchannel = "plant"\n'
NODE = '[[canopen.node]]\nname = "motor"\nid = 40\neds = "ltmr"\n'
SIM = '[[sim]]\ntype = "ltmr"\nnode_id = 40\n'
CANOPEN_BITRATES = [10_000, 20_000, 50_000, 125_000, 250_000, 500_000, 800_000, 1_000_000]


def plant(master: str = "", node: str = "", *tables: str) -> str:
    """One bus, [canopen] with master keys, one node with node keys, then tables."""
    return PLC + CAN + "[canopen]\n" + master + NODE + node + "".join(tables)


def pdo(direction: str, number: int, *entries, keys: str = "") -> str:
    mapped = ", ".join(f'{{ object = "{o}", address = "{a}" }}' for o, a in entries)
    return f"[[canopen.node.{direction}]]\nnumber = {number}\n{keys}map = [{mapped}]\n"


def test_canopen_defaults(tmp_path):
    cfg = load(tmp_path, plant("", "", pdo("tpdo", 1, ("2004:06", "%IW0")), pdo("rpdo", 1, ("2008:05", "%QW0")),
                               SIM))
    assert cfg.can == [CanBusConfig("can0", "virtual", "plant", 250_000, {}, "can[0]")]
    key = "canopen.node[0]"
    assert cfg.canopen == CanopenConfig(
        bus="can0", node_id=127, heartbeat_ms=100, sync_us=0, sdo_timeout_ms=500, boot_timeout_ms=2000,
        retry_ms=1000, key="canopen", nodes=[CanopenNodeConfig(
            name="motor", node_id=40, eds=EDS / "ltmr.eds", mandatory=True, heartbeat_ms=100,
            heartbeat_timeout_ms=300, master_timeout_ms=500, sdo=[], key=key,
            tpdo=[PdoConfig(1, 255, 0, 0, True, [PdoEntryConfig(0x2004, 0x06, addr("%IW0"),
                                                                f"{key}.tpdo[0].map[0]")], f"{key}.tpdo[0]")],
            rpdo=[PdoConfig(1, 255, 0, 0, True, [PdoEntryConfig(0x2008, 0x05, addr("%QW0"),
                                                                f"{key}.rpdo[0].map[0]")], f"{key}.rpdo[0]")])])
    assert cfg.sims == [SimConfig("ltmr", "ltmr40", "can0", 40, {}, "sim[0]")]


def test_file_without_can_sections(tmp_path):
    cfg = load(tmp_path, PLC)
    assert (cfg.can, cfg.canopen, cfg.sims) == ([], None, [])


def test_can_buses(tmp_path):
    cfg = load(tmp_path, PLC + CAN + '[[can]]\nname = "Line2"\ninterface = "socketcan"\nchannel = 1\n'
                               'bitrate = 1000000\noptions = { fd = false, receive_own_messages = true }\n'
                               '[canopen]\nbus = "LINE2"\n'
                               '[[sim]]\ntype = "ltmr"\nnode_id = 3\nbus = "can0"\n'
                               '[[sim]]\ntype = "LTMR"\nname = "spare"\nnode_id = 3\nbus = "line2"\n')
    assert cfg.can == [CanBusConfig("can0", "virtual", "plant", 250_000, {}, "can[0]"),
                       CanBusConfig("Line2", "socketcan", "1", 1_000_000,
                                    {"fd": False, "receive_own_messages": True}, "can[1]")]
    # bus names are case-insensitive; the configuration carries the name as the [[can]] writes it
    assert cfg.canopen.bus == "Line2" and cfg.canopen.nodes == []
    assert [(s.name, s.bus, s.node_id) for s in cfg.sims] == [("ltmr3", "can0", 3), ("spare", "Line2", 3)]


@pytest.mark.parametrize("bitrate", CANOPEN_BITRATES)
def test_canopen_bitrates(tmp_path, bitrate):
    assert load(tmp_path, PLC + CAN + f"bitrate = {bitrate}\n").can[0].bitrate == bitrate


@pytest.mark.parametrize("written, got", [("100000", "100000"), ('"250k"', "'250k'"), ("true", "true"),
                                          ("250000.0", "250000.0")])
def test_other_bitrates_are_refused(tmp_path, written, got):
    assert error(tmp_path, PLC + CAN + f"bitrate = {written}\n") == \
        ("can[0].bitrate", "expected one of the CANopen bitrates 10000, 20000, 50000, 125000, 250000, 500000, "
                           f"800000, 1000000 (got {got})")


def test_can_required_keys_and_types(tmp_path):
    assert errors(tmp_path, PLC + '[[can]]\nname = "can0"\n') == [
        ("can[0].interface", 'required key missing (expected a python-can interface such as "socketcan", '
                             '"pcan" or "virtual")'),
        ("can[0].channel", 'required key missing (expected a channel such as "can0" or "PCAN_USBBUS1")')]
    assert errors(tmp_path, PLC + '[[can]]\nname = "0can"\ninterface = " "\nchannel = true\noptions = 3\n'
                                  'bitrat = 1\n') == [
        ("can[0].name", "expected a bus name: an IEC identifier (letters, digits, _; not starting with a "
                        "digit) (got '0can')"),
        ("can[0].interface", 'expected a python-can interface such as "socketcan", "pcan" or "virtual" '
                             "(got ' ')"),
        ("can[0].channel", "expected a channel such as \"can0\" or \"PCAN_USBBUS1\" (got true)"),
        ("can[0].options", "expected a table of python-can options, such as { fd = false } (got 3)"),
        ("can[0].bitrat", "unknown key (did you mean 'bitrate'?)")]
    assert error(tmp_path, PLC + '[can]\ninterface = "virtual"\nchannel = "x"\n') == \
        ("can", "expected [[can]] tables (got a table)")


def test_duplicate_bus_names(tmp_path):
    assert error(tmp_path, PLC + CAN + '[[can]]\nname = "CAN0"\ninterface = "virtual"\nchannel = "b"\n') == \
        ("can[1].name", "duplicate bus name 'CAN0' (can[0] has it; names are case-insensitive)")
    assert error(tmp_path, PLC + CAN + CAN) == \
        ("can[1]", "duplicate bus name 'can0' (the default; can[0] has it): give each [[can]] its own name")


def test_canopen_and_sims_need_a_bus(tmp_path):
    assert errors(tmp_path, PLC + "[canopen]\n" + SIM) == [
        ("canopen", "the CANopen master needs a [[can]] bus (the file has none): add a [[can]] table with "
                    "interface and channel"),
        ("sim[0]", "a simulated device needs a [[can]] bus (the file has none): add a [[can]] table with "
                   "interface and channel")]


def test_several_buses_need_a_bus_key(tmp_path):
    two = CAN + '[[can]]\nname = "can1"\ninterface = "virtual"\nchannel = "b"\n'
    assert errors(tmp_path, PLC + two + "[canopen]\n" + SIM) == [
        ("canopen.bus", "required key missing: the file has several [[can]] buses (expected one of 'can0', "
                        "'can1')"),
        ("sim[0].bus", "required key missing: the file has several [[can]] buses (expected one of 'can0', "
                       "'can1')")]
    assert errors(tmp_path, PLC + two + '[canopen]\nbus = "can2"\n' + SIM + 'bus = "can_1"\n') == [
        ("canopen.bus", "expected one of 'can0', 'can1', the [[can]] buses (got 'can2')"),
        ("sim[0].bus", "expected one of 'can0', 'can1', the [[can]] buses (got 'can_1')")]


# ---------------------------------------------------------------- [canopen] durations


@pytest.mark.parametrize("written, field, value", [
    ('heartbeat = "250ms"', "heartbeat_ms", 250),
    ("heartbeat = false", "heartbeat_ms", 0),
    ('heartbeat = "0ms"', "heartbeat_ms", 0),
    ('heartbeat = "1.4ms"', "heartbeat_ms", 1),          # rounded to whole ms
    ('heartbeat = "1.6ms"', "heartbeat_ms", 2),
    ('sync = "2.5ms"', "sync_us", 2500),                 # SYNC in microseconds
    ('sync = "T#100us"', "sync_us", 100),
    ("sync = false", "sync_us", 0),
    ('sdo_timeout = "1s"', "sdo_timeout_ms", 1000),
    ("boot_timeout = 3000", "boot_timeout_ms", 3000),    # a bare number is ms
    ('retry = "1.5s"', "retry_ms", 1500),
])
def test_master_durations(tmp_path, written, field, value):
    cfg = load(tmp_path, PLC + CAN + f"[canopen]\n{written}\n")
    assert getattr(cfg.canopen, field) == value


@pytest.mark.parametrize("written, message", [
    ('sdo_timeout = "0ms"', "expected a duration > 0 such as 10ms, 1s, T#250ms (got '0ms')"),
    ("sdo_timeout = false", "expected a duration > 0 such as 10ms, 1s, T#250ms (got false)"),
    ('retry = "0.4ms"', "expected a duration of at least 1ms (got '0.4ms')"),
    ("heartbeat = true", "expected a duration such as 10ms, 1s, T#250ms, or false for no heartbeat (got true)"),
    ('heartbeat = "-5ms"', "expected a duration such as 10ms, 1s, T#250ms, or false for no heartbeat "
                           "(got '-5ms')"),
    ('heartbeat = "0.4ms"', "expected a duration of at least 1ms, or false for no heartbeat (got '0.4ms')"),
    ('sync = "soon"', "expected a duration such as 10ms, 1s, T#250ms, or false for no SYNC (got 'soon')"),
    ('sync = "0.4us"', "expected a duration of at least 1us, or false for no SYNC (got '0.4us')"),
])
def test_master_durations_refused(tmp_path, written, message):
    assert error(tmp_path, PLC + CAN + f"[canopen]\n{written}\n") == (f"canopen.{written.split()[0]}", message)


# ---------------------------------------------------------------- heartbeats


def test_node_heartbeat_defaults(tmp_path):
    def times(master: str, node: str) -> tuple:
        n = load(tmp_path, plant(master, node)).canopen.nodes[0]
        return n.heartbeat_ms, n.heartbeat_timeout_ms, n.master_timeout_ms
    assert times("", "") == (100, 300, 500)                                     # 3 x 100, 5 x 100
    assert times('heartbeat = "50ms"\n', 'heartbeat = "200ms"\n') == (200, 600, 250)
    assert times("", 'heartbeat = "1s"\nheartbeat_timeout = "1.5s"\nmaster_timeout = "150ms"\n') == \
        (1000, 1500, 150)
    assert times("", "heartbeat = false\n") == (0, 0, 500)                      # nothing to watch
    assert times("", 'heartbeat = "0ms"\n') == (0, 0, 500)
    assert times("", "heartbeat_timeout = false\n") == (100, 0, 500)           # sent, not watched
    assert times("heartbeat = false\n", "") == (100, 300, 0)                   # no master heartbeat to watch
    assert times("", "master_timeout = false\n") == (100, 300, 0)
    assert times('heartbeat = "20s"\n', "") == (100, 300, 65535)   # not 5 x 20 s: 0x1016:01 holds 65.535 s


def test_heartbeat_words_of_the_manual(tmp_path):
    """Digest 001 §7.2 (derived from manual 001 L957/L964): the master 0x7F
    watched at 500 ms is 0x1016:01 = 0x007F01F4; a producer time of 1000 ms
    is 0x1017 = 0x03E8."""
    node = load(tmp_path, plant("node_id = 127\n", 'heartbeat = "1s"\nmaster_timeout = "500ms"\n')).canopen
    assert (node.node_id << 16) | node.nodes[0].master_timeout_ms == 0x007F01F4
    assert node.nodes[0].heartbeat_ms == 0x03E8


def test_heartbeat_fields_of_16_bits(tmp_path):
    n = load(tmp_path, plant("", 'heartbeat = "65535ms"\nheartbeat_timeout = "70s"\nmaster_timeout = 65535\n'))
    assert (n.canopen.nodes[0].heartbeat_ms, n.canopen.nodes[0].master_timeout_ms) == (65535, 65535)
    assert errors(tmp_path, plant("", 'heartbeat = "65.536s"\nmaster_timeout = "1min"\n')) == [
        ("canopen.node[0].heartbeat", "expected a duration of at most 65535ms (0x1017 holds ms in 16 bits), or "
                                      "false for no heartbeat (got '65.536s')"),
        ("canopen.node[0].master_timeout", "expected a duration such as 10ms, 1s, T#250ms, or false for the "
                                           "node not watching the master (got '1min')")]
    assert error(tmp_path, plant("", 'master_timeout = "66s"\n')) == \
        ("canopen.node[0].master_timeout", "expected a duration of at most 65535ms (0x1016:01 holds ms in 16 "
                                           "bits), or false for the node not watching the master (got '66s')")


def test_heartbeat_timeout_must_outlast_the_heartbeat(tmp_path):
    assert error(tmp_path, plant("", 'heartbeat = "100ms"\nheartbeat_timeout = "100ms"\n')) == \
        ("canopen.node[0].heartbeat_timeout", "expected a duration longer than the node's heartbeat (100ms), "
                                              "or false for not watching it (got '100ms')")
    assert error(tmp_path, plant("", "heartbeat = false\nheartbeat_timeout = \"300ms\"\n")) == \
        ("canopen.node[0].heartbeat_timeout", "only meaningful with a heartbeat (this node has "
                                              "heartbeat = false)")


def test_master_timeout_must_outlast_the_masters_heartbeat(tmp_path):
    assert error(tmp_path, plant('heartbeat = "200ms"\n', 'master_timeout = "150ms"\n')) == \
        ("canopen.node[0].master_timeout", "expected a duration longer than canopen.heartbeat (200ms), or "
                                           "false for the node not watching the master (got '150ms')")
    assert error(tmp_path, plant('heartbeat = "0ms"\n', 'master_timeout = "500ms"\n')) == \
        ("canopen.node[0].master_timeout", "only meaningful when the master sends a heartbeat "
                                           "(canopen.heartbeat = '0ms')")
    assert error(tmp_path, plant('heartbeat = "65535ms"\n')) == \
        ("canopen.node[0]", "the default master_timeout, 5 x canopen.heartbeat at most 65535ms, is not longer "
                            "than canopen.heartbeat (65535ms): give master_timeout, or false")


# ---------------------------------------------------------------- nodes


def test_node_ids(tmp_path):
    assert load(tmp_path, plant("node_id = 1\n").replace("id = 40", "id = 127")).canopen.nodes[0].node_id == 127
    assert errors(tmp_path, plant("node_id = 0\n").replace("id = 40", "id = 128")) == [
        ("canopen.node_id", "expected an integer from 1 to 127 (got 0)"),
        ("canopen.node[0].id", "expected an integer from 1 to 127 (got 128)")]
    assert error(tmp_path, plant("node_id = 40\n")) == \
        ("canopen.node[0].id", "40 is the master's own node id (canopen.node_id)")
    assert errors(tmp_path, plant("", "", NODE.replace('"motor"', '"Pump"'), NODE.replace("40", "41"))) == [
        ("canopen.node[1].id", "duplicate node id 40 (canopen.node[0] has it)"),
        ("canopen.node[2].name", "duplicate node name 'motor' (canopen.node[0] has it; names are "
                                 "case-insensitive)")]


def test_node_required_keys(tmp_path):
    assert errors(tmp_path, PLC + CAN + "[canopen]\n[[canopen.node]]\nmandatory = 1\n") == [
        ("canopen.node[0].name", 'required key missing (expected a node name such as "motor1")'),
        ("canopen.node[0].id", "required key missing (expected a node id from 1 to 127)"),
        ("canopen.node[0].eds", 'required key missing (expected a shipped EDS name such as "ltmr" or the path '
                                "of an .eds file)"),
        ("canopen.node[0].mandatory", "expected true or false (got 1)")]


def test_node_mandatory(tmp_path):
    assert load(tmp_path, plant("", "mandatory = false\n")).canopen.nodes[0].mandatory is False


@pytest.mark.parametrize("written, path", [('"ltmr"', EDS / "ltmr.eds"), ('"LTMR"', EDS / "ltmr.eds"),
                                           ('"fc280"', EDS / "fc280.eds")])
def test_shipped_eds(tmp_path, written, path):
    text = plant("", "").replace('eds = "ltmr"', f"eds = {written}")
    assert load(tmp_path, text).canopen.nodes[0].eds == path


def test_eds_files(tmp_path):
    (tmp_path / "devices").mkdir()
    (tmp_path / "devices" / "motor.eds").write_text((EDS / "ltmr.eds").read_text())
    text = plant("", "").replace('eds = "ltmr"', 'eds = "devices/motor.eds"')
    assert load(tmp_path, text).canopen.nodes[0].eds == tmp_path / "devices" / "motor.eds"
    for written, message in [
        ('"ltmx"', "expected a shipped EDS name ('fc280', 'ltmr') or the path of an .eds file (got 'ltmx'; did "
                   "you mean 'ltmr'?)"),
        ('"vfd"', "expected a shipped EDS name ('fc280', 'ltmr') or the path of an .eds file (got 'vfd')"),
        ("7", "expected a shipped EDS name ('fc280', 'ltmr') or the path of an .eds file (got 7)"),
        ('"devices/pump.eds"', f"no such file: {tmp_path / 'devices' / 'pump.eds'} (relative paths start at "
                               "the config file's directory)"),
        ('"devices/"', f"not a file: {tmp_path / 'devices'}"),
    ]:
        assert error(tmp_path, plant("", "").replace('eds = "ltmr"', f"eds = {written}")) == \
            ("canopen.node[0].eds", message)


# ---------------------------------------------------------------- boot-time SDO writes


def test_sdo_writes(tmp_path):
    cfg = load(tmp_path, plant("", 'sdo = [{ object = "2007:21", value = 2 }, { object = "0x1017:0", '
                                   'value = 1000, size = 2 }, { object = "1:1", value = -1, size = 4 }, '
                                   '{ object = "2004:6a", value = 4294967295, size = 4 }]\n'))
    assert cfg.canopen.nodes[0].sdo == [
        SdoWriteConfig(0x2007, 0x21, 2, None, "canopen.node[0].sdo[0]"),
        SdoWriteConfig(0x1017, 0x00, 1000, 2, "canopen.node[0].sdo[1]"),
        SdoWriteConfig(0x0001, 0x01, -1, 4, "canopen.node[0].sdo[2]"),
        SdoWriteConfig(0x2004, 0x6A, 4294967295, 4, "canopen.node[0].sdo[3]")]


@pytest.mark.parametrize("written", ['"2004.06"', '"12004:06"', '"2004:123"', '"2004:"', '":06"', '"x2004:06"',
                                     '"2004:0G"', '""', "0x2004"])
def test_bad_objects(tmp_path, written):
    got = written.replace('"', "'") if written.startswith('"') else "8196"
    assert error(tmp_path, plant("", f"sdo = [{{ object = {written}, value = 1 }}]\n")) == \
        ("canopen.node[0].sdo[0].object", f'expected an object "index:subindex" in hex, such as "2004:06" '
                                          f"(got {got})")


@pytest.mark.parametrize("size, value, fits", [
    (1, 255, True), (1, -128, True), (1, 256, False), (1, -129, False),
    (2, 65535, True), (2, -32768, True), (2, 65536, False),
    (4, 4294967295, True), (4, -2147483648, True), (4, 4294967296, False)])
def test_sdo_value_must_fit_its_size(tmp_path, size, value, fits):
    text = plant("", f'sdo = [{{ object = "2007:21", value = {value}, size = {size} }}]\n')
    if fits:
        assert load(tmp_path, text).canopen.nodes[0].sdo[0].value == value
    else:
        lo, hi = -(1 << (8 * size - 1)), (1 << (8 * size)) - 1
        assert error(tmp_path, text) == \
            ("canopen.node[0].sdo[0].value", f"expected an integer from {lo} to {hi} for size = {size} "
                                             f"(got {value})")


def test_sdo_write_errors(tmp_path):
    assert errors(tmp_path, plant("", 'sdo = [{ object = "2007:21" }, { object = "2007:21", value = "2", '
                                      'size = 3 }, { object = "2007:21", value = 1.5, bytes = 2 }]\n')) == [
        ("canopen.node[0].sdo[0].value", "required key missing (expected an integer)"),
        ("canopen.node[0].sdo[1].value", "expected an integer (got '2')"),
        ("canopen.node[0].sdo[1].size", "expected a size in bytes: 1, 2 or 4 (got 3)"),
        ("canopen.node[0].sdo[2].value", "expected an integer (got 1.5)"),
        ("canopen.node[0].sdo[2].bytes", "unknown key (expected one of object, value, size)")]


# ---------------------------------------------------------------- PDOs


def test_pdo_parameters(tmp_path):
    cfg = load(tmp_path, plant(
        "", "",
        pdo("tpdo", 2, ("2004:02", "%IW4"), keys='transmission = 0\ninhibit = "150us"\nevent = "2.5s"\n'
                                                 "configure = false\n"),
        pdo("tpdo", 512, ("2004:0b", "%IW5"), keys="transmission = 240\n"),
        pdo("rpdo", 2, ("2008:05", "%QW4"), keys='transmission = 254\ninhibit = "6553.5ms"\nevent = 65535\n')))
    node = cfg.canopen.nodes[0]
    assert [(p.number, p.transmission, p.inhibit_us, p.event_ms, p.configure) for p in node.tpdo + node.rpdo] \
        == [(2, 0, 150, 2500, False), (512, 240, 0, 0, True), (2, 254, 6_553_500, 65535, True)]
    assert node.tpdo[1].entries == \
        [PdoEntryConfig(0x2004, 0x0B, addr("%IW5"), "canopen.node[0].tpdo[1].map[0]")]


@pytest.mark.parametrize("keys, key, message", [
    ("transmission = 241\n", "transmission", "expected a transmission type 0..240, 254 or 255 (got 241)"),
    ("transmission = 253\n", "transmission", "expected a transmission type 0..240, 254 or 255 (got 253)"),
    ("transmission = -1\n", "transmission", "expected a transmission type 0..240, 254 or 255 (got -1)"),
    ('inhibit = "6553.6ms"\n', "inhibit", "expected a duration of at most 6553500us (the inhibit time is 16 "
                                          "bits of 100us), or false for none (got '6553.6ms')"),
    ('event = "65.536s"\n', "event", "expected a duration of at most 65535ms (the event timer is 16 bits of "
                                     "ms), or false for none (got '65.536s')"),
    ("configure = 1\n", "configure", "expected true or false (got 1)"),
    ("mapping = 1\n", "mapping", "unknown key (did you mean 'map'?)"),
])
def test_pdo_parameters_refused(tmp_path, keys, key, message):
    assert error(tmp_path, plant("", "", pdo("tpdo", 1, ("2004:06", "%IW0"), keys=keys))) == \
        (f"canopen.node[0].tpdo[0].{key}", message)


def test_pdo_numbers(tmp_path):
    text = plant("", "", pdo("tpdo", 0, ("2004:06", "%IW0")), pdo("rpdo", 513, ("2008:05", "%QW0")))
    assert errors(tmp_path, text) == [
        ("canopen.node[0].tpdo[0].number", "expected an integer from 1 to 512 (got 0)"),
        ("canopen.node[0].rpdo[0].number", "expected an integer from 1 to 512 (got 513)")]
    # unique per direction per node: TPDO1 and RPDO1 are two PDOs, and so are two nodes' TPDO1
    second = NODE.replace('"motor"', '"pump"').replace("40", "41")
    cfg = load(tmp_path, plant("", "", pdo("tpdo", 1, ("2004:06", "%IW0")), pdo("rpdo", 1, ("2008:05", "%QW0")),
                               second, pdo("tpdo", 1, ("2004:06", "%IW1"))))
    assert [len(n.tpdo) for n in cfg.canopen.nodes] == [1, 1]
    text = plant("", "", pdo("tpdo", 1, ("2004:06", "%IW0")), pdo("tpdo", 1, ("2004:07", "%IW1")))
    assert error(tmp_path, text) == \
        ("canopen.node[0].tpdo[1].number", "duplicate TPDO number 1 (canopen.node[0].tpdo[0] has it)")


def test_pdo_carries_eight_bytes(tmp_path):
    nine = [(f"2004:{k:02X}", f"%IB{k}") for k in range(9)]
    eight_words = [(f"2004:{k:02X}", f"%IW{k}") for k in range(5)]
    assert error(tmp_path, plant("", "", pdo("tpdo", 1, *nine))) == \
        ("canopen.node[0].tpdo[0].map", 'expected an array of 1 to 8 { object = "2004:06", address = "%IW0" } '
                                        "tables; a PDO carries 8 bytes (got 9 entries)")
    assert load(tmp_path, plant("", "", pdo("tpdo", 1, *nine[:8]))).canopen.nodes[0].tpdo[0].entries[7].key == \
        "canopen.node[0].tpdo[0].map[7]"
    assert error(tmp_path, plant("", "", pdo("tpdo", 1, *eight_words))) == \
        ("canopen.node[0].tpdo[0].map", "the addresses hold 80 bits; a PDO carries at most 64 (8 bytes)")
    assert error(tmp_path, plant("", "", pdo("tpdo", 1))) == \
        ("canopen.node[0].tpdo[0].map", 'expected an array of 1 to 8 { object = "2004:06", address = "%IW0" } '
                                        "tables; a PDO carries 8 bytes (got an empty array)")


def test_pdo_bit_addresses(tmp_path):
    cfg = load(tmp_path, plant("", "", pdo("tpdo", 1, ("2004:06", "%IX0.0"), ("2004:07", "%IX0.1"),
                                           ("2004:08", "%IB1"))))
    assert [e.address for e in cfg.canopen.nodes[0].tpdo[0].entries] == \
        [addr("%IX0.0"), addr("%IX0.1"), addr("%IB1")]
    cfg = load(tmp_path, plant("", "", pdo("rpdo", 1, ("2008:05", "%QW3:X2"), ("2008:06", "%QW3:X3"),
                                           ("2008:07", "%QW4"))).replace(PLC, PLC + 'profile = "schneider"\n'))
    assert [e.address.text for e in cfg.canopen.nodes[0].rpdo[0].entries] == ["%QW3:X2", "%QW3:X3", "%QW4"]


@pytest.mark.parametrize("direction, address, message", [
    ("tpdo", "%QW0", "expected a %I address: a TPDO's entries go to %I inputs (got '%QW0', an output)"),
    ("tpdo", "%MW0", "expected a %I address: a TPDO's entries go to %I inputs (got '%MW0', a memory address)"),
    ("rpdo", "%IW0", "expected a %Q address: an RPDO's entries come from %Q outputs (got '%IW0', an input)"),
    ("tpdo", "IW0", "expected a direct address such as %IW0, %IX0.0 (got 'IW0')"),
    ("rpdo", "%QX0.8", "bit number 8 is not 0..7"),
    ("tpdo", "%IW40000", "%IW40000 (bytes 80000..80001) is outside the 65536-byte %I area"),
    ("tpdo", "%IX70000.0", "'%IX70000.0' is outside the 65536-byte %I area"),
])
def test_pdo_addresses_refused(tmp_path, direction, address, message):
    obj = "2004:06" if direction == "tpdo" else "2008:05"
    assert error(tmp_path, plant("", "", pdo(direction, 1, (obj, address)))) == \
        (f"canopen.node[0].{direction}[0].map[0].address", message)


def test_pdo_word_tables_refused(tmp_path):
    text = plant("", "", pdo("tpdo", 1, ("2004:06", "%IW3:4"))).replace(PLC, PLC + 'profile = "schneider"\n')
    assert error(tmp_path, text) == \
        ("canopen.node[0].tpdo[0].map[0].address", "expected a bit, byte, word, dword or lword address (got "
                                                   "'%IW3:4', a word table): map one object per address")


def test_pdo_entries_may_not_overlap(tmp_path):
    key = "canopen.node[0].tpdo[0].map"
    assert error(tmp_path, plant("", "", pdo("tpdo", 1, ("2004:06", "%IW0"), ("2004:07", "%IB1")))) == \
        (f"{key}[1].address", f"'%IB1' overlaps {key}[0].address ('%IW0')")
    assert error(tmp_path, plant("", "", pdo("tpdo", 1, ("2004:06", "%IX1.3"), ("2004:07", "%IW0")))) == \
        (f"{key}[1].address", f"'%IW0' overlaps {key}[0].address ('%IX1.3')")
    assert error(tmp_path, plant("", "", pdo("tpdo", 1, ("2004:06", "%ID1"), ("2004:07", "%IW3")))) == \
        (f"{key}[1].address", f"'%IW3' overlaps {key}[0].address ('%ID1')")     # %ID1 = bytes 4-7, %IW3 = 6-7
    # neighbours do not overlap, and %I and %Q are different areas
    cfg = load(tmp_path, plant("", "", pdo("tpdo", 1, ("2004:06", "%IW0"), ("2004:07", "%IB2"),
                                           ("2004:08", "%IX3.0"), ("2004:09", "%IX3.1")),
                               pdo("rpdo", 1, ("2008:05", "%QW0"))))
    assert len(cfg.canopen.nodes[0].tpdo[0].entries) == 4


def test_pdos_may_not_overlap_each_other(tmp_path):
    second = NODE.replace('"motor"', '"pump"').replace("40", "41")
    text = plant("", "", pdo("tpdo", 1, ("2004:06", "%IW100")), pdo("rpdo", 1, ("2008:05", "%QW100")),
                 second, pdo("tpdo", 1, ("2004:06", "%IB201")), pdo("rpdo", 1, ("2008:05", "%QD50")))
    assert errors(tmp_path, text) == [
        ("canopen.node[1].tpdo[0].map[0].address",
         "'%IB201' overlaps canopen.node[0].tpdo[0].map[0].address ('%IW100')"),
        ("canopen.node[1].rpdo[0].map[0].address",
         "'%QD50' overlaps canopen.node[0].rpdo[0].map[0].address ('%QW100')")]


def test_pdos_may_not_overlap_a_loopback_target(tmp_path):
    loopback = '[[loopback]]\nfrom = "%QB0"\nto = "%IB10"\nbytes = 4\n'
    assert error(tmp_path, plant("", "", pdo("tpdo", 1, ("2004:06", "%IW6")), loopback)) == \
        ("canopen.node[0].tpdo[0].map[0].address", "'%IW6' overlaps loopback[0].to ('%IB10', 4 bytes)")
    # %IW7 (bytes 14-15) is past the link's bytes 10-13; an RPDO may read what a link reads
    cfg = load(tmp_path, plant("", "", pdo("tpdo", 1, ("2004:06", "%IW7")), pdo("rpdo", 1, ("2008:05", "%QW0")),
                               loopback))
    assert cfg.loopback[0].nbytes == 4 and len(cfg.canopen.nodes[0].tpdo) == 1


def test_pdo_entry_errors(tmp_path):
    assert errors(tmp_path, plant("", "", pdo("tpdo", 1).replace("map = []", 'map = [{ object = "2004:06" }, '
                                                                  '{ address = "%IW0", obj = 1 }, 3]'))) == [
        ("canopen.node[0].tpdo[0].map[0].address", 'required key missing (expected an image address such as '
                                                   '"%IW0" for a TPDO, "%QW0" for an RPDO)'),
        ("canopen.node[0].tpdo[0].map[1].object", 'required key missing (expected an object "index:subindex" '
                                                  'in hex, such as "2004:06")'),
        ("canopen.node[0].tpdo[0].map[1].obj", "unknown key (did you mean 'object'?)"),
        ("canopen.node[0].tpdo[0].map[2]", "expected a table (got 3)")]


# ---------------------------------------------------------------- [[sim]]


def test_sims(tmp_path):
    cfg = load(tmp_path, PLC + CAN + '[[sim]]\ntype = "LTMR"\nnode_id = 40\n'
                                     'registers = { "682" = 2, "0652" = 50 }\n'
                                     '[[sim]]\ntype = "ltmr"\nname = "spare"\nbus = "can0"\nnode_id = 41\n')
    assert cfg.sims == [SimConfig("ltmr", "ltmr40", "can0", 40, {682: 2, 652: 50}, "sim[0]"),
                        SimConfig("ltmr", "spare", "can0", 41, {}, "sim[1]")]
    assert cfg.canopen is None      # a simulator needs no master in this PLC


def test_sim_is_the_canopen_node(tmp_path):
    """A simulator may have the node id of a [[canopen.node]]: it is that node."""
    cfg = load(tmp_path, plant("", "", SIM))
    assert cfg.sims[0].node_id == cfg.canopen.nodes[0].node_id == 40


def test_sim_node_ids(tmp_path):
    other = '[[can]]\nname = "can1"\ninterface = "virtual"\nchannel = "b"\n'
    assert error(tmp_path, PLC + CAN + SIM + SIM + 'name = "second"\n') == \
        ("sim[1].node_id", "duplicate node id 40 on bus 'can0' (sim[0] has it)")
    cfg = load(tmp_path, PLC + CAN + other + SIM + 'bus = "can0"\n' + SIM + 'bus = "can1"\nname = "other"\n')
    assert [(s.bus, s.node_id) for s in cfg.sims] == [("can0", 40), ("can1", 40)]
    assert error(tmp_path, plant("", "", SIM.replace("40", "127"))) == \
        ("sim[0].node_id", "127 is the CANopen master's own node id on bus 'can0' (canopen.node_id)")
    assert errors(tmp_path, PLC + CAN + '[[sim]]\ntype = "fc281"\nnode_id = 0\n[[sim]]\nnode_id = 2\n') == [
        ("sim[0].type", "expected one of 'ltmr', 'da1', 'db1', 'dc1', 'de1', 'de11' (got 'fc281')"),
        ("sim[0].node_id", "expected an integer from 1 to 127 (got 0)"),
        ("sim[1].type", "required key missing (expected 'ltmr', 'da1', 'db1', 'dc1', 'de1' or 'de11')")]


def test_sim_names(tmp_path):
    other = '[[can]]\nname = "can1"\ninterface = "virtual"\nchannel = "b"\n'
    assert error(tmp_path, PLC + CAN + other + SIM + 'bus = "can0"\n' + SIM + 'bus = "can1"\n') == \
        ("sim[1]", "duplicate simulator name 'ltmr40', the default <type><node_id> (sim[0] has it): give one "
                   "a name")
    assert error(tmp_path, PLC + CAN + SIM + 'name = "A"\n' + SIM.replace("40", "41") + 'name = "a"\n') == \
        ("sim[1].name", "duplicate simulator name 'a' (sim[0] has it; names are case-insensitive)")
    assert error(tmp_path, PLC + CAN + SIM + 'name = "ltmr 40"\n') == \
        ("sim[0].name", "expected a simulator name: an IEC identifier (letters, digits, _; not starting with a "
                        "digit) (got 'ltmr 40')")


def test_sim_registers(tmp_path):
    assert errors(tmp_path, PLC + CAN + SIM + 'registers = { "682" = 70000, "abc" = 1, "70000" = 1, "7" = -1, '
                                              '"8" = true }\n') == [
        ('sim[0].registers.682', "expected an integer from 0 to 65535 (got 70000)"),
        ('sim[0].registers.7', "expected an integer from 0 to 65535 (got -1)"),
        ('sim[0].registers.8', "expected an integer from 0 to 65535 (got true)"),
        ('sim[0].registers.abc', "expected a register number from 0 to 65535 in decimal, such as \"682\" "
                                 "(got 'abc')"),
        ('sim[0].registers.70000', "expected a register number from 0 to 65535 in decimal, such as \"682\" "
                                   "(got '70000')")]
    assert error(tmp_path, PLC + CAN + SIM + "registers = [682, 2]\n") == \
        ("sim[0].registers", 'expected a table of register = value, such as { "682" = 2 } (got an array)')


def test_can_sections_errors_reported_together(tmp_path):
    path = write(tmp_path, PLC + '[[can]]\ninterface = "virtual"\nchannel = "a"\nbitrate = 1\n'
                                 '[canopen]\nnode_id = 40\nheartbeat = "0ms"\n'
                                 + NODE + 'master_timeout = "1s"\n'
                                 + pdo("tpdo", 1, ("2004:06", "%QW0"), ("20x4:06", "%IW0"))
                                 + SIM.replace("40", "0"))
    with pytest.raises(ConfigError) as info:
        load_config(path)
    assert str(info.value).splitlines() == [
        f"{path}: can[0].bitrate: expected one of the CANopen bitrates 10000, 20000, 50000, 125000, 250000, "
        "500000, 800000, 1000000 (got 1)",
        f"{path}: canopen.node[0].id: 40 is the master's own node id (canopen.node_id)",
        f"{path}: canopen.node[0].master_timeout: only meaningful when the master sends a heartbeat "
        "(canopen.heartbeat = '0ms')",
        f"{path}: canopen.node[0].tpdo[0].map[0].address: expected a %I address: a TPDO's entries go to %I "
        "inputs (got '%QW0', an output)",
        f'{path}: canopen.node[0].tpdo[0].map[1].object: expected an object "index:subindex" in hex, such as '
        "\"2004:06\" (got '20x4:06')",
        f"{path}: sim[0].node_id: expected an integer from 1 to 127 (got 0)",
    ]


# ====================================================================== all at once


def test_several_errors_reported_together(tmp_path):
    path = write(tmp_path, """\
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
        """)
    with pytest.raises(ConfigError) as info:
        load_config(path)
    assert str(info.value).splitlines() == [
        f"{path}: plc.profile: expected one of 'iec', 'codesys', 'twincat', 'schneider' (got 'siemens')",
        f"{path}: plc.programs[1]: no such file: {tmp_path / 'gone.st'} (relative paths start at the "
        "config file's directory)",
        f"{path}: task[0].interval: expected a duration such as 10ms, 1s, T#250ms (got '10 parsecs')",
        f"{path}: task[0].priority: expected an integer from 0 to 31 (got 99)",
        f"{path}: task[1].name: duplicate task name 'fast' (task[0] has it; names are case-insensitive)",
        f"{path}: task[1].programs[0]: duplicate program instance 'Main' (also at task[0].programs[0]; "
        "instance names are unique across tasks, case-insensitive); give one its own instance name: "
        '{ instance = "Main2", program = "Main" }',
        f'{path}: outputs.safe."%IX0.0": expected a %Q output address (got \'%IX0.0\', an input)',
        f'{path}: outputs.safe."%QW2": expected an integer for a word address (got true)',
        f"{path}: canopen: the CANopen master needs a [[can]] bus (the file has none): add a [[can]] "
        "table with interface and channel",
    ]


# ====================================================================== config_from_dict, ConfigError


def test_config_from_dict(tmp_path):
    (tmp_path / "main.st").write_text(PROG)
    data = {"plc": {"programs": ["main.st"]}, "task": [{"name": "T", "interval": 5, "programs": ["Main"]}]}
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


# ====================================================================== [[modbus]], [[modbus.channel]]
#
# Modbus over serial line / TCP: unit ids 1..247, 0 the broadcast (serial
# line 2.2); a PDU carries at most 2000 bits (01/02), 1968 bits (15),
# 125 registers (03/04/23 read), 123 registers (16), 121 registers (23
# write). The simulated Eaton drives of [[sim]] sit on an RTU line with
# device = "sim" or behind 127.0.0.1.

from softplc.runtime.config import ModbusChannelConfig, ModbusConnectionConfig  # noqa: E402

RTU = '[[modbus]]\nname = "drives"\ntransport = "rtu"\ndevice = "sim"\n'
TCP = '[[modbus]]\nname = "gateway"\ntransport = "tcp"\n'
READ = '[[modbus.channel]]\nunit = 1\nfunction = 3\noffset = 5\ncount = 5\nread_to = "%IW200"\n'
DA1 = '[[sim]]\ntype = "da1"\nunit = 1\n'
DEVICE = 'a serial port such as "/dev/ttyUSB0", or "sim" for the simulated drives of [[sim]]'
ONLY_TCP = "only for transport = 'tcp' (this connection is 'rtu')"
ONLY_RTU = "only for transport = 'rtu' (this connection is 'tcp')"
ONLY_CAN = "only for a CAN device; a Modbus device has modbus and unit"
CH = "modbus[0].channel[0]"


def channel(function, body: str = "", unit: int = 1, offset: int = 0) -> str:
    return f"[[modbus.channel]]\nunit = {unit}\nfunction = {function}\noffset = {offset}\n{body}"


def connection(name: str = "drives", transport: str = "rtu", device: str = "sim", host: str = "127.0.0.1",
               port: int = 502, baud: int = 19200, timeout_ms: int = 200, retries: int = 1,
               reconnect_ms: int = 1000, channels: tuple = (), key: str = "modbus[0]",
               **serial) -> ModbusConnectionConfig:
    """A ModbusConnectionConfig with the defaults of the file format."""
    settings = dict(parity="N", stop_bits=1, data_bits=8, frame_gap_us=None) | serial
    return ModbusConnectionConfig(
        name=name, transport=transport, device=device, baud=baud, host=host, port=port,
        timeout_ms=timeout_ms, retries=retries, reconnect_ms=reconnect_ms, reconnect_max_ms=10_000,
        channels=list(channels), key=key, **settings)


def read_channel(name: str, connection: str = "drives", key: str = CH, unit: int = 1, function: int = 3,
                 offset: int = 5, count: int = 5, read_to: str = "%IW200", **more) -> ModbusChannelConfig:
    values = dict(write_offset=0, write_count=0, write_from=None, trigger="cyclic", period_ns=100 * MS,
                  edge=None) | more
    return ModbusChannelConfig(name=name, connection=connection, unit=unit, function=function, offset=offset,
                               count=count, read_to=addr(read_to) if read_to else None, key=key, **values)


def test_example_modbus_rtu():
    cfg = load_config(EXAMPLES / "modbus_rtu.toml")
    assert cfg.programs == [ST / "eaton_drive.st"]
    assert [(t.name, t.interval_ns, t.programs[0].instance) for t in cfg.tasks] == [("DriveTask", 10 * MS, "Drive")]
    assert cfg.modbus == [ModbusConnectionConfig(
        name="drives", transport="rtu", device="sim", baud=115200, parity="N", stop_bits=1, data_bits=8,
        frame_gap_us=None, host="127.0.0.1", port=502, timeout_ms=100, retries=1, reconnect_ms=1000,
        reconnect_max_ms=10_000, key="modbus[0]", channels=[ModbusChannelConfig(
            name="drive_monitor", connection="drives", unit=1, function=3, offset=5, count=5, write_offset=0,
            write_count=0, read_to=addr("%IW200"), write_from=None, trigger="cyclic", period_ns=100 * MS,
            edge=None, key="modbus[0].channel[0]")])]
    assert cfg.sims == [SimConfig("da1", "da1_1", None, None, {505: 20}, "sim[0]", modbus="drives", unit=1)]
    assert (cfg.can, cfg.canopen) == ([], None)


def test_example_modbus_tcp():
    cfg = load_config(EXAMPLES / "modbus_tcp.toml")
    assert cfg.programs == [ST / "eaton_drive.st"]
    # a TCP connection carries the serial defaults too; nothing uses them
    assert cfg.modbus == [ModbusConnectionConfig(
        name="drives", transport="tcp", device="", baud=19200, parity="N", stop_bits=1, data_bits=8,
        frame_gap_us=None, host="127.0.0.1", port=0, timeout_ms=200, retries=0, reconnect_ms=500,
        reconnect_max_ms=10_000, key="modbus[0]", channels=[ModbusChannelConfig(
            name="drive_monitor", connection="drives", unit=1, function=3, offset=5, count=5, write_offset=0,
            write_count=0, read_to=addr("%IW200"), write_from=None, trigger="cyclic", period_ns=100 * MS,
            edge=None, key="modbus[0].channel[0]")])]
    assert cfg.sims == [SimConfig("dc1", "dc1_1", None, None, {}, "sim[0]", modbus="drives", unit=1)]


def test_file_without_modbus_sections(tmp_path):
    assert load(tmp_path, PLC).modbus == []


def test_modbus_rtu_defaults(tmp_path):
    cfg = load(tmp_path, PLC + '[[modbus]]\ntransport = "rtu"\ndevice = "/dev/ttyUSB0"\n')
    assert cfg.modbus == [connection("modbus0", device="/dev/ttyUSB0")]
    assert (cfg.modbus[0].baud, cfg.modbus[0].parity, cfg.modbus[0].stop_bits) == (19200, "N", 1)
    assert (cfg.modbus[0].timeout_ms, cfg.modbus[0].retries) == (200, 1)
    assert (cfg.modbus[0].reconnect_ms, cfg.modbus[0].reconnect_max_ms) == (1000, 10_000)


def test_modbus_tcp_defaults(tmp_path):
    cfg = load(tmp_path, PLC + '[[modbus]]\ntransport = "tcp"\n')
    assert cfg.modbus == [connection("modbus0", "tcp", device="")]
    assert (cfg.modbus[0].host, cfg.modbus[0].port) == ("127.0.0.1", 502)


def test_modbus_settings(tmp_path):
    cfg = load(tmp_path, PLC + '[[modbus]]\nname = "Line"\ntransport = "RTU"\ndevice = "/dev/ttyS1"\n'
                               'baud = 9600\nparity = "e"\nstop_bits = 2\ndata_bits = 7\nframe_gap = "2ms"\n'
                               'timeout = "T#1s"\nretries = 10\nreconnect = 250\nreconnect_max = "1m"\n'
                               '[[modbus]]\nname = "gw"\ntransport = "Tcp"\nhost = "192.168.0.20"\n'
                               'port = 5020\nretries = 0\n')
    assert cfg.modbus == [
        ModbusConnectionConfig("Line", "rtu", "/dev/ttyS1", 9600, "E", 2, 7, 2000, "127.0.0.1", 502, 1000, 10,
                               250, 60_000, [], "modbus[0]"),
        connection("gw", "tcp", device="", host="192.168.0.20", port=5020, retries=0, key="modbus[1]")]


def test_modbus_channels(tmp_path):
    cfg = load(tmp_path, PLC + RTU + READ
               + channel(16, 'name = "Setpoints"\ncount = 2\nwrite_from = "%QW10"\ntrigger = "CHANGE"\n'
                             'period = "1s"\n', unit=0, offset=1)
               + channel(23, 'write_offset = 0\nwrite_count = 2\nread_to = "%MW4"\nwrite_from = "%MW0"\n'
                             'count = 6\ntrigger = "edge"\nedge = "%QX0.0"\n', unit=247)
               + channel(1, 'count = 16\nread_to = "%IB0"\n', unit=2)
               + channel(5, 'write_from = "%QB7"\ntrigger = "edge"\nedge = "%MX1.7"\n')
               + TCP + READ)
    assert cfg.modbus == [
        connection(channels=[
            read_channel("drives_0"),
            ModbusChannelConfig("Setpoints", "drives", 0, 16, 1, 2, 0, 0, None, addr("%QW10"), "change",
                                1000 * MS, None, "modbus[0].channel[1]"),
            ModbusChannelConfig("drives_2", "drives", 247, 23, 0, 6, 0, 2, addr("%MW4"), addr("%MW0"), "edge",
                                100 * MS, addr("%QX0.0"), "modbus[0].channel[2]"),
            read_channel("drives_3", key="modbus[0].channel[3]", unit=2, function=1, offset=0, count=16,
                         read_to="%IB0"),
            ModbusChannelConfig("drives_4", "drives", 1, 5, 0, 1, 0, 0, None, addr("%QB7"), "edge", 100 * MS,
                                addr("%MX1.7"), "modbus[0].channel[4]")]),
        connection("gateway", "tcp", device="", key="modbus[1]",
                   channels=[read_channel("gateway_0", "gateway", "modbus[1].channel[0]")])]


def test_modbus_section_shapes(tmp_path):
    assert error(tmp_path, PLC + '[modbus]\ntransport = "tcp"\n') == \
        ("modbus", "expected [[modbus]] tables (got a table)")
    assert error(tmp_path, PLC + TCP + 'hots = "x"\n') == ("modbus[0].hots", "unknown key (did you mean 'host'?)")
    assert errors(tmp_path, PLC + TCP + '[[modbus.channel]]\nname = "1st"\nperiod = "0ms"\ncount = 0\n') == [
        (f"{CH}.name", "expected a channel name: an IEC identifier (letters, digits, _; not starting with a "
                       "digit) (got '1st')"),
        (f"{CH}.unit", "required key missing (expected a unit id from 1 to 247 (0: broadcast write))"),
        (f"{CH}.function", "required key missing (expected a function code: 1, 2, 3, 4, 5, 6, 15, 16, 23)"),
        (f"{CH}.offset", "required key missing (expected a PDU address from 0 to 65535 (Eaton ID n is offset "
                         "n-1))"),
        (f"{CH}.count", "expected an integer from 1 to 2000 (got 0)"),
        (f"{CH}.period", "expected a duration > 0 such as 10ms, 1s, T#250ms (got '0ms')")]


def test_modbus_transport(tmp_path):
    assert error(tmp_path, PLC + '[[modbus]]\ndevice = "sim"\n') == \
        ("modbus[0].transport", "required key missing (expected 'rtu' or 'tcp')")
    assert error(tmp_path, PLC + '[[modbus]]\ntransport = "udp"\n') == \
        ("modbus[0].transport", "expected one of 'rtu', 'tcp' (got 'udp')")
    assert error(tmp_path, PLC + '[[modbus]]\ntransport = "tpc"\n') == \
        ("modbus[0].transport", "expected one of 'rtu', 'tcp' (got 'tpc'; did you mean 'tcp'?)")
    assert error(tmp_path, PLC + '[[modbus]]\ntransport = 1\n') == \
        ("modbus[0].transport", "expected one of 'rtu', 'tcp' (got 1)")


def test_modbus_rtu_needs_a_device(tmp_path):
    assert error(tmp_path, PLC + '[[modbus]]\ntransport = "rtu"\n') == \
        ("modbus[0]", f"required key missing: device ({DEVICE})")
    assert error(tmp_path, PLC + '[[modbus]]\ntransport = "rtu"\ndevice = ""\n') == \
        ("modbus[0].device", f"expected {DEVICE} (got '')")


def test_modbus_keys_of_the_other_transport(tmp_path):
    assert errors(tmp_path, PLC + RTU + 'host = "192.168.0.20"\nport = 502\n') == [
        ("modbus[0].host", ONLY_TCP), ("modbus[0].port", ONLY_TCP)]
    assert errors(tmp_path, PLC + TCP + 'device = "sim"\nbaud = 9600\nparity = "E"\nstop_bits = 1\n'
                                        'data_bits = 8\nframe_gap = "2ms"\n') == [
        ("modbus[0].device", ONLY_RTU), ("modbus[0].baud", ONLY_RTU), ("modbus[0].parity", ONLY_RTU),
        ("modbus[0].stop_bits", ONLY_RTU), ("modbus[0].data_bits", ONLY_RTU), ("modbus[0].frame_gap", ONLY_RTU)]


def test_modbus_serial_values_refused(tmp_path):
    assert errors(tmp_path, PLC + RTU + 'baud = 12345\nparity = "X"\nstop_bits = 3\ndata_bits = 9\n'
                                        'frame_gap = "2s"\n') == [
        ("modbus[0].baud", "expected one of 1200, 2400, 4800, 9600, 19200, 38400, 57600, 115200 (got 12345)"),
        ("modbus[0].parity", "expected one of 'N', 'E', 'O' (got 'X')"),
        ("modbus[0].stop_bits", "expected one of 1, 2 (got 3)"),
        ("modbus[0].data_bits", "expected one of 7, 8 (got 9)"),
        ("modbus[0].frame_gap", "expected a duration of at most 1000000us (at most 1s) (got '2s')")]
    assert errors(tmp_path, PLC + TCP + 'port = 70000\nretries = 11\nhost = ""\n') == [
        ("modbus[0].host", "expected a host such as \"192.168.0.20\" (got '')"),
        ("modbus[0].port", "expected an integer from 0 to 65535 (got 70000)"),
        ("modbus[0].retries", "expected an integer from 0 to 10 (got 11)")]


def test_duplicate_connection_names(tmp_path):
    assert error(tmp_path, PLC + RTU + TCP.replace('"gateway"', '"DRIVES"')) == \
        ("modbus[1].name", "duplicate connection name 'DRIVES' (modbus[0] has it; names are case-insensitive)")
    assert error(tmp_path, PLC + '[[modbus]]\ntransport = "tcp"\n[[modbus]]\ntransport = "tcp"\n') == \
        ("modbus[1]", "duplicate connection name 'modbus0' (modbus[0] has it; names are case-insensitive): "
                      "give each [[modbus]] a name")


def test_duplicate_channel_names(tmp_path):
    assert error(tmp_path, PLC + RTU + READ + 'name = "monitor"\n' + READ + 'name = "Monitor"\n') == \
        ("modbus[0].channel[1].name", "duplicate channel name 'Monitor' (channel[0] has it; "
         "names are case-insensitive)")
    # channel names are per connection
    cfg = load(tmp_path, PLC + RTU + READ + 'name = "monitor"\n' + TCP + READ + 'name = "monitor"\n')
    assert [[c.name for c in m.channels] for m in cfg.modbus] == [["monitor"], ["monitor"]]


def test_modbus_function_codes(tmp_path):
    assert error(tmp_path, PLC + RTU + channel(7)) == \
        (f"{CH}.function", "expected one of 1, 2, 3, 4, 5, 6, 15, 16, 23 (got 7)")
    assert error(tmp_path, PLC + RTU + channel("true")) == \
        (f"{CH}.function", "expected one of 1, 2, 3, 4, 5, 6, 15, 16, 23 (got true)")


@pytest.mark.parametrize("function, body, message", [
    (3, 'count = 126\nread_to = "%IW0"\n', "function 3 carries at most 125 registers (got 126)"),
    (4, 'count = 126\nread_to = "%IW0"\n', "function 4 carries at most 125 registers (got 126)"),
    (16, 'count = 124\nwrite_from = "%QW0"\n', "function 16 carries at most 123 registers (got 124)"),
    (15, 'count = 1969\nwrite_from = "%QB0"\n', "function 15 carries at most 1968 bits (got 1969)"),
    (6, 'count = 2\nwrite_from = "%QW0"\n', "function 6 carries at most 1 register (got 2)"),
    (5, 'count = 2\nwrite_from = "%QB0"\n', "function 5 carries at most 1 bit (got 2)"),
    (23, 'count = 126\nread_to = "%IW0"\nwrite_from = "%QW0"\nwrite_offset = 0\nwrite_count = 1\n',
     "function 23 carries at most 125 registers (got 126)"),
    # beyond what any function carries: pass 1 says so, once
    (1, 'count = 2001\nread_to = "%IB0"\n', "expected an integer from 1 to 2000 (got 2001)"),
])
def test_modbus_count_limits(tmp_path, function, body, message):
    assert error(tmp_path, PLC + RTU + channel(function, body)) == (f"{CH}.count", message)


@pytest.mark.parametrize("function, body", [
    (3, 'count = 125\nread_to = "%IW0"\n'), (1, 'count = 2000\nread_to = "%IB0"\n'),
    (16, 'count = 123\nwrite_from = "%QW0"\n'), (15, 'count = 1968\nwrite_from = "%QB0"\n'),
    (23, 'count = 125\nread_to = "%IW0"\nwrite_from = "%QW0"\nwrite_offset = 0\nwrite_count = 121\n')])
def test_modbus_count_limits_accepted(tmp_path, function, body):
    assert load(tmp_path, PLC + RTU + channel(function, body)).modbus[0].channels[0].function == function


def test_function_23_write_block(tmp_path):
    rw = 'read_to = "%IW0"\nwrite_from = "%QW0"\n'
    assert errors(tmp_path, PLC + RTU + channel(23, rw)) == [
        (CH, "required key missing: write_offset (function 23 writes and reads)"),
        (CH, "required key missing: write_count (function 23 writes and reads)")]
    assert error(tmp_path, PLC + RTU + channel(23, rw + "write_offset = 0\nwrite_count = 122\n")) == \
        (f"{CH}.write_count", "expected an integer from 1 to 121 (got 122)")
    assert errors(tmp_path, PLC + RTU + READ + "write_offset = 1\nwrite_count = 1\n") == [
        (f"{CH}.write_offset", "only for function 23 (offset and count give the block)"),
        (f"{CH}.write_count", "only for function 23 (offset and count give the block)")]


def test_channel_read_to(tmp_path):
    assert error(tmp_path, PLC + RTU + channel(3)) == \
        (CH, "required key missing: read_to (the image address the channel reads into)")
    assert error(tmp_path, PLC + RTU + channel(3, 'read_to = "%QW0"\n')) == \
        (f"{CH}.read_to", "expected an address in %I or %M (got '%QW0', an output)")
    assert error(tmp_path, PLC + RTU + channel(3, 'read_to = "IW0"\n')) == \
        (f"{CH}.read_to", "expected a direct address such as %IW100, %MW20 (got 'IW0')")
    assert error(tmp_path, PLC + RTU + channel(3, "read_to = 200\n")) == \
        (f"{CH}.read_to", "expected a direct address such as %IW100, %MW20 (got 200)")
    assert error(tmp_path, PLC + RTU + READ + 'write_from = "%QW0"\n') == \
        (f"{CH}.write_from", "function 3 does not use write_from")


def test_channel_write_from(tmp_path):
    assert error(tmp_path, PLC + RTU + channel(6)) == \
        (CH, "required key missing: write_from (the image address the channel writes from)")
    assert error(tmp_path, PLC + RTU + channel(6, 'write_from = "%IW0"\n')) == \
        (f"{CH}.write_from", "expected an address in %Q or %M (got '%IW0', an input)")
    assert error(tmp_path, PLC + RTU + channel(16, 'write_from = "%QW0"\nread_to = "%IW0"\n')) == \
        (f"{CH}.read_to", "function 16 does not use read_to")


def test_channel_triggers(tmp_path):
    assert error(tmp_path, PLC + RTU + READ + 'trigger = "change"\n') == \
        (f"{CH}.trigger", "'change' watches the data to write; function 3 only reads (use 'cyclic' or 'edge')")
    assert error(tmp_path, PLC + RTU + READ + 'trigger = "edge"\n') == \
        (CH, 'required key missing: edge (the BOOL whose rising edge triggers, such as "%QX10.0")')
    assert error(tmp_path, PLC + RTU + READ + 'trigger = "edge"\nedge = "%QW10"\n') == \
        (f"{CH}.edge", "expected a BOOL (bit) address such as %QX10.0 (got '%QW10')")
    assert error(tmp_path, PLC + RTU + READ + 'trigger = "edge"\nedge = true\n') == \
        (f"{CH}.edge", "expected a direct address such as %QX10.0, %MX2.0 (got true)")
    assert error(tmp_path, PLC + RTU + READ + 'edge = "%QX10.0"\n') == (f"{CH}.edge", "only for trigger = 'edge'")
    assert error(tmp_path, PLC + RTU + READ + 'trigger = "cyclic"\nedge = "%QX10.0"\n') == \
        (f"{CH}.edge", "only for trigger = 'edge'")
    assert error(tmp_path, PLC + RTU + READ + 'trigger = "rising"\n') == \
        (f"{CH}.trigger", "expected one of 'cyclic', 'change', 'edge' (got 'rising')")
    cfg = load(tmp_path, PLC + RTU + READ + 'trigger = "edge"\nedge = "%IX3.1"\n')
    assert (cfg.modbus[0].channels[0].trigger, cfg.modbus[0].channels[0].edge) == ("edge", addr("%IX3.1"))


def test_channel_unit_0_is_for_writes(tmp_path):
    assert error(tmp_path, PLC + RTU + READ.replace("unit = 1", "unit = 0")) == \
        (f"{CH}.unit", "unit 0 is the broadcast address: nobody answers, so only writes can go to it")
    assert error(tmp_path, PLC + RTU + channel(23, 'read_to = "%IW0"\nwrite_from = "%QW0"\nwrite_offset = 0\n'
                                                   'write_count = 1\n', unit=0)) == \
        (f"{CH}.unit", "unit 0 is the broadcast address: nobody answers, so only writes can go to it")
    assert error(tmp_path, PLC + RTU + READ.replace("unit = 1", "unit = 248")) == \
        (f"{CH}.unit", "expected an integer from 0 to 247 (got 248)")
    cfg = load(tmp_path, PLC + RTU + channel(6, 'write_from = "%QW0"\n', unit=0))
    assert cfg.modbus[0].channels[0].unit == 0


def test_channel_inside_the_image(tmp_path):
    assert error(tmp_path, PLC + RTU + READ.replace("%IW200", "%IW32767").replace("count = 5", "count = 10")) == \
        (f"{CH}.read_to", "10 registers from %IW32767 run past the end of the %I area")
    assert error(tmp_path, PLC + RTU + channel(15, 'count = 16\nwrite_from = "%QB65535"\n')) == \
        (f"{CH}.write_from", "16 bits from %QB65535 run past the end of the %Q area")
    assert error(tmp_path, PLC + RTU + READ.replace("%IW200", "%IW40000")) == \
        (f"{CH}.read_to", "%IW40000 (bytes 80000..80001) is outside the 65536-byte %I area")
    assert error(tmp_path, PLC + RTU + channel(1, 'count = 8\nread_to = "%IX0.0"\n')) == \
        (f"{CH}.read_to", "%IX0.0 is a bit; drivers copy whole bytes: give the byte or word that holds it "
                          "(e.g. %IB0, %IW0)")
    cfg = load(tmp_path, PLC + RTU + READ.replace("%IW200", "%IW32763") + channel(15, 'count = 8\nwrite_from = '
                                                                                       '"%QB65535"\n'))
    assert [c.read_to or c.write_from for c in cfg.modbus[0].channels] == [addr("%IW32763"), addr("%QB65535")]


def test_modbus_addresses_follow_the_profile(tmp_path):
    from softplc.runtime.image.address import parse_address
    schneider = '[plc]\nprograms = ["main.st"]\nprofile = "schneider"\n'
    cfg = load(tmp_path, schneider + RTU + READ.replace('"%IW200"', '"%MW100"')
               + channel(23, 'count = 2\nread_to = "%MW10:2"\nwrite_from = "%MW20:4"\nwrite_offset = 0\n'
                             'write_count = 4\ntrigger = "edge"\nedge = "%MW30:X3"\n'))
    assert cfg.profile == "schneider"
    first, second = cfg.modbus[0].channels
    assert first.read_to == parse_address("%MW100", "schneider")
    assert (second.read_to, second.write_from, second.edge) == \
        (parse_address("%MW10:2", "schneider"), parse_address("%MW20:4", "schneider"),
         parse_address("%MW30:X3", "schneider"))
    # the same Schneider forms under an IEC profile
    assert errors(tmp_path, PLC + RTU + channel(23, 'count = 2\nread_to = "%MW10:2"\nwrite_from = "%MW20:4"\n'
                                                    'write_offset = 0\nwrite_count = 4\ntrigger = "edge"\n'
                                                    'edge = "%MW30:X3"\n')) == [
        (f"{CH}.read_to", "%MW10:2 is Schneider addressing; use the schneider profile (IEC addresses a bit as "
                          "%MX<byte>.<bit>)"),
        (f"{CH}.write_from", "%MW20:4 is Schneider addressing; use the schneider profile (IEC addresses a bit "
                             "as %MX<byte>.<bit>)"),
        (f"{CH}.edge", "%MW30:X3 is Schneider addressing; use the schneider profile (IEC addresses a bit as "
                       "%MX<byte>.<bit>)")]


# ---------------------------------------------------------------- [[sim]] on [[modbus]]


def test_modbus_sims(tmp_path):
    cfg = load(tmp_path, PLC + CAN + SIM + RTU + TCP.replace('"tcp"\n', '"tcp"\nhost = "localhost"\nport = 0\n')
               + '[[sim]]\ntype = "DA1"\nmodbus = "DRIVES"\nunit = 1\nregisters = { "505" = 20, "0017" = 3 }\n'
               + '[[sim]]\ntype = "de11"\nname = "pump"\nmodbus = "gateway"\nunit = 247\n'
               + '[[sim]]\ntype = "db1"\nmodbus = "gateway"\nunit = 1\n')
    assert cfg.sims == [SimConfig("ltmr", "ltmr40", "can0", 40, {}, "sim[0]"),
                        SimConfig("da1", "da1_1", None, None, {505: 20, 17: 3}, "sim[1]", modbus="drives", unit=1),
                        SimConfig("de11", "pump", None, None, {}, "sim[2]", modbus="gateway", unit=247),
                        SimConfig("db1", "db1_1", None, None, {}, "sim[3]", modbus="gateway", unit=1)]


def test_modbus_sim_on_the_only_connection(tmp_path):
    """Without modbus, a drive is on the file's only [[modbus]] connection."""
    cfg = load(tmp_path, PLC + '[[modbus]]\ntransport = "rtu"\ndevice = "sim"\n' + DA1)
    assert cfg.sims == [SimConfig("da1", "da1_1", None, None, {}, "sim[0]", modbus="modbus0", unit=1)]
    cfg = load(tmp_path, PLC + TCP + DA1)       # host defaults to 127.0.0.1
    assert (cfg.sims[0].modbus, cfg.sims[0].unit) == ("gateway", 1)


def test_modbus_sim_needs_a_unit(tmp_path):
    assert error(tmp_path, PLC + RTU + '[[sim]]\ntype = "da1"\n') == \
        ("sim[0]", "required key missing: unit (the drive's Modbus address)")
    assert error(tmp_path, PLC + RTU + '[[sim]]\ntype = "da1"\nunit = 0\n') == \
        ("sim[0].unit", "expected an integer from 1 to 247 (got 0)")


def test_modbus_sim_refuses_can_keys(tmp_path):
    assert error(tmp_path, PLC + RTU + DA1 + "node_id = 3\n") == ("sim[0].node_id", ONLY_CAN)
    assert errors(tmp_path, PLC + CAN + RTU + DA1 + 'bus = "can0"\nnode_id = 3\n') == [
        ("sim[0].bus", ONLY_CAN), ("sim[0].node_id", ONLY_CAN)]


def test_can_sim_refuses_modbus_keys(tmp_path):
    only_modbus = "only for a Modbus device (da1, db1, dc1, de1, de11); a CAN device has bus and node_id"
    assert errors(tmp_path, PLC + CAN + RTU + SIM + 'modbus = "drives"\nunit = 1\n') == [
        ("sim[0].modbus", only_modbus), ("sim[0].unit", only_modbus)]


def test_modbus_sim_needs_a_simulated_line(tmp_path):
    assert error(tmp_path, PLC + RTU.replace('"sim"', '"/dev/ttyUSB0"') + DA1) == \
        ("sim[0].modbus", 'modbus[0] is a serial line to real devices; a simulated drive needs device = "sim" '
                          "there")
    assert error(tmp_path, PLC + TCP + 'host = "192.168.0.20"\n' + DA1) == \
        ("sim[0].modbus", "modbus[0] goes to 192.168.0.20; a simulated drive listens on 127.0.0.1 only")


def test_modbus_sim_units(tmp_path):
    assert error(tmp_path, PLC + RTU + DA1 + '[[sim]]\ntype = "dc1"\nunit = 1\n') == \
        ("sim[1].unit", "duplicate unit 1 on modbus[0] (sim[0] has it)")
    # one unit per connection: the same unit on another connection is another drive
    cfg = load(tmp_path, PLC + RTU + TCP + DA1 + 'modbus = "drives"\n' + DA1 + 'modbus = "gateway"\nname = "b"\n')
    assert [(s.name, s.modbus, s.unit) for s in cfg.sims] == [("da1_1", "drives", 1), ("b", "gateway", 1)]


def test_modbus_sim_connection(tmp_path):
    assert error(tmp_path, PLC + RTU + TCP + DA1 + 'modbus = "pumps"\n') == \
        ("sim[0].modbus", "expected one of 'drives', 'gateway', the [[modbus]] connections (got 'pumps')")
    assert error(tmp_path, PLC + DA1) == \
        ("sim[0]", "a simulated drive needs a [[modbus]] connection (the file has none)")
    assert error(tmp_path, PLC + RTU + TCP + DA1) == \
        ("sim[0]", "required key missing: modbus (the [[modbus]] connection the drive is on)")
    assert errors(tmp_path, PLC + CAN + DA1 + 'bus = "can0"\n') == [    # a [[can]] bus is no home for a drive
        ("sim[0].bus", ONLY_CAN),
        ("sim[0]", "a simulated drive needs a [[modbus]] connection (the file has none)")]
    assert error(tmp_path, PLC + RTU + DA1 + 'modbus = "2drives"\n') == \
        ("sim[0].modbus", "expected a connection name: an IEC identifier (letters, digits, _; not starting with "
                          "a digit) (got '2drives')")


def test_modbus_sim_names(tmp_path):
    assert error(tmp_path, PLC + RTU + TCP + DA1 + 'modbus = "drives"\n' + DA1 + 'modbus = "gateway"\n') == \
        ("sim[1]", "duplicate simulator name 'da1_1', the default <type>_<unit> (sim[0] has it): give one a name")
    assert error(tmp_path, PLC + CAN + SIM + RTU + DA1 + 'name = "LTMR40"\n') == \
        ("sim[1].name", "duplicate simulator name 'LTMR40' (sim[0] has it; names are case-insensitive)")
    cfg = load(tmp_path, PLC + RTU + DA1 + '[[sim]]\ntype = "da1"\nunit = 2\n')
    assert [s.name for s in cfg.sims] == ["da1_1", "da1_2"]


def test_modbus_sim_registers(tmp_path):
    assert errors(tmp_path, PLC + RTU + DA1 + 'registers = { "505" = 70000, "abc" = 1, "70000" = 1 }\n') == [
        ("sim[0].registers.505", "expected an integer from 0 to 65535 (got 70000)"),
        ("sim[0].registers.abc", "expected a register number from 0 to 65535 in decimal, such as \"682\" "
                                 "(got 'abc')"),
        ("sim[0].registers.70000", "expected a register number from 0 to 65535 in decimal, such as \"682\" "
                                   "(got '70000')")]


def test_modbus_errors_reported_together(tmp_path):
    path = write(tmp_path, PLC + DA1 + 'bus = "can0"\n'
                 + '[[modbus]]\nname = "drives"\ntransport = "rtu"\ndevice = "sim"\nbaud = 12345\n'
                 + READ + 'trigger = "change"\n'
                 + channel(6, 'write_from = "%IW0"\n')
                 + TCP + 'device = "sim"\n')
    with pytest.raises(ConfigError) as info:
        load_config(path)
    assert str(info.value).splitlines() == [
        f"{path}: sim[0].bus: only for a CAN device; a Modbus device has modbus and unit",
        f"{path}: sim[0]: required key missing: modbus (the [[modbus]] connection the drive is on)",
        f"{path}: modbus[0].baud: expected one of 1200, 2400, 4800, 9600, 19200, 38400, 57600, 115200 "
        "(got 12345)",
        f"{path}: modbus[0].channel[0].trigger: 'change' watches the data to write; function 3 only reads "
        "(use 'cyclic' or 'edge')",
        f"{path}: modbus[0].channel[1].write_from: expected an address in %Q or %M (got '%IW0', an input)",
        f"{path}: modbus[1].device: only for transport = 'rtu' (this connection is 'tcp')",
    ]
