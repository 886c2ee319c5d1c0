"""CODESYS's StringUtils library (placeholder StringUtils, namespace Stu),
its Ansi functions over a pointer to a string, as the CODESYS online help
documents them (content.helpme-codesys.com, libs/StringUtils, Public
Parts/Ansi): functions.py holds the ones that answer a value, ansi.st the
ones that edit the string in place."""
