"""CODESYS's Standard library (placeholder Standard): the counters and
bistables with CODESYS's input names, RTC, and the string functions with
their formal parameter names. Its timers and edge detectors are softplc's
IEC ones (fblocks/iec/standard_fbs.st), whose interface CODESYS shares."""
