"""PLCopen XML as Beremiz and TwinCAT 3 write it (runtime/st/importers/
plcopen.py): a Beremiz project (ST bodies, IEC task intervals, globals of
the resource and the configuration after their tasks and resources) and a
TwinCAT export (a named GVL in the project's addData, the plain-text
interfaces beside the structured ones, a method and a property) run as the
same projects written in ST."""

from __future__ import annotations

from pathlib import Path

import pytest

from softplc.runtime.program import check_files, compile_files
from softplc.testing import PLC

HERE = Path(__file__).parent


BEREMIZ = HERE / "beremiz" / "plc.xml"
BEREMIZ_TWIN = HERE / "beremiz_twin.st"
BEREMIZ_WATCHED = [
    "instance0.toggles",
    "instance0.r.raw",
    "instance0.r.scaled",
    "instance0.mode",
    "instance0.hist",
    "instance0.boots",
    "total",
    "seen",
    "started",
]


def beremiz_values(source: Path, duration: str) -> dict:
    with PLC.from_st([source], profile="matiec") as plc:
        plc.run_for(duration)
        return {path: plc[path] for path in BEREMIZ_WATCHED}


@pytest.mark.parametrize("duration", ["60ms", "500ms", "1s"])
def test_the_beremiz_project_runs_as_its_plain_st_twin(duration):
    got = beremiz_values(BEREMIZ, duration)
    assert got == beremiz_values(BEREMIZ_TWIN, duration)
    if duration == "1s":
        # task0 (T#20ms) ran 50 times; watcher (t#100ms) last saw total at 900 ms
        assert (got["total"], got["seen"]) == (50, 46)
        assert got["instance0.toggles"] == 12 and got["instance0.boots"] == 1
        assert got["instance0.hist"] == [118, 115, 112, 103]  # [4(1)] plus the raw values


def test_the_beremiz_project_checks_clean():
    diags, _ = check_files([str(BEREMIZ)], profile="matiec")
    assert diags == []


TWINCAT = HERE / "twincat_export" / "project.xml"
TWINCAT_TWIN = [HERE / "twincat_export_twin" / "GVL_Main.st", HERE / "twincat_export_twin" / "project.st"]


def twincat_values(sources: list, cycles: int) -> dict:
    r = compile_files([str(s) for s in sources], profile="twincat").runner("MAIN", cycle_time_ms=10)
    r.run(cycles)
    return {v: r.get(v) for v in ("fbAxis.nPos", "fbAxis.nMoves", "GVL_Main.nCycles", "nStep")}


@pytest.mark.parametrize("cycles", [1, 17, 29, 40])
def test_the_twincat_export_runs_as_its_plain_st_twin(cycles):
    got = twincat_values([TWINCAT], cycles)
    assert got == twincat_values(TWINCAT_TWIN, cycles)
    if cycles == 40:  # up 3 per cycle to the limit 50 (GVL_Main.stLimits), then down 11 times
        assert got == {"fbAxis.nPos": 17, "fbAxis.nMoves": 40, "GVL_Main.nCycles": 40, "nStep": 40}


def test_the_twincat_export_checks_clean():
    # the plain-text interfaces and build properties TwinCAT adds are known: no W181
    diags, _ = check_files([str(TWINCAT)], profile="twincat")
    assert diags == []
