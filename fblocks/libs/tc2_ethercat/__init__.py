"""Beckhoff's Tc2_ethercat, declared: see its ST files."""
