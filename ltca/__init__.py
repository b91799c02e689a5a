"""Analyses, case files, command line and reports. Imports `geometry` and `fem`."""
__version__ = "0.1.0"
