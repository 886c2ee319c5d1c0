"""Runtime faults located in the ST source (runtime/st/faults.py): here,
running out of memory."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest

# Fills ever more strings of 65,000 characters until the memory runs out.
HOARDER = """\
PROGRAM main
VAR
  big : STRING[65535] := 'x';
  keep : ARRAY[1..100000] OF STRING[65535];
  i : DINT;
END_VAR
FOR i := 1 TO 17 DO
  big := CONCAT(big, big);
END_FOR
FOR i := 1 TO 100000 DO
  keep[i] := CONCAT(LEFT(big, 65000), DINT_TO_STRING(i));
END_FOR
END_PROGRAM
"""

# `softplc exec`, in a process whose address space may grow 64 MB past
# what compiling the program took (the limit is set after a first compile).
LIMITED_EXEC = """\
import resource, sys
from softplc.runtime import cli
from softplc.runtime.program import compile_files
compile_files([sys.argv[1]])
with open("/proc/self/status") as f:
    size = int(next(line for line in f if line.startswith("VmSize")).split()[1]) * 1024
resource.setrlimit(resource.RLIMIT_AS, (size + (64 << 20), resource.getrlimit(resource.RLIMIT_AS)[1]))
cli.main(["exec", sys.argv[1]])
"""


@pytest.mark.skipif(not Path("/proc/self/status").exists(), reason="the address-space limit is set from /proc (Linux)")
def test_running_out_of_memory_is_a_fault_that_says_so_where(tmp_path):
    path = tmp_path / "hoard.st"
    path.write_text(HOARDER)
    env = dict(os.environ)
    env.pop("SOFTPLC_DEBUG", None)
    proc = subprocess.run(
        [sys.executable, "-c", LIMITED_EXEC, str(path)],
        capture_output=True,
        text=True,
        stdin=subprocess.DEVNULL,
        env=env,
        timeout=120,
    )
    assert proc.returncode == 3, proc.stderr
    [line] = proc.stderr.splitlines()
    assert line.startswith(
        f"{path}:11:3: runtime fault: out of memory: the process could not get the memory this statement needs ("
    )
    assert "address-space limit" in line and "internal" not in line
