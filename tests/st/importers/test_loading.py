"""The importers and the graphical languages are loaded when a file of
their kind is read (st/importers/__init__.py, bodies.py): a program of
plain ST, the usual test or fixture, loads none of them; a PLCopen file
with an FBD body loads both and reads as before."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

HERE = Path(__file__).parent
IMPORTERS = "softplc.runtime.st.importers."
READERS = ("plcopen", "twincat", "codesys23", "fbd", "ld", "sfc", "xmlsafe")

PROBE = """
import json, sys
from softplc.runtime.program import compile_files
program = compile_files([sys.argv[1]])
print(json.dumps(sorted(m for m in sys.modules if m.startswith("softplc.runtime.st.importers."))))
"""


def _loaded(path: Path) -> set[str]:
    done = subprocess.run([sys.executable, "-c", PROBE, str(path)], capture_output=True, text=True, timeout=120)
    assert done.returncode == 0, done.stderr
    return {name.removeprefix(IMPORTERS) for name in json.loads(done.stdout.strip().splitlines()[-1])}


def test_plain_st_loads_no_importer(tmp_path: Path):
    source = tmp_path / "main.st"
    source.write_text("PROGRAM Main VAR x : INT; END_VAR x := x + 1; END_PROGRAM\n")
    assert not _loaded(source) & set(READERS)


def test_an_fbd_body_loads_its_reader_and_its_language():
    assert {"plcopen", "fbd"} <= _loaded(HERE / "fbd_codesys.xml")
