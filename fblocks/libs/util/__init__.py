"""CODESYS's Util library (placeholder Util), as its online help documents
it (content.helpme-codesys.com, libs/Util): analog monitors, BCD and bit
functions, controllers, function manipulators, mathematical functions and
signal generators. Times come from the task clock (TIME()), so the blocks
run in virtual time as on a PLC."""
