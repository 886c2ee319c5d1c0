"""The JUnit XML report of a test run, as CI servers read it (Jenkins,
GitLab, GitHub actions): one <testsuite> per test file, one <testcase> per
test with the wall time it took (time) and its engine time (a property
engine_time, in seconds), a <failure> for a failed assertion or
the timeout, an <error> for a runtime fault.

Written with the standard library's xml.etree: the format is a handful of
elements, and ElementTree escapes what it must.
"""

from __future__ import annotations

import xml.etree.ElementTree as ET
from pathlib import Path

from .runner import ERROR, FAILED, TestResult


def _seconds(ns: int) -> str:
    return f"{ns / 1e9:.3f}"


def report(results: list[TestResult]) -> ET.ElementTree:
    root = ET.Element("testsuites", name="softplc test")
    suites: dict = {}
    for r in results:
        suite = suites.get(r.case.file)
        if suite is None:
            suite = suites[r.case.file] = ET.SubElement(root, "testsuite", name=r.case.suite, file=r.case.file)
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
            message = f"{first.site}: {first.message or first.function}" if first else r.error
            ET.SubElement(
                case, "failure", message=message, type=first.function if first else "timeout"
            ).text = r.describe()
        elif r.outcome == ERROR:
            ET.SubElement(case, "error", message=r.error, type="runtime fault").text = r.describe()
    for element in [root, *suites.values()]:
        mine = list(element.iter("testcase"))
        element.set("tests", str(len(mine)))
        element.set("failures", str(sum(1 for c in mine if c.find("failure") is not None)))
        element.set("errors", str(sum(1 for c in mine if c.find("error") is not None)))
        wall = sum(r.wall_s for r in results if element is root or r.case.file == element.get("file"))
        element.set("time", f"{wall:.3f}")
    ET.indent(root)
    return ET.ElementTree(root)


def write(results: list[TestResult], path: str | Path) -> None:
    """OSError when the file cannot be written."""
    report(results).write(path, encoding="utf-8", xml_declaration=True)
