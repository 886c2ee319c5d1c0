"""The vendor libraries softplc ships, as softplc libraries (issue 30):
Beckhoff's Tc2_*, CODESYS's Standard/Util/StringUtils/CAA types, TcUnit
and the like, each a folder of ST files (a sub-package of this one), with
the Python functions it needs beside them.

A program gets a library when it asks for it: ``[plc] libraries =
["Tc2_System"]`` in a configuration, ``--library Tc2_System`` on the
command line, or a project that references it (a TwinCAT .plcproj's
PlaceholderReference, a CODESYS export's libraries). Its files are then
compiled in as far as the program names what they declare, like a user
library (runtime/program/libraries.py), and its names may be qualified by
the library's name (``Tc2_System.MEMCPY``) or its other namespaces.

``catalogue.toml`` lists what the common vendor libraries declare, shipped
or not, so that an unknown name says which library it comes from.
"""

from __future__ import annotations

from dataclasses import dataclass


@dataclass(frozen=True)
class LibrarySpec:
    """A library softplc ships.

    name: as the vendor names it (``Tc2_System``), also its namespace;
    package: the sub-package holding its ST files (``softplc.fblocks.libs.tc2_system``);
    tools: the kinds of project that have it (``twincat``, ``codesys``, ``beremiz``);
    profile: how its files read (None: as the program's);
    namespaces: further names its names may be qualified with (``CAA``);
    aliases: other names a project references it by (a CODESYS placeholder);
    functions: a module whose ``FUNCTIONS`` (name -> fblocks.iec.functions.StdFunc)
      are functions of the library written in Python;
    natives: a module whose ``NATIVES`` (runtime.st.native.NativeFunction) are
      functions of the library that a service of the runtime answers (the
      clock of SysTime, TcUnit's test bookkeeping bound by the test runner),
      declared whenever the library is chosen;
    unavailable: why it cannot do its work here ('' when it can): a library
      of hardware or a runtime service (EtherCAT, ADS, NC axes, the event
      logger) is declared with its real signatures so that a project
      compiles, its blocks answer "not available" through their own error
      outputs, and a program that uses it gets one warning saying so;
    unavailable_parts: ((file name, why), ...): the same for one file of a
      library that otherwise works (Tc2_System's ADS and file blocks): a
      program that uses what the file declares gets one warning for it;
    requires: the names of the shipped libraries its files use (Tc2_Utilities
      uses Tc2_System's T_MaxString and MEMCPY, SysCom SysTypes2 Interfaces'
      RTS_IEC_HANDLE): a program that chooses it gets them too.
    """

    name: str
    package: str
    tools: tuple = ()
    profile: str | None = None
    namespaces: tuple = ()
    aliases: tuple = ()
    functions: str | None = None
    natives: str | None = None
    unavailable: str = ""
    unavailable_parts: tuple = ()
    requires: tuple = ()


_CODESYS = ("codesys",)
_SYSTEM = ("codesys", "twincat")  # CODESYS's system libraries, which TwinCAT 3 has too
_TWINCAT = ("twincat",)

_ADS = "the blocks answer ERR/bError TRUE with ADS error 6, target port not found"

#: the shipped libraries
SHIPPED: tuple[LibrarySpec, ...] = (
    # ---------------------------------------------------------------- CODESYS
    LibrarySpec(
        "Standard",
        "softplc.fblocks.libs.standard",
        tools=_CODESYS,
        profile="codesys",
        functions="softplc.fblocks.libs.standard.functions",
    ),
    LibrarySpec("Util", "softplc.fblocks.libs.util", tools=_CODESYS, profile="codesys"),
    LibrarySpec(
        "StringUtils",
        "softplc.fblocks.libs.stringutils",
        tools=_CODESYS,
        profile="codesys",
        namespaces=("Stu",),
        functions="softplc.fblocks.libs.stringutils.functions",
    ),
    LibrarySpec(
        "CAA Types",
        "softplc.fblocks.libs.caa_types",
        tools=_CODESYS,
        profile="codesys",
        namespaces=("CAA",),
        aliases=("CAA_Types", "CAA Types Extern"),
    ),
    LibrarySpec(
        "SysTypes2 Interfaces",
        "softplc.fblocks.libs.systypes",
        tools=_SYSTEM,
        profile="codesys",
        namespaces=("SysTypes", "CmpErrors", "Errors"),
        aliases=("SysTypes", "SysTypes2", "CmpErrors", "CmpErrors Interfaces", "CmpErrors2 Interfaces"),
    ),
    LibrarySpec(
        "SysTime",
        "softplc.fblocks.libs.systime",
        tools=_SYSTEM,
        profile="codesys",
        namespaces=("SysTimeRtc",),
        aliases=("SysTimeRtc", "SysTimeCore"),
        natives="softplc.fblocks.libs.systime.natives",
        requires=("SysTypes2 Interfaces",),
    ),
    *(
        LibrarySpec(
            name,
            f"softplc.fblocks.libs.{name.lower()}",
            tools=_SYSTEM,
            profile="codesys",
            requires=("SysTypes2 Interfaces",),
            unavailable=why,
        )
        for name, why in (
            ("SysFile", "softplc gives a program no file system (every call answers ERR_NOTIMPLEMENTED)"),
            ("SysDir", "softplc gives a program no file system (every call answers ERR_NOTIMPLEMENTED)"),
            ("SysSocket", "softplc gives a program no sockets of its own (every call answers ERR_NOTIMPLEMENTED)"),
            (
                "SysCom",
                "a program's serial ports are softplc's Modbus RTU buses (every call answers ERR_NOTIMPLEMENTED)",
            ),
        )
    ),
    # ---------------------------------------------------------------- Beckhoff, of hardware or a service
    *(
        LibrarySpec(name, f"softplc.fblocks.libs.{name.lower()}", tools=_TWINCAT, profile="twincat", unavailable=why)
        for name, why in (
            ("Tc2_EtherCAT", "it needs TwinCAT's EtherCAT master (a call fails with ADS error 16#701)"),
            ("Tc2_TcpIp", "it needs the TwinCAT TCP/IP Connection Server (a call fails with ADS error 16#701)"),
            ("Tc2_ModbusSrv", "it needs the TwinCAT Modbus TCP server (a call fails with ADS error 16#701)"),
            ("Tc2_IoFunctions", "it needs the TwinCAT I/O server (a call fails with ADS error 16#701)"),
            ("Tc2_SerialCom", "its serial lines are TwinCAT's (ErrorID COMERROR_MODENOTSUPPORTED)"),
            ("Tc2_MC2", "its axes are TwinCAT NC's (a command fails with ErrorID 16#701)"),
        )
    ),
    LibrarySpec(
        "Tc3_EventLogger",
        "softplc.fblocks.libs.tc3_eventlogger",
        tools=_TWINCAT,
        profile="twincat",
        requires=("Tc2_System",),
        unavailable="it needs TwinCAT's event logger (a call returns the HRESULT 16#98110701)",
    ),
    # ---------------------------------------------------------------- TcUnit
    # TcUnit (tcunit.org), the unit-test framework of TwinCAT: its API, run by `softplc test`
    LibrarySpec(
        "TcUnit",
        "softplc.fblocks.libs.tcunit",
        tools=("twincat",),
        profile="twincat",
        natives="softplc.fblocks.libs.tcunit.natives",
    ),
    # Beckhoff TwinCAT 3 (fblocks/libs/tc2_*: docs/guide/running.md "Libraries softplc ships")
    LibrarySpec(
        "Tc2_Standard",
        "softplc.fblocks.libs.tc2_standard",
        tools=("twincat",),
        profile="twincat",
        functions="softplc.fblocks.libs.tc2_standard.functions",
    ),
    LibrarySpec(
        "Tc2_System",
        "softplc.fblocks.libs.tc2_system",
        tools=("twincat",),
        profile="twincat",
        namespaces=("TwinCAT_SystemInfoVarList",),
        functions="softplc.fblocks.libs.tc2_system.functions",
        unavailable_parts=(
            ("ads.st", f"it needs TwinCAT's ADS router ({_ADS})"),
            ("files.st", f"softplc writes no files for a PLC program ({_ADS})"),
        ),
    ),
    LibrarySpec(
        "Tc2_Utilities",
        "softplc.fblocks.libs.tc2_utilities",
        tools=("twincat",),
        profile="twincat",
        functions="softplc.fblocks.libs.tc2_utilities.functions",
        unavailable_parts=(("services.st", f"softplc does not act on the computer for a PLC program ({_ADS})"),),
        requires=("Tc2_System",),
    ),
    LibrarySpec("Tc2_Math", "softplc.fblocks.libs.tc2_math", tools=("twincat",), profile="twincat"),
)
