"""The third stage: the checked tree to Python source, one module per
program (codegen.generate). codegen_base holds the emitter (every name
and string escaped, never pasted), codegen_pous the POUs as classes,
codegen_stmts/exprs/calls the bodies; ranges.py and nesting.py keep
deep or wide code within Python's own limits.

The generated code calls only rtlib/ at run time.
"""
