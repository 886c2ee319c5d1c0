"""The second stage: the syntax tree checked and typed.

checker.Checker runs the passes: declarations and types (checker_decls,
checker_types, namespaces), then the bodies (checker_stmts, checker_exprs,
checker_calls, checker_operators, the OOP rules in checker_oop*, SFC in
checker_sfc ...), each a mixin over checker_base. What it leaves for code
generation: the symbols (symbols.py: POUs, variables, calls resolved) and
the types of every expression; conversions.py and oop.py are the rules it
applies. Diagnostics are st/diagnostics.py's.

May import syntax/ and rtlib/ (a constant folded as the runtime computes
it), never codegen/.
"""
