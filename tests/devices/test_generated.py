"""The files the devices generate from their manual tables (ST constants,
EDS files): every shipped one is exactly what its generator writes, and
`python -m softplc.runtime.devices` rewrites them all."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest

from softplc.runtime.plugin.registry import registry

GENERATED = registry().generated()


def test_every_device_file_is_generated():
    assert sorted(g.target.file for g in GENERATED) == [
        "eaton_codes.st",
        "eds/fc280.eds",
        "eds/ltmr.eds",
        "fc280_codes.st",
        "ltmr_codes.st",
        "mpu2s_codes.st",
    ]


@pytest.mark.parametrize("generated", GENERATED, ids=lambda g: g.target.file)
def test_shipped_file_is_what_the_generator_writes(generated):
    # regenerate with: python -m softplc.runtime.devices
    assert generated.target.path.read_text(encoding=generated.encoding) == generated.render()


def test_the_command_writes_every_file(tmp_path):
    done = subprocess.run(
        [sys.executable, "-m", "softplc.runtime.devices", str(tmp_path)], capture_output=True, text=True, check=True
    )
    assert done.stdout.count("wrote ") == len(GENERATED)
    for generated in GENERATED:
        written = tmp_path / Path(generated.target.file).name
        assert written.read_bytes() == generated.target.path.read_bytes()
