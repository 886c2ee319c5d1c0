"""What generated code calls at run time: the IEC functions (rtlib.py and
its rt_* parts: numbers, strings, time and date, conversions, CASE,
byte views, variable-length arrays, SFC, OOP), and references (refs.py).

Imports nothing of syntax/, check/ or codegen/ (pyproject.toml's
import-linter contract "The language's stages").
"""
