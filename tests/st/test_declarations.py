"""Declarations: pragmas on the AST, located variables in both addressing
models, the LTMR manual's examples. CONFIGURATION and type declarations are
tested with the checker's parts (test_checker_config.py, test_checker_types.py)."""

from __future__ import annotations

import struct

from softplc.runtime.io.canopen.sdo import SERVICE as SDO_SERVICE
from softplc.runtime.program import compile_files

from .conftest import run_st


def test_pragmas_are_kept_on_the_ast():
    from softplc.runtime.st.diagnostics import DiagnosticBag
    from softplc.runtime.st.syntax.parser import parse_source

    sf = parse_source(
        "{attribute 'hide'}\nPROGRAM p\nVAR {attribute 'x'} a : INT; END_VAR\nEND_PROGRAM\n", "p.st", DiagnosticBag()
    )
    pou = sf.decls[0]
    assert any("hide" in p for p in pou.pragmas)


def test_iec_located_variables_share_the_byte_image():
    src = """
PROGRAM main
VAR
  w AT %MW1 : WORD;
  lo AT %MB2 : BYTE;
  hi AT %MB3 : BYTE;
  bit9 AT %MX3.1 : BOOL;
  d AT %MD1 : DINT;
END_VAR
w := 16#0201;
d := -2;
END_PROGRAM
"""
    r = run_st(src)
    m = r.ctx.image.areas["M"]
    assert (r.get("lo"), r.get("hi"), r.get("bit9")) == (1, 2, True)  # %MW1 is bytes 2-3, little-endian
    assert struct.unpack_from("<i", m, 4)[0] == -2  # %MD1 is bytes 4-7


def test_schneider_word_model_of_the_ltmr_manual():
    # DOCA0132DE, "Beispiel für ein Schreibe-SDO": %MD3200 overlaps %MW3200/%MW3201
    src = """
PROGRAM main
VAR lo : INT; hi : INT; busy : BOOL; END_VAR
%MD3200 := 16#00032007;
%MW3202 := 50;
lo := %MW3200; hi := %MW3201;
%MW3250 := 1;
busy := %MW3250:X0;
SET %M100;
END_PROGRAM
"""
    r = run_st(src, profile="schneider")
    assert (r.get("lo"), r.get("hi"), r.get("busy")) == (0x2007, 0x0003, True)
    assert r.ctx.image.mbits[100] == 1


def test_the_ltmr_manual_examples_run_verbatim():
    prog = compile_files(["st_programs/ltmr_write_sdo.st", "st_programs/ltmr_read_sdo.st"], profile="schneider")
    for name, idx_word, request_bit, _mgmt, timeout_word, index in (
        ("ltmr_write_sdo", 3200, 100, 3250, 3253, 0x00032007),
        ("ltmr_read_sdo", 3220, 101, 3260, 3263, 0x00032004),
    ):
        runner = prog.runner(name)
        calls = []

        class Recorder:  # stands in for the CANopen master's SDO service
            def request(self, *args, _calls=calls):
                _calls.append(args)
                return True

        runner.ctx.services[SDO_SERVICE] = Recorder()
        image = runner.ctx.image
        image.mbits[request_bit] = 1  # the user's request bit
        runner.run(1)
        assert struct.unpack_from("<i", image.areas["M"], 2 * idx_word)[0] == index
        assert struct.unpack_from("<h", image.areas["M"], 2 * timeout_word)[0] == 2
        assert image.mbits[request_bit] == 0  # RESET %M100 / %M101
        [(fn, addr, obj, number, node, data, table, data_signed, table_signed)] = calls
        assert (fn, addr, obj, number, node) == (
            name[5:].split("_")[0].upper() + "_VAR",
            ("0", "1", "SYS"),
            "SDO",
            index,
            40,
        )
        assert len(data) == 1 and len(table) == 4
        assert data_signed and table_signed  # %MW tables hold INT words
