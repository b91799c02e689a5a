"""Maintainer tooling, not installed with the package: the frozen CalculiX references (``tools.calculix_refs``)
and the tooth-segment mesher (``tools.segment_mesh``). Run from the repository root (``python3 -m tools...``);
tools import ``geometry``, ``fem`` and ``ltca``, never the reverse."""
