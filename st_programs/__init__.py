# Makes st_programs a regular package (softplc.st_programs): the example programs install as package data.
