"""Single values the configuration refuses with the file and the key rather
than a crash (runtime/config/values.py, load.py): paths the system cannot
use, durations beyond a day, inf and nan, and long values cut in every
message."""

from __future__ import annotations

import os

import pytest

from softplc.runtime.config.values import cut, got

from .support import DURATION, PLC, error, errors, load


def task(body: str) -> str:
    return PLC + "[[task]]\n" + body


TOO_LONG = "a" * 300 + ".st"  # one name beyond NAME_MAX (255): ENAMETOOLONG
LONG_PATH = "/".join(["a" * 250] * 30)  # beyond PATH_MAX (4096)


@pytest.mark.parametrize(
    ("section", "key"),
    [("[plc]\nprograms = [{}]\n", "plc.programs[0]"), (PLC + "[retain]\nfile = {}\n", "retain.file")],
)
@pytest.mark.parametrize("path", [TOO_LONG, LONG_PATH])
def test_a_path_the_system_refuses_is_the_keys_error(tmp_path, section, key, path):
    found_key, message = error(tmp_path, section.format(f'"{path}"'))
    assert found_key == key
    assert message.startswith("file name too long: ")
    assert message.endswith(f"… ({len(str(tmp_path / path))} characters)")


def test_a_nul_in_a_path(tmp_path):
    assert error(tmp_path, '[plc]\nprograms = ["main\\u0000.st"]\n') == (
        "plc.programs[0]",
        f"embedded null byte: {tmp_path / 'main'}\0.st",
    )


def test_a_retain_file_in_a_directory_that_does_not_exist(tmp_path):
    """It was taken, and the stop said "retained data saved" of a file never written."""
    assert error(tmp_path, PLC + '[retain]\nfile = "nowhere/plant.retain"\n') == (
        "retain.file",
        f"no such directory: {tmp_path / 'nowhere'} (the file is written there; relative paths start at "
        "the config file's directory)",
    )


def test_a_retain_file_is_a_regular_file_or_not_there_yet(tmp_path):
    """[retain] file = "/dev/null" was taken; run as root, softplc renamed
    /dev/null to /dev/null.corrupt (an empty "file" taken for a damaged one)."""
    expected = "expected a regular file or a name not yet taken (softplc writes the file and renames it into place)"
    assert error(tmp_path, PLC + '[retain]\nfile = "/dev/null"\n') == (
        "retain.file",
        f"/dev/null is a character device; {expected}",
    )
    os.mkfifo(tmp_path / "pipe")
    assert error(tmp_path, PLC + '[retain]\nfile = "pipe"\n') == (
        "retain.file",
        f"{tmp_path / 'pipe'} is a FIFO; {expected}",
    )
    (tmp_path / "link").symlink_to(tmp_path / "elsewhere")
    assert error(tmp_path, PLC + '[retain]\nfile = "link"\n') == (
        "retain.file",
        f"{tmp_path / 'link'} is a symbolic link; {expected}",
    )
    assert load(tmp_path, PLC + '[retain]\nfile = "plant.retain"\n').retain.file == tmp_path / "plant.retain"


@pytest.mark.parametrize(
    ("key", "written", "expected"),
    [
        ("interval", '"2d"', "a duration of at most 1d"),
        ("interval", '"100000000000h"', "a duration of at most 1d"),
        ("watchdog", '"25h"', "a duration of at most 1d, or false for no watchdog"),
    ],
)
def test_durations_longer_than_a_day(tmp_path, key, written, expected):
    interval = 'interval = "10ms"' if key != "interval" else ""
    text = f'name = "T"\n{interval}\n{key} = {written}\nprograms = ["Main"]\n'
    assert error(tmp_path, task(text)) == (f"task[0].{key}", f"expected {expected} (got {written[1:-1]!r})")


def test_a_bus_duration_longer_than_a_day(tmp_path):
    """A huge RTU timeout was an OverflowError in the connection's worker (exit 4)."""
    text = PLC + '[[modbus]]\ntransport = "rtu"\ndevice = "/dev/ttyUSB0"\ntimeout = "100000000000h"\n'
    assert error(tmp_path, text) == ("modbus[0].timeout", "expected a duration of at most 1d (got '100000000000h')")


def test_a_day_is_still_a_duration(tmp_path):
    [t] = load(tmp_path, task('name = "T"\ninterval = "1d"\nwatchdog = "1d"\nprograms = ["Main"]\n')).tasks
    assert t.interval_ns == t.watchdog_ns == 86_400 * 10**9


@pytest.mark.parametrize("written", ["inf", "-inf", "nan"])
def test_inf_and_nan_are_refused_everywhere(tmp_path, written):
    """A device's parameter conversion took them to an OverflowError (exit 4)."""
    text = (
        PLC + '[[can]]\ninterface = "virtual"\nchannel = "c"\n[canopen]\n[[canopen.node]]\nname = "pump"\n'
        f'id = 20\neds = "fc280"\nguard_time = "100ms"\nsdo = [{{ parameter = "8-03", value = {written} }}]\n'
        f'[[sim]]\ntype = "fc280"\nnode_id = 20\nparameters = {{ "3-41" = {written} }}\n'
        f'[outputs]\nsafe = {{ "%QD1" = {written} }}\n'
    )
    assert errors(tmp_path, text) == [
        ("canopen.node[0].sdo[0].value", f"expected an integer (got {written})"),
        ("sim[0].parameters.3-41", f"expected a finite number (got {written})"),
        ('outputs.safe."%QD1"', f"expected a finite number (got {written})"),
    ]


def test_inf_as_a_duration_says_what_the_key_takes(tmp_path):
    assert error(tmp_path, task('name = "T"\ninterval = inf\nprograms = ["Main"]\n')) == (
        "task[0].interval",
        f"expected {DURATION} (got inf)",
    )


def test_a_long_value_is_cut_in_the_message(tmp_path):
    key, message = error(tmp_path, PLC + f'[[task]]\nname = "T"\ninterval = "{"x" * 5000}"\nprograms = ["Main"]\n')
    assert key == "task[0].interval"
    assert message == f"expected {DURATION} (got '{'x' * 60}…' (5000 characters))"


def test_a_long_unknown_key_is_cut_too(tmp_path):
    [(key, message)] = errors(tmp_path, PLC.replace("[plc]\n", f"[plc]\n{'k' * 5000} = 1\n"))
    assert key == f'plc."{"k" * 60}…" (5000 characters)'
    assert message.startswith("unknown key (expected one of ")


def test_cut():
    assert got("x" * 100) == repr("x" * 100)
    assert got("x" * 101) == f"'{'x' * 60}…' (101 characters)"
    quoted = "it's " * 30  # repr chooses double quotes
    assert got(quoted) == f'"{quoted[:60]}…" (150 characters)'
    path = "/plant/" + "d" * 300 + "/main.st"
    assert cut(f"no such file: {path} (relative paths start at the config file's directory)") == (
        f"no such file: {path[:60]}… ({len(path)} characters) (relative paths start at the config file's directory)"
    )
    assert cut("a short message: /a/b.st") == "a short message: /a/b.st"
    assert len(cut("word " * 1000)) == 1000


# ====================================================================== long names and texts
# A 1 MB task name or CAN channel was taken and written whole into the log.


def test_a_name_has_at_most_100_characters(tmp_path):
    body = '[[task]]\nname = "{}"\ninterval = "10ms"\nprograms = ["Main"]\n'
    assert load(tmp_path, PLC + body.format("T" * 100)).tasks[0].name == "T" * 100
    assert error(tmp_path, PLC + body.format("T" * 1_000_000)) == (
        "task[0].name",
        f"expected a task name: an IEC identifier of at most 100 characters (got '{'T' * 60}…' (1000000 characters))",
    )


def test_a_text_value_has_at_most_255_characters(tmp_path):
    can = '[[can]]\ninterface = "virtual"\nchannel = "{}"\n'
    assert load(tmp_path, PLC + can.format("c" * 255)).can[0].channel == "c" * 255
    assert error(tmp_path, PLC + can.format("c" * 1_000_000)) == (
        "can[0].channel",
        'expected a channel such as "can0" or "PCAN_USBBUS1", of at most 255 characters '
        f"(got '{'c' * 60}…' (1000000 characters))",
    )
