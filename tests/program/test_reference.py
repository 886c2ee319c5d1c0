"""The shipped libraries as the manual's "Function blocks" page
(program/reference.py): each POU's declaration as its file writes it, up to
the end of its interface, grouped by library."""

from __future__ import annotations

import re

from softplc.runtime.program.reference import library_reference


def test_the_page_holds_each_block_s_interface_as_written():
    page = library_reference()
    # a built-in vendor block: its header, its doc comment, its inputs and outputs, not its body
    block = page.split("**`LTMR_CONTROL`** (function block)", 1)[1].split("```", 2)[1]
    assert block.startswith("iecst\nFUNCTION_BLOCK LTMR_CONTROL")
    assert "VAR_INPUT" in block and "VAR_OUTPUT" in block and block.rstrip().endswith("END_VAR")
    assert "END_FUNCTION_BLOCK" not in block
    # the standard timers, and a library chosen by name, with its aliases
    assert "**`TON`** (function block)" in page
    assert re.search(r"^### TcUnit", page, re.M)
    assert "## Libraries chosen by name" in page
