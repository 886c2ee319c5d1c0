"""Projects as a whole (issue 29): a TwinCAT solution or PLC project, a
CODESYS PLCopen export, a Beremiz folder or a folder of sources, found
(discover.py), compiled as far as they compile (subset.py), their missing
libraries named (missing.py), summed up in a table (table.py), exported as
ST (export.py) and run with their own tasks (tasks.py).

    [project] = open_projects(["LCLSGeneral.sln"])
    result = analyse(project)            # diagnostics, units, the part that compiles
    result.program                       # a Program of that part, or None

This layer sits above the compiler (program/) and the configuration, below
the command line; it names no bus and no device.
"""

from .discover import open_projects
from .model import LibraryRef, Project, TaskSpec

__all__ = ["LibraryRef", "Project", "TaskSpec", "open_projects"]
