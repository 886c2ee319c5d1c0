"""MkDocs hooks (mkdocs.yml `hooks:`): the reference pages that are
generated from the code at each build, so that they cannot drift from it.

    index.md                     the README (its links into docs/ made the site's)
    reference/configuration.md   every key of the TOML file, from the pydantic
                                 models of the configuration's sections (and
                                 of the registered buses and devices)
    reference/cli.md             every softplc command and option, from click
    reference/diagnostics.md     every diagnostic code's page (check --explain)
    reference/function-blocks.md every shipped ST library's POUs and their
                                 interface, from the ST declarations
    reference/devices.md         every registered device: its package's own
                                 description (the manual, the digest), bus,
                                 [[sim]] type, keys and faults, ST libraries

`mkdocs build --strict` (.ci/run) builds them; they are not in the repository.
"""

from __future__ import annotations

import re
import types
import typing
from pathlib import Path
from typing import Any

from mkdocs.structure.files import File

PYDANTIC_UNDEFINED = "PydanticUndefined"
ROOT = Path(__file__).resolve().parents[1]


def on_files(files, config):
    files.append(File.generated(config, "index.md", content=front_page()))
    for name, render in GENERATED.items():
        files.append(File.generated(config, name, content=render()))
    return files


def front_page() -> str:
    """The README, the site's home page: its links into docs/ made the site's."""
    readme = (ROOT / "README.md").read_text(encoding="utf-8")
    return re.sub(r"\]\(docs/", "](", readme)


# ------------------------------------------------------------- configuration


def _type_text(annotation: Any) -> str:
    origin = typing.get_origin(annotation)
    if origin is typing.Annotated:
        return _type_text(typing.get_args(annotation)[0])
    if origin in (typing.Union, types.UnionType):
        parts = [_type_text(a) for a in typing.get_args(annotation) if a is not type(None)]
        return " or ".join(dict.fromkeys(parts))
    if annotation is Any:
        return "any"
    if origin in (list, tuple):
        args = typing.get_args(annotation)
        return f"array of {_type_text(args[0])}" if args else "array"
    if origin is dict:
        return "table"
    if origin is typing.Literal:
        return " | ".join(repr(a) for a in typing.get_args(annotation))
    if isinstance(annotation, type):
        if _is_model(annotation):
            return "table"
        return {"str": "string", "int": "integer", "float": "number", "bool": "boolean", "tuple": "array"}.get(
            annotation.__name__, annotation.__name__
        )
    return str(annotation).replace("typing.", "")


def _is_model(annotation: Any) -> bool:
    return isinstance(annotation, type) and hasattr(annotation, "model_fields")


def _submodels(annotation: Any) -> list:
    found = []
    if _is_model(annotation):
        return [annotation]
    for arg in typing.get_args(annotation):
        found += _submodels(arg)
    return found


def _default(field) -> str:
    default = field.default
    if str(default) == PYDANTIC_UNDEFINED:
        return "required" if field.is_required() else ""
    if default is None or (field.description and "duration" in field.description):
        return ""
    if isinstance(default, bool):
        return "true" if default else "false"
    if isinstance(default, str):
        return f'`"{default}"`'
    if isinstance(default, int | float):
        return f"`{default}`"
    return ""


def _cell(text: str) -> str:
    return text.replace("|", "\\|").replace("\n", " ")


def _model_table(title: str, model, out: list, seen: set) -> None:
    if model in seen:
        return
    seen.add(model)
    rows = []
    nested = []
    for name, field in model.model_fields.items():
        key = field.alias or name
        what = field.description or ""
        kind = "duration" if "duration" in what else _type_text(field.annotation)
        rows.append(f"| `{key}` | {_cell(kind)} | {_default(field)} | {_cell(what)} |")
        for sub in _submodels(field.annotation):
            nested.append((f"{title}.{key}", sub))
    if rows:
        out += ["| key | type | default | what |", "|---|---|---|---|", *rows, ""]
    else:
        out += ["Any key: each is a path, its value what the path takes.", ""]
    for sub_title, sub in nested:
        out += [f"### `{sub_title}`", ""]
        _model_table(sub_title, sub, out, seen)


def configuration() -> str:
    from softplc.runtime.config.load import _Document
    from softplc.runtime.plugin.registry import registry

    out = [
        "# Configuration keys",
        "",
        "Every key of a configuration file, generated from the models that check it (the core's",
        "sections, then each registered bus's; a device's own `[[sim]]` keys are in `[[sim]]`).",
        'A duration is a string such as `"10ms"`, `"2s"` or `"T#500ms"`. What each key does is in',
        "the guides; an error in a file names the file, the key and what was expected.",
        "",
    ]
    seen: set = set()
    for section in _Document(registry()).sections:
        title = f"[[{section.key}]]" if section.many else f"[{section.key}]"
        out += [f"## `{title}`", "", f"{section.description[0].upper()}{section.description[1:]}.", ""]
        _model_table(section.key, section.model, out, seen)
    return "\n".join(out) + "\n"


# ------------------------------------------------------------------ the CLI


def cli() -> str:
    import click

    from softplc.runtime.cli import cli as group

    out = ["# The softplc command", "", "Generated from the command's own help (`softplc COMMAND --help`).", ""]
    ctx = click.Context(group, info_name="softplc")
    out += ["```text", group.get_help(ctx).rstrip(), "```", ""]
    for name in sorted(group.list_commands(ctx)):
        command = group.get_command(ctx, name)
        if command is None or command.hidden:
            continue
        sub = click.Context(command, info_name=f"softplc {name}", parent=ctx)
        out += [f"## `softplc {name}`", "", "```text", command.get_help(sub).rstrip(), "```", ""]
    return "\n".join(out) + "\n"


# -------------------------------------------------------------- diagnostics


def diagnostics() -> str:
    from softplc.runtime.st import explain

    out = [
        "# Diagnostic codes",
        "",
        "Every code `softplc check` reports, as `softplc check --explain CODE` prints it: what it",
        "means, a program that draws it, how to fix it, and how the profiles differ.",
        "",
    ]
    for code in explain.codes():
        text = explain.page(code) or ""
        # each page's headings one level down: a page is a section here
        text = re.sub(r"^(#+) ", lambda m: "#" + m.group(1) + " ", text, flags=re.M)
        text = text.replace("```st\n", "```iecst\n")
        out += [text.rstrip(), ""]
    return "\n".join(out) + "\n"


# ------------------------------------------------------------------ devices


def devices() -> str:
    import inspect

    from softplc.runtime.plugin.registry import registry

    out = [
        "# Devices",
        "",
        "Every registered device, generated from its package: what it is and the manual and digest",
        "it follows (the package's own description), the bus it sits on, its `[[sim]]` type, keys",
        "and faults, and its ST libraries. The guides say how each is used",
        "([Buses and devices](../guide/buses.md), [Simulated devices](../guide/simulation.md)).",
        "",
    ]
    for device in registry().devices:
        module = inspect.getmodule(device.simulator) if device.simulator else None
        out += [f"## {device.name}", ""]
        doc = inspect.getdoc(module) if module is not None else None
        if doc:
            out += ["```text", doc, "```", ""]
        out += [f"Bus: `{device.bus}`; `[[sim]]` type: {', '.join(f'`{t}`' for t in device.sim_types) or 'none'}.", ""]
        if device.libraries:
            names = ", ".join(f"`{lib.package.split('.')[-1]}/{lib.file}`" for lib in device.libraries)
            out += [f"ST libraries (in softplc.fblocks): {names}.", ""]
        if device.sim_options is not None:
            out += ["### Its own `[[sim]]` keys", ""]
            _model_table(f"sim.{device.name}", device.sim_options, out, set())
        if device.sim_faults:
            out += ["### Its faults (`[[sim]] faults`, `plc.fault`)", ""]
            out += ["| fault | value | lasting | what |", "|---|---|---|---|"]
            for f in device.sim_faults:
                lasting = "yes" if f.lasting else "no"
                out.append(f"| `{f.name}` | {_cell(f.value)} | {lasting} | {_cell(f.description)} |")
            out.append("")
    return "\n".join(out) + "\n"


# ---------------------------------------------------------- function blocks


def function_blocks() -> str:
    from softplc.runtime.program.reference import library_reference

    return library_reference()


GENERATED = {
    "reference/configuration.md": configuration,
    "reference/cli.md": cli,
    "reference/diagnostics.md": diagnostics,
    "reference/function-blocks.md": function_blocks,
    "reference/devices.md": devices,
}
