"""TcUnit's own verifier run by softplc: how many of its expectations hold.

TcUnit (github.com/tcunit/TcUnit, MIT) checks itself with TcUnit-Verifier:
a TwinCAT project of test suites (TcUnit-Verifier_TwinCAT) whose results a
.NET program (TcUnit-Verifier_DotNet) reads from TwinCAT's error list and
compares with what it expects: for each suite, messages that must be
there ("FAILED TEST 'PRG_TEST.PrimitiveTypes@Test_INT_Differ', EXP: -32000,
ACT: 15423, MSG: Values differ"), must not, or must be there n times. This
script runs the TwinCAT project with `softplc test`'s runner (the project's
task, TcUnit's RUN in virtual time), reads those expectations from the .NET
sources (a small reader of the C# calls they make) and counts, per suite,
how many hold on TcUnit's log as softplc writes it.

    python benchmarks/tcunit_verifier.py /work/projects/tcunit+TcUnit/TcUnit-Verifier
    python benchmarks/tcunit_verifier.py VERIFIER --library Tc2_System=/path/to/stand-ins -v

The project is run from a copy in a temporary folder, without the suites
that do not compile (their instances taken out of PRG_TEST): those are
listed with the first error of each. --library NAME=FOLDER adds a folder of
ST as library NAME (stand-ins for a library softplc does not ship yet).
Nothing of the verifier is kept. Nothing is asserted: the numbers are a
measurement (README: "TcUnit tests").
"""

from __future__ import annotations

import argparse
import re
import shutil
import sys
import tempfile
from dataclasses import dataclass, field
from pathlib import Path

from softplc.runtime.program import Library
from softplc.runtime.project import open_projects
from softplc.runtime.project.analysis import analyse
from softplc.runtime.project.running import project_config
from softplc.runtime.testing.tcunit import run_tcunit, tcunit_library

LEVELS = {"High": "error", "Medium": "warning", "Low": "hint"}
_TOKEN = re.compile(r'\s*(?:("(?:[^"\\]|\\.)*")|([A-Za-z_][\w.]*)|(\d+(?:\.\d+)?)|(.))', re.S)
_FLOAT = r"[+-]?(\d+([.]\d*)?([eE][+-]?\d+)?|[.]\d+([eE][+-]?\d+)?)"


@dataclass
class Check:
    suite: str  # the .NET class (FB_PrimitiveTypes)
    what: str  # the call, shown when it does not hold
    holds: bool


@dataclass
class Suite:
    name: str
    checks: list[Check] = field(default_factory=list)
    skipped: list[str] = field(default_factory=list)  # statements the reader does not take


# ---------------------------------------------------------------- the log


class Log:
    """TcUnit's messages as TwinCAT's error list holds them for the
    verifier: upper-cased descriptions with a level."""

    def __init__(self, lines) -> None:
        self.items = [(line.text.upper(), line.level) for line in lines]

    def count(self, message: str, level: str) -> int:
        if "%f" not in message:
            want = message.upper()
            return sum(1 for text, lv in self.items if want in text and lv == level)
        pattern = re.compile(".*?" + re.escape(message).replace("%f", _FLOAT) + ".*?", re.I)
        return sum(1 for text, lv in self.items if pattern.match(text) and lv == level)

    def has_both(self, ident: str, message: str, level: str) -> bool:
        return any(ident.upper() in t and message.upper() in t and lv == level for t, lv in self.items)

    def result_set(self, test: str, cls: str, status: str, asserts: int) -> bool:
        for i, (text, lv) in enumerate(self.items):
            if lv == "hint" and f"| TEST NAME={test}".upper() in text:
                nxt = self.items[i + 1 : i + 3]
                if len(nxt) < 2 or f"| TEST CLASS NAME={cls}".upper() not in nxt[0][0]:
                    return False
                m = re.search(r"TEST STATUS=(\w+), NUMBER OF ASSERTS=(\d+)", nxt[1][0])
                return bool(m) and m.group(1) == status.upper() and int(m.group(2)) == asserts
        return False


# ---------------------------------------------------------------- the C# reader


def _tokens(text: str) -> list:
    out = []
    for m in _TOKEN.finditer(text):
        s, ident, num, punct = m.groups()
        if s is not None:
            out.append(("str", bytes(s[1:-1], "utf-8").decode("unicode_escape")))
        elif ident is not None:
            out.append(("id", ident))
        elif num is not None:
            out.append(("num", float(num) if "." in num else int(num)))
        elif punct is not None and not punct.isspace():
            out.append(("p", punct))
    return out


class _Reader:
    """Evaluates the statements of one method of a verifier class."""

    def __init__(self, instance: str, log: Log, suite: Suite) -> None:
        self.instance = instance
        self.log = log
        self.suite = suite
        self.vars: dict = {}

    def failed_prefix(self, method: str) -> str:
        return f"FAILED TEST 'PRG_TEST.{self.instance}@{method}'"

    def statement(self, toks: list) -> None:
        if toks and toks[0] == ("id", "var") or (toks and toks[0][0] == "id" and toks[0][1] in ("string", "int")):
            toks = toks[1:]
            if toks[:2] == [("p", "["), ("p", "]")]:
                toks = toks[2:]
        if len(toks) >= 2 and toks[0][0] == "id" and toks[1] == ("p", "="):
            self.vars[toks[0][1]], _ = self.expr(toks, 2)
            return
        if len(toks) >= 2 and toks[0][0] == "id" and toks[0][1].startswith("Assert") and toks[1] == ("p", "("):
            value, _ = self.expr(toks, 0)
            return
        self.suite.skipped.append(" ".join(str(v) for _k, v in toks)[:80])

    def expr(self, toks: list, i: int):
        value, i = self.primary(toks, i)
        while i < len(toks) and toks[i] == ("p", "+"):
            right, i = self.primary(toks, i + 1)
            value = f"{value}{right}"
        return value, i

    def primary(self, toks: list, i: int):
        kind, v = toks[i]
        if kind in ("str", "num"):
            return v, i + 1
        if kind == "id" and v == "new":  # new String[] { a, b }
            while toks[i] != ("p", "{"):
                i += 1
            items, i = self.args(toks, i + 1, "}")
            return items, i
        if kind == "id" and i + 1 < len(toks) and toks[i + 1] == ("p", "("):
            args, j = self.args(toks, i + 2, ")")
            return self.call(v, args), j
        if kind == "id":
            if v.startswith("EnvDTE80."):
                return LEVELS[v.rsplit("vsBuildErrorLevel", 1)[1]], i + 1
            if v == "_testFunctionBlockInstance":
                return self.instance, i + 1
            return self.vars.get(v, f"<{v}>"), i + 1
        raise ValueError(f"unexpected {v!r}")

    def args(self, toks: list, i: int, close: str):
        out = []
        while toks[i] != ("p", close):
            value, i = self.expr(toks, i)
            out.append(value)
            if toks[i] == ("p", ","):
                i += 1
        return out, i + 1

    def call(self, name: str, a: list):
        log, check = self.log, self._check
        if name == "CreateFailedTestMessage":
            return f"{self.failed_prefix(a[0])}, EXP: {a[1]}, ACT: {a[2]}, MSG: {a[3]}"
        if name == "CreateFailedTestMessageNoAssertionMessage":
            return f"{self.failed_prefix(a[0])}, EXP: {a[1]}, ACT: {a[2]}"
        if name == "CreateFailedTestCommonString":
            return self.failed_prefix(a[0])
        if name == "AssertContainsMessage":
            return check(f"contains {a[0]!r}", log.count(a[0], a[1]) > 0)
        if name == "AssertDoesNotContainMessage" and len(a) == 2:
            return check(f"does not contain {a[0]!r}", log.count(a[0], a[1]) == 0)
        if name == "AssertDoesNotContainMessage":
            ident = self.failed_prefix(a[0])
            return check(f"{ident} without {a[1]!r}", not log.has_both(ident, a[1], a[2]))
        if name == "AssertMessageCount":
            found = log.count(a[0], a[2])
            return check(f"{a[1]} x {a[0]!r} (found {found})", found == a[1])
        if name == "AssertContainsAtLeastOneMessage":
            return check(f"one of {a[0]!r}", any(log.count(m, a[1]) > 0 for m in a[0]))
        if name == "AssertAtLeastOneMessageCount":
            found = sum(log.count(m, a[2]) for m in a[0])
            return check(f"{a[1]} x one of {a[0]!r} (found {found})", found == a[1])
        if name == "AssertContainsResultSet":  # (duration: measured in engine time here, not compared)
            return check(f"result set of {a[0]}: {a[2]}, {a[3]} asserts", log.result_set(a[0], a[1], a[2], a[3]))
        raise ValueError(f"unknown call {name}")

    def _check(self, what: str, holds: bool) -> bool:
        self.suite.checks.append(Check(self.suite.name, what, holds))
        return holds


def expectations(cs: Path, log: Log) -> Suite:
    """The checks of one verifier class, evaluated on log."""
    text = cs.read_text(encoding="utf-8-sig")
    name = re.search(r"class (\w+) : TestFunctionBlockAssert", text)
    suite = Suite(name.group(1) if name else cs.stem)
    instance = suite.name[3:] if suite.name.startswith("FB_") else suite.name
    for m in re.finditer(r"private void \w+\(\)\s*\{(.*?)\n        \}", text, re.S):
        body = re.sub(r"//[^\n]*", "", m.group(1))
        reader = _Reader(instance, log, suite)
        for stmt in body.split(";\n"):
            toks = _tokens(stmt.strip().rstrip(";"))
            if toks:
                try:
                    reader.statement(toks)
                except (ValueError, IndexError, KeyError) as e:
                    suite.skipped.append(f"{stmt.strip()[:60]} ({e})")
    return suite


# ---------------------------------------------------------------- the run


def _project_copy(verifier: Path, into: Path) -> Path:
    src = verifier / "TcUnit-Verifier_TwinCAT"
    shutil.copytree(src, into / "TcUnit-Verifier_TwinCAT")
    return into / "TcUnit-Verifier_TwinCAT"


def _drop(project_dir: Path, suites: list) -> None:
    """Take the instances of the suites (FB names) out of PRG_TEST."""
    for prg in project_dir.rglob("PRG_TEST.TcPOU"):
        text = prg.read_text(encoding="utf-8-sig")
        for fb in suites:
            text = re.sub(rf"\n[ \t]*\w+\s*:\s*{fb}\s*;", "", text)
        prg.write_text(text, encoding="utf-8")


def run(verifier: Path, libraries: tuple, verbose: bool) -> int:
    with tempfile.TemporaryDirectory() as tmp:
        project_dir = _project_copy(verifier, Path(tmp))
        dropped: dict = {}
        for _round in range(4):  # the suites that do not compile out of PRG_TEST, until it compiles
            [project] = open_projects([str(project_dir)])
            a = analyse(project, None, libraries=(tcunit_library(), *libraries), subset=True)
            broken = {u.name: u for u in a.units.all if u.is_pou and not a.compiled(u) and u.name != "PRG_TEST"}
            for name, unit in broken.items():
                first = next((d for d in a.errors if d.pos.file == unit.file), None)
                why = first.format(a.sources).splitlines()[0] if first else "(uses one that does not compile)"
                dropped.setdefault(name, why.split("TcUnitVerifier/")[-1])
            if any(u.name == "PRG_TEST" and a.compiled(u) for u in a.units.all):
                break
            _drop(project_dir, list(broken))
        if a.program is None:
            print("PRG_TEST does not compile")
            return 1
        result = run_tcunit(project_config(a, a.program), a.program, 60_000_000_000)
    log = Log(result.log)
    outcomes = {k: sum(r.outcome == k for r in result.results) for k in ("passed", "failed", "skipped", "error")}
    print(f"ran {result.suites} test suites, {len(result.results)} tests: {outcomes}")
    print(f"engine time {result.time_ns / 1e9:g} s, wall {result.wall_s:.2f} s")
    failed_line = next((line.text for line in result.log if line.text.startswith("| Failed tests:")), "")
    print(f"TcUnit says: {failed_line[2:]}")
    print(f"left out ({len(dropped)}, they do not compile here):")
    for name, why in sorted(dropped.items()):
        print(f"  {name}: {why}")
    total = held = 0
    print("per verifier class: checks that hold / checks")
    dotnet = verifier / "TcUnit-Verifier_DotNet" / "TcUnit-Verifier"
    for cs in sorted(dotnet.glob("FB_*.cs")):
        suite = expectations(cs, log)
        if suite.name in dropped:
            print(f"  {suite.name}: not run")
            continue
        ok = sum(c.holds for c in suite.checks)
        total, held = total + len(suite.checks), held + ok
        print(f"  {suite.name}: {ok}/{len(suite.checks)}")
        for c in suite.checks:
            if not c.holds or verbose:
                print(f"      {'ok  ' if c.holds else 'FAIL'} {c.what}")
        for s in suite.skipped if verbose else ():
            print(f"      (not read: {s})")
    print(f"total: {held}/{total} checks hold")
    return 0


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("verifier", type=Path, help="the TcUnit-Verifier folder (TwinCAT and .NET projects)")
    ap.add_argument("--library", action="append", default=[], metavar="NAME=FOLDER", help="a further library")
    ap.add_argument("-v", "--verbose", action="store_true", help="every check, and what the reader skipped")
    args = ap.parse_args()
    libs = tuple(Library(Path(spec.split("=", 1)[1]), spec.split("=", 1)[0]) for spec in args.library)
    sys.exit(run(args.verifier, libs, args.verbose))


if __name__ == "__main__":
    main()
