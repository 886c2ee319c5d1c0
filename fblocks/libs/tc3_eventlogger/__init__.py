"""Beckhoff's Tc3_EventLogger, declared: see its ST files."""
