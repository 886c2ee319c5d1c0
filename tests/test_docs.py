"""The manual's code blocks run (issue 34: a manual that cannot lie). Every
fenced block of README.md and docs/ is a test, by its language:

  python  executed; each test_... function it defines is called (one
          parametrisation of a parametrised one)
  iecst   compiled, with the page's earlier ST blocks and the assertion
          natives of softplc test (a page's blocks build on each other)
  toml    read, then checked: a sweep file as softplc sweep checks it, any
          other as tables of a configuration (pass 1: every key known, every
          value of its type)
  sh      every softplc command run (`.venv/bin/softplc` too), in a folder
          that has the repository's io_config/ and st_programs/, `cd`
          followed; exit code 0. Lines that install, build or call other
          programs (pip, python3 -m venv, bash, mkdocs, openssl, pytest) are
          the reader's, and a synopsis (`softplc run [CONFIG ...]`) is no
          command.

An HTML comment right before a fence says more:
  <!-- docs-test: skip REASON -->             not run, with the reason
  <!-- docs-test: before CMD; CMD -->         commands run first (the page's
                                              earlier steps: softplc new mixer)
  <!-- docs-test: in [[sim]] KEY = VALUE ... -->  the keys of one [[sim]] table,
                                              checked in one with these keys
Text, JSON and unlabelled blocks (diagrams, outputs) are not run.
"""

from __future__ import annotations

import os
import re
import shlex
import subprocess
import sys
import tomllib
from dataclasses import dataclass
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
PAGES = [ROOT / "README.md", *sorted((ROOT / "docs").rglob("*.md"))]
RUN = ("python", "iecst", "toml", "sh")
_FENCE = re.compile(r"(?:<!-- docs-test: (?P<note>[^>]*?) -->\n)?^```(?P<lang>\w*)\n(?P<body>.*?)^```", re.M | re.S)
#: programs a command block may name that the runner leaves to the reader
READERS = ("pip", "python3", "python", "bash", "mkdocs", "openssl", "pytest", "cd ..", "sudo", "systemctl", "docker")
TIMEOUT_S = 180


@dataclass(frozen=True)
class Block:
    page: Path
    line: int
    lang: str
    body: str
    note: str
    earlier_st: tuple  # the page's ST blocks before this one

    @property
    def id(self) -> str:
        return f"{self.page.relative_to(ROOT)}:{self.line}"


def blocks() -> list:
    found = []
    for page in PAGES:
        text = page.read_text(encoding="utf-8")
        st: list = []
        for m in _FENCE.finditer(text):
            lang = m.group("lang")
            line = text[: m.start("lang")].count("\n") + 1
            block = Block(page, line, lang, m.group("body"), m.group("note") or "", tuple(st))
            if lang == "iecst":
                st.append(m.group("body"))
            if lang in RUN:
                found.append(block)
    return found


BLOCKS = blocks()


def test_the_manual_has_blocks_of_every_kind_the_runner_runs():
    assert {b.lang for b in BLOCKS} == set(RUN)
    assert len(BLOCKS) > 30


@pytest.mark.parametrize("block", BLOCKS, ids=lambda b: b.id)
def test_block(block: Block, tmp_path, monkeypatch):
    note = block.note
    if note.startswith("skip"):
        pytest.skip(f"{block.id}: {note[4:].strip()}")
    monkeypatch.chdir(tmp_path)
    for link in ("io_config", "st_programs"):
        (tmp_path / link).symlink_to(ROOT / link)
    {"python": _python, "iecst": _st, "toml": _toml, "sh": _sh}[block.lang](block, tmp_path)


def _python(block: Block, _where: Path) -> None:
    scope: dict = {"__name__": f"docs_{block.line}"}
    exec(compile(block.body, block.id, "exec"), scope)
    for name, fn in list(scope.items()):
        if not (name.startswith("test_") and callable(fn)):
            continue
        marks = getattr(fn, "pytestmark", [])
        params = [m for m in marks if m.name == "parametrize"]
        if params:
            argname, values = params[0].args[0], params[0].args[1]
            first = values[0].values[0] if hasattr(values[0], "values") else values[0]
            fn(**{argname: first})
        else:
            fn()


def _st(block: Block, _where: Path) -> None:
    from softplc.runtime.program import compile_files
    from softplc.runtime.testing.natives import NATIVES

    texts = {f"{block.id}-{i}.st": text for i, text in enumerate((*block.earlier_st, block.body))}
    compile_files([], texts=texts, natives=NATIVES)  # CompileError names the block's line


def _toml(block: Block, where: Path) -> None:
    from softplc.runtime.config.load import _Document
    from softplc.runtime.plugin.registry import registry
    from softplc.runtime.sweep.matrix import sweep_from_dict

    data = tomllib.loads(block.body)
    if block.note.startswith("in [[sim]]"):  # the keys of one [[sim]] table: in one, of the type given
        data = {"sim": [{**tomllib.loads(block.note[len("in [[sim]]") :].replace('" ', '"\n')), **data}]}
    if {"matrix", "scenario", "random"} & set(data):
        sweep_from_dict(data, block.id)
        return
    (where / "main.st").write_text("PROGRAM Main\nEND_PROGRAM\n", encoding="utf-8")
    data.setdefault("plc", {"programs": ["main.st"]})
    if "programs" in data["plc"]:
        data["plc"]["programs"] = ["main.st"]  # the block's are the reader's files
    data["plc"].pop("libraries", None)
    root = _Document(registry()).root
    root.model_validate(data, context={"base_dir": where})


def _sh(block: Block, where: Path) -> None:
    cwd = where
    before = block.note[len("before") :].split(";") if block.note.startswith("before") else []
    for command in [*before, *_commands(block.body)]:
        words = _without_environment(shlex.split(command, comments=True))
        if not words:
            continue
        if words[0] == "cd":
            cwd = (cwd / words[1]).resolve()
            continue
        program = Path(words[0]).name
        if words[0].startswith("["):  # a synopsis's next line
            continue
        if program != "softplc" or _is_synopsis(words):
            assert program in READERS or program == "softplc", f"{block.id}: {command!r}: run what?"
            continue
        done = subprocess.run(
            [sys.executable, "-m", "softplc.runtime.cli", *words[1:]],
            cwd=cwd,
            capture_output=True,
            text=True,
            timeout=TIMEOUT_S,
            env={**os.environ, "PYTHONDONTWRITEBYTECODE": "1"},
            stdin=subprocess.DEVNULL,
        )
        assert done.returncode == 0, f"{block.id}: {command}\n{done.stderr[-3000:]}"


def _commands(body: str) -> list:
    """The block's commands: continued lines joined, `&&` chains split."""
    joined = re.sub(r"\\\n\s*", " ", body)
    out = []
    for line in joined.splitlines():
        out += [part.strip() for part in line.split("&&")]
    return [c for c in out if c and not c.startswith("#")]


def _is_synopsis(words: list) -> bool:
    """`softplc run [CONFIG | PROJECT] ...`: brackets, bars, ellipses, NAME placeholders."""
    return any(
        w.startswith("[") or w == "|" or w.endswith(("...", "…")) or re.fullmatch(r"[A-Z]{3,}", w) for w in words[1:]
    )


def _without_environment(words: list) -> list:
    """The command without its leading NAME=value assignments."""
    while words and re.fullmatch(r"[A-Za-z_][A-Za-z0-9_]*=.*", words[0]):
        words = words[1:]
    return words
