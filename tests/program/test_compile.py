"""program/compile.py: the libraries compiled with every program."""

from __future__ import annotations

from softplc.runtime.program.compile import _library_sources
from softplc.runtime.st.syntax.lexer import strip_comments


def test_the_libraries_read_alike_whether_comments_nest_or_not():
    # The library files are parsed once for every profile, so none may hold
    # a comment that nesting (CODESYS) and not nesting (IEC, MatIEC) read
    # differently: '(*' inside a (* *) comment.
    sources = _library_sources()
    assert len(sources) > 10
    problems: list = []
    for name, text in sources:
        nested, _ = strip_comments(text, lambda *a: problems.append(a), nested=True)
        flat, _ = strip_comments(text, lambda *a: problems.append(a), nested=False)
        assert problems == [] and nested == flat, name


def test_a_binary_file_given_as_a_program_is_one_e000(tmp_path):
    """/bin/ls as a program printed 100 kB of its bytes, an E002 for each
    character the lexer did not know."""
    import pytest

    from softplc.runtime.program import compile_files
    from softplc.runtime.st.diagnostics import CompileError

    binary = tmp_path / "ls"
    binary.write_bytes(b"\x7fELF\x02\x01\x01\x00" + bytes(range(256)) * 400)
    with pytest.raises(CompileError) as info:
        compile_files([binary])
    [diag] = info.value.diagnostics
    assert (diag.code, diag.message) == ("E000", "not a text file (a NUL byte at byte 7): an ST file is text")
    assert len(str(info.value)) < 300


def test_a_utf16_file_with_its_byte_order_mark_is_read_as_text(tmp_path):
    from softplc.runtime.program import compile_files

    source = tmp_path / "main.st"
    source.write_bytes("PROGRAM Main\nVAR x : INT; END_VAR\nx := x + 1; (* größer *)\nEND_PROGRAM\n".encode("utf-16"))
    runner = compile_files([source]).runner("Main", cycle_time_ms=10)
    runner.run(3)
    assert runner.get("x") == 3
