"""Which dialect a source reads like: the markers of each profile, for the
hint of ``softplc check`` ("reads like schneider (...); try --profile
schneider").

A marker is text only one dialect writes (comments and strings do not
count): C-style ``0x1F`` literals, ``%MW3250:X0`` bits and ``ADR#0.1.SYS``
(Schneider), ``{{ }}`` embedded C (MatIEC), the ``Tc2_``/``Tc3_`` library
namespaces (TwinCAT), a comma ending an argument list, ``{attribute ...}``
pragmas, ``Standard.`` and the object-oriented keywords (CODESYS and
TwinCAT). The markers only pick the candidates; the command re-checks the
files with one before it names it (runtime/cli.py), so the hint never
proposes a profile that does worse.
"""

from __future__ import annotations

import re

from .syntax.lexer import strip_comments

# (profile, what the user reads, pattern): in the order the hint lists them.
_MARKERS = (
    ("schneider", "0x literals", re.compile(r"(?<![\w#])0x[0-9a-f]", re.IGNORECASE)),
    ("schneider", "%MW..:X bits and %MW..:n tables", re.compile(r"%M[WD]\d+:X?\d", re.IGNORECASE)),
    ("schneider", "ADR#", re.compile(r"\bADR#", re.IGNORECASE)),
    ("matiec", "{{ }} embedded C", re.compile(r"\{\{")),
    ("twincat", "Tc2_/Tc3_ libraries", re.compile(r"\bTc[23]_\w+\.", re.IGNORECASE)),
    ("codesys", "a comma ending an argument list", re.compile(r",\s*\)")),
    ("codesys", "{attribute} pragmas", re.compile(r"\{\s*attribute\b", re.IGNORECASE)),
    ("codesys", "Standard. names", re.compile(r"\bStandard\.\w", re.IGNORECASE)),
    (
        "codesys",
        "METHOD, PROPERTY, INTERFACE or REFERENCE TO",
        re.compile(r"\b(?:METHOD|PROPERTY|INTERFACE|REFERENCE\s+TO|__NEW|__QUERYINTERFACE)\b", re.IGNORECASE),
    ),
)
# TwinCAT is CODESYS underneath: a CODESYS marker counts for it too.
_ALSO = {"codesys": ("twincat",)}
_STRING = re.compile(r"'(?:[^'$\n]|\$[^\n])*'|\"(?:[^\"$\n]|\$[^\n])*\"")


def markers(text: str) -> dict:
    """{profile: [markers found]} for one source text."""
    code, _pragmas = strip_comments(text, lambda *a: None, True)
    code = _STRING.sub("''", code)
    raw = _STRING.sub("''", text)  # pragmas are blanked out of code
    found: dict[str, list] = {}
    for profile, what, pattern in _MARKERS:
        if pattern.search(raw if what.startswith("{") else code):
            for p in (profile, *_ALSO.get(profile, ())):
                found.setdefault(p, []).append(what)
    return found


def candidates(texts: list, current: str) -> list:
    """[(profile, [markers])] other than current, the most markers first."""
    found: dict[str, list] = {}
    for text in texts:
        for p, whats in markers(text).items():
            found.setdefault(p, [])
            found[p] += [w for w in whats if w not in found[p]]
    ranked = sorted(found.items(), key=lambda kv: -len(kv[1]))
    return [(p, whats) for p, whats in ranked if p != current]


def hint(profile: str, whats: list) -> str:
    return f"reads like {profile} ({', '.join(whats)}); try --profile {profile}"
