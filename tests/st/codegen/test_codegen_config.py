"""What VAR_CONFIG does when the plant runs (runtime/st/codegen/codegen_config.py):
each instance's variables at the addresses and with the initial values its
VAR_CONFIG lines give, read from and written to the process image."""

from __future__ import annotations

from softplc.testing import PLC

PLANT = """
FUNCTION_BLOCK Valve
VAR_INPUT cmd : BOOL; END_VAR
VAR
  open AT %QX* : BOOL;
  ready AT %IX* : BOOL;
  level AT %IW* : INT;
  limit : INT := 10;
  table : ARRAY[1..3] OF INT;
  seen : BOOL;
END_VAR
seen := open;
open := cmd AND ready AND level < limit;
END_FUNCTION_BLOCK
PROGRAM Line
VAR
  v1 : Valve;
  v2 : Valve;
  go : BOOL := TRUE;
END_VAR
v1(cmd := go); v2(cmd := go);
END_PROGRAM
CONFIGURATION Plant
  RESOURCE Cpu ON PLC
    TASK Main (INTERVAL := T#10ms, PRIORITY := 1);
    PROGRAM line1 WITH Main : Line;
    PROGRAM line2 WITH Main : Line;
  END_RESOURCE
  VAR_CONFIG
    Cpu.line1.v1.open AT %QX0.1 : BOOL;
    Cpu.line1.v1.ready AT %IX0.0 : BOOL;
    Cpu.line1.v1.level AT %IW2 : INT;
    Cpu.line1.v1.limit : INT := 50;
    Cpu.line1.v2.open AT %QX0.2 : BOOL := TRUE;
    Cpu.line1.v2.ready AT %IX0.0 : BOOL;
    Cpu.line1.v2.level AT %IW2 : INT;
    line2.v1.open AT %QX1.1 : BOOL;
    line2.v1.ready AT %IX1.0 : BOOL;
    line2.v1.level AT %IW4 : INT;
    line2.v2.open AT %QX1.2 : BOOL;
    line2.v2.ready AT %IX1.0 : BOOL;
    line2.v2.level AT %IW4 : INT;
    line2.go : BOOL := FALSE;
    line2.v2.table : ARRAY[1..3] OF INT := [1, 2, 3];
  END_VAR
END_CONFIGURATION
"""


def test_each_instance_runs_with_its_own_addresses_and_initial_values():
    plc = PLC.from_st(PLANT)
    plc.start()
    # an output's initial value is in the image before the first cycle
    assert plc["%QX0.2"] is True and plc["%QX0.1"] is False
    assert (plc["line1.v1.limit"], plc["line1.v2.limit"], plc["line2.go"]) == (50, 10, False)
    assert plc["line2.v2.table"] == [1, 2, 3] and plc["line2.v1.table"] == [0, 0, 0]
    plc["%IX0.0"] = True
    plc["%IW2"] = 20
    plc["%IX1.0"] = True
    plc.step()
    # line1.v1: 20 < its limit 50; line1.v2: not below the FB's own 10; line2 is not to go
    assert [plc["%QX0.1"], plc["%QX0.2"], plc["%QX1.1"], plc["%QX1.2"]] == [True, False, False, False]
    assert plc["line1.v1.open"] is True and plc["line1.v1.level"] == 20
    plc["%IW2"] = 60  # an input is read at each cycle
    plc.step()
    assert plc["%QX0.1"] is False
    plc.force("%QX0.2", True)  # a forced output is what the instance reads back
    plc.step()
    assert plc["%QX0.2"] is True and plc["line1.v2.seen"] is True
