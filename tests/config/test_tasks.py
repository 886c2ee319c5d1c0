"""The [[task]] tables of a configuration: the interval, watchdog, pause and
priority spellings and their limits, the program instances, what is refused
and how the message names the file and the key."""

from __future__ import annotations

import textwrap

import pytest

from softplc.runtime.config import (
    ConfigError,
    ProgramInstance,
    TaskConfig,
    load_config,
)

from .support import DURATION, MS, PLC, error, errors, load, write

# ====================================================================== [[task]]


def task(body: str) -> str:
    return PLC + "[[task]]\n" + textwrap.dedent(body)


@pytest.mark.parametrize(
    "written, ns",
    [
        ('"10ms"', 10 * MS),
        ('"1s500ms"', 1_500_000_000),
        ('"T#250ms"', 250 * MS),
        ('"TIME#1s"', 1_000_000_000),
        ('"1000us"', MS),  # the least interval
        ('"1.5ms"', 1_500_000),
        ('"1m"', 60_000 * MS),
        ('"1h30m"', 5_400_000 * MS),
    ],
)
def test_interval_spellings(tmp_path, written, ns):
    cfg = load(tmp_path, task(f'name = "T"\ninterval = {written}\nprograms = ["Main"]\n'))
    assert cfg.tasks[0].interval_ns == ns


@pytest.mark.parametrize("written", ['"1us"', '"999us"', '"T#0.5ms"', '"100ns"'])
def test_an_interval_shorter_than_a_millisecond_is_refused(tmp_path, written):
    """interval = "1us" ran 653,403 scans with 2,338,823 overruns in 3 s of
    the real clock, a core busy: no Python scan keeps such a period."""
    assert error(tmp_path, task(f'name = "T"\ninterval = {written}\nprograms = ["Main"]\n')) == (
        "task[0].interval",
        "expected an interval of at least 1ms: a scan runs Python, a shorter period only overruns "
        f"(freewheeling = true runs the cycles back to back) (got {_got(written)})",
    )


@pytest.mark.parametrize("written", ['"1s1s1s1s"', '"10ms10ms"', '"500ms1s"', '"T#1m1h"'])
def test_a_unit_twice_or_out_of_order_is_no_duration(tmp_path, written):
    """ "1s1s1s1s" was read as 4 s; IEC writes each unit once, the largest first."""
    assert error(tmp_path, task(f'name = "T"\ninterval = {written}\nprograms = ["Main"]\n')) == (
        "task[0].interval",
        f"expected {DURATION} (got {_got(written)})",
    )


@pytest.mark.parametrize(("written", "hint"), [("10", "10"), ("2.5", "2.5"), ('"10"', "10"), ('" 250 "', "250")])
def test_a_number_without_its_unit_is_refused_with_a_hint(tmp_path, written, hint):
    """interval = 10 was taken for 10 ms: ms or s is the user's to say."""
    assert error(tmp_path, task(f'name = "T"\ninterval = {written}\nprograms = ["Main"]\n')) == (
        "task[0].interval",
        f"expected a duration with its unit, such as {hint}ms or {hint}s "
        f"(got {_got(written)}: a number alone has none)",
    )


def test_zero_needs_no_unit(tmp_path):
    assert load(tmp_path, PLC + "spin = 0\n").spin_ns == 0


def test_task_defaults(tmp_path):
    cfg = load(tmp_path, task('name = "T"\ninterval = "10ms"\nprograms = ["Main"]\n'))
    assert cfg.tasks == [
        TaskConfig(
            name="T",
            interval_ns=10 * MS,
            pause_ns=1 * MS,
            priority=1,
            watchdog_ns=100 * MS,
            sensitivity=1,
            programs=[ProgramInstance("Main", "Main", "task[0].programs[0]")],
            key="task[0]",
        )
    ]


@pytest.mark.parametrize(
    "timing, watchdog_ns",
    [
        ('interval = "1ms"', 100 * MS),  # at least 100 ms
        ('interval = "50ms"', 500 * MS),  # 10 x interval
        ("freewheeling = true", 1000 * MS),  # freewheeling: 1 s
        ('interval = "10ms"\nwatchdog = "20ms"', 20 * MS),
        ('interval = "10ms"\nwatchdog = "15ms"', 15 * MS),
        ('interval = "10ms"\nwatchdog = false', None),
        ("freewheeling = true\nwatchdog = false", None),
    ],
)
def test_watchdog(tmp_path, timing, watchdog_ns):
    cfg = load(tmp_path, task(f'name = "T"\n{timing}\nprograms = ["Main"]\n'))
    assert cfg.tasks[0].watchdog_ns == watchdog_ns


def test_freewheeling_task(tmp_path):
    t = load(
        tmp_path,
        task('name = "T"\nfreewheeling = true\npause = "250us"\npriority = 31\nsensitivity = 3\nprograms = ["Main"]\n'),
    ).tasks[0]
    assert (t.interval_ns, t.pause_ns, t.priority, t.sensitivity) == (None, 250_000, 31, 3)
    t = load(tmp_path, task('name = "T"\nfreewheeling = true\nprograms = ["Main"]\n')).tasks[0]
    assert t.pause_ns == 1 * MS


def test_interval_and_freewheeling(tmp_path):
    assert error(tmp_path, task('name = "T"\ninterval = "10ms"\nfreewheeling = true\nprograms = ["Main"]\n')) == (
        "task[0].freewheeling",
        "a task has either an interval or freewheeling = true, not both",
    )


def test_interval_with_freewheeling_false_is_cyclic(tmp_path):
    t = load(tmp_path, task('name = "T"\ninterval = "10ms"\nfreewheeling = false\nprograms = ["Main"]\n'))
    assert t.tasks[0].interval_ns == 10 * MS


@pytest.mark.parametrize("timing", ["", "freewheeling = false\n"])
def test_neither_interval_nor_freewheeling(tmp_path, timing):
    assert error(tmp_path, task(f'name = "T"\n{timing}programs = ["Main"]\n')) == (
        "task[0]",
        'expected interval = "10ms" (a cyclic task) or freewheeling = true (got neither)',
    )


def test_pause_with_interval(tmp_path):
    assert error(tmp_path, task('name = "T"\ninterval = "10ms"\npause = "1ms"\nprograms = ["Main"]\n')) == (
        "task[0].pause",
        "only for a freewheeling task (this one has an interval)",
    )


def test_sensitivity_without_watchdog(tmp_path):
    assert error(
        tmp_path, task('name = "T"\ninterval = "10ms"\nwatchdog = false\nsensitivity = 2\nprograms = ["Main"]\n')
    ) == ("task[0].sensitivity", "only meaningful with a watchdog (this task has watchdog = false)")


def test_bad_duration_text(tmp_path):
    path = write(tmp_path, task('name = "T"\ninterval = "10 parsecs"\nprograms = ["Main"]\n'))
    with pytest.raises(ConfigError) as info:
        load_config(path)
    assert str(info.value) == f"{path}: task[0].interval: expected {DURATION} (got '10 parsecs')"


@pytest.mark.parametrize(
    "key, written",
    [
        ("interval", "0"),
        ("interval", '"0ms"'),
        ("interval", "-5"),
        ("interval", '"-5ms"'),
        ("interval", '"T#-5ms"'),
        ("interval", "-0.5"),
        ("interval", '"0.1ns"'),
    ],
)
def test_zero_and_negative_durations(tmp_path, key, written):
    assert error(tmp_path, task(f'name = "T"\n{key} = {written}\nprograms = ["Main"]\n')) == (
        f"task[0].{key}",
        f"expected a duration > 0 such as 10ms, 1s, T#250ms (got {_got(written)})",
    )


def _got(toml_value: str) -> str:
    """How the messages quote a TOML value: strings in single quotes."""
    return f"'{toml_value[1:-1]}'" if toml_value.startswith('"') else toml_value


@pytest.mark.parametrize("written", ["true", '"fast"', "[10]", "inf", "nan", "1979-05-27"])
def test_durations_of_the_wrong_type(tmp_path, written):
    key, message = error(tmp_path, task(f'name = "T"\ninterval = {written}\nprograms = ["Main"]\n'))
    assert key == "task[0].interval"
    assert message.startswith(f"expected {DURATION} (got ")


def test_zero_pause_and_watchdog(tmp_path):
    assert errors(
        tmp_path, task('name = "T"\nfreewheeling = true\npause = 0\nwatchdog = "0s"\nprograms = ["Main"]\n')
    ) == [
        ("task[0].pause", "expected a duration > 0 such as 10ms, 1s, T#250ms (got 0)"),
        ("task[0].watchdog", "expected a duration > 0 such as 10ms, 1s, T#250ms, or false for no watchdog (got '0s')"),
    ]


def test_watchdog_true_is_refused(tmp_path):
    assert error(tmp_path, task('name = "T"\ninterval = "10ms"\nwatchdog = true\nprograms = ["Main"]\n')) == (
        "task[0].watchdog",
        "expected a duration > 0 such as 10ms, 1s, T#250ms, or false for no watchdog (got true)",
    )


@pytest.mark.parametrize("written", ["32", "-1", "100"])
def test_priority_out_of_range(tmp_path, written):
    assert error(tmp_path, task(f'name = "T"\ninterval = "10ms"\npriority = {written}\nprograms = ["Main"]\n')) == (
        "task[0].priority",
        f"expected an integer from 0 to 31 (got {written})",
    )


@pytest.mark.parametrize("written, got", [('"10"', "'10'"), ("1.0", "1.0"), ("true", "true")])
def test_priority_wrong_type(tmp_path, written, got):
    assert error(tmp_path, task(f'name = "T"\ninterval = "10ms"\npriority = {written}\nprograms = ["Main"]\n')) == (
        "task[0].priority",
        f"expected an integer from 0 to 31 (got {got})",
    )


def test_priority_bounds_accepted(tmp_path):
    cfg = load(
        tmp_path,
        task(
            'name = "A"\ninterval = "10ms"\npriority = 0\nprograms = ["Main"]\n'
            '[[task]]\nname = "B"\ninterval = "10ms"\npriority = 31\nprograms = ["M2"]\n'
        ),
    )
    assert [t.priority for t in cfg.tasks] == [0, 31]


def test_sensitivity_range(tmp_path):
    assert error(tmp_path, task('name = "T"\ninterval = "10ms"\nsensitivity = 0\nprograms = ["Main"]\n')) == (
        "task[0].sensitivity",
        "expected an integer >= 1 (got 0)",
    )


def test_freewheeling_wrong_type(tmp_path):
    assert error(tmp_path, task('name = "T"\nfreewheeling = "yes"\nprograms = ["Main"]\n')) == (
        "task[0].freewheeling",
        "expected true or false (got 'yes')",
    )


def test_task_unknown_key(tmp_path):
    assert errors(tmp_path, task('name = "T"\nintervall = "10ms"\nprograms = ["Main"]\n')) == [
        ("task[0].intervall", "unknown key (did you mean 'interval'?)"),
        ("task[0]", 'expected interval = "10ms" (a cyclic task) or freewheeling = true (got neither)'),
    ]


def test_task_missing_keys(tmp_path):
    assert errors(tmp_path, task('interval = "10ms"\n')) == [
        ("task[0].name", 'required key missing (expected a task name such as "Fast")'),
        (
            "task[0].programs",
            "required key missing (expected an array of PROGRAM names or "
            '{ instance = "...", program = "..." } tables, such as ["Conveyor"])',
        ),
    ]


def test_task_as_a_table_instead_of_an_array(tmp_path):
    assert error(tmp_path, PLC + '[task]\nname = "T"\n') == ("task", "expected [[task]] tables (got a table)")


def test_task_name_must_be_an_identifier(tmp_path):
    assert error(tmp_path, task('name = "1st task"\ninterval = "10ms"\nprograms = ["Main"]\n')) == (
        "task[0].name",
        "expected a task name: an IEC identifier (letters, digits, _; not starting with a digit) (got '1st task')",
    )


def test_duplicate_task_names(tmp_path):
    assert error(
        tmp_path,
        task(
            'name = "Fast"\ninterval = "10ms"\nprograms = ["Main"]\n'
            '[[task]]\nname = "FAST"\ninterval = "20ms"\nprograms = ["Other"]\n'
        ),
    ) == ("task[1].name", "duplicate task name 'FAST' (task[0] has it; names are case-insensitive)")


def test_program_instances(tmp_path):
    cfg = load(
        tmp_path, task('name = "T"\ninterval = "10ms"\nprograms = ["Main", { instance = "Main2", program = "Main" }]\n')
    )
    assert cfg.tasks[0].programs == [
        ProgramInstance("Main", "Main", "task[0].programs[0]"),
        ProgramInstance("Main2", "Main", "task[0].programs[1]"),
    ]


def test_duplicate_instance_names_across_tasks(tmp_path):
    assert error(
        tmp_path,
        task(
            'name = "A"\ninterval = "10ms"\nprograms = ["Main"]\n'
            '[[task]]\nname = "B"\ninterval = "20ms"\nprograms = ["main"]\n'
        ),
    ) == (
        "task[1].programs[0]",
        "duplicate program instance 'main' (also at task[0].programs[0]; instance "
        "names are unique across tasks, case-insensitive); give one its own "
        'instance name: { instance = "main2", program = "main" }',
    )


def test_duplicate_instance_names_in_tables(tmp_path):
    assert error(
        tmp_path, task('name = "A"\ninterval = "10ms"\nprograms = ["Main", { instance = "Main", program = "Other" }]\n')
    ) == (
        "task[0].programs[1].instance",
        "duplicate program instance 'Main' (also at task[0].programs[0]; "
        "instance names are unique across tasks, case-insensitive)",
    )


def test_bad_program_entries(tmp_path):
    assert errors(
        tmp_path,
        task(
            'name = "A"\ninterval = "10ms"\nprograms = [5, "no good", '
            '{ instance = "X" }, { instance = "Y", program = "P", prio = 1 }]\n'
        ),
    ) == [
        (
            "task[0].programs[0]",
            'expected a PROGRAM name such as "Conveyor" or a table '
            '{ instance = "Line2", program = "Conveyor" } (got 5)',
        ),
        ("task[0].programs[1]", "expected a PROGRAM name (an IEC identifier) (got 'no good')"),
        ("task[0].programs[2].program", 'required key missing (expected a PROGRAM name such as "Conveyor")'),
        ("task[0].programs[3].prio", "unknown key (expected one of instance, program)"),
    ]


def test_empty_program_list(tmp_path):
    assert error(tmp_path, task('name = "A"\ninterval = "10ms"\nprograms = []\n')) == (
        "task[0].programs",
        'expected an array of PROGRAM names or { instance = "...", program = "..." } '
        'tables, such as ["Conveyor"] (got an empty array)',
    )
