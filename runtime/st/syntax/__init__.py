"""The first stage: ST (and IL) text to the syntax tree (st/ast.py).

lexer (tokens, pragmas and comments blanked, the profile's dialect rules)
-> parser (the LALR(1) table of grammar.lark, read once by lark_adapter and
kept as plain data in st_grammar; parse_recovery and parse_stack go on
after an error) -> build_* (the rules' callbacks: declarations, statements,
expressions, SFC networks) -> ast nodes; literals and pragmas are read here
too. il* reads Instruction List and lowers it to the same tree.

Imports nothing of check/, codegen/ or rtlib/ (pyproject.toml's
import-linter contract "The language's stages").
"""
