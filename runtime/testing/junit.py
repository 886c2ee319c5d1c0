"""The JUnit XML report of a test run, as CI servers read it (Jenkins,
GitLab, GitHub actions): one <testsuite> per test file (per test suite for
TcUnit's tests: PRG_TEST.fbSum_Test), one <testcase> per test with the wall
time it took (time) and its engine time (a property engine_time, in
seconds), a <failure> for a failed assertion or the timeout (its message
TcUnit's own line for a TcUnit assert), an <error> for a runtime fault, a
<skipped/> for a disabled TcUnit test.

Written with the standard library's xml.etree: the format is a handful of
elements, and ElementTree escapes what it must.
"""

from __future__ import annotations

import xml.etree.ElementTree as ET
from pathlib import Path

from .runner import ERROR, FAILED, SKIPPED, TestResult


def _seconds(ns: int) -> str:
    return f"{ns / 1e9:.3f}"


def report(results: list[TestResult]) -> ET.ElementTree:
    root = ET.Element("testsuites", name="softplc test")
    suites: dict = {}
    for r in results:
        key = (r.case.suite, r.case.file) if r.case.classname is None else (r.case.suite, None)
        suite = suites.get(key)
        if suite is None:
            suite = suites[key] = ET.SubElement(root, "testsuite", name=r.case.suite, file=r.case.file)
        case = ET.SubElement(
            suite,
            "testcase",
            name=r.case.name,
            classname=r.case.suite,
            file=r.case.file,
            line=str(r.case.line),
            time=f"{r.wall_s:.3f}",
            assertions=str(r.asserts),
        )
        props = ET.SubElement(case, "properties")
        ET.SubElement(props, "property", name="engine_time", value=_seconds(r.time_ns))
        if r.outcome == FAILED:
            first = r.failures[0] if r.failures else None
            message = (first.detail or f"{first.site}: {first.message or first.function}") if first else r.error
            ET.SubElement(
                case, "failure", message=message, type=first.function if first else "timeout"
            ).text = r.describe()
        elif r.outcome == ERROR:
            ET.SubElement(case, "error", message=r.error, type="runtime fault").text = r.describe()
        elif r.outcome == SKIPPED:
            ET.SubElement(case, "skipped")
    for element in [root, *suites.values()]:
        mine = list(element.iter("testcase"))
        element.set("tests", str(len(mine)))
        element.set("failures", str(sum(1 for c in mine if c.find("failure") is not None)))
        element.set("errors", str(sum(1 for c in mine if c.find("error") is not None)))
        element.set("skipped", str(sum(1 for c in mine if c.find("skipped") is not None)))
        element.set("time", f"{sum(float(c.get('time', '0')) for c in mine):.3f}")
    ET.indent(root)
    return ET.ElementTree(root)


def write(results: list[TestResult], path: str | Path) -> None:
    """OSError when the file cannot be written."""
    report(results).write(path, encoding="utf-8", xml_declaration=True)
