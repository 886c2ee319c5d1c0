"""The compiler's limits, in one place (docs/reference/language.md "Limits").

Each keeps the time and memory a compilation (and the building of the
variables when the program is loaded) may take bounded, whatever the
input; going past one is a coded diagnostic at the file, line and column
where it happens, never a crash or a hang:

  E007  MAX_SOURCE_CHARS     characters in one source file
  E008  MAX_COMMENT_DEPTH    (* *) comments nested in each other
  E006  MAX_NESTING          the parser's stack: nested parentheses, calls,
                             unary operators, statements (IF in IF ...)
  E006  MAX_OPERATORS        binary operators in one expression (a chain
                             a + b + c ... is checked and generated in a
                             loop, not a call per operator: 10,000 take 2 s)
  E006  (the Python compiler's own: 20 nested loops, 100 levels of blocks)
  E006  MAX_TYPE_NESTING     STRUCTs and ARRAYs of named types in each other
  E054  MAX_VAR_ELEMENTS     elements of one variable (or array type)
  E055  MAX_TOTAL_ELEMENTS   elements of all variables together
  E022  MAX_STRING_LENGTH    characters of a STRING[n]
  E001  MAX_ERRORS           syntax errors reported before the parse stops

An element is one elementary value (a number, a string, a reference); a
STRUCT or FB instance counts one more for itself. ``ARRAY[1..10] OF
Point`` with a two-field Point is 10 * (2 + 1) = 30 elements.
"""

from __future__ import annotations

# 6 to 7 s and 600 MB to check and compile a 1 MiB file of dense
# statements (the generated Python is about four times the ST, and
# Python's compiler takes most of the memory); the ST files of a plant are
# far smaller, a POU or a few each.
MAX_SOURCE_CHARS = 1 << 20

# Deeper nesting of comments is no longer a comment but a mistake.
MAX_COMMENT_DEPTH = 100

# The parser's stack grows by 1 to 4 entries per level of nesting: about
# 290 parentheses, 95 IFs. Later stages walk the tree recursively, and the
# generated Python has limits of its own (100 levels of indentation, 200
# nested brackets).
MAX_NESTING = 300
# A chain of 10,000 operators (a + b + c ..., any precedence) checks and
# compiles in about 2 s (benchmarks/bench_language_limits.py).
MAX_OPERATORS = 10_000

# A STRUCT in a STRUCT (or an ARRAY of an ARRAY type) ... 100 deep: the
# checker, the code generator and the generated code (each level a nested
# constructor call) walk a value's type recursively, a few frames a level.
MAX_TYPE_NESTING = 100

# 10 million elements are 80 MB of references for an array of numbers
# (equal values are shared). The worst case within both limits, two
# arrays of 5 million one-field STRUCTs (an object per element), loads in
# 3 to 7 s and 600 MB.
MAX_VAR_ELEMENTS = 10_000_000
MAX_TOTAL_ELEMENTS = 20_000_000

MAX_STRING_LENGTH = 65535
MAX_ERRORS = 100
