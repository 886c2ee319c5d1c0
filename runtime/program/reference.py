"""The shipped ST libraries as a reference (the documentation site's
"Function blocks" page, docs: tools/mkdocs_hooks.py): each POU's
declaration as its file writes it, from the header to the end of its
interface (VAR_INPUT, VAR_OUTPUT, VAR_IN_OUT; the comments among them
included), grouped by library. Generated from the files, so that the page
says what a program gets."""

from __future__ import annotations

from importlib import resources
from pathlib import Path

from ...fblocks.libs import SHIPPED
from ..st import ast as A
from ..st.profile import DEFAULT, get_profile
from .libraries import parse_cached
from .shipped import as_library

#: the folders of softplc.fblocks compiled into every program (or on use)
BUILT_IN = ("iec", "system", "comm", "vendor")
_INTERFACE = ("VAR_INPUT", "VAR_OUTPUT", "VAR_IN_OUT")
_KINDS = ("FUNCTION_BLOCK", "FUNCTION")


def library_reference() -> str:
    out = [
        "# Function blocks and functions",
        "",
        "What the shipped ST libraries declare, as their files write it (generated from the files).",
        "The built-in ones are compiled into every program that names them; a library of the",
        'second part is chosen by name: `[plc] libraries = ["Tc2_Utilities"]` or `--library`.',
        "",
        "## Built in",
        "",
    ]
    root = resources.files("softplc.fblocks")
    for folder in BUILT_IN:
        for path in sorted(Path(str(root.joinpath(folder))).glob("*.st")):
            out += _file_section(f"{folder}/{path.name}", path, DEFAULT)
    out += ["## Libraries chosen by name", ""]
    for spec in SHIPPED:
        lib = as_library(spec)
        profile = get_profile(spec.profile) if spec.profile else DEFAULT
        aliases = f" (also: {', '.join(spec.aliases)})" if spec.aliases else ""
        out += [f"### {spec.name}{aliases}", ""]
        if spec.unavailable:
            out += [f"Declared for porting; {spec.unavailable}.", ""]
        for path in sorted(lib.files(), key=lambda p: p.name):
            out += _file_section(path.name, path, profile, level="####")
    return "\n".join(out) + "\n"


def _file_section(title: str, path: Path, profile, level: str = "###") -> list:
    text = path.read_text("utf-8")
    lines = text.splitlines()
    files, _ = parse_cached(str(path), text, profile)
    pous = [d for sf in files for d in sf.decls if isinstance(d, A.POU) and d.kind in _KINDS]
    if not pous:
        return []
    out = [f"{level} `{title}`", ""]
    for pou in pous:
        interface = [b for b in pou.var_blocks if b.kind in _INTERFACE]
        last = max((b.pos.end_line for b in interface), default=pou.pos.line)
        out += [f"**`{pou.name}`** ({pou.kind.lower().replace('_', ' ')})", "", "```iecst"]
        out += lines[pou.pos.line - 1 : last]
        out += ["```", ""]
    return out
