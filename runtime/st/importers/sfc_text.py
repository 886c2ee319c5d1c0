"""Reading ST text as an SFC import needs it: which form a named
transition's ST body has, and lines joined into one without a ``//``
comment swallowing what follows. A small scanner that knows ST's string
literals, comments and pragmas, nothing else."""

from __future__ import annotations

# form -> (between the TRANSITION header and the body, before END_TRANSITION)
ST_FORMS = {
    "assign": ("", ""),  # ":= expression;" (as Beremiz writes a transition's ST body)
    "statements": (":", ""),  # statements assigning the transition's name
    "expression": (":=", "; "),  # a bare expression
}


def _spans(text: str) -> list:
    """(start, end, kind) of each string literal ("string"), comment or
    pragma ("comment") and // comment ("line") in text."""
    out = []
    i, n = 0, len(text)
    while i < n:
        c, two = text[i], text[i : i + 2]
        if c in "'\"":
            j = i + 1
            while j < n and text[j] != c:
                j += 2 if text[j] == "$" else 1
            out.append((i, min(j + 1, n), "string"))
            i = j + 1
        elif two == "//":
            j = text.find("\n", i)
            j = n if j < 0 else j
            out.append((i, j, "line"))
            i = j
        elif two in ("(*", "/*"):
            j = _comment_end(text, i)
            out.append((i, j, "comment"))
            i = j
        elif c == "{":
            j = text.find("}", i)
            j = n if j < 0 else j + 1
            out.append((i, j, "comment"))
            i = j
        else:
            i += 1
    return out


def _comment_end(text: str, i: int) -> int:
    """The end of the comment opening at i ((* *) nest, /* */ do not)."""
    if text.startswith("/*", i):
        j = text.find("*/", i + 2)
        return len(text) if j < 0 else j + 2
    depth, j = 0, i
    while j < len(text):
        if text.startswith("(*", j):
            depth += 1
            j += 2
        elif text.startswith("*)", j):
            depth -= 1
            j += 2
            if depth == 0:
                return j
        else:
            j += 1
    return len(text)


def code_only(text: str) -> str:
    """text with its strings, comments and pragmas blanked."""
    chars = list(text)
    for start, end, _kind in _spans(text):
        chars[start:end] = " " * (end - start)
    return "".join(chars)


def st_form(text: str) -> str:
    """The form of a named transition's ST body: "assign" (it starts with
    :=), "statements" (it assigns something or ends statements with ;) or
    "expression"."""
    code = code_only(text).strip()
    if code.startswith(":="):
        return "assign"
    if ":=" in code or ";" in code:
        return "statements"
    return "expression"


def has_line_comment(text: str) -> bool:
    """Whether a // comment in text would swallow what follows it on its line."""
    return any(kind == "line" for _s, _e, kind in _spans(text))


def one_line(lines: list) -> str:
    """lines as one line: // comments left out, the rest joined by blanks."""
    text = "\n".join(lines)
    for start, end, kind in reversed(_spans(text)):
        if kind == "line":
            text = text[:start] + text[end:]
    return " ".join(part.strip() for part in text.split("\n") if part.strip())
