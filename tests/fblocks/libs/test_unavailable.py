"""The Beckhoff libraries of hardware or a TwinCAT service (Tc2_EtherCAT,
Tc2_TcpIp, Tc2_ModbusSrv, Tc2_IoFunctions, Tc2_SerialCom, Tc2_MC2): their
blocks compile with their real signatures and answer "not available"
through their own error outputs, as each library documents a failed
call; W230 once per library a program uses."""

from __future__ import annotations

from softplc.runtime.program import check_files

from .bench import chosen, runner, trace

ADSERR_DEVICE_SRVNOTSUPP = 0x701
COMERROR_MODENOTSUPPORTED = 0x0101
LIBS = ("Tc2_EtherCAT", "Tc2_TcpIp", "Tc2_ModbusSrv", "Tc2_IoFunctions", "Tc2_SerialCom", "Tc2_MC2")

DECLS = """sdo : FB_EcCoESdoRead; count : FB_EcGetSlaveCount; buf : ARRAY[0..3] OF BYTE; n : INT;
    sock : FB_ConnectionlessSocket; send : FB_SocketUdpSendTo; coils : FB_MBReadCoils; name : IOF_GetBoxNameByAddr;
    line : SerialLineControl; tx : ComBuffer; rx : ComBuffer; out : SendString;
    axis : AXIS_REF; power : MC_Power; move : MC_MoveAbsolute; pos : MC_ReadActualPosition;"""
BODY = """n := n + 1;
sdo(sNetId := '', nSlaveAddr := 1001, nIndex := 16#1018, nSubIndex := 1, pDstBuf := ADR(buf), cbBufLen := 4,
    bExecute := n >= 2);
count(sNetId := '', bExecute := n >= 3);
sock(nMode := CONNECT_MODE_ENABLEDBG, bEnable := TRUE);
send(hSocket := sock.hSocket, sRemoteHost := '10.0.0.1', nRemotePort := 514, cbLen := 4, pSrc := ADR(buf),
    bExecute := TRUE);
coils(sIPAddr := '10.0.0.2', nQuantity := 8, nMBAddr := 0, cbLength := 1, pDestAddr := ADR(buf), bExecute := TRUE);
name(NETID := '', DEVICEID := 1, BOXADDR := 1001, START := TRUE);
line(Mode := SERIALLINEMODE_PC_COM_PORT, pComIn := 0, pComOut := 0, SizeComIn := 0, TxBuffer := tx, RxBuffer := rx);
out(SendString := 'hello', TXbuffer := tx);
power(Axis := axis, Enable := TRUE, Enable_Positive := TRUE, Enable_Negative := TRUE);
move(Axis := axis, Execute := TRUE, Position := 100, Velocity := 10);
pos(Axis := axis, Enable := TRUE);"""


def test_a_call_falls_through_busy_into_the_documented_error():
    r = runner(DECLS, BODY, *LIBS, profile="twincat")
    got = trace(r, 3, "sdo.bBusy", "sdo.bError", "sdo.nErrId", "count.bError")
    # nothing before the rising edge of bExecute; then bBusy FALSE, bError TRUE at once
    assert got == [(False, False, 0, False), (False, True, ADSERR_DEVICE_SRVNOTSUPP, False)] + [
        (False, True, ADSERR_DEVICE_SRVNOTSUPP, True)
    ]
    assert (r.get("sock.bError"), r.get("sock.nErrId"), r.get("send.nErrId")) == (True, 0x701, 0x701)
    assert (r.get("coils.bError"), r.get("coils.bBusy"), r.get("name.ERR"), r.get("name.ERRID")) == (
        True,
        False,
        True,
        0x701,
    )
    assert (r.get("line.Error"), r.get("line.ErrorID"), r.get("out.Error")) == (True, COMERROR_MODENOTSUPPORTED, 0x0101)
    assert (r.get("power.Status"), r.get("power.Error"), r.get("move.Error"), r.get("move.Done")) == (
        False,
        True,
        True,
        False,
    )
    assert (r.get("pos.Valid"), r.get("pos.ErrorID")) == (False, 0x701)


def test_each_library_used_warns_once_and_an_unused_one_not_at_all():
    src = {
        "a.st": f"PROGRAM A VAR {DECLS} END_VAR {BODY} END_PROGRAM",
        "b.st": f"PROGRAM B VAR {DECLS} END_VAR {BODY} END_PROGRAM",
    }
    diags, _ = check_files(
        [], texts=src, profile="twincat", libraries=chosen(*LIBS, "Tc2_MC2")
    )  # named twice: taken once
    assert not [d for d in diags if d.is_error]
    assert sorted(d.message.split(" ")[0] for d in diags if d.code == "W230") == sorted(LIBS)
    src = {"a.st": "PROGRAM A VAR x : INT; END_VAR x := x + 1; END_PROGRAM"}
    assert check_files([], texts=src, profile="twincat", libraries=chosen(*LIBS))[0] == []


def test_the_ethercat_state_texts_compute():
    decls = "s : ST_EcSlaveState; t1 : STRING; t2 : STRING; id : ST_EcSlaveIdentity; t3 : STRING;"
    body = """s.deviceState := EC_DEVICE_STATE_OP; t1 := F_ConvSlaveStateToString(s);
    s.deviceState := EC_DEVICE_STATE_PREOP OR EC_DEVICE_STATE_ERROR; s.linkState := EC_LINK_STATE_NOT_PRESENT;
    t2 := F_ConvSlaveStateToString(s); id.productCode := 16#0C1E3052; t3 := F_ConvProductCodeToString(id);"""
    r = runner(decls, body, "Tc2_EtherCAT", profile="twincat")
    r.run(1)
    assert (r.get("t1"), r.get("t2"), r.get("t3")) == ("OP", "PREOP ERR NOT_PRESENT", "EL3102")
