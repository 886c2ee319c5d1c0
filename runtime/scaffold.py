"""``softplc new NAME``: a project folder that runs at once on the
simulated plant of the default configuration (io_config/default.toml);
the project's files are the templates in io_config/project/.

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
    templates = resources.files("softplc.io_config").joinpath("project")
    for src, dst in (("main.st", "src/main.st"), ("test_main.st", "tests/test_main.st"), ("README.md", "README.md")):
        text = templates.joinpath(src).read_text(encoding="utf-8").replace("{name}", name)
        (root / dst).write_text(text, encoding="utf-8")
    return root
