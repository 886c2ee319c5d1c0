"""Beckhoff's Tc3_EventLogger (fblocks/libs/tc3_eventlogger), declared: a
program's messages, alarms, listeners and text requests compile with the
library's signatures, keep the program's own data (arguments, source
name, JSON attribute) and answer every call to TwinCAT's event logger
with a failing HRESULT; W230 once per program."""

from __future__ import annotations

from softplc.runtime.program import check_files, compile_files

from .bench import chosen

NOT_AVAILABLE = -1743714559  # 16#98110701: ADS error 16#701 as an HRESULT

DECLS = """msg : FB_TcMessage; alarm : FB_TcAlarm; src : FB_TcSourceInfo; ip : I_TcMessage; entry : TcEventEntry;
    hrCreate : HRESULT; hrSend : HRESULT; hrAlarm : HRESULT; hrRaise : HRESULT; bad : BOOL; sev : TcEventSeverity;
    name : STRING; json : STRING; active : BOOL; id : UDINT; txt : FB_RequestEventText;
    listener : Listener; hrListen : HRESULT;"""
BODY = """entry.nEventId := 3; entry.eSeverity := TcEventSeverity.Error; src.sName := 'Main.Pump';
hrCreate := msg.CreateEx(entry, src); msg.ipArguments.Clear(); msg.ipArguments.AddString('overpressure');
msg.SetJsonAttribute('{"bar":7}'); hrSend := msg.Send(0); bad := FAILED(hrSend);
hrAlarm := alarm.CreateEx(stEventEntry := entry, bWithConfirmation := TRUE, ipSourceInfo := src);
hrRaise := alarm.Raise(0);
ip := msg; sev := ip.eSeverity; name := src.sName; msg.GetJsonAttribute(json, SIZEOF(json));
txt.Request(eventClass := msg.EventClass, nEventId := msg.nEventId, nLangId := 1033, ipArgs := msg.ipArguments);
hrListen := listener.Execute(); active := alarm.bActive; id := msg.nEventId;"""
LISTENER = """FUNCTION_BLOCK Listener EXTENDS FB_ListenerBase2
VAR_OUTPUT seen : INT; END_VAR
METHOD OnMessageSent
VAR_INPUT fbEvent : REFERENCE TO FB_TcEvent; END_VAR
seen := seen + 1;
END_METHOD
END_FUNCTION_BLOCK
"""


def test_the_calls_to_the_logger_fail_and_the_program_keeps_its_own_data():
    src = {"main.st": f"{LISTENER}PROGRAM Main VAR {DECLS} END_VAR {BODY} END_PROGRAM"}
    prog = compile_files([], texts=src, profile="twincat", libraries=chosen("Tc3_EventLogger"))
    r = prog.runner("Main", cycle_time_ms=10)
    r.run(1)
    assert [r.get(n) for n in ("hrCreate", "hrSend", "hrAlarm", "hrRaise", "hrListen")] == [NOT_AVAILABLE] * 5
    assert r.get("bad") is True and r.get("active") is False
    # the event entry, the source and the JSON attribute are the program's
    assert (r.get("sev"), r.get("id"), r.get("name"), r.get("json")) == (3, 3, "Main.Pump", '{"bar":7}')
    assert (r.get("txt.bError"), r.get("txt.bBusy"), r.get("txt.hrErrorCode")) == (True, False, NOT_AVAILABLE)
    assert r.get("listener.seen") == 0  # no event arrives


def test_one_warning_for_a_program_that_uses_it_none_for_one_that_does_not():
    src = {
        "a.st": f"{LISTENER}PROGRAM A VAR {DECLS} END_VAR {BODY} END_PROGRAM",
        "b.st": f"PROGRAM B VAR {DECLS} END_VAR {BODY} END_PROGRAM",
    }
    diags, _ = check_files([], texts=src, profile="twincat", libraries=chosen("Tc3_EventLogger"))
    assert not [d for d in diags if d.is_error]
    assert [d.message.split(" ")[0] for d in diags if d.code == "W230"] == ["Tc3_EventLogger"]
    src = {"a.st": "PROGRAM A VAR x : INT; END_VAR x := x + 1; END_PROGRAM"}
    assert check_files([], texts=src, profile="twincat", libraries=chosen("Tc3_EventLogger"))[0] == []
