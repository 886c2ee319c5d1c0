"""Reading a project's own files (.sln, .plcproj, .TcTTO, beremiz.xml):
UTF-8 (a byte order mark allowed) or Latin-1, as Windows tools write them;
a file that cannot be read is E000 at its first line."""

from __future__ import annotations

from pathlib import Path

from ..st.ast import Pos
from ..st.limits import MAX_SOURCE_CHARS
from .model import Project


def read_text(path: Path, project: Project) -> str | None:
    """The text of path, kept in project.texts for the messages; None with
    E000 when it cannot be read."""
    try:
        with open(path, "rb") as f:
            data = f.read(4 * MAX_SOURCE_CHARS + 4)
    except OSError as exc:
        project.diags.error("E000", f"cannot read the file: {exc.strerror or exc}", Pos(str(path), 1, 1))
        return None
    try:
        text = data.decode("utf-8-sig")
    except UnicodeDecodeError:
        text = data.decode("latin-1")
    project.texts[str(path)] = text
    return text
