"""Small projects for the tests of runtime/project/: copies of the
self-written projects beside this file, with POUs added the way TwinCAT
adds them (a .TcPOU file, a <Compile Include> in the .plcproj)."""

from __future__ import annotations

import shutil
from pathlib import Path

HERE = Path(__file__).parent

#: a block that needs Tc3_JsonXml (referenced by the project, not in softplc)
LOGGER = (
    """FUNCTION_BLOCK FB_Logger
VAR_INPUT
    sIn : STRING;
END_VAR
VAR
    sLine : SJsonValue;
    fbJson : FB_JsonSaxWriter;
    nCopied : UDINT;
END_VAR
""",
    """fbJson.AddString(sIn);
nCopied := nCopied + 1;
sLine := CONCAT(sLine, '!');""",
)
#: a block with an error of its own (a typing mistake)
BROKEN = (
    """FUNCTION_BLOCK FB_Broken
VAR
    nCount : INT;
END_VAR
""",
    """nCount := nCuont + 1;""",
)
#: a block without errors that uses the broken one
USES_BROKEN = (
    """FUNCTION_BLOCK FB_UsesBroken
VAR
    fbInner : FB_Broken;
END_VAR
""",
    """fbInner();""",
)


def tcpou(name: str, declaration: str, implementation: str) -> str:
    return f"""<?xml version="1.0" encoding="utf-8"?>
<TcPlcObject Version="1.1.0.1" ProductVersion="3.1.4024.12">
  <POU Name="{name}" Id="{{00000000-0000-4000-8000-000000000000}}" SpecialFunc="None">
    <Declaration><![CDATA[{declaration}]]></Declaration>
    <Implementation>
      <ST><![CDATA[{implementation}]]></ST>
    </Implementation>
  </POU>
</TcPlcObject>
"""


def twincat(tmp_path: Path, *pous: tuple) -> Path:
    """A copy of the TwinCAT solution with the POUs (name, (declaration,
    implementation)) added to its PLC project; returns the copy's folder."""
    root = tmp_path / "twincat"
    shutil.copytree(HERE / "twincat", root)
    plc = root / "Plant" / "Plc"
    plcproj = plc / "Plc.plcproj"
    text = plcproj.read_text()
    for name, (declaration, implementation) in pous:
        (plc / "POUs" / f"{name}.TcPOU").write_text(tcpou(name, declaration, implementation))
        entry = f'    <Compile Include="POUs\\{name}.TcPOU">\n      <SubType>Code</SubType>\n    </Compile>\n'
        text = text.replace("  </ItemGroup>", entry + "  </ItemGroup>", 1)
    plcproj.write_text(text)
    return root


def line_of(path: Path, needle: str) -> int:
    """The line of path that holds needle (one-based)."""
    return path.read_text().split(needle)[0].count("\n") + 1
