"""``softplc new NAME``: a project folder that runs at once on the
simulated plant of the default configuration.

    NAME/plc.toml             the default plant's buses, devices and tasks, and a task for Main
    NAME/src/main.st          the project's program (it counts the LTMR motor's starts)
    NAME/plant/*.st           the default plant's programs, copied (edit them freely)
    NAME/tests/test_main.st   a test in ST of the program, against the simulated plant
    NAME/README.md            the commands to run, test and check it
"""

from __future__ import annotations

import re
from importlib import resources
from pathlib import Path

from .config.load import default_config_path

MAIN_ST = """\
(* {name}: the project's program. It watches the simulated TeSys T motor
   starter of the plant (plant/ltmr_motor.st drives it) through the
   process image and counts the motor's starts. *)
VAR_GLOBAL
    motorStarts : UDINT;        (* rising edges of the LTMR's Running bit *)
    motorRunning : BOOL;
END_VAR

PROGRAM Main
VAR
    status1 AT %IW100 : WORD;   (* LTMR register 455, mapped by the plant's TPDO *)
    started : R_TRIG;
END_VAR
motorRunning := (status1 AND LTMR_STATUS1_RUNNING) <> 0;
started(CLK := motorRunning);
IF started.Q THEN
    motorStarts := motorStarts + 1;
END_IF
END_PROGRAM
"""

TEST_ST = """\
(* Tests of src/main.st against the simulated plant, in virtual time:
       softplc test plc.toml tests/test_main.st *)

(* The plant runs the motor forward, stops it after 3 s and runs it in
   reverse 1 s later: two starts within 6 s. *)
FUNCTION_BLOCK TEST_MotorStartsAreCounted
IF TIME() >= T#6s THEN
    ASSERT_EQUAL(2, motorStarts, 'forward, then reverse');
    ASSERT_TRUE(motorRunning, 'the motor runs in reverse');
    TEST_FINISHED();
END_IF
END_FUNCTION_BLOCK
"""

README = """\
# {name}

A softplc project: `src/main.st` on the simulated plant of softplc's default
configuration (a TeSys T motor starter and a Danfoss FC 280 pump on CANopen,
an Eaton DA1 drive on Modbus, all simulated), in `plc.toml`.

    softplc run plc.toml --virtual-time --duration 10s --watch motorStarts,motorRunning
    softplc test plc.toml tests/test_main.st
    softplc check .

`plant/` holds the plant's programs, copied from softplc's examples: change them,
or replace `plc.toml`'s buses and devices by your own. Real hardware: set the
`[[can]]` and `[[modbus]]` interfaces and remove the `[[sim]]` tables.
"""


PROJECT_TASK = """
# The project's program (src/main.st)
[[task]]
name = "ProjectTask"
interval = "10ms"
priority = 5
programs = ["Main"]
"""


def new_project(name: str, where: Path) -> Path:
    """Create the project folder where/name; FileExistsError if it exists,
    ValueError if name is not a folder name."""
    if not re.fullmatch(r"[A-Za-z0-9_][A-Za-z0-9_.-]*", name):
        raise ValueError(f"{name!r} is not a project name: letters, digits, '_', '-' and '.'")
    root = where / name
    root.mkdir(parents=True)
    for sub in ("src", "plant", "tests"):
        (root / sub).mkdir()
    config = default_config_path().read_text(encoding="utf-8")
    examples = resources.files("softplc.st_programs")
    used = re.findall(r'"\.\./st_programs/([A-Za-z0-9_]+\.st)"', config)
    for file in used:
        (root / "plant" / file).write_text(examples.joinpath(file).read_text(encoding="utf-8"), encoding="utf-8")
    config = config.replace('"../st_programs/', '"plant/')
    config = re.sub(r'(programs = \[[^\]]*"plant/[^\]]*)\]', r'\1, "src/main.st"]', config, count=1)
    config += PROJECT_TASK
    header = f"# {name}: softplc's default plant (io_config/default.toml) and src/main.st\n"
    (root / "plc.toml").write_text(header + config, encoding="utf-8")
    (root / "src" / "main.st").write_text(MAIN_ST.format(name=name), encoding="utf-8")
    (root / "tests" / "test_main.st").write_text(TEST_ST, encoding="utf-8")
    (root / "README.md").write_text(README.format(name=name), encoding="utf-8")
    return root
