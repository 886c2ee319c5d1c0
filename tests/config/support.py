"""What the configuration tests share: a file written into tmp_path next to
a tiny ST program, loaded, and its ConfigError taken apart (after checking
that every line of the message names the file)."""

from __future__ import annotations

import os
import textwrap
from importlib import resources
from pathlib import Path

import pytest

from softplc.runtime.config import ConfigError, PlcConfig, load_config
from softplc.runtime.config.errors import SHOWN
from softplc.runtime.st.ast import LocatedAddress

REPO = Path(__file__).resolve().parents[2]
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
    assert len(lines) == min(len(err.errors), SHOWN + 1)  # and "... N more errors" after SHOWN
    for line, (key, message) in zip(lines[:SHOWN], err.errors):
        assert line == (f"{path}: {key}: {message}" if key else f"{path}: {message}")
    return err.errors


def error(tmp_path: Path, text: str) -> tuple:
    found = errors(tmp_path, text)
    assert len(found) == 1, found
    return found[0]


def addr(text: str) -> LocatedAddress:
    from softplc.runtime.image.address import parse_address

    return parse_address(text)


# ---------------------------------------------------------------- CAN, CANopen and simulated devices
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
