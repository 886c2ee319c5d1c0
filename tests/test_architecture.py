"""The architecture's promises that a test can keep (docs/architecture.md):
the core names no bus and no device, no module is over 600 lines, every
package folder is installed. The import layers are import-linter's contracts
in pyproject.toml (.ci/run)."""

from __future__ import annotations

import ast
import io
import re
import tokenize
import tomllib
from pathlib import Path

REPO = Path(__file__).resolve().parents[1]
SOURCES = sorted(p for folder in ("runtime", "fblocks") for p in (REPO / folder).rglob("*.py"))
#: every module of the repository: the code, its tests, the benchmarks, the tools
MODULES = sorted(
    p
    for folder in ("runtime", "fblocks", "testing", "tests", "benchmarks", "tools")
    for p in (REPO / folder).rglob("*.py")
)

# Only a bus's, a device's or a simulator's own package may name a bus or a
# device; so may a module whose own path names the thing. The Modbus TCP
# server ([modbus_server], runtime/surfaces/modbus_server) is a server of the
# PLC, not the bus: its name is no bus name, and its own package uses pymodbus.
NAMES = re.compile(
    r"ltmr|eaton|\bd[abce]1\b|\bde11\b|fc[ _]?280|mpu2|genset|modbus(?!_?server)|canopen|\bsdo|\bpdo|sdo\b|pdo\b",
    re.I,
)
PLUGIN_PACKAGES = [REPO / "runtime" / "io", REPO / "runtime" / "devices", REPO / "runtime" / "sim", REPO / "fblocks"]
SURFACE_PACKAGES = [REPO / "runtime" / "surfaces" / "modbus_server"]


def _docstring_lines(tree: ast.AST) -> set:
    lines: set = set()
    for node in ast.walk(tree):
        if isinstance(node, (ast.Module, ast.ClassDef, ast.FunctionDef, ast.AsyncFunctionDef)) and node.body:
            first = node.body[0]
            if (
                isinstance(first, ast.Expr)
                and isinstance(first.value, ast.Constant)
                and isinstance(first.value.value, str)
            ):
                lines.update(range(first.lineno, first.end_lineno + 1))
    return lines


def names_in_code(path: Path, root: Path = REPO) -> list:
    """Identifiers and string literals (not comments, not docstrings) that
    name a bus or a device."""
    text = path.read_text(encoding="utf-8")
    docstrings = _docstring_lines(ast.parse(text))
    found = []
    for tok in tokenize.generate_tokens(io.StringIO(text).readline):
        if tok.type in (tokenize.NAME, tokenize.STRING) and tok.start[0] not in docstrings and NAMES.search(tok.string):
            found.append(f"{path.relative_to(root)}:{tok.start[0]}: {tok.string[:60]}")
    return found


CORE = [
    p
    for p in SOURCES
    if (not any(root in p.parents for root in PLUGIN_PACKAGES) or p.parent in PLUGIN_PACKAGES)
    and not any(root in p.parents for root in SURFACE_PACKAGES)
]


def test_the_core_names_no_bus_and_no_device():
    assert [p for p in CORE if p.name == "cli.py"], "the core list is empty: the test looks at nothing"
    assert [hit for path in CORE for hit in names_in_code(path)] == []


def test_the_rule_sees_what_it_looks_for(tmp_path):
    code = tmp_path / "example.py"
    code.write_text(
        '"""The LTMR, in a docstring: fine."""\n# a comment about Modbus: fine\nx = "canopen"\nsdo_timeout = 1\n'
    )
    assert [hit.split(": ", 1)[1] for hit in names_in_code(code, tmp_path)] == ['"canopen"', "sdo_timeout"]


def test_no_module_is_over_600_lines():
    sizes = {str(p.relative_to(REPO)): len(p.read_text(encoding="utf-8").splitlines()) for p in MODULES}
    assert len(sizes) > 600  # the code and its tests, all seen
    assert {path: n for path, n in sizes.items() if n > 600} == {}, "split these by concern"


def test_every_package_folder_is_installed():
    """pyproject lists the packages one by one (the folders map into the
    softplc namespace): a folder missing there works in a development
    install and is absent from a real one."""
    listed = set(tomllib.loads((REPO / "pyproject.toml").read_text())["tool"]["setuptools"]["packages"])
    folders = set()
    for top, name in (("runtime", "softplc.runtime"), ("fblocks", "softplc.fblocks")):
        for init in (REPO / top).rglob("__init__.py"):
            rel = init.parent.relative_to(REPO / top)
            folders.add(".".join([name, *rel.parts]))
    assert folders <= listed
